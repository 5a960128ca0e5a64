r"""Candidate mechanisms for the paper's critical-frequency constant c (docs/c_hypotheses.md).

Ours: c = f_d*/f_0 = 0.229, 0.271, 0.323, 0.354 for Delta RMS thresholds 0.05, 0.07, 0.10, 0.12;
the paper: 0.311, 0.345, 0.385, 0.404 (+- 0.001).  Each named hypothesis changes one thing in how
RMS_dyn, RMS_QS, Delta RMS or f_0 are obtained (what the paper's pipeline might have done), and
`c_for_hypothesis` returns the c it gives for every threshold at once.  `grid_c` then applies the
paper's first-grid-point rule on a coarse scan to the same lines, and `study_table` writes the
long table (hypothesis, threshold, c, c_err) the workflow rule `c_hypotheses` produces.

A hypothesis is a set of options (`Hypothesis`):

* ``model``: the dynamic model, ours or `rotbeam.paper.printed_model.PrintedElastica` with
  printed misprints (dynamic only: the paper's quasi-static answer came from bvp4c).
* ``qs``: quasi-static response from the same discrete model ("discrete") or from the continuum
  ("continuum": Richardson limit of the discrete static problem on N = 80 and 160, which agrees
  with `rotbeam.solve.static_bvp.solve_static_bvp` to 1e-5 relative; tested).
* ``s_dyn``/``N_dyn``: where and on which grid the dynamic y_m is read (QS always at s = 1/2;
  s_dyn None: node N/2 counted from the clamp as node 1, s = (N/2 - 1)/N).
* ``measure``: "y" (rotating frame), "lab" (the drive's rigid oscillation added: a frame turning
  uniformly at Omega_0), "chord" (deflection normal to the clamp-tip chord).
* ``dynamics``: "periodic" (the steady orbit by collocation), "steps" / "steps_rest" (RMS over
  the integrator's own output steps, from the orbit or from rest) or "rest" (time stepping from
  rest) with ``window`` (("periods", 10), ("seconds", 5.0), or ("last", 1): the last period of a
  run of ``t_end_tau``) and ``method``/``rtol``/``atol`` (e.g. TR-BDF2 at MATLAB's 1e-3 / 1e-6).
* ``f0``: "linear_max" (ours: linearised in-plane frequency at Omega_0 + a), "linear_mean"
  (at Omega_0), "southwell_flap" / "southwell_inplane" (Eq. Southwell with S_1 flapwise /
  in-plane), "fn_printed" (ours shifted to f_n = 6.37 Hz), "peak" (peak of the dynamic RMS scan).
* ``zeta``: damping ratio (None: the beam's gamma, zeta = 0.0203).
* ``denominator``: "dyn" (Eq. Delta_RMS) or "qs"; ``mean``: "keep" or "remove"; ``qs_scale``:
  RMS_QS multiplied by this (the size of bias that would explain the paper, for calibration).
* ``coriolis_ny``: the printed +2 I y_t of the n_y integrand with Coriolis on; for small angles
  an extra damping 2 lam W Theta_t, modelled as eta -> eta + 2 lam0.

Only public functions of rotbeam are used; everything here is downstream of the model.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd
from scipy.interpolate import PchipInterpolator

from ..config.checks import check_positive, check_threshold
from ..config.errors import RotbeamInputError
from ..model.criterion import critical_from_scan, rms
from ..model.modes import modes, resonance_frequency_hz
from ..model.params import Beam, Dimensionless, Drive, Effects, omega0_for_cmax
from ..model.surrogate import southwell_frequency_hz
from .c_response import dynamic_response, hypothesis_quasistatic_midspan, midspan_measure
from .printed import printed_per_threshold, read_claims

THRESHOLDS = (0.05, 0.07, 0.10, 0.12)
_CLAIMS = read_claims()[1]
PAPER_C = printed_per_threshold(_CLAIMS, "c_")  #: App. D: threshold -> printed c
PAPER_C_ERR = float(_CLAIMS.loc[_CLAIMS["id"] == "c_0.10", "tolerance"].iloc[0])  #: its +-
F_N_PRINTED = 6.37  #: Hz, Sec. 5
QS_SCALE = "qs_scale_"  #: prefix of the calibration hypotheses, e.g. qs_scale_1.05


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
    "continuum_qs": Hypothesis(
        "discrete dynamic model N beside a continuum quasi-static answer", qs="continuum"
    ),
    "printed_bracket": Hypothesis(
        _PRINTED.format("the tension bracket"), model=("bracket",), qs="continuum"
    ),
    "printed_U3": Hypothesis(
        _PRINTED.format("the last column of 3s in U"), model=("U3",), qs="continuum"
    ),
    "printed_symS": Hypothesis(
        _PRINTED.format("the symmetric S~"), model=("symS",), qs="continuum"
    ),
    "printed_Kds": Hypothesis(_PRINTED.format("K with 1/ds"), model=("Kds",), qs="continuum"),
    "printed_U3_symS": Hypothesis(
        _PRINTED.format("U3 and symmetric S~ (the plausible slips)"),
        model=("U3", "symS"),
        qs="continuum",
    ),
    "printed_all_but_K": Hypothesis(
        _PRINTED.format("bracket, U3, symmetric S~"),
        model=("bracket", "U3", "symS"),
        qs="continuum",
    ),
    "printed_ny_coriolis": Hypothesis(
        "Coriolis on with the printed +2 I y_t of n_y (extra damping 2 lam0), QS continuum",
        qs="continuum",
        coriolis_ny=True,
    ),
    "ym_node_matlab": Hypothesis(
        "dynamic y_m at node N/2 counted from the clamp as node 1 (s = (N/2 - 1)/N), QS at s = 1/2",
        s_dyn=None,
        qs="continuum",
    ),
    "ym_39_intervals": Hypothesis(
        "'N = 40 nodes' as 39 intervals, dynamic y_m at node 20 from "
        "the clamp as node 1 (s = 19/39), QS at s = 1/2",
        s_dyn=19 / 39,
        N_dyn=39,
        qs="continuum",
    ),
    "ym_lab_frame": Hypothesis(
        "y_m in a frame turning uniformly at Omega_0 (the drive's "
        "rigid oscillation included), dynamic and QS",
        measure="lab",
    ),
    "ym_normal_to_chord": Hypothesis(
        "midspan deflection normal to the clamp-tip chord", measure="chord"
    ),
    "rest_10_periods": Hypothesis(
        "from rest, RMS over the first 10 drive periods", dynamics="rest", window=("periods", 10)
    ),
    "rest_20_periods": Hypothesis(
        "from rest, RMS over the first 20 drive periods", dynamics="rest", window=("periods", 20)
    ),
    "rest_5_s": Hypothesis(
        "from rest, RMS over the first 5 s", dynamics="rest", window=("seconds", 5.0)
    ),
    "rest_10_s": Hypothesis(
        "from rest, RMS over the first 10 s", dynamics="rest", window=("seconds", 10.0)
    ),
    "f0_linear_mean": Hypothesis("f_0 linear at Omega_0 (not Omega_0 + a)", f0="linear_mean"),
    "f0_southwell_flap": Hypothesis(
        "f_0 by Eq. Southwell with the flapwise S_1", f0="southwell_flap"
    ),
    "f0_southwell_inplane": Hypothesis(
        "f_0 by Eq. Southwell with the in-plane S_1", f0="southwell_inplane"
    ),
    "f0_fn_printed": Hypothesis(
        "f_0 with f_n = 6.37 Hz (printed) in place of 6.52 Hz", f0="fn_printed"
    ),
    "f0_peak": Hypothesis("f_0 = peak of the dynamic RMS scan (nonlinear, a = 1)", f0="peak"),
    "zeta_0.017": Hypothesis("damping zeta = 0.017 (App. E) instead of 0.020", zeta=0.017),
    "mean_removed": Hypothesis("RMS of y_m with its mean removed", mean="remove"),
    "qs_denominator": Hypothesis("Delta RMS with RMS_QS in the denominator", denominator="qs"),
    "ode_steps_trbdf2_1e-3": Hypothesis(
        "RMS_dyn over the integrator's own output steps (ode23tb returns its steps, Refine 1), "
        "TR-BDF2 at rtol 1e-3, atol 1e-6, last 2 of 3 periods from the orbit; QS uniform",
        dynamics="steps",
        method="TRBDF2",
        rtol=1e-3,
        atol=1e-6,
        qs="continuum",
    ),
    "ode_steps_trbdf2_1e-4": Hypothesis(
        "as ode_steps_trbdf2_1e-3 at rtol 1e-4",
        dynamics="steps",
        method="TRBDF2",
        rtol=1e-4,
        atol=1e-6,
        qs="continuum",
    ),
    "ode_steps_trbdf2_1e-3_from_rest": Hypothesis(
        "RMS_dyn over TR-BDF2's own steps (rtol 1e-3, atol 1e-6) over the last period of a run "
        "from rest of 2 ln(1000)/eta; QS uniform",
        dynamics="steps_rest",
        method="TRBDF2",
        rtol=1e-3,
        atol=1e-6,
        qs="continuum",
        t_end_tau=2 * math.log(1000.0) / Beam().eta,
    ),
    "trbdf2_loose": Hypothesis(
        "TR-BDF2 (ode23tb's method) from rest at rtol 1e-3, atol 1e-6, "
        "RMS over the last period of 2 ln(1000)/eta",
        dynamics="rest",
        method="TRBDF2",
        rtol=1e-3,
        atol=1e-6,
        window=("last", 1),
        t_end_tau=2 * math.log(1000.0) / Beam().eta,
    ),
}


def hypothesis(name: str | Hypothesis) -> Hypothesis:
    """The named hypothesis; ``qs_scale_<k>`` is the calibration RMS_QS x k."""
    if isinstance(name, Hypothesis):
        return name
    if name.startswith(QS_SCALE):
        try:
            k = check_positive(name, float(name[len(QS_SCALE) :]))
        except ValueError:
            raise RotbeamInputError(
                f"hypothesis {name!r}: {QS_SCALE}<k> needs a number k > 0, e.g. {QS_SCALE}1.05"
            ) from None
        return Hypothesis(f"RMS_QS multiplied by {k:g}", qs_scale=k)
    if name not in HYPOTHESES:
        raise RotbeamInputError(
            f"hypothesis {name!r}: unknown; allowed: {', '.join(HYPOTHESES)} or {QS_SCALE}<k>"
        )
    return HYPOTHESES[name]


@dataclass(frozen=True)
class ScanSpec:
    """The lines a hypothesis is run on: f_d = f_0 linspace(lo, hi, points) (f_0 ours) at the
    Omega_0 of each C_max, grid N, `samples` per period, velocity amplitude a."""

    c_max: tuple[float, ...] = (1.0,)
    N: int = 40
    lo: float = 0.15
    hi: float = 0.5
    points: int = 15
    samples: int = 32
    amplitude: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "c_max", tuple(float(c) for c in self.c_max))
        if not self.c_max:
            raise RotbeamInputError("c_max = []: needs at least one C_max line")
        for c in self.c_max:
            check_positive("c_max", c)
        for name, lo, hi in (("N", 4, 2000), ("points", 3, 1000), ("samples", 8, 4096)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
                raise RotbeamInputError(f"{name} = {v!r}: must be an integer in [{lo}, {hi}]")
        check_positive("amplitude", self.amplitude)
        if not 0 < check_positive("lo", self.lo) < check_positive("hi", self.hi) <= 3:
            raise RotbeamInputError(
                f"lo = {self.lo!r}, hi = {self.hi!r}: must be 0 < lo < hi <= 3 (fractions of f_0)"
            )


@dataclass(frozen=True)
class GridRule:
    """The paper's first-grid-point rule on a coarse scan: f_d* is the first point of the scan
    f_d = k step (unit "Hz") or f_d = k step f_0 (unit "f0", f_0 ours), k = 1, 2, ..., at or
    above the line's Delta RMS root."""

    step: float
    unit: str = "Hz"

    def __post_init__(self) -> None:
        check_positive("grid step", self.step)
        if self.unit not in ("Hz", "f0"):
            raise RotbeamInputError(f"grid unit = {self.unit!r}: must be 'Hz' or 'f0'")

    @property
    def label(self) -> str:
        return f"grid_{self.step:g}{self.unit}"

    def point_above(self, root_hz: float, f_ref: float) -> float:
        """The first grid point >= root_hz."""
        h = self.step if self.unit == "Hz" else self.step * f_ref
        return math.ceil(root_hz / h - 1e-9) * h


# --- one scene, one line ---------------------------------------------------------------------
def _beam_for(beam: Beam, h: Hypothesis) -> Beam:
    if h.zeta is None:
        return beam
    return replace(beam, gamma=beam.gamma * h.zeta / beam.zeta)


def _rms(y: np.ndarray, mean: str) -> float:
    """RMS of y (Eq. RMS), with its mean removed first when `mean` is "remove"."""
    y = np.asarray(y, float)
    return rms(y - y.mean() if mean == "remove" else y)


def scene_delta(
    h: Hypothesis | str,
    beam: Beam,
    omega0: float,
    f_d: float,
    scan: ScanSpec = ScanSpec(),
    state: dict | None = None,
) -> dict:
    """RMS_dyn, RMS_QS and Delta RMS of one scene under hypothesis h (`state` carries the orbit
    from one f_d to the next along a line)."""
    h = hypothesis(h)
    state = {} if state is None else state
    beam = _beam_for(beam, h)
    N, m = h.N or scan.N, scan.samples
    drive = Drive(omega0=omega0, amplitude=scan.amplitude, f_d=f_d)
    dl = Dimensionless.from_physical(beam, drive, Effects())
    grid, theta, taus = dynamic_response(h, dl, h.N_dyn or N, m, state, beam.T)
    s_dyn = h.s_dyn if h.s_dyn is not None else (grid.N // 2 - 1) / grid.N
    y_dyn = midspan_measure(grid, theta, s_dyn, h.measure, dl, taus)
    if h.dynamics in ("steps", "steps_rest"):  # QS on a uniform grid of one period
        taus = np.arange(m) / m * dl.period
    y_qs = hypothesis_quasistatic_midspan(h, dl, N, taus)
    r_dyn, r_qs = _rms(y_dyn, h.mean), h.qs_scale * _rms(y_qs, h.mean)
    den = r_dyn if h.denominator == "dyn" else r_qs
    return {"rms_dynamic": r_dyn, "rms_quasistatic": r_qs, "delta_rms": abs(r_dyn - r_qs) / den,
            "f_d": f_d, "omega0": omega0, "samples": int(np.size(y_dyn))}  # fmt: skip


def _peak_frequency_hz(beam: Beam, omega0: float, scan: ScanSpec) -> float:
    """Peak of our dynamic RMS on f_lin [0.9, 1.15] (11 points, PCHIP on 401)."""
    f_lin = resonance_frequency_hz(beam, omega0, scan.amplitude)
    fs = f_lin * np.linspace(0.9, 1.15, 11)
    st: dict = {}
    r = [scene_delta(Hypothesis(), beam, omega0, f, scan, st)["rms_dynamic"] for f in fs]
    j = min(max(int(np.argmax(r)), 1), len(fs) - 2)
    fine = np.linspace(fs[j - 1], fs[j + 1], 401)
    return float(fine[np.argmax(PchipInterpolator(fs, r)(fine))])


def f0_for(h: Hypothesis, beam: Beam, omega0: float, scan: ScanSpec = ScanSpec()) -> float:
    """f_0 [Hz] on one line as the hypothesis defines it."""
    a = scan.amplitude
    if h.f0 == "linear_max":
        return resonance_frequency_hz(beam, omega0, a)
    if h.f0 == "linear_mean":
        return float(modes(beam, abs(omega0), 1, 80)[0])
    if h.f0 in ("southwell_flap", "southwell_inplane"):
        return southwell_frequency_hz(beam, abs(omega0) + a, softening=h.f0 == "southwell_inplane")
    if h.f0 == "fn_printed":
        f0 = resonance_frequency_hz(beam, omega0, a)
        return math.sqrt(f0 * f0 - beam.f_n**2 + F_N_PRINTED**2)
    if h.f0 == "peak":
        return _peak_frequency_hz(beam, omega0, scan)
    raise RotbeamInputError(f"f0 = {h.f0!r}: unknown f_0 definition")


def line_scan(h: Hypothesis | str, beam: Beam, c_max: float, scan: ScanSpec = ScanSpec()) -> dict:
    """Delta RMS on f_d = f_0 linspace(lo, hi, points) (f_0 ours) at Omega_0 for C_max."""
    h = hypothesis(h)
    omega0 = omega0_for_cmax(beam, c_max, scan.amplitude)
    f_ref = resonance_frequency_hz(beam, omega0, scan.amplitude)
    fds = f_ref * np.linspace(scan.lo, scan.hi, scan.points)
    state: dict = {}
    rows = [scene_delta(h, beam, omega0, float(f), scan, state) for f in fds]
    return {"c_max": c_max, "omega0": omega0, "f_ref": f_ref, "f_d": fds,
            "delta": np.array([r["delta_rms"] for r in rows]),
            "rms_dynamic": np.array([r["rms_dynamic"] for r in rows]),
            "rms_quasistatic": np.array([r["rms_quasistatic"] for r in rows]),
            "f0": f0_for(h, _beam_for(beam, h), omega0, scan)}  # fmt: skip


# --- c over the lines ------------------------------------------------------------------------
def slope_fit(f0: Sequence[float], fd: Sequence[float]) -> tuple[float, float]:
    """Least-squares slope c of fd = c f0 through the origin and its standard error (as
    `boundary.fit_c`; NaN error with fewer than 2 lines, NaN c with none)."""
    f0, fd = np.asarray(f0, float), np.asarray(fd, float)
    if f0.size == 0:
        return math.nan, math.nan
    c = float(f0 @ fd / (f0 @ f0))
    if f0.size < 2:
        return c, math.nan
    resid = fd - c * f0
    return c, float(math.sqrt(resid @ resid / (f0.size - 1) / (f0 @ f0)))


def line_roots(lines: Sequence[dict], threshold: float, lo: float) -> tuple[list[dict], list[str]]:
    """The PCHIP root f_d* of each line for one threshold (lines without one give a note)."""
    roots, notes = [], []
    for ln in lines:
        cr = critical_from_scan(ln["f_d"], ln["delta"], threshold)
        if cr["found"] and math.isfinite(cr["f_d_root"]):
            roots.append({"c_max": ln["c_max"], "root": cr["f_d_root"], "f0": ln["f0"],
                          "f_ref": ln["f_ref"]})  # fmt: skip
        else:
            notes.append(f"C_max {ln['c_max']:g}, threshold {threshold:g}: {cr.get('message')} "
                         f"(Delta RMS at f_d = {lo:g} f_0: {ln['delta'][0]:.3g})")  # fmt: skip
    return roots, notes


def c_for_hypothesis(
    name: str | Hypothesis,
    beam: Beam | None = None,
    scan: ScanSpec = ScanSpec(),
    thresholds: Iterable[float] = THRESHOLDS,
) -> dict:
    """c = f_d*/f_0 per threshold for a named hypothesis: f_d* the PCHIP root of Delta RMS on
    each line, c the least-squares slope of f_d* = c f_0 over the lines.

    Returns {"c", "c_err", "per_line": {threshold: [c per line]}, "roots": {threshold: [...]},
    "notes", "lines"}; a threshold not reached from below on a line (Delta RMS already above it at
    the lowest scanned f_d, or never reached) drops that line, with a note (NaN c with no line).
    """
    beam = beam or Beam()
    h = hypothesis(name)
    thresholds = [check_threshold(t) for t in thresholds]
    lines = [line_scan(h, beam, cm, scan) for cm in scan.c_max]
    out: dict = {"name": name if isinstance(name, str) else h.description,
                 "description": h.description, "c": {}, "c_err": {}, "per_line": {},
                 "roots": {}, "notes": [], "lines": lines}  # fmt: skip
    for th in thresholds:
        roots, notes = line_roots(lines, th, scan.lo)
        out["notes"] += notes
        out["roots"][th] = roots
        out["c"][th], out["c_err"][th] = slope_fit([r["f0"] for r in roots],
                                                   [r["root"] for r in roots])  # fmt: skip
        found = {r["c_max"]: r["root"] / r["f0"] for r in roots}
        out["per_line"][th] = [found.get(ln["c_max"], math.nan) for ln in lines]
    return out


def grid_c(result: dict, rule: GridRule) -> dict[float, tuple[float, float]]:
    """{threshold: (c, c_err)} of a `c_for_hypothesis` result under the first-grid-point rule.

    The first grid point at or above the PCHIP root is the first with Delta RMS >= threshold on
    the interpolant (PCHIP does not overshoot its data, and every scanned point below the root's
    bracket is below the threshold); grid points below the scan's lo are taken as below it too.
    """
    out = {}
    for th, roots in result["roots"].items():
        fds = [rule.point_above(r["root"], r["f_ref"]) for r in roots]
        out[th] = slope_fit([r["f0"] for r in roots], fds)
    return out


# --- the study's table -----------------------------------------------------------------------
def _rows(name: str, description: str, fits: dict, result: dict) -> list[dict]:
    """One row per threshold; `fits` {threshold: (c, c_err)}, lines_used from `result`."""
    return [
        {"hypothesis": name, "threshold": th, "c": c, "c_err": err,
         "c_paper": PAPER_C.get(round(th, 4), math.nan),
         "lines_used": len(result["roots"][th]), "description": description}
        for th, (c, err) in fits.items()
    ]  # fmt: skip


def _grid_description(description: str, rule: GridRule) -> str:
    unit = "Hz" if rule.unit == "Hz" else "f_0"
    return f"{description}; f_d* the first scan point f_d = k {rule.step:g} {unit} above the root"


def study_table(
    names: Sequence[str],
    beam: Beam,
    scan: ScanSpec,
    thresholds: Iterable[float] = THRESHOLDS,
    grid_rules: Sequence[GridRule] = (),
    grid_hypotheses: Sequence[str] = (),
    log: Callable[[str], None] = lambda msg: None,
) -> pd.DataFrame:
    """Long table (hypothesis, threshold, c, c_err, c_paper, lines_used, description) of every
    named hypothesis, and of each of `grid_hypotheses` under each grid rule (named
    "<hypothesis>+grid_<step><unit>").  lines_used: the lines with a root at that threshold."""
    thresholds = [check_threshold(t) for t in thresholds]
    todo = list(dict.fromkeys([*names, *grid_hypotheses]))
    for name in todo:
        hypothesis(name)  # every name checked before the first simulation
    results = {}
    for name in todo:
        results[name] = r = c_for_hypothesis(name, beam, scan, thresholds)
        cs = ", ".join(f"{c:.4f}" for c in r["c"].values())
        log(f"{name}: c = {cs}" + (f"; {'; '.join(r['notes'])}" if r["notes"] else ""))
    rows = []
    for name in names:
        r = results[name]
        rows += _rows(name, r["description"], {t: (r["c"][t], r["c_err"][t]) for t in r["c"]}, r)
    for name in grid_hypotheses:
        r = results[name]
        for rule in grid_rules:
            desc = _grid_description(r["description"], rule)
            rows += _rows(f"{name}+{rule.label}", desc, grid_c(r, rule), r)
    return pd.DataFrame(rows)


@dataclass(frozen=True)
class Study:
    """The workflow's study: hypotheses on the lines of `scan`, and `grid_hypotheses` under each
    of `grid_rules` (config section ``c_hypotheses``)."""

    hypotheses: tuple[str, ...]
    scan: ScanSpec = ScanSpec()
    thresholds: tuple[float, ...] = THRESHOLDS
    grid_rules: tuple[GridRule, ...] = ()
    grid_hypotheses: tuple[str, ...] = ()

    def run(self, beam: Beam, log: Callable[[str], None] = lambda msg: None) -> pd.DataFrame:
        return study_table(self.hypotheses, beam, self.scan, self.thresholds, self.grid_rules,
                           self.grid_hypotheses, log)  # fmt: skip

    def describe(self) -> str:
        s = self.scan
        lines = ", ".join(f"{c:g}" for c in s.c_max)
        return (f"C_max = {lines}; N = {s.N}; f_d = f_0 linspace({s.lo:g}, {s.hi:g}, {s.points}),"
                f" {s.samples} samples per period; a = {s.amplitude:g} rad/s")  # fmt: skip


def study_from_config(section: dict, amplitude: float = 1.0) -> Study:
    """A `Study` from the workflow config's ``c_hypotheses`` section (and its amplitude)."""
    scan = ScanSpec(c_max=tuple(section["c_max"]), N=int(section["N"]), lo=section["lo"],
                    hi=section["hi"], points=int(section["points"]),
                    samples=int(section.get("samples", 32)), amplitude=amplitude)  # fmt: skip
    grid = section.get("grid", {})
    rules = [GridRule(float(s), "Hz") for s in grid.get("step_hz", [])]
    rules += [GridRule(float(s), "f0") for s in grid.get("step_f0", [])]
    return Study(tuple(section["hypotheses"]), scan,
                 tuple(float(t) for t in section.get("thresholds", THRESHOLDS)), tuple(rules),
                 tuple(grid.get("hypotheses", [])))  # fmt: skip
