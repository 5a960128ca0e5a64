r"""Largest Lyapunov exponent and stroboscopic (Poincare) samples of a trajectory.

Benettin's method: the state and one tangent vector are integrated together over intervals of
one drive period, the tangent renormalised after each and its log growth accumulated.  Beside
the running mean from the first interval, which keeps a transient the run began in, the result
gives the mean growth over the second half of the intervals (`LyapunovResult.late`).  Method
and checks: docs/stability.md, "When there is no stable periodic state".
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .ivp import IvpInterval


@dataclass
class LyapunovResult:
    """Benettin's estimate of the largest Lyapunov exponent, its convergence, and the
    stroboscopic section of the run.  Rates are per unit of the system's time (per unit tau,
    dimensionless, for the beam: divide by T for 1/s)."""

    exponent: float  #: largest Lyapunov exponent (per unit of the system's time)
    spread: float  #: max - min of the running estimate over the last half of the intervals
    intervals: int  #: intervals integrated (fewer than asked when stopped early)
    interval: float  #: length of one interval (the drive period)
    running: np.ndarray  #: estimate after each interval
    section: np.ndarray  #: (intervals + 1, dim) states at t0 + k T (stroboscopic section)
    seconds: float  #: wall time of the run [s]
    message: str = ""  #: why it stopped early, else the number of intervals
    samples: list[np.ndarray] = field(default_factory=list)  #: per interval, (k, dim) states
    late: float = math.nan  #: mean growth rate over the second half of the intervals
    late_spread: float = math.inf  #: |third quarter's rate - fourth quarter's|


#: one interval of a trajectory: (ta, tb, y at ta, t_eval or None) -> (y at tb, the first half
#: of y, the state, at t_eval[:-1] as columns or None, '' or why the step failed)
IntervalStep = Callable[
    [float, float, np.ndarray, "np.ndarray | None"], "tuple[np.ndarray, np.ndarray | None, str]"
]


def largest_lyapunov(
    rhs: Callable[[float, np.ndarray], np.ndarray] | None,
    jac: Callable[[float, np.ndarray], np.ndarray] | None,
    z0: np.ndarray,
    interval: float,
    intervals: int,
    t0: float = 0.0,
    method: str = "Radau",
    rtol: float = 1e-8,
    atol: float | np.ndarray = 1e-10,
    samples_per_interval: int = 0,
    deadline: float | None = None,
    v0: np.ndarray | None = None,
    progress: Callable[[int], None] | None = None,
    stepper: IntervalStep | None = None,
) -> LyapunovResult:
    """Benettin's estimate of the largest Lyapunov exponent of z' = f(t, z) from z0 at t0.

    The state and one tangent vector are integrated together (`tangent_system`), one
    `rotbeam.solve.ivp.IvpInterval` call per interval; after each interval the tangent is
    renormalised and its log growth kept.  Never raises for a solver failure: the result's
    message says where it stopped.

    Parameters
    ----------
    rhs : callable or None
        rhs(t, z) -> f, shape (dim,); None with a `stepper`, which carries its own.
    jac : callable or None
        jac(t, z) -> df/dz, shape (dim, dim); None with a `stepper`.
    z0 : numpy.ndarray
        Initial state, shape (dim,).
    interval : float
        Length of one interval (the drive period), in the system's time unit.
    intervals : int
        Number of intervals K.
    t0 : float
        Time at z0.
    method : str
        The scipy solver (`IvpInterval`); Radau, BDF and LSODA get the Jacobian of the
        augmented system.
    rtol : float
        Relative tolerance of the stepper.
    atol : float or numpy.ndarray
        Absolute tolerance of the state, scalar or shape (dim,); the tangent's is 1e-10.
    samples_per_interval : int
        With m > 0, the states at m equispaced instants of every interval are kept (for
        spectra), shape (m, dim) each.
    deadline : float or None
        A `time.perf_counter` value after which the run stops at the end of an interval.
    v0 : numpy.ndarray or None
        The initial tangent, shape (dim,) (normalised here); None: a fixed pseudo-random one.
    progress : callable or None
        progress(k) after the k-th interval.
    stepper : callable or None
        What integrates the state and the tangent over one interval (`IntervalStep`), e.g.
        a `rotbeam.solve.stepping.PeriodStepper`'s `tangent`; it then replaces `rhs`, `jac`,
        `method`, `rtol` and `atol`.  None: an `IvpInterval` with `method` on
        `tangent_system`.

    Returns
    -------
    LyapunovResult
        The exponent (running mean after the last interval), its spread, the late rate, the
        section z(t0 + k interval) and the samples (`benettin_result`).
    """
    start = time.perf_counter()
    z = np.asarray(z0, dtype=float).copy()
    d = z.size
    rng = np.random.default_rng(12345)
    v = rng.standard_normal(d) if v0 is None else np.asarray(v0, dtype=float).copy()
    v /= np.linalg.norm(v)
    if stepper is None:
        atol = np.broadcast_to(np.asarray(atol, dtype=float), (d,))
        aug, aug_jac = tangent_system(rhs, jac, d)
        implicit = method in ("Radau", "BDF", "LSODA")
        stepper = IvpInterval(aug, method, rtol, np.concatenate([atol, np.full(d, 1e-10)]),
                              aug_jac if implicit else None)  # fmt: skip
    logs, section, samples = [], [z.copy()], []
    msg = ""
    for k in range(intervals):
        ta = t0 + k * interval
        t_eval = None
        if samples_per_interval:
            t_eval = ta + np.arange(samples_per_interval) * interval / samples_per_interval
            t_eval = np.append(t_eval, ta + interval)
        y, ys, why = stepper(ta, ta + interval, np.concatenate([z, v]), t_eval)
        if why or not np.all(np.isfinite(y)):
            msg = f"integration failed in interval {k + 1}: {why or 'not finite'}"
            break
        z, v = y[:d], y[d:]
        g = float(np.linalg.norm(v))
        logs.append(math.log(g))
        v = v / g
        section.append(z.copy())
        if samples_per_interval:
            samples.append(ys)
        if progress is not None:
            progress(k + 1)
        if deadline is not None and time.perf_counter() > deadline:
            msg = f"stopped by the time budget after {k + 1} of {intervals} intervals"
            break
    return benettin_result(logs, interval, section, samples, time.perf_counter() - start, msg)


def tangent_system(rhs: Callable, jac: Callable, d: int) -> tuple[Callable, Callable]:
    """The state and one tangent vector as one system, y = (z, v): y' = (f(t, z), J(t, z) v).

    The Jacobian given to the implicit steppers is diag(J, J): it leaves out d(J v)/dz, which
    changes only how fast their simplified Newton converges, not the accuracy (the error control
    sees the exact right-hand side).

    Parameters
    ----------
    rhs : callable
        rhs(t, z) -> f, shape (d,).
    jac : callable
        jac(t, z) -> df/dz, shape (d, d).
    d : int
        Dimension of the state.

    Returns
    -------
    aug : callable
        aug(t, y) -> y', shape (2 d,).
    aug_jac : callable
        aug_jac(t, y) -> diag(J, J), shape (2 d, 2 d).
    """

    def aug(t, y):
        return np.concatenate([rhs(t, y[:d]), jac(t, y[:d]) @ y[d:]])

    def aug_jac(t, y):
        J = jac(t, y[:d])
        A = np.zeros((2 * d, 2 * d))
        A[:d, :d] = J
        A[d:, d:] = J
        return A

    return aug, aug_jac


def benettin_result(
    logs: list[float], interval: float, section: list, samples: list, seconds: float, msg: str
) -> LyapunovResult:
    """The result of a Benettin run from the log growth of the tangent over each interval.

    Parameters
    ----------
    logs : list of float
        log |v_k| over each of the K intervals (the tangent renormalised after each).
    interval : float
        Length of one interval.
    section : list of numpy.ndarray
        The states at the start and at the end of every interval, K + 1 of shape (dim,).
    samples : list of numpy.ndarray
        Per-interval samples, shape (m, dim) each (may be empty).
    seconds : float
        Wall time of the run [s].
    msg : str
        Why the run stopped early ('' when it did not).

    Returns
    -------
    LyapunovResult
        The running estimate (mean log growth per unit time after each interval), the exponent
        (its last value), its spread max - min over the second half of the intervals (inf with
        fewer than 2), and the late rate and its spread (`late_rate`).
    """
    K = len(logs)
    running = np.cumsum(logs) / (interval * np.arange(1, K + 1)) if K else np.array([])
    half = running[K // 2 :] if K else np.array([math.nan])
    late, late_spread = late_rate(np.asarray(logs, dtype=float), interval)
    return LyapunovResult(
        exponent=float(running[-1]) if K else math.nan,
        spread=float(np.max(half) - np.min(half)) if K >= 2 else math.inf,
        intervals=K,
        interval=interval,
        running=running,
        section=np.array(section),
        seconds=seconds,
        message=msg or f"{K} intervals",
        samples=samples,
        late=late,
        late_spread=late_spread,
    )


def late_rate(logs: np.ndarray, interval: float) -> tuple[float, float]:
    """The growth rate of the tangent once the first half of the run is discarded as transient.

    Parameters
    ----------
    logs : numpy.ndarray
        log |v_k| over each interval, shape (K,).
    interval : float
        Length of one interval.

    Returns
    -------
    rate : float
        Mean log growth per unit time over the second half of the intervals (nan with fewer
        than four intervals).
    spread : float
        |rate over the third quarter - rate over the fourth| (inf with fewer than four).
    """
    K = logs.size
    if K < 4:
        return math.nan, math.inf
    half, quarter = logs[K // 2 :], (K - K // 2) // 2
    rate = float(np.mean(half)) / interval
    q3, q4 = half[:quarter], half[quarter:]
    return rate, abs(float(np.mean(q3)) - float(np.mean(q4))) / interval
