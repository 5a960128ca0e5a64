"""The engineer's question for one scene: is the quasi-static answer good enough here?

`judge` gives the full model's verdict (Delta RMS against a threshold, the paper's criterion)
and the linear estimate f_d* ~ c_0 f_0 of where the boundary lies; `critical` finds f_d* of the
full model at one speed by root finding started at that estimate (`rotbeam critical`).  The
criterion, the estimate, its lag branch for overdamped beams and the search: docs/model.md, "The
verdict and the linear estimate of f_d*".  The verdict's figure is `rotbeam.report.verdict_plot`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace

from ..config.checks import check_threshold
from ..config.errors import RotbeamInputError
from ..model.modes import damping_ratio, resonance_frequency_hz
from ..model.params import Beam, Drive
from ..model.secondorder import c0_root
from ..runs.move import SETTLED, MoveResult
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
    fd_star_estimate_hz: float  #: c0 f0, or the lag-branch estimate where c0 does not exist
    text: str  #: one line for a reader

    def as_dict(self) -> dict[str, float | bool | str | None]:
        """The verdict as JSON-ready fields (part of `rotbeam simulate --json`).

        Returns
        -------
        dict
            ``threshold``, ``quasistatic_ok``, ``f0_hz`` [Hz], ``c0`` (dimensionless),
            ``fd_star_estimate_hz`` [Hz] and ``verdict`` (the one-line text).  Delta RMS is not
            repeated here: the scene's summary carries it.
        """
        return {
            "threshold": self.threshold,
            "quasistatic_ok": self.quasistatic_ok,
            "f0_hz": self.f0_hz,
            "c0": self.c0,
            "fd_star_estimate_hz": self.fd_star_estimate_hz,
            "verdict": self.text,
        }


def judge(result: SceneResult, threshold: float = 0.10) -> Verdict:
    """The verdict of the full model on one scene, and the linear estimate of the boundary.

    Quasi-static is good enough where Delta RMS < `threshold`; a dynamic run without a steady
    state gives no verdict.  The linear estimate f_d* = c_0 f_0 (or the lag branch for overdamped
    beams) tells how far from the boundary the scene's f_d lies (docs/model.md, "The verdict and
    the linear estimate of f_d*").

    Parameters
    ----------
    result : SceneResult
        The simulated scene (`rotbeam.runs.scene.simulate`).
    threshold : float
        The Delta RMS threshold, dimensionless, in (0, 1); 0.10 is the paper's.

    Returns
    -------
    Verdict
        The answer (`quasistatic_ok`: True, False or None), f_0 [Hz], c_0, the estimate of f_d*
        [Hz] and one line of text.

    Raises
    ------
    RotbeamInputError
        If `threshold` is not a number in (0, 1).
    """
    th = check_threshold(threshold)
    beam, drive = result.scene.beam, result.scene.drive
    f0 = resonance_frequency_hz(beam, drive.omega_max)
    c0, ratio, branch = linear_estimate(damping_ratio(beam), th)
    k = dominant_harmonic(drive)
    if k > 1:  # harmonic k meets the first mode first
        ratio, branch = ratio / k, f"{branch} / {k} (harmonic {k} has the largest Euler load)"
    where = f"f_d / f_0 = {drive.f_d / f0:.3g}; linear estimate f_d* = {ratio * f0:.3g} Hz{branch}"
    d = result.delta_rms
    if not result.converged or not math.isfinite(d):
        ok = None
        text = f"no verdict: the dynamic run reached no steady state ({where})"
    elif d < th:
        ok = True
        text = f"quasi-static is good enough: Delta RMS {d:.3g} < {th:g} ({where})"
    else:
        ok = False
        text = f"inertia matters: Delta RMS {d:.3g} >= {th:g}, use the dynamic model ({where})"
    return Verdict(th, d, ok, f0, c0, ratio * f0, text)


def linear_estimate(zeta: float, threshold: float) -> tuple[float, float, str]:
    """The linear estimate of f_d* / f_0 at a damping ratio: App. E's c_0, or the lag branch.

    c_0 is the first root of the canonical damped oscillator's Delta RMS; a beam too damped for
    it crosses where its response lags the static one by the threshold (docs/model.md, "The
    verdict and the linear estimate of f_d*").

    Parameters
    ----------
    zeta : float
        Damping ratio of the first mode, dimensionless, >= 0.
    threshold : float
        The Delta RMS threshold, dimensionless, in (0, 1).

    Returns
    -------
    c0 : float
        App. E's c_0 (dimensionless), NaN where no root exists.
    ratio : float
        The ratio f_d* / f_0 to use: c_0, or the lag branch's root.
    note : str
        " = c_0 f_0", or a note naming the lag branch, for the verdict's text.
    """
    try:
        c0 = c0_root(zeta, threshold)
        return c0, c0, " = c_0 f_0"
    except RotbeamInputError:  # too damped to exceed the static response: where it lags it
        return math.nan, _lag_ratio(zeta, threshold), f", where the response lags (zeta {zeta:.3g})"


def _lag_ratio(zeta: float, threshold: float) -> float:
    """Where the canonical oscillator's response falls below its static one by the threshold:
    sqrt((1 - c^2)^2 + (2 zeta c)^2) = 1 + threshold, i.e. c^4 - 2 B c^2 + 1 - (1 + t)^2 = 0 with
    B = 1 - 2 zeta^2 (the |.| branch of App. E's Delta RMS, the one overdamped beams cross)."""
    B = 1.0 - 2.0 * zeta * zeta
    C = 1.0 - (1.0 + threshold) ** 2  # < 0: one positive root in c^2
    return (
        math.sqrt(B + math.sqrt(B * B - C))
        if B >= 0
        else math.sqrt(-C / (-B + math.sqrt(B * B - C)))
    )


class _NoSteadyState(Exception):
    """A run of the f_d* search reached no steady state: the search stops and says why."""


@dataclass(frozen=True)
class Critical:
    """The drive frequency f_d* at which Delta RMS reaches the threshold, at one rotation speed.

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

    def as_dict(self) -> dict[str, object]:
        """The search as JSON-ready fields (`rotbeam critical --json`).

        Returns
        -------
        dict
            ``found``, ``f_d_star`` [Hz], ``threshold``, ``f0_hz`` [Hz], ``estimate_hz`` [Hz],
            ``seconds`` [s], ``message``, ``c`` = f_d* / f_0 (dimensionless), ``evaluations``
            (full-model runs) and ``visited`` ([f_d Hz, Delta RMS] per run, in order).
        """
        out = {k: getattr(self, k) for k in ("found", "f_d_star", "threshold", "f0_hz",
                                             "estimate_hz", "seconds", "message")}  # fmt: skip
        out["c"] = self.f_d_star / self.f0_hz
        out["evaluations"] = len(self.visited)
        out["visited"] = [list(v) for v in self.visited]
        return out


#: Bracket search: steps of this factor in f_d from the linear estimate, at most MAX_STEPS each way.
BRACKET_FACTOR = 1.25
MAX_STEPS = 12


class _Excess:
    """Delta RMS - threshold of the full model at the scene's speed, as a function of f_d.  Each
    f_d runs once (brentq evaluates the bracket ends again) and the last orbit seeds the next
    collocation; a run without a steady state, or the time budget spent, raises _NoSteadyState."""

    def __init__(
        self,
        scene: Scene,
        th: float,
        time_budget: TimeBudget,
        progress: Callable[[], None] | None = None,
    ) -> None:
        self.scene, self.th, self.progress = scene, th, progress
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
            if not res.converged or not math.isfinite(res.delta_rms):
                raise _NoSteadyState(
                    f"no steady state at f_d = {f_d:.4g} Hz: {res.dynamic.message}"
                )
            orbit = res.dynamic.periodic
            self.guess = orbit.theta.T if orbit is not None and orbit.converged else None
            self.seen[f_d] = res.delta_rms
            if self.progress is not None:
                self.progress()
        return self.seen[f_d] - self.th


def _bracket(
    excess: Callable[[float], float], f: float, g: float, th: float
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
    return (f"Delta RMS stays {side} {th:g} from {start:.4g} Hz to {f:.4g} Hz ({MAX_STEPS} "
            f"steps of x{step:.3g})")  # fmt: skip


def critical_start_hz(scene: Scene, threshold: float = 0.10) -> float:
    """Where `critical` starts: the linear estimate of f_d* [Hz] (`linear_estimate` times f_0
    at |Omega_0| + a); `rotbeam critical --effects auto` budgets the effects here.

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
        If `threshold` is not a number in (0, 1).
    """
    beam, drive = scene.beam, scene.drive
    f0 = resonance_frequency_hz(beam, drive.omega_max)
    return _linear_start(beam, check_threshold(threshold), f0) / dominant_harmonic(drive)


def dominant_harmonic(drive: Drive) -> int:
    """The harmonic of a periodic drive with the largest Euler load: where the f_d* search starts.

    Harmonic k puts an Euler load of amplitude proportional to k |a_k| at k f_d, so it meets
    the first mode at f_d = f_0 / k; the one with the largest k |a_k| sets the linear estimate
    c_0 f_0 / k that `judge` prints and `critical` starts from (docs/model.md, "Drives").

    Parameters
    ----------
    drive : Drive
        A periodic drive: the sine, harmonics or a sampled profile (its interpolant's
        harmonics).

    Returns
    -------
    int
        k >= 1 (1 for the sine).

    Raises
    ------
    RotbeamInputError
        For a single move, which has no repetition rate and no f_d*.
    """
    if drive.move is not None:
        raise RotbeamInputError("a single move has no repetition rate: no f_d* to find")
    terms = drive.law(1.0).terms
    return max(terms, key=lambda t: abs(t[1]) * t[0])[0] if terms else 1


def _linear_start(beam: Beam, threshold: float, f0: float) -> float:
    """App. E's c_0 (or the lag branch) at the beam's zeta, times f_0 [Hz]."""
    return linear_estimate(damping_ratio(beam), threshold)[1] * f0


def critical(
    scene: Scene,
    threshold: float = 0.10,
    rtol: float = 1e-3,
    progress: Callable[[], None] | None = None,
    time_budget: TimeBudget | None = None,
) -> Critical:
    """f_d* [Hz]: the drive frequency at which Delta RMS of the full model reaches `threshold`,
    at the scene's speed and amplitude, by root finding instead of a dense scan.

    Starts at the linear estimate (App. E's c_0 f_0, within a few per cent on the reference
    beam, or the lag branch for overdamped beams: `linear_estimate`), steps by BRACKET_FACTOR
    until Delta RMS - threshold changes sign, then runs brentq to a relative tolerance `rtol`
    in f_d.  This is the crossing nearest the estimate; it is the paper's first crossing where
    Delta RMS rises monotonically below it.  A run without a steady state, or the time budget
    spent, ends the search with found = False and its reason.

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

    Returns
    -------
    Critical
        f_d* [Hz] and ``found = True``, or NaN, ``found = False`` and the reason in ``message``;
        with f_0, the start, every run made and the wall time.

    Raises
    ------
    RotbeamInputError
        If `threshold` is not in (0, 1) or `rtol` not a float in [1e-8, 0.1].
    """
    from scipy.optimize import brentq

    th = check_threshold(threshold)
    if not (isinstance(rtol, float) and 1e-8 <= rtol <= 0.1):
        raise RotbeamInputError(f"rtol must be in [1e-8, 0.1], got {rtol!r}")
    t0 = time.perf_counter()
    beam, drive = scene.beam, scene.drive
    f0 = resonance_frequency_hz(beam, drive.omega_max)
    start = estimate = _linear_start(beam, th, f0) / dominant_harmonic(drive)
    excess = _Excess(scene, th, time_budget or TimeBudget(scene.numerics.max_seconds), progress)

    def done(found: bool, f: float, msg: str) -> Critical:
        visited = list(excess.seen.items())
        return Critical(found, f, th, f0, estimate, visited, time.perf_counter() - t0, msg)

    try:
        g = excess(start)
        if g == 0.0:
            return done(True, start, "Delta RMS equals the threshold at the start")
        bracket = _bracket(excess, start, g, th)
        if isinstance(bracket, str):
            return done(False, math.nan, bracket)
        lo, hi = bracket
        root = brentq(excess, lo, hi, rtol=rtol, xtol=1e-12 * hi)
    except _NoSteadyState as exc:
        return done(False, math.nan, str(exc))
    return done(True, float(root), f"brentq in [{lo:.4g}, {hi:.4g}] Hz to rtol {rtol:g}")


def judge_move(result: MoveResult, threshold: float = 0.10) -> Verdict:
    """The verdict on a single move: the same threshold on Delta RMS over the move, with the
    size of the vibration it leaves behind.

    Parameters
    ----------
    result : MoveResult
        The move, simulated (`rotbeam.runs.move.simulate_move`).
    threshold : float
        Delta RMS below which quasi-static is good enough, in (0, 1).

    Returns
    -------
    Verdict
        f0_hz is the first in-plane frequency at the move's largest speed; c0 and the estimate
        of f_d* are NaN (a move has no repetition rate).
    """
    th = check_threshold(threshold)
    scene = result.scene
    f0 = resonance_frequency_hz(scene.beam, scene.drive.omega_max)
    d = result.delta_rms
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
        ok, text = True, f"quasi-static is good enough: Delta RMS {d:.3g} < {th:g}; {after}"
    else:
        ok = False
        text = f"inertia matters: Delta RMS {d:.3g} >= {th:g}, use the dynamic model; {after}"
    return Verdict(th, d, ok, f0, math.nan, math.nan, text)
