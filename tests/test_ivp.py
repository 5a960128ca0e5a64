"""The one time stepper (rotbeam/solve/ivp.py): its samples, end state and counts are scipy's
solve_ivp's bit for bit (the samples as with t_eval, the end state and the steps as with dense
output), and it never raises: a failing solver and a passed deadline come back as a status and
a message."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotbeam.solve.ivp import CUT, FAILED, REACHED, IvpInterval
from rotbeam.solve.timebudget import OutOfTime


def forced(t: float, y: np.ndarray) -> np.ndarray:
    """A damped, forced Duffing oscillator with a slow and a fast mode."""
    x, v, u, w = y
    return np.array([v, -0.1 * v - x - x**3 + np.sin(2.0 * t), w, -50.0 * w - 400.0 * u])


def forced_jac(t: float, y: np.ndarray) -> np.ndarray:
    """The Jacobian of `forced`."""
    J = np.zeros((4, 4))
    J[0, 1] = J[2, 3] = 1.0
    J[1, 0], J[1, 1] = -1.0 - 3.0 * y[0] ** 2, -0.1
    J[3, 2], J[3, 3] = -400.0, -50.0
    return J


Y0 = np.array([1.0, 0.0, 0.1, 0.0])


@pytest.mark.parametrize("method", ["Radau", "BDF", "LSODA", "DOP853"])
def test_samples_and_counts_are_solve_ivps(method):
    """Samples at t_eval (the end included), nfev and njev as solve_ivp with t_eval; the end
    state and the steps as solve_ivp with dense output; totals add up over calls."""
    implicit = method != "DOP853"
    kw = {"jac": forced_jac} if implicit else {}
    t_eval = np.append(np.linspace(0.0, 3.0, 37, endpoint=False), 3.0)
    ref = solve_ivp(forced, (0.0, 3.0), Y0, method=method, rtol=1e-6, atol=1e-9,
                    t_eval=t_eval, **kw)  # fmt: skip
    dense = solve_ivp(forced, (0.0, 3.0), Y0, method=method, rtol=1e-6, atol=1e-9,
                      dense_output=True, **kw)  # fmt: skip
    ivp = IvpInterval(forced, method, 1e-6, 1e-9, forced_jac if implicit else None)
    out = ivp.run(0.0, 3.0, Y0, t_eval)
    assert out.status == REACHED and out.message == ""
    assert np.array_equal(out.t, ref.t) and np.array_equal(out.y, ref.y.T)
    assert (out.nfev, out.njev) == (ref.nfev, ref.njev)
    assert np.array_equal(out.end, dense.y[:, -1]) and out.steps == dense.t.size - 1
    again = ivp.run(0.0, 3.0, Y0)
    assert again.t.size == 0 and again.y.shape == (0, 4) and np.array_equal(again.end, out.end)
    assert ivp.nfev == out.nfev + again.nfev and ivp.steps == 2 * out.steps
    assert ivp.last is again


def test_interval_step_is_the_dense_one():
    """As an IntervalStep: the solver's end state and the first half of the state at
    t_eval[:-1], as dense output evaluates them."""
    t_eval = np.append(np.linspace(0.0, 2.0, 16, endpoint=False), 2.0)
    dense = solve_ivp(forced, (0.0, 2.0), Y0, method="DOP853", rtol=1e-8, atol=1e-10,
                      dense_output=True)  # fmt: skip
    y, samples, why = IvpInterval(forced, "DOP853", 1e-8, 1e-10)(0.0, 2.0, Y0, t_eval)
    assert why == "" and np.array_equal(y, dense.y[:, -1])
    assert np.array_equal(samples, dense.sol(t_eval[:-1])[:2].T)


def test_a_passed_deadline_and_a_failure_are_said():
    """A right-hand side that raises OutOfTime gives CUT with the instant reached; a solver
    that fails gives FAILED with scipy's message; one that blows up, FAILED, not finite."""
    calls = []

    def late(t, y):
        calls.append(t)
        if len(calls) > 30:
            raise OutOfTime
        return forced(t, y)

    ivp = IvpInterval(late, "Radau", 1e-8, 1e-10, forced_jac)
    out = ivp.run(0.0, 50.0, Y0, np.linspace(0.0, 50.0, 11))
    assert out.status == CUT and "deadline" in out.message and 0 < out.t.size < 11
    assert ivp.nfev == out.nfev > 0
    blown = IvpInterval(lambda t, y: y**2, "RK45", 1e-6, 1e-9).run(0.0, 2.0, np.ones(1))
    assert blown.status == FAILED and blown.message and blown.end[0] > 1e6
    with np.errstate(invalid="ignore"):  # scipy's step control meets the infinite rates
        inf = IvpInterval(lambda t, y: np.full(1, np.inf), "RK23", 1e-6, 1e-9).run(0.0, 1.0, Y0[:1])
    assert inf.status == FAILED
