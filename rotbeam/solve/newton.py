"""Newton's method, written once: the nonlinear solver of the collocated periodic orbit, the
quasi-static equilibria and the continuation of branches of orbits.

One loop (`newton`) with two steps (damped by a backtracking line search on the residual's
max-norm, or the full step) and one convergence test on the step taken (`step_converged`:
relative to max |x|, with a floor, or a weighted max-norm)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .timebudget import check_deadline

#: the line search stops halving the step below this fraction of it; a step so short that
#: still raises the residual ends Newton unless it passes the step test (over the test suite:
#: 469 of 9145 converged solves took such a step, each its last, the step test passed; 150 of
#: 198 failed solves took one and went on to fail, 3851 of their 5746 steps after it)
MIN_STEP_FRACTION = 1e-3

#: the contraction test (`newton`'s `contraction`) trusts the ratio of two steps below this, of
#: steps that each cut the residual by as much (a contraction by 10 or more a step: Newton in
#: its quadratic or its inexact-linear range, not a direction that stalls)
CONTRACTION_MAX = 0.1

#: the default floor of max |x| in the relative step test (a pure relative test)
TINY_SCALE = 1e-300


@dataclass
class NewtonResult:
    """Where Newton stopped and why."""

    x: np.ndarray  #: the last iterate
    residual: np.ndarray  #: its residual
    norm: float  #: max |residual|
    converged: bool
    iterations: int
    message: str  #: why it stopped: "exact", "converged in k iterations", or why not


def step_converged(
    step: np.ndarray,
    x: np.ndarray,
    rtol: float,
    floor: float = TINY_SCALE,
    weights: np.ndarray | None = None,
    axis: int | None = None,
) -> bool:
    """Newton's convergence test on the step taken.

    Without weights: max |step| <= rtol max(floor, max |x|); floor = 1 makes it an absolute test
    for small x.  With weights: max |weights step| <= rtol (the weights carry the scale).

    Parameters
    ----------
    step : numpy.ndarray
        The step taken.
    x : numpy.ndarray
        The iterate after it, the shape of `step`.
    rtol : float
        The tolerance.
    floor : float
        The least scale of x in the relative test.
    weights : numpy.ndarray or None
        The weights of the weighted test, broadcast against `step`; None: the relative test.
    axis : int or None
        None: one test over all of x; an axis: one test per slice along it (an independent
        system each, e.g. -1 for the rows of a batch), every one of which must pass.

    Returns
    -------
    bool
        Whether the step is small enough.
    """
    if weights is not None:
        return bool(np.all(np.max(np.abs(step * weights), axis=axis) <= rtol))
    scale = np.maximum(np.max(np.abs(x), axis=axis), floor)
    return bool(np.all(np.max(np.abs(step), axis=axis) <= rtol * scale))


def evaluate(
    residual: Callable[[np.ndarray], np.ndarray], x: np.ndarray
) -> tuple[np.ndarray, float]:
    """The residual at x and its max-norm; a residual that raises ValueError (x outside its
    domain, e.g. a parameter out of range) counts as not finite.

    Parameters
    ----------
    residual : callable
        x -> residual, any shape.
    x : numpy.ndarray
        Where to evaluate it.

    Returns
    -------
    r : numpy.ndarray
        The residual (NaN, the shape of x, where it raised).
    norm : float
        max |r| (inf where it raised).
    """
    try:
        r = residual(x)
    except ValueError:
        return np.full(np.shape(x), np.nan), np.inf
    return r, float(np.max(np.abs(r)))


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
        rt, nt = evaluate(residual, xt)
        if np.isfinite(nt) and (nt < norm or t < MIN_STEP_FRACTION):
            return t, xt, rt, nt
        t *= 0.5


def full_step(
    residual: Callable[[np.ndarray], np.ndarray], x: np.ndarray, step: np.ndarray, norm: float
) -> tuple[float, np.ndarray, np.ndarray, float]:
    """The whole Newton step, whatever the residual there (the undamped step).

    Parameters
    ----------
    residual : callable
        x -> residual, any shape.
    x, step : numpy.ndarray
        The iterate and the Newton step.
    norm : float
        max |residual(x)| (unused: the signature of `line_search`).

    Returns
    -------
    t : float
        1.
    x_new, r_new : numpy.ndarray
        x + step and its residual.
    norm_new : float
        max |r_new|.
    """
    xt = x + step
    rt, nt = evaluate(residual, xt)
    return 1.0, xt, rt, nt


def newton(
    residual: Callable[[np.ndarray], np.ndarray],
    direction: Callable[[np.ndarray, np.ndarray], np.ndarray],
    x: np.ndarray,
    rtol: float,
    maxiter: int,
    damped: bool = True,
    floor: float = TINY_SCALE,
    weights: np.ndarray | None = None,
    axis: int | None = None,
    contraction: bool = False,
) -> NewtonResult:
    """Newton's method: steps from `direction`, damped by `line_search` or taken whole, until the
    step taken passes `step_converged` (or, with `contraction`, the step it predicts next).

    Parameters
    ----------
    residual : callable
        x -> r; may raise ValueError outside its domain (then r counts as not finite).
    direction : callable
        (x, r) -> the Newton step (J^-1 (-r), exactly or inexactly); may raise
        numpy.linalg.LinAlgError or ValueError for a singular Jacobian.
    x : numpy.ndarray
        The start.
    rtol : float
        The tolerance of the step test (`step_converged`).
    maxiter : int
        Most Newton steps.
    damped : bool
        True: each step shortened by `line_search` until the residual's max-norm falls; False:
        the full step (`full_step`).
    floor : float
        The least scale of x in the relative step test: the step against rtol max(floor, |x|).
    weights : numpy.ndarray or None
        The weights of a weighted step test, max |weights step| <= rtol; None: the relative test.
    axis : int or None
        The step test per slice along this axis (a batch of independent systems); None: one.
    contraction : bool
        Also stop where the next step, predicted from the contraction of the last two, passes
        the test: after two whole steps that each cut the residual to CONTRACTION_MAX of what it
        was or less, theta = max |step| over the step before's, and the iterate's error is
        estimated as theta / (1 - theta) times the step taken (Hairer and Wanner, Solving ODEs
        II, IV.8), for theta < CONTRACTION_MAX. This saves the last step, which only confirms an
        iterate already within rtol (one of the three steps from a sweep's neighbouring orbit).
        Only with axis None.

    Returns
    -------
    NewtonResult
        The last iterate, its residual, whether the step test passed and why it stopped: the
        message is "exact" (a zero residual at the start), "converged in k iterations" (with
        "(contraction theta)" where the contraction test stopped it),
        "residual not finite" (at the start or after a step), "iterate not finite", "singular
        Jacobian" (`direction` raised), "line search failed" (a damped step shortened to
        MIN_STEP_FRACTION that still raised the residual, short of the step test: Newton has
        lost its way, and the steps left would be spent in vain) or "no convergence" (maxiter
        steps).

    Raises
    ------
    OutOfTime
        When a time budget watches the caller (`rotbeam.solve.timebudget.TimeBudget.watch`)
        and is spent before a step.
    """
    step_along = line_search if damped else full_step
    r, norm = evaluate(residual, x)
    if norm == 0.0:
        return NewtonResult(x, r, norm, True, 0, "exact")
    if not np.isfinite(norm):
        return NewtonResult(x, r, norm, False, 0, "residual not finite")
    if contraction and axis is not None:
        raise ValueError("newton: the contraction test is for one system (axis None)")
    last = None  # max |step| of the last whole step that cut the residual tenfold
    for it in range(1, maxiter + 1):
        check_deadline()
        try:
            step = direction(x, r)
        except (np.linalg.LinAlgError, ValueError):
            return NewtonResult(x, r, norm, False, it, "singular Jacobian")
        before = norm
        t, x, r, norm = step_along(residual, x, step, norm)
        if not np.isfinite(norm):
            return NewtonResult(x, r, norm, False, it, "residual not finite")
        if not np.all(np.isfinite(x)):  # a residual may stay finite there (arctan at inf)
            return NewtonResult(x, r, norm, False, it, "iterate not finite")
        if step_converged(t * step, x, rtol, floor, weights, axis):
            return NewtonResult(x, r, norm, True, it, f"converged in {it} iterations")
        if t < MIN_STEP_FRACTION and not norm < before:
            return NewtonResult(x, r, norm, False, it, "line search failed")
        # a whole step that cut the residual tenfold (not one of a direction that stalled,
        # e.g. GMRES short of its tolerance, whose steps shrink while the residual does not)
        whole = contraction and t == 1.0 and norm < CONTRACTION_MAX * before
        size = float(np.max(np.abs(step))) if whole else None
        if size is not None and last is not None and size < CONTRACTION_MAX * last:
            theta = size / last
            if step_converged(theta / (1.0 - theta) * step, x, rtol, floor, weights):
                why = f"converged in {it} iterations (contraction {theta:.1e})"
                return NewtonResult(x, r, norm, True, it, why)
        last = size
    return NewtonResult(x, r, norm, False, maxiter, "no convergence")
