"""The one Newton (rotbeam.solve.newton) on closed-form problems: quadratic convergence, and each
mode (damped, undamped, the weighted step test, a batch of systems) stopping for the reason its
result says."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotbeam.solve.newton import newton, step_converged


def _exp_system(c: float):
    """R(x) = exp(x) - c elementwise: root log(c), Jacobian diag(exp(x))."""

    def residual(x: np.ndarray) -> np.ndarray:
        return np.exp(x) - c

    def direction(x: np.ndarray, r: np.ndarray) -> np.ndarray:
        return -r / np.exp(x)

    return residual, direction


def _arctan():
    """R(x) = arctan(x): root 0; full Newton steps from |x| > 1.39 overshoot and diverge."""

    def residual(x: np.ndarray) -> np.ndarray:
        return np.arctan(x)

    def direction(x: np.ndarray, r: np.ndarray) -> np.ndarray:
        return -r * (1.0 + x * x)

    return residual, direction


def test_quadratic_convergence_on_a_closed_form_root():
    """exp(x) = 2 from x = 0: the error e_k = x_k - log 2 obeys e_{k+1} / e_k^2 -> 1/2 (the
    closed-form constant R'' / (2 R') at the root), each mode the same iterates."""
    residual, direction = _exp_system(2.0)
    root = math.log(2.0)
    errors = []
    for k in range(1, 7):
        res = newton(residual, direction, np.zeros(1), 0.0, k, damped=False)
        errors.append(abs(float(res.x[0]) - root))
    ratios = [errors[i + 1] / errors[i] ** 2 for i in range(len(errors) - 1) if errors[i] > 1e-6]
    assert len(ratios) >= 3 and abs(ratios[-1] - 0.5) < 0.01, (errors, ratios)
    assert all(0.1 < q < 0.6 for q in ratios) and errors[-1] <= 2e-16
    damped = newton(residual, direction, np.zeros(1), 1e-12, 30)
    undamped = newton(residual, direction, np.zeros(1), 1e-12, 30, damped=False)
    assert damped.converged and undamped.converged
    assert damped.x[0] == undamped.x[0] and damped.iterations == undamped.iterations


def test_damped_steps_reach_a_root_the_full_steps_leave():
    """arctan(x) = 0 from x = 2: the full steps diverge (|x| grows: "no convergence" in 5 steps,
    "iterate not finite" with more, where arctan is still finite), the damped ones converge and
    say in how many."""
    residual, direction = _arctan()
    full = newton(residual, direction, np.array([2.0]), 1e-12, 5, damped=False)
    assert not full.converged and full.message == "no convergence" and abs(full.x[0]) > 1e3
    with np.errstate(over="ignore", invalid="ignore"):
        far = newton(residual, direction, np.array([2.0]), 1e-12, 50, damped=False)
    assert not far.converged and far.message == "iterate not finite" and far.iterations < 50
    damped = newton(residual, direction, np.array([2.0]), 1e-12, 50)
    assert damped.converged and damped.message == f"converged in {damped.iterations} iterations"
    assert abs(damped.x[0]) < 1e-12 and damped.norm < 1e-12


def test_a_line_search_that_cannot_lower_the_residual_ends_newton():
    """x^2 + 1 = 0 has no real root (|R| >= 1, least at x = 0, where the Jacobian vanishes):
    from 0.5, 2 and -3 the damped steps soon reach a point where even a thousandth of the step
    raises the residual, and Newton stops there ("line search failed") instead of spending the
    200 steps it may take."""

    def residual(x: np.ndarray) -> np.ndarray:
        return x * x + 1.0

    def direction(x: np.ndarray, r: np.ndarray) -> np.ndarray:
        return -r / (2.0 * x)

    for x0 in (0.5, 2.0, -3.0):
        res = newton(residual, direction, np.array([x0]), 1e-12, 200)
        assert not res.converged and res.message == "line search failed"
        assert res.iterations <= 10 and res.norm >= 1.0


def _quadratic_at_zero():
    """R(x) = x + x^2: root 0, x_{k+1} = x_k^2 / (1 + 2 x_k)."""

    def residual(x: np.ndarray) -> np.ndarray:
        return x + x * x

    def direction(x: np.ndarray, r: np.ndarray) -> np.ndarray:
        return -r / (1.0 + 2.0 * x)

    return residual, direction


def test_relative_and_floored_step_tests():
    """A root at 0 (x + x^2 from 0.1, steps 0.092, 8.3e-3, 6.9e-5, 4.8e-9, 2.3e-17): the
    relative test, max |dx| <= rtol max |x|, is not met in five steps (each is about |x|) and
    stops with "no convergence"; with the floor 1 (the step against rtol max(1, |x|), the first
    orbit of a branch) it stops converged at the first step below rtol, the fifth."""
    residual, direction = _quadratic_at_zero()
    rel = newton(residual, direction, np.array([0.1]), 1e-10, 5, damped=False)
    assert not rel.converged and rel.message == "no convergence" and rel.iterations == 5
    floored = newton(residual, direction, np.array([0.1]), 1e-10, 5, damped=False, floor=1.0)
    assert floored.converged and floored.message == "converged in 5 iterations"
    x3, x4 = (newton(residual, direction, np.array([0.1]), 0.0, k, damped=False).x for k in (3, 4))
    assert abs(x4[0] - x3[0]) > 1e-10 >= abs(floored.x[0] - x4[0])
    assert abs(floored.x[0]) < 1e-16


def test_weighted_step_test_stops_when_the_weighted_step_is_small():
    """exp(x) = 2 from 0, steps 1, 0.26, 0.042, 8.8e-4, 3.9e-7: the weighted test
    max |w dx| <= 1e-3 stops at the 4th step with w = 1 and at the 5th with w = 1e3; at the stop
    the weighted step is below the tolerance and the one before was not."""
    residual, direction = _exp_system(2.0)
    x0 = np.zeros(1)
    counts = {}
    for weight in (1.0, 1e3):
        w = np.array([weight])
        res = newton(residual, direction, x0, 1e-3, 30, damped=False, weights=w)
        assert res.converged and res.message == f"converged in {res.iterations} iterations"
        before = newton(residual, direction, x0, 0.0, res.iterations - 1, damped=False)
        prev = newton(residual, direction, x0, 0.0, res.iterations - 2, damped=False)
        assert step_converged(res.x - before.x, res.x, 1e-3, weights=w)
        assert not step_converged(before.x - prev.x, before.x, 1e-3, weights=w)
        counts[weight] = res.iterations
    assert counts == {1.0: 4, 1e3: 5}


def test_batched_test_asks_every_row():
    """A batch of rows x^2 = a_i from 1: with axis = -1 each row's step is tested against its
    own max |x|, so the row whose roots are 1e-8 and 2e-8 converges to round-off; one test
    over the whole batch lets the other row's scale (3) carry it, 1e-5 off."""
    a = np.array([[4.0, 9.0], [1e-16, 4e-16]])

    def residual(x: np.ndarray) -> np.ndarray:
        return x * x - a

    def direction(x: np.ndarray, r: np.ndarray) -> np.ndarray:
        return -r / (2.0 * x)

    start = np.ones((2, 2))
    whole = newton(residual, direction, start, 1e-10, 60, damped=False)
    rows = newton(residual, direction, start, 1e-10, 60, damped=False, axis=-1)
    assert whole.converged and rows.converged and rows.iterations > whole.iterations
    assert np.max(np.abs(rows.x / np.sqrt(a) - 1.0)) < 1e-14
    assert np.max(np.abs(whole.x[1] / np.sqrt(a[1]) - 1.0)) > 1e-5


@pytest.mark.parametrize("damped", [True, False])
def test_stops_on_a_singular_jacobian_and_a_residual_outside_its_domain(damped):
    """A direction that raises LinAlgError stops with "singular Jacobian"; a residual that
    raises ValueError at the start stops with "residual not finite"; a zero residual at the
    start is "exact"."""

    def singular(x, r):
        raise np.linalg.LinAlgError("singular")

    res = newton(np.sin, singular, np.array([1.0]), 1e-12, 5, damped=damped)
    assert not res.converged and res.message == "singular Jacobian" and res.x[0] == 1.0

    def outside(x):
        raise ValueError("out of range")

    res = newton(outside, singular, np.array([1.0]), 1e-12, 5, damped=damped)
    assert not res.converged and res.message == "residual not finite" and res.iterations == 0
    res = newton(np.sin, singular, np.array([0.0]), 1e-12, 5, damped=damped)
    assert res.converged and res.message == "exact" and res.iterations == 0


def _chord_system(c: float, slope: float):
    """exp(x) = c with the fixed derivative `slope` (a chord): each step contracts the error by
    the closed-form factor |1 - c / slope| near the root log(c)."""

    def residual(x: np.ndarray) -> np.ndarray:
        return np.exp(x) - c

    def direction(x: np.ndarray, r: np.ndarray) -> np.ndarray:
        return -r / slope

    return residual, direction


@pytest.mark.parametrize("rtol", [1e-4, 1e-6, 1e-8, 1e-10, 1e-12])
def test_the_contraction_test_stops_within_rtol_of_the_root(rtol):
    """exp(x) = 2 from x = 0 by Newton: with `contraction` Newton stops no later than the step
    test, at an iterate within rtol of the closed-form root log 2."""
    residual, direction = _exp_system(2.0)
    root = math.log(2.0)
    plain = newton(residual, direction, np.zeros(1), rtol, 30)
    quick = newton(residual, direction, np.zeros(1), rtol, 30, contraction=True)
    assert plain.converged and quick.converged
    assert quick.iterations <= plain.iterations
    assert abs(float(quick.x[0]) - root) <= rtol * root, (quick.iterations, quick.x[0] - root)


def test_the_contraction_test_saves_steps_of_a_linear_convergence_and_keeps_rtol():
    """A chord (fixed slope 2.5 for exp(x) = 2: contraction 0.2 a step, above CONTRACTION_MAX)
    is stopped by the step test alone; with slopes 2.1 and 2.01 (contractions 0.048 and 0.005,
    as an inexact Newton step's) the contraction test stops it sooner, and the error of its
    iterate, against log 2, is within rtol in all three."""
    from rotbeam.solve.newton import CONTRACTION_MAX

    root, rtol = math.log(2.0), 1e-9
    for slope, predicted in ((2.5, False), (2.1, True), (2.01, True)):
        assert (abs(1 - 2.0 / slope) < CONTRACTION_MAX) == predicted
        residual, direction = _chord_system(2.0, slope)
        plain = newton(residual, direction, np.zeros(1), rtol, 200, damped=False)
        quick = newton(residual, direction, np.zeros(1), rtol, 200, damped=False, contraction=True)
        assert plain.converged and quick.converged
        assert ("contraction" in quick.message) == predicted, quick.message
        assert quick.iterations < plain.iterations if predicted else quick.x[0] == plain.x[0]
        assert abs(float(quick.x[0]) - root) <= rtol * root, (slope, quick.x[0] - root)


def test_the_contraction_test_is_refused_for_a_batch():
    """A batch of systems has one contraction a row: `contraction` with an axis is refused."""
    residual, direction = _exp_system(2.0)
    with pytest.raises(ValueError, match="contraction"):
        newton(residual, direction, np.zeros((2, 3)), 1e-9, 10, axis=-1, contraction=True)


def test_the_contraction_test_is_not_fooled_by_a_stalled_direction():
    """A direction that stalls after its first step (each later step 1e-7 of Newton's, as a
    GMRES far short of its tolerance gives): the steps shrink by 1e-8 while the residual does
    not fall, so the contraction test must not call the iterate, still 0.04 off log 2,
    converged; Newton runs out of steps instead."""
    residual, exact = _exp_system(2.0)
    calls = []

    def stalled(x: np.ndarray, r: np.ndarray) -> np.ndarray:
        calls.append(1)
        return exact(x, r) * (1.0 if len(calls) == 1 else 1e-7)

    res = newton(residual, stalled, np.zeros(1), 1e-12, 8, damped=False, contraction=True)
    assert not res.converged and res.message == "no convergence", res.message
    assert abs(float(res.x[0]) - math.log(2.0)) > 1e-2
