"""Time stepping of the discrete model to its periodic steady state.

Contract (in the spirit of scipy.integrate): `steady_state` never raises for a solver failure; it
returns a `SteadyState` whose `converged` says whether a steady state was reached, `status` and
`message` say why not, and the samples are what the integration actually saw.

Steady-state criterion.  Every mode of the linearised model decays as exp(-eta tau / 2) (the
damping matrix is eta M, mass-proportional).  Let Z_k be the state after k drive periods P and
d_k = |Z_k - Z_{k-1}| (max-norm, velocities divided by max(omega, 1)).  For a decaying transient
the distance still to go obeys |Z_k - Z_inf| <= d_k rho / (1 - rho) with rho = exp(-eta P / 2).
We stop when that bound is below `ss_tol` times the size of the response (max |Theta| over the
last period).  The RMS samples are the last `rms_periods` periods integrated if even their first
instant is within ss_tol of the steady state (always so from the periodic start), else
`rms_periods` more periods are integrated and sampled uniformly.
From a converged collocated orbit (start="periodic") the first period is a check: the stepper
runs at the tolerance the bound needs (ss_tol (1 - rho) / (3 rho), not `rtol`) and, when the
orbit passes, its own samples are reported (spectrally accurate; the stepper's would carry the
stepper's error).  An orbit that fails is left behind: the transient is followed at `rtol`.
A single period cannot expose a slowly growing instability (its multiplier would have to exceed
1 / rho to show), so the orbit's Floquet multipliers are computed first (`rotbeam.solve.stability`):
an unstable orbit is left along its unstable direction and time stepping decides; the reported
steady state carries the multipliers of the orbit it is (docs/stability.md).
Without damping no steady state is reached: we say so and return the last periods seen.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..model.elastica import DiscreteElastica
from ..model.modes import dimensionless_frequencies, linear_forced_response
from ..model.params import Dimensionless
from ..model.quasistatic import quasistatic_series
from .floquet import FloquetResult
from .numerics import Numerics
from .periodic import PeriodicResult, solve_periodic_adaptive
from .spectral import trig_interpolate
from .stability import (
    STATUS_UNSTABLE,
    leave_orbit,
    orbit_stability,
    stability_note,
    window_stability,
)


class OutOfTime(Exception):
    """Raised inside the right-hand side when the wall-time budget is spent."""


@dataclass
class SteadyState:
    """Result of `steady_state`: samples over the RMS window and how we got there."""

    tau: np.ndarray  #: sample instants (whole periods, endpoint excluded)
    theta: np.ndarray  #: (N-1, m) angles at the samples
    y_m: np.ndarray  #: midspan deflection at the samples
    converged: bool
    status: int  #: 0 steady, 1 no steady state within budget, 2 only an unstable orbit, -1 failure
    message: str
    periods: int  #: drive periods integrated in all
    transient: float  #: last bound on the remaining relative transient
    nfev: int = 0
    njev: int = 0
    seconds: float = 0.0
    history: list[float] = field(default_factory=list)  #: transient bound per period
    periodic: PeriodicResult | None = None  #: the collocation result, if one was made
    floquet: FloquetResult | None = None  #: multipliers of the reported orbit (else: collocated)


def period_samples(dl: Dimensionless, k0: int, periods: int, m: int) -> np.ndarray:
    P = dl.period
    return (k0 + np.arange(periods * m) / m) * P


def initial_state(
    model: DiscreteElastica,
    dl: Dimensionless,
    start: str,
    tail_tol: float = 1e-3,
    guess: np.ndarray | None = None,
) -> tuple[np.ndarray, PeriodicResult | None]:
    """Initial state (Theta, Theta_t) at tau = 0, and the collocation result if one was made."""
    n = model.n
    if start == "rest":
        return np.zeros(2 * n), None
    if start == "periodic":
        res = solve_periodic_adaptive(dl, model.grid.N, tail_tol=tail_tol, guess=guess)
        if res.converged:
            return np.concatenate([res.theta[:, 0], res.theta_t[:, 0]]), res
        start = "quasistatic"  # fall back to a physical state; the time stepping still decides
    if start == "linear":
        amp, _ = linear_forced_response(dl, model.grid.N)
        return np.concatenate([amp.real, -dl.omega * amp.imag]), None
    h = dl.period * 1e-4
    th = quasistatic_series(model, dl, np.array([-h, 0.0, h]))
    return np.concatenate([th[:, 1], (th[:, 2] - th[:, 0]) / (2 * h)]), None


def slowest_decay_rate(model: DiscreteElastica, dl: Dimensionless) -> float:
    """Slowest decay rate of the linearised transient, per unit tau.

    The damping is mass-proportional (eta M), so a mode of undamped frequency w decays as
    exp(-eta tau / 2) when underdamped (w > eta / 2) and, overdamped, as exp(-r tau) with
    r = eta / 2 - sqrt(eta^2 / 4 - w^2) ~ w^2 / eta: slower.  The first mode at the lowest
    rotation of the cycle is the slowest (stiffening only raises w).
    """
    eta = model.eta
    if eta == 0.0:
        return 0.0
    ef = model.effects
    lam_min = max(0.0, abs(dl.lam0) - abs(dl.alpha)) if ef.centrifugal else 0.0
    w1 = float(dimensionless_frequencies(lam_min, dl.hub_ratio, 1, model.grid.N, ef.softening)[0])
    half = eta / 2.0
    return half - math.sqrt(half * half - w1 * w1) if w1 < half else half


def first_order_rhs(
    model: DiscreteElastica, dl: Dimensionless, deadline: float
) -> Callable[[float, np.ndarray], np.ndarray]:
    """(Theta_t, Theta_tt) of the state z = (Theta, Theta_t); raises OutOfTime after `deadline`
    (a time.perf_counter value), so that solve_ivp stops inside a step."""
    n = model.n

    def rhs(tau: float, z: np.ndarray) -> np.ndarray:
        if time.perf_counter() > deadline:
            raise OutOfTime
        acc, _, _ = model.acceleration(z[:n], z[n:], dl.lam(tau), dl.lam_dot(tau))
        return np.concatenate([z[n:], acc])

    return rhs


def _from_collocation(
    model: DiscreteElastica, dl: Dimensionless, num: Numerics, res: PeriodicResult, t0: float
) -> SteadyState:
    """SteadyState straight from the collocation (no time stepping): `integrate=False`."""
    m = num.samples_per_period
    one = trig_interpolate(res.theta.T, m).T  # (n, m) over one period
    theta = np.tile(one, (1, num.rms_periods))
    taus = period_samples(dl, 0, num.rms_periods, m)
    fl = orbit_stability(model, dl, res)
    ok = res.converged and res.harmonic_tail <= num.tail_tol and model.eta > 0.0
    msg = f"collocation M={res.M}: {res.message}, harmonic tail {res.harmonic_tail:.2g}"
    msg += stability_note(fl)
    unstable = ok and fl is not None and not fl.stable
    if unstable:
        ok = False
        msg += " (not a steady state: the orbit is unstable)"
    elif model.eta == 0.0:
        msg += "; undamped model has no steady state (a periodic orbit, not an attractor)"
    elif not ok:
        msg += " (not verified: collocation did not meet its tolerance)"
    return SteadyState(
        tau=taus,
        theta=theta,
        y_m=np.atleast_1d(model.grid.midspan(theta)),
        converged=ok,
        status=0 if ok else (STATUS_UNSTABLE if unstable else 1),
        message=msg,
        periods=0,
        transient=res.harmonic_tail,
        seconds=time.perf_counter() - t0,
        periodic=res,
        floquet=fl,
    )


def steady_state(
    dl: Dimensionless,
    numerics: Numerics | None = None,
    progress: Callable[[int, float], None] | None = None,
    response_scale: float | None = None,
    guess: np.ndarray | None = None,
) -> SteadyState:
    """Integrate from `numerics.start` until the periodic steady state, then sample it.

    With numerics.integrate = False (and start = "periodic") the collocation result is returned
    as it is: fastest, but not checked by time stepping.  `guess` (M, N-1) seeds the collocation
    (continuation along a sweep).
    """
    num = numerics if numerics is not None else Numerics()
    t0 = time.perf_counter()
    model = DiscreteElastica(num.N, dl.hub_ratio, dl.eta, dl.effects)
    n = model.n
    P = dl.period
    m = num.samples_per_period
    z, periodic = initial_state(model, dl, num.start, num.tail_tol, guess)
    if not num.integrate and periodic is not None:
        return _from_collocation(model, dl, num, periodic, t0)

    # scale for absolute tolerances: the quasi-static response size if known, but never more
    # than a converged orbit's: an overdamped beam driven above its corner frequency moves far
    # less than quasi-statically (x140 for Fig. 7's E=1e5, L=0.1 mm), and an atol sized by the
    # quasi-static response then lets the stepper's error swamp the transient bound, which stalls
    # above ss_tol until max_tau
    scale = response_scale if response_scale else float(np.max(np.abs(z[:n])))
    if periodic is not None and periodic.converged:
        orbit = float(np.max(np.abs(periodic.theta)))
        scale = min(scale, orbit) if orbit > 0.0 and math.isfinite(orbit) else scale
    if not scale or not math.isfinite(scale):
        scale = abs(dl.alpha * dl.omega) * (dl.hub_ratio + 1.0) / 8.0 or 1.0
    wref = max(dl.omega, 1.0)
    orbit_fl = orbit_stability(model, dl, periodic)  # an unstable orbit is left, not verified
    unstable_orbit = orbit_fl is not None and not orbit_fl.stable
    if unstable_orbit:
        z = leave_orbit(z, orbit_fl, scale)
    rho = math.exp(-slowest_decay_rate(model, dl) * P)
    # the per-period integration error must stay below what the transient bound can tell apart
    rtol = min(num.rtol, 0.1 * num.ss_tol * (1.0 - rho)) if rho < 1.0 else num.rtol
    rtol = max(rtol, 1e-12)
    # From a converged collocated orbit the first period only has to confirm it: its difference
    # d passes when d rho / (1 - rho) <= ss_tol, so an integration error a third of that
    # threshold suffices, whatever `rtol` asks of a transient (the reported samples are then the
    # collocation's, accurate to its harmonic tail).  Should the check fail, the following
    # periods follow the transient at the tight `rtol` and their samples are reported.
    from_orbit = periodic is not None and periodic.converged and not unstable_orbit
    check = min(1e-2, num.ss_tol * (1.0 - rho) / (3.0 * rho)) if from_orbit and 0 < rho < 1 else 0.0
    rtol_first = max(rtol, check)

    def atol_for(r: float) -> np.ndarray:
        return np.concatenate([np.full(n, r * scale), np.full(n, r * scale * wref)])

    nfev = njev = 0

    deadline = t0 + num.max_seconds

    rhs = first_order_rhs(model, dl, deadline)

    def jac(tau, z):
        return model.first_order_jacobian(z[:n], z[n:], dl.lam(tau), dl.lam_dot(tau))

    method = num.method
    if method == "TRBDF2":
        from .trbdf2 import TRBDF2 as method

    def run(tau_a, tau_b, z_a, t_eval, r=rtol):
        """solve_ivp over [tau_a, tau_b]; None when the wall-time budget ran out."""
        nonlocal nfev, njev
        try:
            sol = solve_ivp(
                rhs, (tau_a, tau_b), z_a, method=method, rtol=r, atol=atol_for(r),
                jac=jac if num.jacobian == "exact" else None, t_eval=t_eval,
            )  # fmt: skip
        except OutOfTime:
            return None
        nfev += sol.nfev
        njev += sol.njev
        return sol

    def out_of_time(k: int) -> str:
        return (
            f"no steady state within the time budget of {num.max_seconds:g} s "
            f"({k} whole periods, tau={k * P:.4g}); remaining transient bound {bound:.3g}"
        )

    # from a converged collocated orbit one period measures its distance to the time-stepped
    # orbit; from any other start the first period's difference may be a lucky crossing
    min_periods = 1 if from_orbit else 2
    history: list[float] = []
    window: list[tuple[np.ndarray, np.ndarray]] = []  #: the last rms_periods periods seen
    reuse = False
    k = 0
    converged = False
    status, message = 1, ""
    bound = math.inf
    seen_tau, seen_theta = np.array([0.0]), z[:n, None].copy()  # what we saw last
    max_periods = min(num.max_periods, max(2, int(num.max_tau / P)))
    if model.eta == 0.0:  # no transient ever decays: show a few periods and say so
        max_periods = min(max_periods, max(2, num.rms_periods))
    while k < max_periods:
        taus_k = period_samples(dl, k, 1, m)
        sol = run(
            k * P, (k + 1) * P, z, np.append(taus_k, (k + 1) * P), rtol_first if k == 0 else rtol
        )
        if sol is None:
            message = out_of_time(k)
            break
        if sol.status < 0 or not np.all(np.isfinite(sol.y)):
            status, message = -1, f"integrator failed in period {k + 1}: {sol.message}"
            break
        seen_tau, seen_theta = sol.t[:-1], sol.y[:n, :-1]
        z_new = sol.y[:, -1]
        k += 1
        size = max(float(np.max(np.abs(sol.y[:n]))), 1e-300)
        d = max(
            float(np.max(np.abs(z_new[:n] - z[:n]))),
            float(np.max(np.abs(z_new[n:] - z[n:]))) / wref,
        )
        z = z_new
        if d == 0.0:
            bound = 0.0
        elif rho < 1.0:
            bound = d * rho / (1.0 - rho) / size
        else:
            bound = math.inf
        history.append(bound)
        if progress is not None:
            progress(k, bound)
        window.append((sol.t[:-1], sol.y[:n, :-1]))
        del window[: -num.rms_periods]
        if k >= min_periods and bound <= num.ss_tol:
            converged, status, message = True, 0, f"steady after {k} periods"
            # the periods just integrated serve as the RMS window when even their first sample
            # is within ss_tol of the steady state:
            # |Z_{k-p} - Z_inf| <= d (sum_{q<p} rho^-q + rho / (1 - rho))
            p = num.rms_periods
            if d == 0.0:  # an exact fixed point of the period map (also undamped: rho = 1)
                reach = 0.0
            elif rho > 0.0:  # bound <= ss_tol with d > 0 means rho < 1
                reach = sum(rho**-q for q in range(p)) + rho / (1.0 - rho)
            else:
                reach = math.inf
            reuse = k >= p and len(window) == p and d * reach / size <= num.ss_tol
            break
    else:
        message = (
            f"no steady state within {max_periods} periods (tau={k * P:.4g}); "
            f"remaining transient bound {bound:.3g} > ss_tol {num.ss_tol:g}"
            + ("; undamped model has no steady state" if model.eta == 0 else "")
        )

    taus, theta = seen_tau, seen_theta
    if status == 0 and k == 1 and from_orbit and periodic.harmonic_tail <= num.tail_tol:
        # the collocated orbit passed: report it (spectrally accurate, exact trigonometric
        # samples) rather than the stepper's samples, whose error is the stepper's tolerance
        taus = period_samples(dl, 0, num.rms_periods, m)
        theta = np.tile(trig_interpolate(periodic.theta.T, m).T, (1, num.rms_periods))
        message = (
            f"collocation orbit (M={periodic.M}, harmonic tail {periodic.harmonic_tail:.2g}) "
            f"verified by one period of time stepping (transient bound {bound:.2g})"
        )
    elif status == 0 and reuse:
        taus = np.concatenate([w[0] for w in window])
        theta = np.concatenate([w[1] for w in window], axis=1)
        message += f" (RMS window: the last {num.rms_periods} of them)"
    elif status == 0:
        window = period_samples(dl, k, num.rms_periods, m)
        sol = run(k * P, (k + num.rms_periods) * P, z, window)
        if sol is None:
            status, converged, message = 1, False, out_of_time(k) + " (in the RMS window)"
        elif sol.status < 0 or sol.y.shape[1] != window.size or not np.all(np.isfinite(sol.y)):
            status, converged = -1, False
            message = f"integrator failed in the RMS window: {sol.message}"
        else:
            taus, theta = window, sol.y[:n]
            k += num.rms_periods
    fl = orbit_fl if status == 0 and k == 1 and from_orbit else None
    if status == 0 and fl is None:  # the orbit time stepping settled on: its own multipliers
        fl = window_stability(model, dl, theta[:, -m:])
        if fl is not None and not fl.stable:
            status, converged = STATUS_UNSTABLE, False
            message += "; but the orbit reached is unstable (a slow transient, not a steady state)"
    if unstable_orbit:
        message = f"collocated orbit unstable ({orbit_fl.crossing()}); {message}"
    message += stability_note(fl if fl is not None else orbit_fl)
    y_m = model.grid.midspan(theta)
    return SteadyState(
        tau=taus,
        theta=theta,
        y_m=np.atleast_1d(y_m),
        converged=converged,
        status=status,
        message=message,
        periods=k,
        transient=bound,
        nfev=nfev,
        njev=njev,
        seconds=time.perf_counter() - t0,
        history=history,
        periodic=periodic,
        floquet=fl if fl is not None else orbit_fl,
    )
