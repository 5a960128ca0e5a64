"""The search for the periodic steady state of the discrete model: start, march, window.

`steady_state` never raises for a solver failure: its `SteadyState` says whether a steady state
was reached (`converged`, `status`) and why not (`message`), and its samples are the model's
states the integration saw (observables such as y_m are evaluated on them by `rotbeam.runs`).
It starts from a collocated orbit, asks `rotbeam.solve.certify` whether that orbit is the
steady state (`certify_orbit`), or else marches period by period until the bound on the
remaining transient is below ss_tol, samples the RMS window and asks for the verdict on it
(`certify_window`).  The criterion, the steps and their tolerances: docs/numerics.md, "The
steady-state march"; what the certification decides: docs/stability.md.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..model.base import DiscreteModel
from ..model.modes import linear_forced_response
from ..model.params import Dimensionless
from .certify import OrbitVerdict, certify_orbit, certify_window
from .floquet import FloquetResult
from .ivp import CUT, FAILED, IvpInterval, Stepped
from .numerics import Numerics
from .periodic import Neighbour, PeriodicResult, as_neighbour, solve_periodic_adaptive
from .quasistatic import quasistatic_series
from .spectral import highest_harmonic, trig_interpolate
from .system import FirstOrderSystem
from .timebudget import OutOfTime, TimeBudget


@dataclass
class SteadyState:
    """Result of `steady_state`: samples over the RMS window and how they were reached.

    Times are dimensionless (tau, in units of T = sqrt(rho A L^4 / EI)) and angles in rad.  The
    result holds states, not outputs: the runs evaluate observables such as y_m on `theta`
    (`rotbeam.runs.observables`).
    """

    tau: np.ndarray  #: sample instants (whole periods, endpoint excluded)
    theta: np.ndarray  #: (m, n) the model's coordinates at the samples (the elastica's: its angles)
    converged: bool  #: status == 0: a verified, stable steady state
    status: int  #: 0 steady, 1 no steady state within budget, 2 only an unstable orbit, -1 failure
    message: str  #: how the state was reached, or why not
    periods: int  #: drive periods integrated in all
    transient: float  #: last bound on the remaining relative transient
    nfev: int = 0  #: right-hand side evaluations of the time stepping
    njev: int = 0  #: Jacobian evaluations of the time stepping
    seconds: float = 0.0  #: wall time [s]
    history: list[float] = field(default_factory=list)  #: transient bound per period
    periodic: PeriodicResult | None = None  #: the collocation result, if one was made
    floquet: FloquetResult | None = None  #: multipliers of the reported orbit (else: collocated)
    #: (Theta, Theta_t) after the last whole period of the march, or a certified orbit's start
    #: (None otherwise): the start of the next point of a sweep that follows the beam
    state: np.ndarray | None = None
    #: instants per drive period of the window (`window_samples`; 0 where no period was sampled)
    samples_per_period: int = 0


#: the RMS window's instants per period of the highest harmonic it must resolve, the drive's or
#: the collocated orbit's (docs/numerics.md, "The RMS window")
SAMPLES_PER_HARMONIC = 4


def window_samples(dl: Dimensionless, num: Numerics, periodic: PeriodicResult | None = None) -> int:
    """Instants per drive period of the RMS window: numerics.samples_per_period, or more where
    the drive or the response carries harmonics that many instants would alias.

    K is the highest harmonic of the drive (`DriveLaw.highest_harmonic`) and of a converged
    collocated orbit (its highest harmonic above numerics.tail_tol of its size:
    `rotbeam.solve.spectral.highest_harmonic`).  Where SAMPLES_PER_HARMONIC K exceeds
    samples_per_period, the window takes that many instants rounded up to a power of two (the
    FFT sizes of `trig_interpolate`).  The paper's sine and drives of a few low harmonics keep
    samples_per_period; a trapezoid's 256 harmonics take 1024.

    Parameters
    ----------
    dl : Dimensionless
        The scene (its drive law).
    num : Numerics
        samples_per_period (the least count) and tail_tol.
    periodic : PeriodicResult or None
        The collocated orbit, if one was made.

    Returns
    -------
    int
        The instants per drive period.
    """
    k = dl.law.highest_harmonic
    if periodic is not None and periodic.converged:
        k = max(k, highest_harmonic(periodic.theta, num.tail_tol))
    need = SAMPLES_PER_HARMONIC * k
    if need <= num.samples_per_period:
        return num.samples_per_period
    return 1 << (need - 1).bit_length()


def period_samples(dl: Dimensionless, k0: int, periods: int, m: int) -> np.ndarray:
    """Sample instants of whole drive periods, the end excluded.

    Parameters
    ----------
    dl : Dimensionless
        The scene (its drive period P, dimensionless).
    k0 : int
        The first period: samples start at tau = k0 P.
    periods : int
        Number of periods.
    m : int
        Samples per period.

    Returns
    -------
    numpy.ndarray
        tau = (k0 + j / m) P, j = 0 .. periods m - 1, shape (periods m,).
    """
    P = dl.period
    return (k0 + np.arange(periods * m) / m) * P


def initial_state(
    model: DiscreteModel,
    start: str,
    tail_tol: float = 1e-3,
    guess: np.ndarray | Neighbour | None = None,
) -> tuple[np.ndarray, PeriodicResult | None]:
    """The state time stepping starts from at tau = 0.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    start : str
        "periodic" (the collocated orbit; when collocation fails, the quasi-static state, as
        for a scene solved alone), "linear" (the linearised forced
        response), "quasistatic" (the static equilibrium and its rate, by central differences)
        or "rest" (the straight beam at rest).
    tail_tol : float
        Harmonic tail the collocated orbit must reach (`solve_periodic_adaptive`).
    guess : numpy.ndarray, Neighbour or None
        An orbit (M, n) that seeds the collocation, or a neighbouring scene's
        (`rotbeam.solve.periodic.Neighbour`).

    Returns
    -------
    state : numpy.ndarray
        (Theta [rad], Theta_t [rad per unit tau]), shape (2 n,).
    periodic : PeriodicResult or None
        The collocation result when one converged, else None.
    """
    n, dl = model.n, model.dl
    if start == "rest":
        return np.zeros(2 * n), None
    if start == "periodic":
        seed = as_neighbour(guess, dl.omega)
        res = solve_periodic_adaptive(model, tail_tol=tail_tol, guess=seed)
        if res.converged:
            return np.concatenate([res.theta[0], res.theta_t[0]]), res
        start = "quasistatic"  # fall back to a physical state; the time stepping still decides
    if start == "linear":
        theta, rate = np.zeros(n), np.zeros(n)  # Theta and Theta_t at tau = 0
        for k, amp in linear_forced_response(model).items():
            theta, rate = theta + amp.real, rate - (k * dl.omega) * amp.imag
        return np.concatenate([theta, rate]), None
    h = dl.period * 1e-4
    th = quasistatic_series(model, np.array([-h, 0.0, h]))
    return np.concatenate([th[1], (th[2] - th[0]) / (2 * h)]), None


def starting_state(
    model: DiscreteModel,
    num: Numerics,
    guess: np.ndarray | Neighbour | None,
    state0: np.ndarray | None,
) -> tuple[np.ndarray, PeriodicResult | None]:
    """The state time stepping starts from: `state0` when given, else `initial_state`.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    num : Numerics
        start and tail_tol.
    guess : numpy.ndarray, Neighbour or None
        An orbit (M, n) that seeds the collocation, or a neighbouring scene's.
    state0 : numpy.ndarray or None
        (Theta, Theta_t) at tau = 0, shape (2 n,).

    Returns
    -------
    state : numpy.ndarray
        Shape (2 n,).
    periodic : PeriodicResult or None
        The collocation result, if one was made.

    Raises
    ------
    ValueError
        When state0 does not have shape (2 n,).
    """
    if state0 is None:
        return initial_state(model, num.start, num.tail_tol, guess)
    z = np.array(state0, dtype=float)
    if z.shape != (2 * model.n,):
        raise ValueError(f"state0 must have shape ({2 * model.n},), got {z.shape}")
    return z, None


def slowest_decay_rate(model: DiscreteModel) -> float:
    """Slowest decay rate of the linearised transient, per unit tau.

    A mode of undamped frequency w and modal damping c (`DiscreteModel.first_mode_decay`;
    c = eta for mass-proportional damping eta M) decays as exp(-c tau / 2) when underdamped
    (w > c / 2) and, overdamped, as exp(-r tau) with r = c / 2 - sqrt(c^2 / 4 - w^2) ~ w^2 / c:
    slower.  The first mode at the lowest rotation of the cycle is the slowest (stiffening only
    raises w).  A payload carries no damping: c is eta times the beam's share of the first
    mode's mass.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.

    Returns
    -------
    float
        r, per unit tau (0 without damping).
    """
    w1, c = model.first_mode_decay(model.dl.law.lam_min)
    if c == 0.0:
        return 0.0
    half = c / 2.0
    return half - math.sqrt(half * half - w1 * w1) if w1 < half else half


def collocation_window(
    dl: Dimensionless, num: Numerics, res: PeriodicResult
) -> tuple[np.ndarray, np.ndarray]:
    """The RMS window sampled from the collocated orbit's trigonometric interpolant.

    Parameters
    ----------
    dl : Dimensionless
        The scene (its drive period and law).
    num : Numerics
        rms_periods, and what `window_samples` reads.
    res : PeriodicResult
        The collocated orbit.

    Returns
    -------
    tau : numpy.ndarray
        `rms_periods` periods of m = `window_samples` instants from tau = 0, shape (p m,).
    theta : numpy.ndarray
        The orbit's angles [rad] there, shape (p m, n).
    """
    m, p = window_samples(dl, num, res), num.rms_periods
    return period_samples(dl, 0, p, m), np.tile(trig_interpolate(res.theta, m), (p, 1))


def _orbit_state(
    model: DiscreteModel, num: Numerics, orbit: OrbitVerdict, t0: float
) -> SteadyState:
    """A SteadyState reported from the collocated orbit itself (no time stepping), as
    `certify_orbit` decided it."""
    res = orbit.periodic
    tau, theta = collocation_window(model.dl, num, res)
    return SteadyState(
        tau=tau,
        theta=theta,
        converged=orbit.status == 0,
        status=orbit.status,
        message=orbit.message,
        periods=0,
        transient=orbit.transient,
        seconds=time.perf_counter() - t0,
        periodic=res,
        floquet=orbit.floquet,
        state=np.concatenate([res.theta[0], res.theta_t[0]]) if orbit.status == 0 else None,
        samples_per_period=window_samples(model.dl, num, res),
    )


@dataclass(frozen=True)
class Tolerances:
    """What the stepper is asked for, derived from `Numerics` and the slowest transient."""

    rho: float  #: decay factor of the slowest transient over one period (1: none decays)
    rtol: float  #: relative tolerance while following a transient (see `tolerances`)
    rtol_first: float  #: ... in the first period, looser when it only checks a collocated orbit
    scale: float  #: size of Theta behind the absolute tolerance
    wref: float  #: velocities are compared divided by this (max(omega, 1))

    def atol(self, r: float, n: int) -> np.ndarray:
        """Absolute tolerances of the state (Theta, Theta_t) at a relative tolerance.

        Parameters
        ----------
        r : float
            The relative tolerance.
        n : int
            Angles in the state.

        Returns
        -------
        numpy.ndarray
            r scale for the angles, r scale wref for the rates, shape (2 n,).
        """
        return np.concatenate([np.full(n, r * self.scale), np.full(n, r * self.scale * self.wref)])


def tolerances(
    model: DiscreteModel,
    num: Numerics,
    z: np.ndarray,
    response_scale: float | None,
    periodic: PeriodicResult | None,
    from_orbit: bool,
) -> Tolerances:
    """The stepper's tolerances for a march from the state z.

    The per-period integration error must stay below what the transient bound can tell apart:
    rtol <= 0.1 ss_tol (1 - rho).  From a converged collocated orbit the first period only has to
    confirm it: its difference d passes when d rho / (1 - rho) <= ss_tol, so an integration error
    a third of that threshold suffices, whatever `rtol` asks of a transient (the reported samples
    are then the collocation's, accurate to its harmonic tail).  Should the check fail, the
    following periods follow the transient at the tight `rtol` and their samples are reported.
    The absolute tolerance scales with the quasi-static response size if known (`response_scale`),
    else with the initial state, else with a rough linear estimate; never with more than a
    converged orbit's size: an overdamped beam driven above its corner frequency moves far less
    than quasi-statically (x140 for Fig. 7's E = 1e5 Pa, L = 0.1 mm beam), and an atol sized by
    the quasi-static response lets the stepper's error swamp the transient bound, which then
    stalls above ss_tol until max_tau.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    num : Numerics
        rtol and ss_tol.
    z : numpy.ndarray
        The starting state (Theta, Theta_t), shape (2 n,).
    response_scale : float or None
        The quasi-static max |Theta| [rad], if known.
    periodic : PeriodicResult or None
        The collocated orbit, if any.
    from_orbit : bool
        Whether the march starts on a converged, not unstable collocated orbit.

    Returns
    -------
    Tolerances
        rho, the rtol of a transient and of the first period, the scale of Theta and the
        velocity reference max(omega, 1).
    """
    n, dl = model.n, model.dl
    scale = response_scale if response_scale else float(np.max(np.abs(z[:n])))
    if periodic is not None and periodic.converged:
        orbit = float(np.max(np.abs(periodic.theta)))
        scale = min(scale, orbit) if orbit > 0.0 and math.isfinite(orbit) else scale
    if not scale or not math.isfinite(scale):
        scale = dl.law.lam_dot_max * (dl.hub_ratio + 1.0) / 8.0 or 1.0
    wref = max(dl.omega, 1.0)
    rho = math.exp(-slowest_decay_rate(model) * dl.period)
    rtol = min(num.rtol, 0.1 * num.ss_tol * (1.0 - rho)) if rho < 1.0 else num.rtol
    rtol = max(rtol, 1e-12)
    check = min(1e-2, num.ss_tol * (1.0 - rho) / (3.0 * rho)) if from_orbit and 0 < rho < 1 else 0.0
    return Tolerances(rho=rho, rtol=rtol, rtol_first=max(rtol, check), scale=scale, wref=wref)


class TransientStepper:
    """The march's time stepper: whole drive periods a call of one `IvpInterval`
    (`rotbeam.solve.ivp`), within the wall-time budget, sampled `samples` times a period
    (`window_samples`); counts the right-hand side and Jacobian evaluations over all its calls
    (`nfev`, `njev`)."""

    def __init__(
        self,
        model: DiscreteModel,
        num: Numerics,
        tol: Tolerances,
        time_budget: TimeBudget,
        samples: int,
    ) -> None:
        self.model, self.dl, self.num, self.tol = model, model.dl, num, tol
        self.n, self.time_budget, self.samples = model.n, time_budget, samples
        system = FirstOrderSystem(model, time_budget.deadline, compiled=True)
        method: str | type = num.method
        if num.method == "TRBDF2":
            from .trbdf2 import TRBDF2

            method = TRBDF2
        jac = system.jac if num.jacobian == "exact" else None
        self.ivp = IvpInterval(system.rhs, method, tol.rtol, tol.atol(tol.rtol, self.n), jac)

    @property
    def nfev(self) -> int:
        """Right-hand-side evaluations over all calls."""
        return self.ivp.nfev

    @property
    def njev(self) -> int:
        """Jacobian evaluations over all calls."""
        return self.ivp.njev

    def periods(
        self, k: int, count: int, z: np.ndarray, t_eval: np.ndarray, rtol: float
    ) -> Stepped:
        """Whole drive periods from tau = k P.

        Parameters
        ----------
        k : int
            The first period: from tau = k P.
        count : int
            Periods to integrate.
        z : numpy.ndarray
            State at tau = k P, shape (2 n,).
        t_eval : numpy.ndarray
            Instants to sample.
        rtol : float
            Relative tolerance (the absolute one from `Tolerances.atol`).

        Returns
        -------
        Stepped
            The samples and the status: CUT when the wall-time budget ran out inside it.
        """
        P = self.dl.period
        return self.ivp.run(k * P, (k + count) * P, z, t_eval, rtol, self.tol.atol(rtol, self.n))


def _out_of_time(stepper: TransientStepper, k: int, bound: float) -> str:
    """No steady state: which phase the budget cut, and the transient bound it left."""
    where = f"the time stepping at {stepper.model.label} after {k} whole periods"
    return (
        f"no steady state: {stepper.time_budget.cut(where)} (tau={k * stepper.dl.period:.4g}); "
        f"remaining transient bound {bound:.3g}"
    )


def transient_bound(d: float, rho: float, size: float) -> float:
    """Bound on the remaining transient relative to the response: d rho / (1 - rho) / size.

    Parameters
    ----------
    d : float
        |Z_k - Z_{k-1}|, the change over the last period (max-norm, rates divided by wref).
    rho : float
        Decay factor of the slowest transient over one period.
    size : float
        The response's size, max |Theta| over the last period [rad].

    Returns
    -------
    float
        The bound (0 for an exact fixed point, inf when nothing decays).
    """
    if d == 0.0:  # an exact fixed point of the period map (also undamped: rho = 1)
        return 0.0
    if rho < 1.0:
        return d * rho / (1.0 - rho) / size
    return math.inf


def window_reach(d: float, rho: float, p: int) -> float:
    """How far the state p periods back may lie from the steady state, per unit of the last
    period's change: whether the periods just integrated can serve as the RMS window.

    Parameters
    ----------
    d : float
        |Z_k - Z_{k-1}|, the change over the last period.
    rho : float
        Decay factor of the slowest transient over one period.
    p : int
        Periods back.

    Returns
    -------
    float
        r with |Z_{k-p} - Z_inf| <= d r, r = sum_{q<p} rho^-q + rho / (1 - rho) (0 for an exact
        fixed point, inf for rho = 0).
    """
    if d == 0.0:  # an exact fixed point of the period map (also undamped: rho = 1)
        return 0.0
    if rho > 0.0:  # bound <= ss_tol with d > 0 means rho < 1
        return sum(rho**-q for q in range(p)) + rho / (1.0 - rho)
    return math.inf


@dataclass
class March:
    """Where `march` stopped and why."""

    z: np.ndarray  #: state after the last whole period
    last: tuple[np.ndarray, np.ndarray]  #: (tau (m,), Theta (m, n)) of the last period seen
    status: int = 1  #: 0 steady, 1 no steady state within the budget, -1 integrator failure
    message: str = ""
    k: int = 0  #: whole periods integrated
    bound: float = math.inf  #: last transient bound
    history: list[float] = field(default_factory=list)  #: transient bound per period
    window: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)  #: last periods
    reusable: bool = False  #: `window` is within ss_tol of the steady state from its first instant


def march(
    stepper: TransientStepper,
    z: np.ndarray,
    from_orbit: bool,
    progress: Callable[[int, float], None] | None = None,
) -> March:
    """Period after period from the state z until the transient bound is below ss_tol, the
    budget (max_periods, max_tau, max_seconds) is spent or the integrator fails.

    From a converged collocated orbit one period may suffice (it measures the orbit's distance
    to the time-stepped one); from any other start at least two are taken (the first period's
    difference may be a lucky crossing).  The first period runs at `Tolerances.rtol_first`.

    Parameters
    ----------
    stepper : TransientStepper
        The solver, its tolerances and deadline.
    z : numpy.ndarray
        The state at tau = 0, shape (2 n,).
    from_orbit : bool
        Whether z is a converged, not unstable collocated orbit's start.
    progress : callable or None
        progress(period, transient bound) after every period.

    Returns
    -------
    March
        Where it stopped (state, last period's samples, the last periods), the status, the
        message and the transient bounds.
    """
    dl, num, tol, n = stepper.dl, stepper.num, stepper.tol, stepper.n
    P, m, p = dl.period, stepper.samples, num.rms_periods
    # from a converged collocated orbit one period measures its distance to the time-stepped
    # orbit; from any other start the first period's difference may be a lucky crossing
    min_periods = 1 if from_orbit else 2
    max_periods = min(num.max_periods, max(2, int(num.max_tau / P)))
    if not stepper.model.damped:  # no transient ever decays: show a few periods and say so
        max_periods = min(max_periods, max(2, p))
    out = March(z=z, last=(np.array([0.0]), z[None, :n].copy()))
    while out.k < max_periods:
        k = out.k
        t_eval = np.append(period_samples(dl, k, 1, m), (k + 1) * P)
        sol = stepper.periods(k, 1, out.z, t_eval, tol.rtol_first if k == 0 else tol.rtol)
        if sol.status == CUT:
            out.message = _out_of_time(stepper, k, out.bound)
            return out
        if sol.status == FAILED:
            out.status, out.message = -1, f"integrator failed in period {k + 1}: {sol.message}"
            return out
        out.last = (sol.t[:-1], sol.y[:-1, :n])
        z_new = sol.y[-1]
        out.k = k = k + 1
        size = max(float(np.max(np.abs(sol.y[:, :n]))), 1e-300)
        d = max(
            float(np.max(np.abs(z_new[:n] - out.z[:n]))),
            float(np.max(np.abs(z_new[n:] - out.z[n:]))) / tol.wref,
        )
        out.z = z_new
        out.bound = transient_bound(d, tol.rho, size)
        out.history.append(out.bound)
        if progress is not None:
            progress(k, out.bound)
        out.window.append(out.last)
        del out.window[:-p]
        if k >= min_periods and out.bound <= num.ss_tol:
            out.status, out.message = 0, f"steady after {k} periods"
            # the periods just integrated serve as the RMS window when even their first sample
            # is within ss_tol of the steady state
            reach = window_reach(d, tol.rho, p)
            out.reusable = k >= p and len(out.window) == p and d * reach / size <= num.ss_tol
            return out
    out.message = (
        f"no steady state within {max_periods} periods (tau={out.k * P:.4g}); "
        f"remaining transient bound {out.bound:.3g} > ss_tol {num.ss_tol:g}"
        + ("; undamped model has no steady state" if not stepper.model.damped else "")
    )
    return out


@dataclass
class Window:
    """The RMS window: samples, and the march's outcome as the window leaves it."""

    tau: np.ndarray  #: (m,) the instants
    theta: np.ndarray  #: (m, n) the model's coordinates at them
    status: int
    message: str
    periods: int  #: drive periods integrated in all
    samples: int  #: instants per drive period


def rms_window(
    stepper: TransientStepper, run: March, periodic: PeriodicResult | None, from_orbit: bool
) -> Window:
    """The samples to report once the march stopped.

    A collocated orbit that passed its one-period check is reported itself (spectrally accurate,
    exact trigonometric samples, rather than the stepper's, whose error is its tolerance); else
    the periods just integrated when they are close enough (`March.reusable`); else `rms_periods`
    more periods are integrated and sampled.  Without a steady state: the last period seen.

    Parameters
    ----------
    stepper : TransientStepper
        The solver the march used.
    run : March
        Where the march stopped.
    periodic : PeriodicResult or None
        The collocated orbit the march started from, if any.
    from_orbit : bool
        Whether it started from that orbit.

    Returns
    -------
    Window
        The samples (tau, Theta), the status and message, and the periods integrated in all.
    """
    dl, num, n = stepper.dl, stepper.num, stepper.n
    p, m, k = num.rms_periods, stepper.samples, run.k
    if run.status != 0:
        return Window(*run.last, run.status, run.message, k, m)
    if k == 1 and from_orbit and periodic.harmonic_tail <= num.tail_tol:
        return Window(
            *collocation_window(dl, num, periodic),
            0,
            f"collocation orbit (M={periodic.M}, harmonic tail {periodic.harmonic_tail:.2g}) "
            f"verified by one period of time stepping (transient bound {run.bound:.2g})",
            k,
            m,
        )
    if run.reusable:
        return Window(
            np.concatenate([w[0] for w in run.window]),
            np.concatenate([w[1] for w in run.window]),
            0,
            run.message + f" (RMS window: the last {p} of them)",
            k,
            m,
        )
    taus = period_samples(dl, k, p, m)
    sol = stepper.periods(k, p, run.z, taus, stepper.tol.rtol)
    if sol.status == CUT:
        msg = _out_of_time(stepper, k, run.bound) + " (in the RMS window)"
        return Window(*run.last, 1, msg, k, m)
    if sol.status == FAILED:
        return Window(*run.last, -1, f"integrator failed in the RMS window: {sol.message}", k, m)
    return Window(taus, sol.y[:, :n], 0, run.message, k + p, m)


def steady_state(
    model: DiscreteModel,
    numerics: Numerics | None = None,
    progress: Callable[[int, float], None] | None = None,
    response_scale: float | None = None,
    guess: np.ndarray | Neighbour | None = None,
    state0: np.ndarray | None = None,
    time_budget: TimeBudget | None = None,
) -> SteadyState:
    """The periodic steady state of `model` under its drive, sampled over the RMS window.

    The steps: the initial state (`starting_state`), the verdict on a collocated orbit
    (`rotbeam.solve.certify.certify_orbit`), the stepper's tolerances (`tolerances`), the march
    period by period to the steady state (`march`, with a `TransientStepper`), the RMS window
    (`rms_window`) and the verdict on it (`rotbeam.solve.certify.certify_window`).  Never raises
    for a solver failure: the result says whether a steady state was reached and why not.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    numerics : Numerics or None
        Tolerances, budgets and strategy (default `Numerics()`; its N is the caller's: the
        model has its grid).  With integrate = False (and start = "periodic") the collocation
        result is returned as it is: fastest, but not checked by time stepping.
    progress : callable or None
        progress(period, transient bound) after every period of time stepping.
    response_scale : float or None
        Size of the response behind the absolute tolerance (the quasi-static max |Theta|).
    guess : numpy.ndarray, Neighbour or None
        An orbit (M, n) that seeds the collocation, or a neighbouring scene's
        (`rotbeam.solve.periodic.Neighbour`: continuation along a sweep; where the continued
        orbit is not a certified stable one, the scene's own start is tried next).
    state0 : numpy.ndarray or None
        (Theta, Theta_t) at tau = 0 instead of `numerics.start`: time stepping from where the
        beam is (no collocation), e.g. the previous drive frequency's final `state` in a sweep
        that shows hysteresis.
    time_budget : TimeBudget or None
        The wall-time budget the collocation, its Floquet passes and the time stepping stop
        at (a command's, shared with its other phases); None: `numerics.max_seconds` from the
        call.

    Returns
    -------
    SteadyState
        The samples over the RMS window (tau in units of T, the model's coordinates), whether
        and how a steady state was reached, the multipliers of the reported orbit, and the
        final state.
    """
    num = numerics if numerics is not None else Numerics()
    t0 = time.perf_counter()
    budget = time_budget or TimeBudget(num.max_seconds, t0)
    try:
        with budget.watch():  # the collocation and its Floquet passes stop at the budget too
            z, periodic = starting_state(model, num, guess, state0)
            orbit = certify_orbit(model, num, periodic)
            continued_orbit = guess is not None and state0 is None and num.start == "periodic"
            if (
                continued_orbit
                and not orbit.decided
                and orbit.periodic is not None
                and orbit.periodic.converged
            ):
                # a continued orbit that is unstable or not certified (another branch; a
                # coarse grid's resampled neighbour): the scene's own start, as solved alone,
                # before time stepping (an orbit that did not converge was already solved
                # alone: solve_periodic_adaptive)
                _, own = starting_state(model, num, None, None)
                own_orbit = certify_orbit(model, num, own)
                orbit = own_orbit if own_orbit.decided else orbit
    except OutOfTime:
        return _collocation_cut(model, budget, t0)
    if orbit.decided:
        return _orbit_state(model, num, orbit, t0)
    periodic, from_orbit = orbit.periodic, orbit.on_orbit
    if from_orbit:
        z = np.concatenate([periodic.theta[0], periodic.theta_t[0]])
    tol = tolerances(model, num, z, response_scale, periodic, from_orbit)
    z = orbit.march_start(z, tol.scale)
    stepper = TransientStepper(model, num, tol, budget, window_samples(model.dl, num, periodic))
    run = march(stepper, z, from_orbit, progress)
    win = rms_window(stepper, run, periodic, from_orbit)
    verdict = certify_window(
        model, num, orbit, win.status, win.message, win.periods, win.theta[-win.samples :]
    )
    return SteadyState(
        tau=win.tau,
        theta=win.theta,
        converged=verdict.status == 0,
        status=verdict.status,
        message=verdict.message,
        periods=win.periods,
        transient=run.bound,
        nfev=stepper.nfev,
        njev=stepper.njev,
        seconds=time.perf_counter() - t0,
        history=run.history,
        periodic=periodic,
        floquet=verdict.floquet,
        state=run.z.copy(),
        samples_per_period=win.samples,
    )


def _collocation_cut(model: DiscreteModel, budget: TimeBudget, t0: float) -> SteadyState:
    """No steady state: the budget was spent in the collocation or its Floquet passes, before
    any time stepping (one sample, the straight beam, stands for the missing window)."""
    where = f"the collocation at {model.label}"
    return SteadyState(
        tau=np.zeros(1),
        theta=np.zeros((1, model.n)),
        converged=False,
        status=1,
        message=f"no steady state: {budget.cut(where)}, before any time stepping",
        periods=0,
        transient=math.inf,
        seconds=time.perf_counter() - t0,
    )
