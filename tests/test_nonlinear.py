"""Lyapunov exponents and response classes against published values: Lorenz (sigma = 10,
rho = 28, beta = 8/3: lambda_max = 0.9056, Sprott, "Chaos and Time-Series Analysis", 2003) and
the double-well Duffing oscillator x'' + 0.3 x' - x + x^3 = g cos(1.2 t), whose period-doubling
route has period 1, 2, 4, 5 and chaos at g = 0.20, 0.28, 0.29, 0.37, 0.50 (the sequence shown
in Wikipedia's "Duffing equation" article, after Jordan & Smith, Nonlinear ODEs, 4th ed.)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotbeam.runs.response import classify, section_distances
from rotbeam.solve.continuation import FirstOrderProblem, continue_branch
from rotbeam.solve.lyapunov import largest_lyapunov, late_rate

SIGMA, RHO, BETA = 10.0, 28.0, 8.0 / 3.0


def _lorenz(t, z):
    return np.array([SIGMA * (z[1] - z[0]), z[0] * (RHO - z[2]) - z[1], z[0] * z[1] - BETA * z[2]])


def _lorenz_jac(t, z):
    return np.array([[-SIGMA, SIGMA, 0.0], [RHO - z[2], -1.0, -z[0]], [z[1], z[0], -BETA]])


@pytest.mark.slow
def test_lorenz_largest_lyapunov_exponent():
    """0.9056 within 0.03 after 500 time units (finite-time estimates fluctuate by ~0.015 here:
    the reported spread), and the spread says so."""
    z0 = solve_ivp(_lorenz, (0, 50), [1.0, 1.0, 1.0], rtol=1e-10, atol=1e-12).y[:, -1]
    res = largest_lyapunov(_lorenz, _lorenz_jac, z0, 1.0, 500, method="DOP853", rtol=1e-9,
                           atol=1e-11)  # fmt: skip
    assert abs(res.exponent - 0.9056) < 0.03
    assert res.spread < 0.05


def test_late_rate_discards_the_first_half():
    """Growth +2 a unit interval for six intervals (a transient), then -0.5 for six: the late
    rate is -0.5 with no spread, where the running mean is still +0.75; with the fourth
    quarter at -1.0 the spread is the quarters' difference."""
    logs = np.array([2.0] * 6 + [-0.5] * 6)
    assert late_rate(logs, 1.0) == (-0.5, 0.0)
    assert late_rate(logs, 0.5) == (-1.0, 0.0)  # per unit time
    assert np.mean(logs) == 0.75
    rate, spread = late_rate(np.array([2.0] * 6 + [-0.5] * 3 + [-1.0] * 3), 1.0)
    assert rate == pytest.approx(-0.75) and spread == pytest.approx(0.5)
    assert math.isnan(late_rate(np.ones(3), 1.0)[0])


def test_damped_oscillator_exponent_is_minus_zeta():
    """x'' + 2 zeta x' + x = cos t: every tangent vector decays like exp(-zeta t), and over the
    damped period 2 pi / sqrt(1 - zeta^2) it comes back to its direction, so the late rate and
    Benettin's mean are -zeta (closed form) to the stepper's accuracy."""
    zeta = 0.05
    Pd = 2.0 * math.pi / math.sqrt(1.0 - zeta**2)

    def f(t, z):
        return np.array([z[1], -2.0 * zeta * z[1] - z[0] + math.cos(t)])

    def jac(t, z):
        return np.array([[0.0, 1.0], [-1.0, -2.0 * zeta]])

    ly = largest_lyapunov(f, jac, np.zeros(2), Pd, 8, method="DOP853", rtol=1e-11, atol=1e-13)
    assert ly.late == pytest.approx(-zeta, abs=1e-7) and ly.late_spread < 1e-7
    assert ly.exponent == pytest.approx(-zeta, abs=1e-7)


D, W = 0.3, 1.2
P = 2.0 * math.pi / W


def _duffing(g):
    def f(t, z):
        return np.array([z[1], -D * z[1] + z[0] - z[0] ** 3 + g * math.cos(W * t)])

    def jac(t, z):
        return np.array([[0.0, 1.0], [1.0 - 3.0 * z[0] ** 2, -D]])

    return f, jac


@pytest.mark.slow
@pytest.mark.parametrize(
    "g, expected",
    [(0.20, ("periodic", 1)), (0.28, ("subharmonic", 2)), (0.29, ("subharmonic", 4)),
     (0.37, ("subharmonic", 5)), (0.50, ("chaotic", 0))],
)  # fmt: skip
def test_duffing_period_doubling_route_classified(g, expected):
    f, jac = _duffing(g)
    z = solve_ivp(f, (0, 300 * P), [1.0, 0.0], rtol=1e-10, atol=1e-12).y[:, -1]
    ly = largest_lyapunov(f, jac, z, P, 200, method="DOP853", rtol=1e-10, atol=1e-12)
    got = classify(section_distances(ly.section), ly.exponent * P, ly.spread * P, 1e-3)
    assert got == expected
    if expected[0] == "chaotic":
        assert ly.exponent - ly.spread > 0.05


@pytest.mark.slow
def test_duffing_first_period_doubling_on_the_period_one_branch():
    """Continuation of the period-1 orbit in g finds a multiplier through -1 between the
    period-1 (0.20) and period-2 (0.28) responses, and stable/unstable flips there."""
    pr = FirstOrderProblem(lambda t, z, g: _duffing(g)[0](t, z),
                           lambda t, z, g: _duffing(g)[1](t, z), lambda g: P, 2, M=65)  # fmt: skip
    f, _ = _duffing(0.20)
    sol = solve_ivp(f, (0, 101 * P), [1.0, 0.0], rtol=1e-10, atol=1e-12, dense_output=True)
    x0 = sol.sol(100 * P + np.arange(pr.M) * P / pr.M).T.ravel()
    br = continue_branch(pr, x0, 0.20, (0.19, 0.30), ds=0.005, ds_max=0.03, p_scale=0.05)
    pd = [b for b in br.bifurcations if b.kind == "period doubling"]
    assert len(pd) >= 1 and 0.20 < pd[0].p < 0.28
    i = pd[0].index
    assert br.points[i - 1].stable and not br.points[i].stable
    assert br.points[i].floquet.crossing() == "period doubling"
