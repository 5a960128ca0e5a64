r"""What the beam does when there is no stable periodic steady state: classification of the
time-stepped response.

`response_of` steps past a transient, then integrates a stroboscopic (Poincare) section with one
tangent vector (`rotbeam.solve.lyapunov`) and calls the motion periodic, subharmonic,
quasiperiodic or chaotic from the section's distances d(q) and the largest Lyapunov exponent
over the section's second half; 16 samples a period of y_m give its spectrum.  The
classification is as good as the run is long: the message gives the periods, the exponent's
spread and the grid.  Rules and measurements: docs/stability.md, "When there is no stable
periodic state".
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..model.base import DiscreteModel
from ..solve.lyapunov import largest_lyapunov
from ..solve.steady import initial_state
from ..solve.stepping import period_stepper
from ..solve.timebudget import TimeBudget

if TYPE_CHECKING:
    from .scene import SceneResult

RESPONSES = ("periodic", "subharmonic", "quasiperiodic", "chaotic")
#: the answer of a run too short for a class (the time budget ended it first)
UNCLASSIFIED = "unclassified"
#: section periods a class needs at least: the exponent's late rate and its spread take four
MIN_SECTION_PERIODS = 4
#: stepper tolerance of the classification run (Radau's; DOP853 runs at
#: `rotbeam.solve.stepping.EXPLICIT_TOL` times it).  At a = 3 rad/s, 7 Hz (N = 6, chaotic) the
#: tangent's growth over two periods is the same to 4e-6 (relative) with Radau at rtol 1e-5 and
#: 1e-7; the lightly damped top bending modes, rung by the large motion, set the step
#: (docs/stability.md "The response at a = 3 rad/s, 7 Hz")
RTOL = 1e-5
MAX_SUBHARMONIC = 8  #: the largest q of a subharmonic (period q P) looked for
CHAOS_MIN = 0.01  #: lambda P above which a clearly positive exponent counts as chaos
SAMPLES = 16  #: samples per period for the spectrum


@dataclass
class ResponseResult:
    """The class of a time-stepped response, with the section, spectrum and Lyapunov exponent
    it rests on (`response_of`)."""

    response: str  #: one of RESPONSES, or UNCLASSIFIED
    period_multiple: int  #: q for periodic (1) and subharmonic; 0 otherwise
    lyapunov_max: float  #: largest Lyapunov exponent over the section's second half [1/s]
    lyapunov_spread: float  #: its third quarter's rate minus its fourth's (absolute) [1/s]
    section: np.ndarray  #: (K, 2) y_m / L and its rate [1/s] at t = k / f_d
    spectrum_hz: np.ndarray  #: frequencies of `spectrum` [Hz]
    spectrum: np.ndarray  #: |FFT| of y_m (Hann window)
    peaks_hz: list[float]  #: the five largest peaks of the spectrum [Hz], largest first
    periods: int  #: transient + section periods integrated
    N: int  #: grid intervals of the run
    seconds: float  #: wall time of the run [s]
    message: str  #: the class, the run's length, grid and exponent, in words
    distances: list[float] = field(default_factory=list)  #: d(q), q = 1..MAX_SUBHARMONIC
    #: the exponent's running estimate after each section period [1/s] (its convergence)
    lyapunov_running: np.ndarray = field(default_factory=lambda: np.zeros(0))
    start: str = "quasistatic"  #: initial state of the run (`rotbeam.solve.steady.initial_state`)

    def as_dict(self) -> dict:
        """The columns a result carries (`rotbeam simulate --json`).

        Returns
        -------
        dict
            response, lyapunov_max and lyapunov_spread [1/s], period_multiple,
            response_periods, response_N, response_peaks_hz (the five largest, [Hz]) and
            response_message.
        """
        return {"response": self.response, "lyapunov_max": self.lyapunov_max,
                "lyapunov_spread": self.lyapunov_spread, "period_multiple": self.period_multiple,
                "response_periods": self.periods, "response_N": self.N,
                "response_peaks_hz": self.peaks_hz[:5],
                "response_message": self.message}  # fmt: skip


def classify(distances: list[float], lam_P: float, spread_P: float, tol: float) -> tuple[str, int]:
    """The class of a response from its section distances and its Lyapunov exponent.

    Periodic (q = 1) or subharmonic (period q P) for the smallest q with d(q) <= tol, or when
    the exponent is clearly negative (lambda P + spread P < 0: a periodic attractor still
    converging; then q minimises d); otherwise chaotic when it is clearly positive
    (lambda P - spread P > 0 and lambda P > CHAOS_MIN), else quasiperiodic.

    Parameters
    ----------
    distances : list of float
        d(q), q = 1 .. MAX_SUBHARMONIC (`section_distances`).
    lam_P : float
        The exponent times the drive period: the log growth per period.
    spread_P : float
        Its uncertainty, times the period.
    tol : float
        The largest d(q) of a periodic or subharmonic section (relative).

    Returns
    -------
    response : str
        One of RESPONSES.
    q : int
        The period multiple: 1 for periodic, q > 1 for subharmonic, 0 otherwise.
    """
    for q, d in enumerate(distances, start=1):
        if d <= tol:
            return ("periodic" if q == 1 else "subharmonic"), q
    if lam_P + spread_P < 0.0:
        q = int(np.argmin(distances)) + 1
        return ("periodic" if q == 1 else "subharmonic"), q
    if lam_P - spread_P > 0.0 and lam_P > CHAOS_MIN:
        return "chaotic", 0
    return "quasiperiodic", 0


def section_distances(section: np.ndarray, max_q: int = MAX_SUBHARMONIC) -> list[float]:
    """How far the section is from repeating after q periods, q = 1 .. max_q.

    Parameters
    ----------
    section : numpy.ndarray
        The states at whole drive periods, shape (K, dim).
    max_q : int
        The largest q.

    Returns
    -------
    list of float
        d(q): the largest |z_{j+q} - z_j| (max-norm) over the last half of the section,
        relative to the largest |z| on the whole section; inf where the last half holds no
        pair q apart.
    """
    K = section.shape[0]
    size = max(float(np.max(np.abs(section))), 1e-300)
    tail = section[K // 2 :]
    out = []
    for q in range(1, max_q + 1):
        if tail.shape[0] <= q:
            out.append(math.inf)
            continue
        out.append(float(np.max(np.abs(tail[q:] - tail[:-q]))) / size)
    return out


def _transient(stepper, z, P, periods, deadline, progress, total):
    """Step `periods` periods from z, one call of `stepper` (`rotbeam.solve.stepping`) a period
    so that the time budget (`deadline`, time.perf_counter) and `progress` are seen between
    periods: (final state, periods done, why it stopped early or '')."""
    done = 0
    for k in range(periods):
        y, why = stepper.state(k * P, (k + 1) * P, z)
        if why or not np.all(np.isfinite(y)):
            return z, done, f"transient failed in period {k + 1}: {why or 'not finite'}"
        z, done = y, k + 1
        if progress is not None:
            progress(done, total)
        if time.perf_counter() > deadline:
            return z, done, f"transient cut from {periods} periods by the time budget"
    return z, done, ""


def _spectrum(y: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray, list]:
    """Hann-windowed amplitude spectrum of y and its five largest peaks [Hz]."""
    yw = (y - y.mean()) * np.hanning(y.size)
    amp = np.abs(np.fft.rfft(yw))
    f = np.fft.rfftfreq(y.size, dt)
    inner = np.where((amp[1:-1] > amp[:-2]) & (amp[1:-1] >= amp[2:]))[0] + 1
    top = inner[np.argsort(-amp[inner])][:5]
    return f, amp, [float(f[i]) for i in top]


def response_of(
    model: DiscreteModel,
    time_scale: float,
    transient_periods: int = 100,
    section_periods: int = 100,
    max_seconds: float = 1800.0,
    rtol: float = RTOL,
    tol: float = 1e-3,
    start: str = "quasistatic",
    progress: Callable[[int, int], None] | None = None,
    time_budget: TimeBudget | None = None,
    method: str = "auto",
) -> ResponseResult:
    """Time-step the scene past its transient and classify what it settles into.

    The transient is stepped one period a call (so the budget and `progress` are seen between
    periods), then `rotbeam.solve.lyapunov.largest_lyapunov` integrates the section with one
    tangent vector; `classify` decides (docs/stability.md, "When there is no stable periodic
    state").  The stepper is `rotbeam.solve.stepping.period_stepper`'s: DOP853 while the
    steps are set by accuracy (compiled for the models its kernel covers), Radau while they
    are set by stiffness.  The absolute tolerances scale with the quasi-static response, also
    from rest.

    Parameters
    ----------
    model : DiscreteModel
        The model, its grid and its drive (dimensionless time tau in units of T).
    time_scale : float
        T [s] of the beam: rates per unit tau are divided by it to give 1/s.
    transient_periods : int
        Drive periods stepped before the section.
    section_periods : int
        Drive periods of the section (and of the Lyapunov estimate).
    max_seconds : float
        Wall-time budget [s] when `time_budget` is None: the transient gets its share
        (transient / all periods), the section the rest; the message says where the budget cut
        a phase short.  With fewer than MIN_SECTION_PERIODS section periods the response is
        UNCLASSIFIED.
    rtol : float
        Relative tolerance of the stepper.
    tol : float
        Section distance d(q) below which the motion repeats after q periods.
    start : str
        The state at tau = 0: "quasistatic", "rest" or "linear" (`initial_state`).
    progress : callable or None
        progress(done, total) after every period.
    time_budget : TimeBudget or None
        The wall-time budget shared with a command's other phases (replaces `max_seconds`).
    method : str
        "auto", "radau" or "dop853" (`rotbeam.solve.stepping.period_stepper`).

    Returns
    -------
    ResponseResult
        The class, the section of y_m / L and its rate, the spectrum, the exponent per second
        and how long the run was.

    Raises
    ------
    ValueError
        For another `start` or `method`.
    """
    if start not in ("quasistatic", "rest", "linear"):
        raise ValueError(f"start must be quasistatic, rest or linear, got {start!r}")
    time_budget = time_budget or TimeBudget(max_seconds)
    t0 = time.perf_counter()
    dl, N = model.dl, model.grid.N
    n, P, T = model.n, dl.period, time_scale
    qs, _ = initial_state(model, "quasistatic")  # the tolerances' scale, also from rest
    z = qs if start == "quasistatic" else initial_state(model, start)[0]
    atol = _atol(qs[:n], rtol, dl.omega)
    stepper = period_stepper(model, rtol, atol, method)
    total = transient_periods + section_periods
    share = time_budget.part(transient_periods / total)
    z, done, note = _transient(stepper, z, P, transient_periods, share.deadline, progress, total)
    if note.startswith("transient cut"):
        note = share.cut(f"the transient at {done} of {transient_periods} periods")
    asked = 0 if time_budget.spent() else section_periods  # no section period: no class

    def per_interval(k: int) -> None:
        if progress is not None:
            progress(done + k, total)

    ly = largest_lyapunov(None, None, z, P, asked, t0=done * P,
                          samples_per_interval=SAMPLES, deadline=time_budget.deadline,
                          progress=per_interval, stepper=stepper.tangent)  # fmt: skip
    periods = done + ly.intervals
    if ly.intervals < MIN_SECTION_PERIODS:
        return _unclassified(model, time_budget, ly, done, start, N, note, t0)
    found = _classified(model, T, P, ly, tol)
    q = found["period_multiple"]
    msg = (f"{found['response']}{f' (period {q} P)' if q > 1 else ''}: {periods} periods at "
           f"N={N} ({done} transient, from {start}, rtol {rtol:g}, {stepper.name}), largest "
           f"Lyapunov exponent "
           f"{found['lyapunov_max']:.3g} +- {found['lyapunov_spread']:.2g} 1/s (last half; "
           f"whole run {ly.exponent / T:.3g}), section distance d(1)={found['distances'][0]:.2g}"
           + (f"; {note}" if note else "")
           + (f"; {_section_note(time_budget, ly, asked)}" if ly.intervals < asked
              else ""))  # fmt: skip
    return ResponseResult(**found, periods=periods, N=N, seconds=time.perf_counter() - t0,
                          message=msg, start=start)  # fmt: skip


def _section_note(time_budget: TimeBudget, ly, asked: int) -> str:
    """Why the section is shorter than asked: the budget's cut, or the stepper's failure."""
    if "time budget" in ly.message:
        return time_budget.cut(f"the section at {ly.intervals} of {asked} periods")
    return ly.message


def _unclassified(
    model: DiscreteModel,
    time_budget: TimeBudget,
    ly,
    done: int,
    start: str,
    N: int,
    note: str,
    t0: float,
) -> ResponseResult:
    """The answer of a run the budget ended before MIN_SECTION_PERIODS section periods."""
    k = ly.intervals
    cut = (
        time_budget.cut(f"the classification after {k} section period{'s' * (k != 1)}")
        if time_budget.spent()
        else ly.message
    )
    msg = (f"{UNCLASSIFIED}: {cut} ({done} transient at N={N}, from {start}); a class needs "
           f"at least {MIN_SECTION_PERIODS} section periods"
           + (": give a larger numerics.max_seconds or a smaller response N"
              if time_budget.spent() else ""))  # fmt: skip
    if note:
        msg += f"; {note}"
    return ResponseResult(
        response=UNCLASSIFIED, period_multiple=0, lyapunov_max=math.nan,
        lyapunov_spread=math.inf, section=np.zeros((0, 2)), spectrum_hz=np.zeros(0),
        spectrum=np.zeros(0), peaks_hz=[], periods=done + k, N=N,
        seconds=time.perf_counter() - t0, message=msg, start=start,
    )  # fmt: skip


def _atol(theta_qs: np.ndarray, rtol: float, omega: float) -> np.ndarray:
    """Absolute tolerances of angles and rates: 1e-3 rtol of the quasi-static state's largest
    angle (and that times the drive's angular frequency for the rates)."""
    scale = max(float(np.max(np.abs(theta_qs))), 1e-6)
    n = theta_qs.size
    return np.concatenate([np.full(n, 1e-3 * rtol * scale),
                           np.full(n, 1e-3 * rtol * scale * omega)])  # fmt: skip


def _classified(model: DiscreteModel, T: float, P: float, ly, tol: float) -> dict:
    """What a time-stepped section (`largest_lyapunov`'s result) says: its class, Poincare
    section in y_m, spectrum and exponent (the ResponseResult fields but the run's account)."""
    n = model.n
    sec = ly.section
    dist = section_distances(sec)
    # the second half of the section only: a chaotic transient the run began in stays in the
    # running mean (rotbeam.solve.lyapunov); Benettin's full-run mean is kept as `running`
    lam, spread = (ly.late, ly.late_spread) if math.isfinite(ly.late) else (ly.exponent, ly.spread)
    response, q = classify(dist, lam * P, spread * P, tol)
    theta_s = sec[:, :n]
    y_sec = np.atleast_1d(model.midspan(theta_s))
    rates = model.beam_angles(sec[:, n:])
    yt_sec = np.atleast_1d(model.grid.midspan_rate(model.beam_angles(theta_s), rates)) / T
    theta_all = np.concatenate(ly.samples)[:, :n] if ly.samples else theta_s
    y_all = np.atleast_1d(model.midspan(theta_all))
    f, amp, peaks = _spectrum(y_all, P * T / SAMPLES)
    return {
        "response": response,
        "period_multiple": q,
        "lyapunov_max": lam / T,
        "lyapunov_spread": spread / T,
        "section": np.column_stack([y_sec, yt_sec]),
        "spectrum_hz": f,
        "spectrum": amp,
        "peaks_hz": peaks,
        "distances": dist,
        "lyapunov_running": np.asarray(ly.running, dtype=float) / T,
    }


def response_of_result(
    result: SceneResult,
    N: int = 6,
    periods: int = 100,
    progress: Callable[[int, int], None] | None = None,
    time_budget: TimeBudget | None = None,
) -> tuple[dict, ResponseResult | None]:
    """`response` and `lyapunov_max` of a simulated scene: from the multipliers of a stable
    periodic steady state (ln |mu|max per drive period), else by classifying the time-stepped
    response (`response_of` on grid N, `periods` of transient and as many classified).

    Parameters
    ----------
    result : SceneResult
        The scene's steady-state run.
    N : int
        Grid of the classification run.
    periods : int
        Its transient periods, and its classified ones.
    progress : callable or None
        progress(done, total) after every period of the classification.
    time_budget : TimeBudget or None
        The classification's wall-time budget (a command's, what its steady state left);
        None: `response_of`'s default.

    Returns
    -------
    columns : dict
        response, lyapunov_max [1/s] and, after a classification, its other fields.
    classification : ResponseResult or None
        The classification run, None for a stable periodic state.
    """
    fl = result.dynamic.floquet
    if result.converged and fl is not None:
        P = 1.0 / result.scene.drive.f_d
        lyap = math.log(fl.max_abs) / P if fl.max_abs > 0 else -math.inf
        return {"response": "periodic", "lyapunov_max": lyap}, None
    scene = result.scene
    r = response_of(scene.model(N), scene.beam.T, periods, periods, progress=progress,
                    time_budget=time_budget)  # fmt: skip
    return r.as_dict(), r
