"""The engineer's question for one scene: is the quasi-static answer good enough here?

`judge` gives the full model's verdict (Delta RMS against a threshold, the paper's criterion)
and the linear estimate of where the boundary lies (the damped first mode driven by every
harmonic of the drive; c_0 f_0 for the sine); `critical` finds f_d* of the full model at one
speed by root finding started at that estimate (`rotbeam critical`).  Both read Delta RMS of one
observable, the criterion (`rotbeam.runs.observables`: y_m, the paper's, by default).  The
criterion, the estimate, its lag branch for overdamped beams and the search: docs/model.md, "The
verdict and the linear estimate of f_d*".  The verdict's figure is `rotbeam.report.verdict_plot`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from ..config.checks import check_threshold
from ..config.errors import RotbeamInputError
from ..config.threads import one_blas_thread
from ..model.modes import damping_ratio, resonance_frequency_hz
from ..model.params import Drive
from ..model.secondorder import c0_root, delta_rms_harmonics, first_crossing, inverse_gain2
from ..runs.move import SETTLED, MoveResult
from ..runs.observables import criterion_name
from ..runs.scene import Scene, SceneResult, simulate
from ..solve.timebudget import TimeBudget


@dataclass(frozen=True)
class Verdict:
    """Whether the quasi-static model is adequate for one simulated scene.

    What `judge` returns: the full model's answer (Delta RMS against the threshold, both
    dimensionless) beside the linear estimate of where the boundary lies, so that a reader sees
    how far from it the scene is.
    """

    threshold: float
    delta_rms: float
    #: True: Delta RMS < threshold; False: inertia matters; None: no steady state, no verdict
    quasistatic_ok: bool | None
    f0_hz: float  #: first in-plane frequency at Omega_0 + a (linearised model)
    c0: float  #: App. E ratio f_d* / f_0 at the beam's zeta (NaN where no root exists)
    #: the linear estimate of f_d* [Hz] (`linear_estimate`); NaN without an Euler load
    fd_star_estimate_hz: float
    text: str  #: one line for a reader
    criterion: str = "y_m"  #: the observable whose Delta RMS is judged (`criterion_delta_rms`)

    def as_dict(self) -> dict[str, float | bool | str | None]:
        """The verdict as JSON-ready fields (part of `rotbeam simulate --json`).

        Returns
        -------
        dict
            ``threshold``, ``criterion`` (the observable's name), ``criterion_delta_rms`` (its
            Delta RMS, dimensionless), ``quasistatic_ok``, ``f0_hz`` [Hz], ``c0``
            (dimensionless), ``fd_star_estimate_hz`` [Hz] and ``verdict`` (the one-line text).
            The scene's summary carries y_m's Delta RMS as ``delta_rms``.
        """
        return {
            "threshold": self.threshold,
            "criterion": self.criterion,
            "criterion_delta_rms": self.delta_rms,
            "quasistatic_ok": self.quasistatic_ok,
            "f0_hz": self.f0_hz,
            "c0": self.c0,
            "fd_star_estimate_hz": self.fd_star_estimate_hz,
            "verdict": self.text,
        }


def judge(result: SceneResult, threshold: float = 0.10, criterion: str = "y_m") -> Verdict:
    """The verdict of the full model on one scene, and the linear estimate of the boundary.

    Quasi-static is good enough where Delta RMS of the criterion < `threshold`; a dynamic run
    without a steady state gives no verdict.  The linear estimate of f_d* (`linear_estimate`:
    c_0 f_0 for the sine) tells how far from the boundary the scene's f_d lies; it is the first
    mode's whatever the criterion; a drive without an Euler load has none, and the text says so
    (docs/model.md, "The verdict and the linear estimate of f_d*").

    Parameters
    ----------
    result : SceneResult
        The simulated scene (`rotbeam.runs.scene.simulate`).
    threshold : float
        The Delta RMS threshold, dimensionless, in (0, 1); 0.10 is the paper's.
    criterion : str
        The observable whose Delta RMS is judged (`rotbeam.runs.observables.OBSERVABLES`);
        "y_m", the paper's, by default.

    Returns
    -------
    Verdict
        The answer (`quasistatic_ok`: True, False or None), f_0 [Hz], c_0, the estimate of f_d*
        [Hz], one line of text and the criterion's name.

    Raises
    ------
    RotbeamInputError
        If `threshold` is not a number in (0, 1) or `criterion` is not an observable's name.
    """
    th = check_threshold(threshold)
    name = criterion_name(criterion)
    beam, drive = result.scene.beam, result.scene.drive
    f0 = resonance_frequency_hz(beam, drive.omega_max)
    zeta = damping_ratio(beam)
    ratio, note = linear_estimate(drive, zeta, th)
    first_mode = "" if name == "y_m" else ", the first mode's"
    where = f"f_d / f_0 = {drive.f_d / f0:.3g}; " + (
        f"linear estimate f_d* = {ratio * f0:.3g} Hz{note}{first_mode}"
        if math.isfinite(ratio)
        else note
    )
    d = criterion_delta_rms(result, name)
    label = criterion_label(name)
    if not result.converged or not math.isfinite(d):
        ok = None
        text = f"no verdict: the dynamic run reached no steady state ({where})"
    elif d < th:
        ok = True
        text = f"quasi-static is good enough: {label} {d:.3g} < {th:g} ({where})"
    else:
        ok = False
        text = f"inertia matters: {label} {d:.3g} >= {th:g}, use the dynamic model ({where})"
    return Verdict(th, d, ok, f0, _app_e_c0(zeta, th), ratio * f0, text, name)


def criterion_delta_rms(result: SceneResult | MoveResult, criterion: str = "y_m") -> float:
    """Delta RMS = |RMS_dyn - RMS_qs| / RMS_dyn of one observable over the result's window.

    For y_m it is the result's own `delta_rms` (Richardson's where numerics.extrapolate asks);
    for another observable, its `observables` entry over the same window, at grid N.

    Parameters
    ----------
    result : SceneResult or MoveResult
        A simulated scene or move.
    criterion : str
        An observable's name (`rotbeam.runs.observables.OBSERVABLES`).

    Returns
    -------
    float
        Delta RMS, dimensionless; NaN where the window holds no dynamic values.

    Raises
    ------
    RotbeamInputError
        If `criterion` is not an observable's name.
    """
    name = criterion_name(criterion)
    if name == "y_m":
        return result.delta_rms
    return float(result.observables((name,))[name]["delta_rms"])


def criterion_label(criterion: str) -> str:
    """How the verdict's text names Delta RMS: plain for y_m, the paper's; with the observable's
    name otherwise ("Delta RMS of root_moment").

    Parameters
    ----------
    criterion : str
        An observable's name.

    Returns
    -------
    str
        The label.
    """
    return "Delta RMS" if criterion == "y_m" else f"Delta RMS of {criterion}"


#: A harmonic whose Euler load k |a_k| is below this fraction of the drive's largest |Omega| is
#: round-off of a sampled profile's transform (a constant profile leaves ~1e-16), not a load.
LOAD_FLOOR = 1e-12

#: What the verdict and `critical` say of a periodic drive without an Euler load.
NO_EULER_LOAD = "the drive has no Euler load (a constant speed): no f_d*"


def euler_loads(drive: Drive) -> tuple[tuple[int, ...], tuple[float, ...]]:
    """The harmonics of a periodic drive that load the beam, and their Euler loads.

    Harmonic k of Omega, a_k sin(2 pi k f_d t + phase_k), has the rate
    2 pi f_d k a_k cos(...): its Euler load, at k f_d, is proportional to k |a_k|, the factor
    2 pi f_d being common to all harmonics (docs/model.md, "The verdict and the linear estimate
    of f_d*").  Harmonics below LOAD_FLOOR of the largest |Omega| are left out.

    Parameters
    ----------
    drive : Drive
        A periodic drive: the sine, harmonics or a sampled profile (its interpolant's
        harmonics).

    Returns
    -------
    orders : tuple of int
        The harmonics k >= 1 with a load; empty for a constant speed.
    loads : tuple of float
        k |a_k| [rad/s], one per order.

    Raises
    ------
    RotbeamInputError
        For a single move, which has no repetition rate and no f_d*.
    """
    if not drive.periodic:
        raise RotbeamInputError("a single move has no repetition rate: no f_d* to find")
    floor = LOAD_FLOOR * drive.omega_max
    terms = drive.law(1.0).harmonic_terms()
    loaded = [(k, k * abs(a)) for k, a, _ in terms if k * abs(a) > floor]
    return tuple(k for k, _ in loaded), tuple(load for _, load in loaded)


def linear_estimate(drive: Drive, zeta: float, threshold: float) -> tuple[float, str]:
    """The linear estimate of f_d* / f_0: the lowest f_d at which the damped first mode, driven
    by every harmonic's Euler load, has Delta RMS = threshold.

    Each harmonic k loads the first mode (damping ratio zeta) at k f_d through
    H(r) = 1 / (1 - r^2 + 2 i zeta r), r = k f_d / f_0, and the quasi-static response follows the
    load; their RMS over the period give Delta RMS (`rotbeam.model.secondorder.first_crossing`).
    For one harmonic k this is App. E's c_0 / k, or where the response lags the static one for
    a beam too damped for c_0 (docs/model.md, "The verdict and the linear estimate of f_d*").

    Parameters
    ----------
    drive : Drive
        A periodic drive (its f_d is not read).
    zeta : float
        Damping ratio of the first mode, dimensionless, >= 0.
    threshold : float
        The Delta RMS threshold, dimensionless, in (0, 1).

    Returns
    -------
    ratio : float
        f_d* / f_0, dimensionless; NaN where the drive has no Euler load.
    note : str
        For the verdict's text: how the estimate is made (" = c_0 f_0" for the sine), or
        NO_EULER_LOAD.

    Raises
    ------
    RotbeamInputError
        For a single move, or `zeta` or `threshold` out of range.
    """
    orders, loads = euler_loads(drive)
    if not orders:
        return math.nan, NO_EULER_LOAD
    ratio = first_crossing(orders, loads, zeta, threshold)
    return ratio, _estimate_note(orders, loads, zeta, ratio)


def _estimate_note(orders: tuple[int, ...], loads: tuple[float, ...], zeta: float,
                   ratio: float) -> str:  # fmt: skip
    """How the estimate is made, for the verdict's text: App. E's c_0 for one harmonic; else the
    number of harmonics and the one that carries most of RMS_dyn^2 - RMS_qs^2 at the crossing."""
    lags = delta_rms_harmonics(ratio, orders, loads, zeta) < 0.0
    lag = f", where the response lags (zeta {zeta:.3g})" if lags else ""
    if len(orders) == 1:
        k = orders[0]
        if lags:
            return lag if k == 1 else f"{lag[:-1]}, harmonic {k})"
        return " = c_0 f_0" if k == 1 else f" = c_0 f_0 / {k}"
    r = np.asarray(orders, dtype=float) * ratio
    w = np.asarray(loads) ** 2
    share = w * np.abs(1.0 / inverse_gain2(r, zeta) - 1.0)
    i = int(np.argmax(share))
    return (f" ({len(orders)} harmonics through the first mode; mostly harmonic {orders[i]}, at "
            f"{orders[i]} f_d* = {r[i]:.3g} f_0{lag})")  # fmt: skip


def _app_e_c0(zeta: float, threshold: float) -> float:
    """App. E's c_0 at the beam's zeta, NaN where it does not exist (an overdamped beam)."""
    try:
        return c0_root(zeta, threshold)
    except RotbeamInputError:
        return math.nan


class _NoSteadyState(Exception):
    """A run of the f_d* search reached no steady state: the search stops and says why."""


@dataclass(frozen=True)
class Critical:
    """The drive frequency f_d* at which Delta RMS of the criterion reaches the threshold, at one
    rotation speed.

    What `critical` returns: the root (or why there is none), where the search started and every
    full-model run it made, so that a reader can judge the answer and its cost.
    """

    found: bool
    f_d_star: float  #: Hz; NaN unless found
    threshold: float
    f0_hz: float
    estimate_hz: float  #: the linear estimate where the search started (`linear_estimate`)
    visited: list[tuple[float, float]]  #: (f_d, Delta RMS) of every full-model run, in order
    seconds: float
    message: str
    criterion: str = "y_m"  #: the observable whose Delta RMS the search reads

    def as_dict(self) -> dict[str, object]:
        """The search as JSON-ready fields (`rotbeam critical --json`).

        Returns
        -------
        dict
            ``found``, ``f_d_star`` [Hz], ``threshold``, ``f0_hz`` [Hz], ``estimate_hz`` [Hz],
            ``seconds`` [s], ``message``, ``criterion`` (the observable's name), ``c`` =
            f_d* / f_0 (dimensionless), ``evaluations`` (full-model runs) and ``visited``
            ([f_d Hz, Delta RMS of the criterion] per run, in order).
        """
        out = {k: getattr(self, k) for k in ("found", "f_d_star", "threshold", "f0_hz",
                                             "estimate_hz", "seconds", "message",
                                             "criterion")}  # fmt: skip
        out["c"] = self.f_d_star / self.f0_hz
        out["evaluations"] = len(self.visited)
        out["visited"] = [list(v) for v in self.visited]
        return out


#: Bracket search: steps of this factor in f_d from the linear estimate, at most MAX_STEPS each way.
BRACKET_FACTOR = 1.25
MAX_STEPS = 12


class _Excess:
    """Delta RMS of the criterion - threshold of the full model at the scene's speed, as a
    function of f_d.  Each
    f_d runs once (brentq evaluates the bracket ends again) and the last orbit seeds the next
    collocation; a run without a steady state, or the time budget spent, raises _NoSteadyState."""

    def __init__(
        self,
        scene: Scene,
        th: float,
        time_budget: TimeBudget,
        progress: Callable[[], None] | None = None,
        criterion: str = "y_m",
    ) -> None:
        self.scene, self.th, self.progress = scene, th, progress
        self.criterion = criterion
        self.time_budget = time_budget
        self.seen: dict[float, float] = {}  #: f_d -> Delta RMS, in the order run
        self.guess = None

    def __call__(self, f_d: float) -> float:
        if f_d not in self.seen:
            if self.time_budget.spent():
                raise _NoSteadyState(
                    self.time_budget.cut(f"the search after {len(self.seen)} full-model runs")
                )
            drive = replace(self.scene.drive, f_d=f_d)
            res = simulate(replace(self.scene, drive=drive), guess=self.guess,
                           time_budget=self.time_budget)  # fmt: skip
            d = criterion_delta_rms(res, self.criterion) if res.converged else math.nan
            if not math.isfinite(d):
                raise _NoSteadyState(
                    f"no steady state at f_d = {f_d:.4g} Hz: {res.dynamic.message}"
                )
            orbit = res.dynamic.periodic
            self.guess = orbit.theta if orbit is not None and orbit.converged else None
            self.seen[f_d] = d
            if self.progress is not None:
                self.progress()
        return self.seen[f_d] - self.th


def _bracket(
    excess: Callable[[float], float], f: float, g: float, th: float, label: str = "Delta RMS"
) -> tuple[float, float] | str:
    """From f (where excess(f) = g != 0) step by BRACKET_FACTOR towards the threshold until
    excess changes sign: the bracket (lo, hi), or why there is none within MAX_STEPS."""
    start = f
    step = BRACKET_FACTOR if g < 0 else 1.0 / BRACKET_FACTOR
    for _ in range(MAX_STEPS):
        g_next = excess(f * step)
        if g_next == 0.0 or (g_next > 0) != (g > 0):
            lo, hi = sorted((f, f * step))
            return lo, hi
        f, g = f * step, g_next
    side = "below" if step > 1 else "above"
    return (f"{label} stays {side} {th:g} from {start:.4g} Hz to {f:.4g} Hz ({MAX_STEPS} "
            f"steps of x{step:.3g})")  # fmt: skip


def critical_start_hz(scene: Scene, threshold: float = 0.10) -> float:
    """Where `critical` starts: the linear estimate of f_d* [Hz] (`linear_estimate` times f_0
    at the drive's largest |Omega|); `rotbeam critical --effects auto` budgets the effects here.

    Parameters
    ----------
    scene : Scene
        The beam and the drive's speed and amplitude (its f_d is not read).
    threshold : float
        The Delta RMS threshold, dimensionless, in (0, 1).

    Returns
    -------
    float
        The linear estimate of f_d* [Hz].

    Raises
    ------
    RotbeamInputError
        If `threshold` is not a number in (0, 1), or the drive is a single move or has no Euler
        load (no f_d* to find).
    """
    return _start(scene, check_threshold(threshold))[1]


def _start(scene: Scene, threshold: float) -> tuple[float, float]:
    """f_0 [Hz] at the drive's largest |Omega| and the linear estimate of f_d* [Hz]; a drive
    without an Euler load has no f_d* to find (RotbeamInputError)."""
    beam, drive = scene.beam, scene.drive
    f0 = resonance_frequency_hz(beam, drive.omega_max)
    ratio, _ = linear_estimate(drive, damping_ratio(beam), threshold)
    if not math.isfinite(ratio):
        raise RotbeamInputError(f"{NO_EULER_LOAD} to find: Delta RMS is 0 at every f_d")
    return f0, ratio * f0


@one_blas_thread
def critical(
    scene: Scene,
    threshold: float = 0.10,
    rtol: float = 1e-3,
    progress: Callable[[], None] | None = None,
    time_budget: TimeBudget | None = None,
    criterion: str = "y_m",
) -> Critical:
    """f_d* [Hz]: the drive frequency at which Delta RMS of the full model reaches `threshold`,
    at the scene's speed and amplitude, by root finding instead of a dense scan.

    Delta RMS is the criterion's (`criterion_delta_rms`: y_m's, the paper's, by default).
    Starts at the linear estimate (`linear_estimate`: App. E's c_0 f_0 for the sine, within a
    few per cent on the reference beam, or its lag branch for overdamped beams), steps by
    BRACKET_FACTOR until Delta RMS - threshold changes sign, then runs brentq to a relative
    tolerance `rtol` in f_d.  This is the crossing nearest the estimate; it is the paper's first
    crossing where Delta RMS rises monotonically below it.  A run without a steady state, or the
    time budget spent, ends the search with found = False and its reason.

    Parameters
    ----------
    scene : Scene
        Beam, drive (its f_d is not read: the search sets it), effects, numerics.
    threshold : float
        The Delta RMS threshold, dimensionless, in (0, 1).
    rtol : float
        Relative tolerance on f_d*, dimensionless, in [1e-8, 0.1].
    progress : callable or None
        Called after every full-model run of the search.
    time_budget : TimeBudget or None
        The wall-time budget of the whole search; None: the scene's numerics.max_seconds.
    criterion : str
        The observable whose Delta RMS reaches `threshold` at f_d*
        (`rotbeam.runs.observables.OBSERVABLES`); the search starts at the first mode's linear
        estimate whatever the criterion.

    Returns
    -------
    Critical
        f_d* [Hz] and ``found = True``, or NaN, ``found = False`` and the reason in ``message``;
        with f_0, the start, every run made, the wall time and the criterion.

    Raises
    ------
    RotbeamInputError
        If `threshold` is not in (0, 1), `rtol` not a float in [1e-8, 0.1], `criterion` not an
        observable's name, or the drive is a single move or has no Euler load (no f_d* to find).
    """
    from scipy.optimize import brentq

    th = check_threshold(threshold)
    name = criterion_name(criterion)
    if not (isinstance(rtol, float) and 1e-8 <= rtol <= 0.1):
        raise RotbeamInputError(f"rtol must be in [1e-8, 0.1], got {rtol!r}")
    t0 = time.perf_counter()
    f0, start = _start(scene, th)
    estimate = start
    budget = time_budget or TimeBudget(scene.numerics.max_seconds)
    excess = _Excess(scene, th, budget, progress, name)

    def done(found: bool, f: float, msg: str) -> Critical:
        visited = list(excess.seen.items())
        seconds = time.perf_counter() - t0
        return Critical(found, f, th, f0, estimate, visited, seconds, msg, name)

    try:
        g = excess(start)
        if g == 0.0:
            return done(True, start, f"{criterion_label(name)} equals the threshold at the start")
        bracket = _bracket(excess, start, g, th, criterion_label(name))
        if isinstance(bracket, str):
            return done(False, math.nan, bracket)
        lo, hi = bracket
        root = brentq(excess, lo, hi, rtol=rtol, xtol=1e-12 * hi)
    except _NoSteadyState as exc:
        return done(False, math.nan, str(exc))
    return done(True, float(root), f"brentq in [{lo:.4g}, {hi:.4g}] Hz to rtol {rtol:g}")


def judge_move(result: MoveResult, threshold: float = 0.10, criterion: str = "y_m") -> Verdict:
    """The verdict on a single move: the same threshold on Delta RMS of the criterion over the
    move, with the size of the vibration (y_m) it leaves behind.

    Parameters
    ----------
    result : MoveResult
        The move, simulated (`rotbeam.runs.move.simulate_move`).
    threshold : float
        Delta RMS below which quasi-static is good enough, in (0, 1).
    criterion : str
        The observable whose Delta RMS is judged (`rotbeam.runs.observables.OBSERVABLES`);
        "y_m", the paper's, by default.

    Returns
    -------
    Verdict
        f0_hz is the first in-plane frequency at the move's largest speed; c0 and the estimate
        of f_d* are NaN (a move has no repetition rate).

    Raises
    ------
    RotbeamInputError
        If `threshold` is not a number in (0, 1) or `criterion` is not an observable's name.
    """
    th = check_threshold(threshold)
    name = criterion_name(criterion)
    scene = result.scene
    f0 = resonance_frequency_hz(scene.beam, scene.drive.omega_max)
    d = criterion_delta_rms(result, name)
    label = criterion_label(name)
    settle = "does not settle in the window"
    if math.isfinite(result.settling_time_s):
        settle = (f"settles below {100 * SETTLED:g} % of the peak in "
                  f"{result.settling_time_s:.3g} s")  # fmt: skip
    after = (
        f"residual vibration {result.residual_ym:.3g} L after the move ({settle}; the move "
        f"lasts {result.move_s:.3g} s, the first mode's period is {1.0 / f0:.3g} s)"
    )
    if not result.converged or not math.isfinite(d):
        ok, text = None, f"no verdict: {result.message}"
    elif d < th:
        ok, text = True, f"quasi-static is good enough: {label} {d:.3g} < {th:g}; {after}"
    else:
        ok = False
        text = f"inertia matters: {label} {d:.3g} >= {th:g}, use the dynamic model; {after}"
    return Verdict(th, d, ok, f0, math.nan, math.nan, text, name)
