r"""Candidate mechanisms for the paper's critical-frequency constant c (research/c_hypotheses.md).

Ours: c = f_d*/f_0 = 0.229, 0.271, 0.323, 0.354 for Delta RMS thresholds 0.05, 0.07, 0.10, 0.12;
the paper: 0.311, 0.345, 0.385, 0.404 (+- 0.001).  Each named hypothesis below changes one thing
in how RMS_dyn, RMS_QS, Delta RMS or f_0 are obtained (what the paper's pipeline might have done)
and `c_for_hypothesis` returns the c it gives for every threshold at once.

A hypothesis is a set of options (`Hypothesis`):

* ``model``: the dynamic model, ours or `rotbeam.elastica_printed.PrintedElastica` with printed
  misprints (dynamic only: the paper's quasi-static answer came from bvp4c on the continuum).
* ``qs``: quasi-static response from the same discrete model ("discrete") or from the continuum
  ("continuum": Richardson limit of the discrete static problem on N = 80 and 160, which agrees
  with `rotbeam.quasistatic.solve_static_bvp` to 1e-6 relative; tested).
* ``s_dyn``/``N_dyn``: where and on which grid the dynamic y_m is read (QS always at s = 1/2).
* ``measure``: "y" (rotating frame), "lab" (the drive's rigid oscillation added: a frame turning
  uniformly at Omega_0), "chord" (deflection normal to the clamp-tip chord).
* ``dynamics``: "periodic" (the steady orbit by collocation), or time stepping from rest with
  ``window`` (RMS over [0, T_end], e.g. ("periods", 10) or ("seconds", 5.0); ("last", 1) is the
  last period of a run of ``t_end_tau``) and ``method``/``rtol``/``atol`` (e.g. TR-BDF2 at
  MATLAB's defaults 1e-3 / 1e-6).
* ``f0``: "linear_max" (ours: linearised in-plane frequency at Omega_0 + a), "linear_mean"
  (at Omega_0), "southwell_flap" / "southwell_inplane" (Eq. Southwell with S_1 flapwise / in-plane),
  "fn_printed" (ours shifted to f_n = 6.37 Hz), "peak" (peak of the dynamic RMS scan).
* ``zeta``: damping ratio (None: the beam's gamma, zeta = 0.0203).
* ``denominator``: "dyn" (Eq. Delta_RMS) or "qs"; ``mean``: "keep" or "remove"; ``qs_scale``:
  RMS_QS multiplied by this (the size of bias that would explain the paper, for calibration).
* ``coriolis_ny``: the printed +2 I y_t of the n_y integrand with Coriolis on; for small angles
  it is an extra damping 2 lam W Theta_t, modelled here as eta -> eta + 2 lam0 (see
  `rotbeam.elastica_printed`).

Only public functions of rotbeam are used; everything here is downstream of the model.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.linalg as sla
from scipy.integrate import solve_ivp
from scipy.interpolate import PchipInterpolator
from scipy.sparse.linalg import LinearOperator, gmres

from .criterion import critical_from_scan
from .elastica import DiscreteElastica, Grid
from .elastica_printed import PrintedCollocation, PrintedElastica
from .integrate import Numerics, first_order_rhs, steady_state
from .modes import natural_frequencies_hz
from .params import Beam, Dimensionless, Drive, Effects, omega0_for_cmax
from .periodic import linear_guess
from .quasistatic import quasistatic_series
from .spectral import harmonic_tail, trig_interpolate
from .surrogate import southwell_frequency_hz
from .sweeps import resonance_frequency_hz

THRESHOLDS = (0.05, 0.07, 0.10, 0.12)
PAPER_C = {0.05: 0.311, 0.07: 0.345, 0.10: 0.385, 0.12: 0.404}
OURS_C = {0.05: 0.229, 0.07: 0.271, 0.10: 0.323, 0.12: 0.354}  #: full run, README
F_N_PRINTED = 6.37  #: Hz, Sec. 5


@dataclass(frozen=True)
class Hypothesis:
    description: str = "ours: collocated orbit N, quasi-static on the same grid, y at s = 1/2"
    model: tuple[str, ...] = ()  #: printed misprints of the dynamic model (elastica_printed)
    qs: str = "discrete"
    s_dyn: float = 0.5
    N_dyn: int | None = None
    measure: str = "y"
    dynamics: str = "periodic"
    window: tuple = ("last", 1)
    t_end_tau: float = 0.0  #: time-stepped runs: at least this long (dimensionless)
    method: str = "Radau"
    rtol: float = 1e-6
    atol: float = 1e-9
    f0: str = "linear_max"
    zeta: float | None = None
    denominator: str = "dyn"
    mean: str = "keep"
    qs_scale: float = 1.0
    coriolis_ny: bool = False
    N: int | None = None  #: grid (None: the numerics' N)
    step_periods: int = 3  #: dynamics "steps": periods stepped from the orbit (last 2 sampled)


_PRINTED = "printed appendix: dynamic model with {}, quasi-static continuum"

HYPOTHESES: dict[str, Hypothesis] = {
    "ours": Hypothesis(),
    "continuum_qs": Hypothesis("discrete dynamic model N beside a continuum quasi-static answer",
                               qs="continuum"),
    "printed_bracket": Hypothesis(_PRINTED.format("the tension bracket"), model=("bracket",),
                                  qs="continuum"),
    "printed_U3": Hypothesis(_PRINTED.format("the last column of 3s in U"), model=("U3",),
                             qs="continuum"),
    "printed_symS": Hypothesis(_PRINTED.format("the symmetric S~"), model=("symS",),
                               qs="continuum"),
    "printed_Kds": Hypothesis(_PRINTED.format("K with 1/ds"), model=("Kds",), qs="continuum"),
    "printed_U3_symS": Hypothesis(_PRINTED.format("U3 and symmetric S~ (the plausible slips)"),
                                  model=("U3", "symS"), qs="continuum"),
    "printed_all_but_K": Hypothesis(_PRINTED.format("bracket, U3, symmetric S~"),
                                    model=("bracket", "U3", "symS"), qs="continuum"),
    "printed_ny_coriolis": Hypothesis(
        "Coriolis on with the printed +2 I y_t of n_y (extra damping 2 lam0), QS continuum",
        qs="continuum", coriolis_ny=True),
    "ym_node_matlab": Hypothesis("dynamic y_m at node N/2 counted from the clamp as node 1 "
                                 "(s = (N/2 - 1)/N), QS at s = 1/2", s_dyn=None, qs="continuum"),
    "ym_39_intervals": Hypothesis("'N = 40 nodes' as 39 intervals, dynamic y_m at node 20 from "
                                  "the clamp as node 1 (s = 19/39), QS at s = 1/2",
                                  s_dyn=19 / 39, N_dyn=39, qs="continuum"),
    "ym_lab_frame": Hypothesis("y_m in a frame turning uniformly at Omega_0 (the drive's "
                               "rigid oscillation included), dynamic and QS", measure="lab"),
    "ym_normal_to_chord": Hypothesis("midspan deflection normal to the clamp-tip chord",
                                     measure="chord"),
    "rest_10_periods": Hypothesis("from rest, RMS over the first 10 drive periods",
                                  dynamics="rest", window=("periods", 10)),
    "rest_20_periods": Hypothesis("from rest, RMS over the first 20 drive periods",
                                  dynamics="rest", window=("periods", 20)),
    "rest_5_s": Hypothesis("from rest, RMS over the first 5 s", dynamics="rest",
                           window=("seconds", 5.0)),
    "rest_10_s": Hypothesis("from rest, RMS over the first 10 s", dynamics="rest",
                            window=("seconds", 10.0)),
    "f0_linear_mean": Hypothesis("f_0 linear at Omega_0 (not Omega_0 + a)", f0="linear_mean"),
    "f0_southwell_flap": Hypothesis("f_0 by Eq. Southwell with the flapwise S_1",
                                    f0="southwell_flap"),
    "f0_southwell_inplane": Hypothesis("f_0 by Eq. Southwell with the in-plane S_1",
                                       f0="southwell_inplane"),
    "f0_fn_printed": Hypothesis("f_0 with f_n = 6.37 Hz (printed) in place of 6.52 Hz",
                                f0="fn_printed"),
    "f0_peak": Hypothesis("f_0 = peak of the dynamic RMS scan (nonlinear, a = 1)", f0="peak"),
    "zeta_0.017": Hypothesis("damping zeta = 0.017 (App. E) instead of 0.020", zeta=0.017),
    "mean_removed": Hypothesis("RMS of y_m with its mean removed", mean="remove"),
    "qs_denominator": Hypothesis("Delta RMS with RMS_QS in the denominator", denominator="qs"),
    "ode_steps_trbdf2_1e-3": Hypothesis(
        "RMS_dyn over the integrator's own output steps (ode23tb returns its steps, Refine 1), "
        "TR-BDF2 at rtol 1e-3, atol 1e-6, last 2 of 3 periods from the orbit; QS uniform",
        dynamics="steps", method="TRBDF2", rtol=1e-3, atol=1e-6, qs="continuum"),
    "ode_steps_trbdf2_1e-4": Hypothesis(
        "as ode_steps_trbdf2_1e-3 at rtol 1e-4", dynamics="steps", method="TRBDF2", rtol=1e-4,
        atol=1e-6, qs="continuum"),
    "ode_steps_trbdf2_1e-3_from_rest": Hypothesis(
        "RMS_dyn over TR-BDF2's own steps (rtol 1e-3, atol 1e-6) over the last period of a run "
        "from rest of 2 ln(1000)/eta; QS uniform", dynamics="steps_rest", method="TRBDF2",
        rtol=1e-3, atol=1e-6, qs="continuum", t_end_tau=2 * math.log(1000.0) / Beam().eta),
    "trbdf2_loose": Hypothesis("TR-BDF2 (ode23tb's method) from rest at rtol 1e-3, atol 1e-6, "
                               "RMS over the last period of 2 ln(1000)/eta", dynamics="rest",
                               method="TRBDF2", rtol=1e-3, atol=1e-6, window=("last", 1),
                               t_end_tau=2 * math.log(1000.0) / Beam().eta),
}


def hypothesis(name: str | Hypothesis) -> Hypothesis:
    if isinstance(name, Hypothesis):
        return name
    if name.startswith("qs_scale_"):  # calibration: RMS_QS times a factor
        k = float(name[len("qs_scale_"):])
        return Hypothesis(f"RMS_QS multiplied by {k:g}", qs_scale=k)
    if name not in HYPOTHESES:
        raise KeyError(f"unknown hypothesis {name!r}; known: {', '.join(HYPOTHESES)}")
    return HYPOTHESES[name]


# --- pieces ---------------------------------------------------------------------------------
def _beam_for(beam: Beam, h: Hypothesis) -> Beam:
    if h.zeta is None:
        return beam
    return replace(beam, gamma=beam.gamma * h.zeta / beam.zeta)


def midspan_measure(grid: Grid, theta: np.ndarray, s: float, measure: str = "y",
                    dl: Dimensionless | None = None, tau: np.ndarray | None = None) -> np.ndarray:
    """y_m at arclength s from Theta (n, m): rotating-frame y, lab-frame (uniform Omega_0) y, or
    the deflection normal to the clamp-tip chord; linear interpolation between nodes."""
    theta = np.atleast_2d(theta.T).T if theta.ndim == 1 else theta
    x, y = grid.positions(theta)  # nodes 1..N
    S = np.concatenate([[0.0], grid.s])
    X = np.vstack([np.zeros((1, x.shape[1])), x])
    Y = np.vstack([np.zeros((1, y.shape[1])), y])
    xm = np.array([np.interp(s, S, X[:, k]) for k in range(X.shape[1])])
    ym = np.array([np.interp(s, S, Y[:, k]) for k in range(Y.shape[1])])
    if measure == "y":
        return ym
    if measure == "chord":
        xt, yt = X[-1], Y[-1]
        return (ym * xt - xm * yt) / np.hypot(xt, yt)
    if measure == "lab":
        phi = -(dl.alpha / dl.omega) * np.cos(dl.omega * tau)  # disk angle minus Omega_0 t
        return (dl.hub_ratio + xm) * np.sin(phi) + ym * np.cos(phi)
    raise ValueError(f"unknown measure {measure!r}")


def continuum_quasistatic_theta(dl: Dimensionless, taus: np.ndarray, N: int = 160):
    """Quasi-static Theta on grids N/2 and N: (grid_N, theta_N, grid_N/2, theta_N/2)."""
    out = []
    for n in (N // 2, N):
        model = DiscreteElastica(n, dl.hub_ratio, dl.eta, dl.effects)
        out.append((model.grid, quasistatic_series(model, dl, taus)))
    return out


def _rms(y: np.ndarray, mean: str) -> float:
    y = np.asarray(y, float)
    if mean == "remove":
        y = y - y.mean()
    return float(np.sqrt(np.mean(y * y)))


def periodic_orbit(dl: Dimensionless, model: DiscreteElastica, M: int = 33,
                   guess: np.ndarray | None = None, rtol: float = 1e-10, maxiter: int = 30):
    """Collocated periodic orbit (M, n) of any `DiscreteElastica` (subclass): inexact Newton,
    GMRES preconditioned by the time-averaged Jacobian (dense LU when that stalls)."""
    col = PrintedCollocation(dl, model, M)
    X = linear_guess(dl, model.grid.N, col.tau) if guess is None else np.array(guess, float)
    R = col.residual(X)
    rn = float(np.max(np.abs(R)))
    for _ in range(maxiter):
        blocks = col.jacobian_blocks(X)
        inv = col.averaged_inverse(blocks)
        size, shape = R.size, R.shape
        op = LinearOperator((size, size), lambda v: col.jacobian_times(blocks, v.reshape(shape)).ravel())
        pre = LinearOperator((size, size), lambda r: inv(r.reshape(shape)).ravel())
        step, info = gmres(op, -R.ravel(), rtol=1e-6, atol=0.0, restart=60, maxiter=20, M=pre)
        if info != 0:
            step = -sla.solve(col.dense_jacobian(blocks), R.ravel())
        step = step.reshape(shape)
        t = 1.0
        while True:
            Xt = X + t * step
            Rt = col.residual(Xt)
            rt = float(np.max(np.abs(Rt)))
            if np.isfinite(rt) and (rt < rn or t < 1e-3):
                break
            t *= 0.5
        X, R, rn = Xt, Rt, rt
        if float(np.max(np.abs(t * step))) <= rtol * max(float(np.max(np.abs(X))), 1e-300):
            return X, True, harmonic_tail(X)
    return X, False, harmonic_tail(X)


def _dynamic(h: Hypothesis, dl: Dimensionless, N: int, m: int, state: dict):
    """Dynamic Theta (n, k) and its instants, and the grid they live on."""
    model_eff = dl
    if h.coriolis_ny:
        model_eff = replace(dl, eta=dl.eta + 2.0 * abs(dl.lam0))
    if h.model:
        model = PrintedElastica(N, dl.hub_ratio, model_eff.eta, dl.effects, h.model)
    else:
        model = DiscreteElastica(N, dl.hub_ratio, model_eff.eta, dl.effects)
    P = dl.period
    if h.dynamics == "periodic":
        if not h.model:
            ss = steady_state(model_eff, Numerics(N=N, integrate=False, samples_per_period=m,
                                                  tail_tol=1e-5), guess=state.get("guess"))
            if not ss.converged:
                raise RuntimeError(f"no periodic orbit: {ss.message}")
            state["guess"] = ss.periodic.theta.T
            return model.grid, ss.theta, ss.tau
        X, ok, tail = periodic_orbit(model_eff, model, guess=state.get("guess"))
        if not ok or tail > 1e-4:
            X, ok, tail = periodic_orbit(model_eff, model)
        if not ok:
            raise RuntimeError("no periodic orbit of the printed model")
        state["guess"] = X
        return model.grid, trig_interpolate(X, m).T, np.arange(m) / m * P
    n = model.n
    method = h.method
    if method == "TRBDF2":
        from .trbdf2 import TRBDF2 as method

    def jac(tau, z):
        return model.first_order_jacobian(z[:n], z[n:], model_eff.lam(tau), model_eff.lam_dot(tau))

    rhs = first_order_rhs(model, model_eff, math.inf)
    if h.dynamics in ("steps", "steps_rest"):  # the integrator's own steps are the samples
        if h.dynamics == "steps":
            ss = steady_state(model_eff, Numerics(N=N, integrate=False, tail_tol=1e-5),
                              guess=state.get("guess"))
            state["guess"] = ss.periodic.theta.T
            z0 = np.concatenate([ss.periodic.theta[:, 0], ss.periodic.theta_t[:, 0]])
            t_end, keep = h.step_periods * P, (h.step_periods - 2) * P
        else:
            z0 = np.zeros(2 * n)
            t_end = math.ceil(h.t_end_tau / P) * P
            keep = t_end - P
        sol = solve_ivp(rhs, (0.0, t_end), z0, method=method, rtol=h.rtol, atol=h.atol, jac=jac)
        if not sol.success:
            raise RuntimeError(f"time stepping failed: {sol.message}")
        sel = sol.t >= keep - 1e-12 * P
        if sol.t[sel][-1] >= t_end - 1e-12 * P:  # [keep, t_end): one end of a whole period
            sel &= sol.t < t_end - 1e-12 * P
        state["steps"] = int(sel.sum())
        return model.grid, sol.y[:n, sel], sol.t[sel]
    # time stepping from rest
    kind, value = h.window
    T = state["beam"].T
    if kind == "periods":
        t_end = value * P
    elif kind == "seconds":
        t_end = value / T
    else:
        t_end = max(h.t_end_tau, value * P)
        t_end = math.ceil(t_end / P) * P
    k = max(1, int(round(t_end / P * m)))
    if kind == "last":
        taus = t_end - value * P + np.arange(value * m) / m * P
    else:
        taus = np.arange(k) / k * t_end  # uniform over [0, T_end)
    sol = solve_ivp(rhs, (0.0, t_end), np.zeros(2 * n), method=method, rtol=h.rtol,
                    atol=h.atol, jac=jac, t_eval=taus)
    if not sol.success:
        raise RuntimeError(f"time stepping failed: {sol.message}")
    return model.grid, sol.y[:n], taus


def scene_delta(h: Hypothesis | str, beam: Beam, omega0: float, f_d: float,
                numerics: Numerics | None = None, state: dict | None = None) -> dict:
    """RMS_dyn, RMS_QS and Delta RMS of one scene under hypothesis h."""
    h = hypothesis(h)
    num = numerics or Numerics(N=40)
    state = {} if state is None else state
    beam = _beam_for(beam, h)
    state["beam"] = beam
    N = h.N or num.N
    m = 32
    dl = Dimensionless.from_physical(beam, Drive(omega0=omega0, amplitude=1.0, f_d=f_d), Effects())
    grid, theta, taus = _dynamic(replace(h), dl, h.N_dyn or N, m, state)
    s_dyn = h.s_dyn if h.s_dyn is not None else (grid.N // 2 - 1) / grid.N
    y_dyn = midspan_measure(grid, theta, s_dyn, h.measure, dl, taus)
    if h.dynamics in ("steps", "steps_rest"):  # QS on a uniform grid of one period
        taus = np.arange(m) / m * dl.period
    if h.qs == "discrete":
        model = DiscreteElastica(N, dl.hub_ratio, dl.eta, dl.effects)
        th_qs = quasistatic_series(model, dl, taus)
        y_qs = midspan_measure(model.grid, th_qs, 0.5, h.measure, dl, taus)
    else:
        (g1, t1), (g2, t2) = continuum_quasistatic_theta(dl, taus)
        y1 = midspan_measure(g1, t1, 0.5, h.measure, dl, taus)
        y2 = midspan_measure(g2, t2, 0.5, h.measure, dl, taus)
        y_qs = (4.0 * y2 - y1) / 3.0
    r_dyn, r_qs = _rms(y_dyn, h.mean), h.qs_scale * _rms(y_qs, h.mean)
    den = r_dyn if h.denominator == "dyn" else r_qs
    return {"rms_dynamic": r_dyn, "rms_quasistatic": r_qs, "delta_rms": abs(r_dyn - r_qs) / den,
            "f_d": f_d, "omega0": omega0, "samples": int(np.size(y_dyn))}


def f0_for(h: Hypothesis, beam: Beam, omega0: float, numerics: Numerics,
           state: dict | None = None) -> float:
    """f_0 [Hz] on one line as the hypothesis defines it."""
    a = 1.0
    if h.f0 == "linear_max":
        return resonance_frequency_hz(beam, omega0, a)
    if h.f0 == "linear_mean":
        return float(natural_frequencies_hz(beam, abs(omega0), 1, 80)[0])
    if h.f0 == "southwell_flap":
        return southwell_frequency_hz(beam, abs(omega0) + a, softening=False)
    if h.f0 == "southwell_inplane":
        return southwell_frequency_hz(beam, abs(omega0) + a, softening=True)
    if h.f0 == "fn_printed":
        f0 = resonance_frequency_hz(beam, omega0, a)
        return math.sqrt(f0 * f0 - beam.f_n**2 + F_N_PRINTED**2)
    if h.f0 == "peak":
        f_lin = resonance_frequency_hz(beam, omega0, a)
        fs = f_lin * np.linspace(0.9, 1.15, 11)
        st: dict = {}
        r = [scene_delta(Hypothesis(), beam, omega0, f, numerics, st)["rms_dynamic"] for f in fs]
        j = int(np.argmax(r))
        j = min(max(j, 1), len(fs) - 2)
        fine = np.linspace(fs[j - 1], fs[j + 1], 401)
        return float(fine[np.argmax(PchipInterpolator(fs, r)(fine))])
    raise ValueError(f"unknown f0 definition {h.f0!r}")


def line_scan(h: Hypothesis | str, beam: Beam, c_max: float, numerics: Numerics | None = None,
              lo: float = 0.15, hi: float = 0.5, points: int = 15) -> dict:
    """Delta RMS on f_d = f_0 linspace(lo, hi, points) (f_0 ours) at Omega_0 for C_max."""
    h = hypothesis(h)
    num = numerics or Numerics(N=40)
    omega0 = omega0_for_cmax(beam, c_max)
    f_ref = resonance_frequency_hz(beam, omega0)
    fds = f_ref * np.linspace(lo, hi, points)
    state: dict = {}
    rows = [scene_delta(h, beam, omega0, float(f), num, state) for f in fds]
    return {"c_max": c_max, "omega0": omega0, "f_ref": f_ref, "f_d": fds,
            "delta": np.array([r["delta_rms"] for r in rows]),
            "rms_dynamic": np.array([r["rms_dynamic"] for r in rows]),
            "rms_quasistatic": np.array([r["rms_quasistatic"] for r in rows]),
            "f0": f0_for(h, _beam_for(beam, h), omega0, num)}


def c_for_hypothesis(name: str | Hypothesis, beam: Beam | None = None,
                     c_max_lines: Sequence[float] = (1.0,),
                     thresholds: Iterable[float] = THRESHOLDS,
                     numerics: Numerics | None = None, lo: float = 0.15, hi: float = 0.5,
                     points: int = 15) -> dict:
    """c = f_d*/f_0 per threshold for a named hypothesis: f_d* the PCHIP root of Delta RMS on
    each line, c the least-squares slope of f_d* = c f_0 over the lines (as boundary.fit_c).

    Returns {"c": {threshold: c}, "per_line": {threshold: [c per line]}, "notes": [...],
    "lines": [line scans]}; a threshold not reached from below on a line (Delta RMS already
    above it at the lowest scanned f_d, or never reached) gives NaN there, with a note.
    """
    beam = beam or Beam()
    h = hypothesis(name)
    thresholds = [float(t) for t in thresholds]
    lines = [line_scan(h, beam, cm, numerics, lo, hi, points) for cm in c_max_lines]
    out: dict = {"name": name if isinstance(name, str) else h.description,
                 "description": h.description, "c": {}, "per_line": {}, "notes": [],
                 "lines": lines}
    for th in thresholds:
        f0s, fds, per = [], [], []
        for ln in lines:
            cr = critical_from_scan(ln["f_d"], ln["delta"], th)
            root = cr["f_d_root"]
            if not (cr["found"] and math.isfinite(root)):
                out["notes"].append(f"C_max {ln['c_max']:g}, threshold {th:g}: {cr.get('message')}"
                                    f" (Delta RMS at f_d = {lo:g} f_0: {ln['delta'][0]:.3g})")
                per.append(math.nan)
                continue
            f0s.append(ln["f0"])
            fds.append(root)
            per.append(root / ln["f0"])
        f0s, fds = np.array(f0s), np.array(fds)
        out["c"][th] = float(f0s @ fds / (f0s @ f0s)) if f0s.size else math.nan
        out["per_line"][th] = per
    return out
