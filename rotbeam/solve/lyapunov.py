r"""Largest Lyapunov exponent and stroboscopic (Poincare) samples of a trajectory.

Benettin's method: the state z and one tangent vector v are integrated together,
z' = f(t, z), v' = J(t, z) v, over intervals of length T (the drive period for a driven
system); after each interval v is renormalised and log |v| accumulated:
lambda ~ (1 / (K T)) sum_k log |v_k|.  The stiff stepper (Radau) gets the block-diagonal
diag(J, J) as its Jacobian: that ignores d(J v)/dz, which changes only how fast its simplified
Newton converges, not the accuracy (the error control sees the exact right-hand side).
Convergence is reported as the spread of the running estimate over the last half of the run
(max - min), an honest error bar for the finite-time estimate.

The running estimate averages from the first interval on, so a transient that the run started
in (a chaotic transient before the motion settles) stays in it and decays only like 1 / K.
`late` is the mean growth over the second half of the intervals alone, and `late_spread` the
difference of its third and fourth quarters: what the motion does once the first half is
discarded as further transient.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np


@dataclass
class LyapunovResult:
    exponent: float  #: largest Lyapunov exponent (per unit of the system's time)
    spread: float  #: max - min of the running estimate over the last half of the intervals
    intervals: int
    interval: float
    running: np.ndarray  #: estimate after each interval
    section: np.ndarray  #: (intervals + 1, dim) states at t0 + k T (stroboscopic section)
    seconds: float
    message: str = ""
    samples: list[np.ndarray] = field(default_factory=list)  #: optional per-interval samples
    late: float = math.nan  #: mean growth rate over the second half of the intervals
    late_spread: float = math.inf  #: |third quarter's rate - fourth quarter's|


def largest_lyapunov(
    rhs: Callable[[float, np.ndarray], np.ndarray],
    jac: Callable[[float, np.ndarray], np.ndarray],
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
) -> LyapunovResult:
    """Benettin's estimate over `intervals` intervals of length `interval` from z0 at t0.

    With samples_per_interval > 0 the states at that many equispaced instants of every interval
    are kept (for spectra).  `deadline` (time.perf_counter) stops early; the result says so.
    `progress(k)` is called after the k-th interval.
    """
    from scipy.integrate import solve_ivp  # here: only a time-stepped run needs it

    start = time.perf_counter()
    z = np.asarray(z0, dtype=float).copy()
    d = z.size
    rng = np.random.default_rng(12345)
    v = rng.standard_normal(d) if v0 is None else np.asarray(v0, dtype=float).copy()
    v /= np.linalg.norm(v)
    atol = np.broadcast_to(np.asarray(atol, dtype=float), (d,))
    aug, aug_jac = tangent_system(rhs, jac, d)
    kwargs = {"jac": aug_jac} if method in ("Radau", "BDF", "LSODA") else {}
    logs, section, samples = [], [z.copy()], []
    msg = ""
    for k in range(intervals):
        ta = t0 + k * interval
        t_eval = None
        if samples_per_interval:
            t_eval = ta + np.arange(samples_per_interval) * interval / samples_per_interval
            t_eval = np.append(t_eval, ta + interval)
        sol = solve_ivp(aug, (ta, ta + interval), np.concatenate([z, v]), method=method,
                        rtol=rtol, atol=np.concatenate([atol, np.full(d, 1e-10)]),
                        t_eval=t_eval, **kwargs)  # fmt: skip
        if sol.status < 0 or not np.all(np.isfinite(sol.y[:, -1])):
            msg = f"integration failed in interval {k + 1}: {sol.message}"
            break
        z, v = sol.y[:d, -1], sol.y[d:, -1]
        g = float(np.linalg.norm(v))
        logs.append(math.log(g))
        v = v / g
        section.append(z.copy())
        if samples_per_interval:
            samples.append(sol.y[:d, :-1])
        if progress is not None:
            progress(k + 1)
        if deadline is not None and time.perf_counter() > deadline:
            msg = f"stopped by the time budget after {k + 1} of {intervals} intervals"
            break
    return benettin_result(logs, interval, section, samples, time.perf_counter() - start, msg)


def tangent_system(rhs: Callable, jac: Callable, d: int) -> tuple[Callable, Callable]:
    """The state and one tangent vector together, y = (z, v): y' = (f(t, z), J(t, z) v), and
    the Jacobian of that system (block diagonal, J twice) for the implicit steppers."""

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
    """The running estimate (mean log growth per unit time after each interval), the exponent
    (its last value) and its spread over the second half of the intervals (the convergence)."""
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
    """Mean log growth per unit time over the second half of the intervals, and the difference
    of the rates over its two halves (the third and fourth quarters of the run); (nan, inf)
    with fewer than four intervals."""
    K = logs.size
    if K < 4:
        return math.nan, math.inf
    half, quarter = logs[K // 2 :], (K - K // 2) // 2
    rate = float(np.mean(half)) / interval
    q3, q4 = half[:quarter], half[quarter:]
    return rate, abs(float(np.mean(q3)) - float(np.mean(q4))) / interval
