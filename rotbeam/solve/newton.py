"""Newton's method with a backtracking line search on the residual's max-norm: the nonlinear
solver of the collocated periodic orbit and of the quasi-static equilibria."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .timebudget import check_deadline

#: the line search stops halving the step below this fraction of it
MIN_STEP_FRACTION = 1e-3


@dataclass
class NewtonResult:
    """Where Newton stopped and why."""

    x: np.ndarray  #: the last iterate
    residual: np.ndarray  #: its residual
    norm: float  #: max |residual|
    converged: bool
    iterations: int
    message: str


def line_search(
    residual: Callable[[np.ndarray], np.ndarray], x: np.ndarray, step: np.ndarray, norm: float
) -> tuple[float, np.ndarray, np.ndarray, float]:
    """Halve the step until the residual's max-norm falls below `norm`.

    Parameters
    ----------
    residual : callable
        x -> residual, any shape.
    x, step : numpy.ndarray
        The iterate and the Newton step.
    norm : float
        max |residual(x)|.

    Returns
    -------
    t : float
        The fraction of the step taken (down to MIN_STEP_FRACTION, where it is taken whatever
        the residual).
    x_new, r_new : numpy.ndarray
        x + t step and its residual.
    norm_new : float
        max |r_new|.
    """
    t = 1.0
    while True:
        xt = x + t * step
        rt = residual(xt)
        nt = float(np.max(np.abs(rt)))
        if np.isfinite(nt) and (nt < norm or t < MIN_STEP_FRACTION):
            return t, xt, rt, nt
        t *= 0.5


def newton(
    residual: Callable[[np.ndarray], np.ndarray],
    direction: Callable[[np.ndarray, np.ndarray], np.ndarray],
    x: np.ndarray,
    rtol: float,
    maxiter: int,
) -> NewtonResult:
    """Damped Newton: steps from `direction`, each shortened by `line_search`.

    Parameters
    ----------
    residual : callable
        x -> r.
    direction : callable
        (x, r) -> the Newton step (J^-1 (-r), exactly or inexactly); may raise
        numpy.linalg.LinAlgError or ValueError for a singular Jacobian.
    x : numpy.ndarray
        The start.
    rtol : float
        Converged when the step taken is at most rtol times max |x|.
    maxiter : int
        Most Newton steps.

    Returns
    -------
    NewtonResult

    Raises
    ------
    OutOfTime
        When a time budget watches the caller (`rotbeam.solve.timebudget.TimeBudget.watch`)
        and is spent before a step.
    """
    r = residual(x)
    norm = float(np.max(np.abs(r)))
    if norm == 0.0:
        return NewtonResult(x, r, norm, True, 0, "exact")
    for it in range(1, maxiter + 1):
        check_deadline()
        try:
            step = direction(x, r)
        except (np.linalg.LinAlgError, ValueError):
            return NewtonResult(x, r, norm, False, it, "singular Jacobian")
        t, x, r, norm = line_search(residual, x, step, norm)
        if not np.isfinite(norm):
            return NewtonResult(x, r, norm, False, it, "residual not finite")
        scale = max(float(np.max(np.abs(x))), 1e-300)
        if float(np.max(np.abs(t * step))) <= rtol * scale:
            return NewtonResult(x, r, norm, True, it, f"converged in {it} iterations")
    return NewtonResult(x, r, norm, False, maxiter, "no convergence")
