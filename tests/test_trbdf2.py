"""TR-BDF2 (rotbeam.trbdf2) against closed forms, scipy's Radau and its own coefficients."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.runs.scene import build_scene
from rotbeam.solve.steady import initial_state
from rotbeam.solve.trbdf2 import (
    A_Y,
    A_Z,
    E_1,
    E_N,
    E_Z,
    GAMMA,
    TRBDF2,
    D,
    fixed_steps,
    stability_function,
)

# --- problems with closed forms -------------------------------------------------------------


def forced(t, y):
    """y' = -y + sin t, y(0) = 1."""
    return -y + np.sin(t)


def forced_exact(t):
    return 0.5 * (np.sin(t) - np.cos(t)) + 1.5 * np.exp(-t)


# damped oscillator x'' + 0.2 x' + 4 x = 0, x(0) = 1, x'(0) = 0
OSC = np.array([[0.0, 1.0], [-4.0, -0.2]])


def osc_exact(t):
    wd = math.sqrt(4.0 - 0.01)
    x = np.exp(-0.1 * t) * (np.cos(wd * t) + 0.1 / wd * np.sin(wd * t))
    v = -np.exp(-0.1 * t) * (4.0 / wd) * np.sin(wd * t)
    return np.array([x, v])


# stiff linear: eigenvalues -1 and -1e6 in a rotated basis
_Q = np.array([[1.0, 1.0], [1.0, -1.0]]) / math.sqrt(2.0)
_LAM = np.array([-1.0, -1e6])
STIFF = _Q @ np.diag(_LAM) @ _Q.T
STIFF_Y0 = np.array([1.0, 0.0])


def stiff_exact(t):
    t = np.atleast_1d(t)
    return _Q @ (np.exp(np.outer(_LAM, t)) * (_Q.T @ STIFF_Y0)[:, None])


# Van der Pol, mu = 1000
MU = 1000.0


def vdp(t, y):
    return np.array([y[1], MU * (1 - y[0] ** 2) * y[1] - y[0]])


def vdp_jac(t, y):
    return np.array([[0.0, 1.0], [-2 * MU * y[0] * y[1] - 1.0, MU * (1 - y[0] ** 2)]])


def observed_order(errors, ns):
    return np.log(errors[:-1] / errors[1:]) / np.log(np.asarray(ns[1:]) / np.asarray(ns[:-1]))


# --- the coefficients -----------------------------------------------------------------------


def test_coefficients_second_order_and_l_stable():
    """R(z) - e^z = O(z^3) (order 2, not 3), |R| <= 1 on the imaginary axis, R(-inf) = 0."""
    assert A_Z + A_Y == pytest.approx(1.0, abs=1e-15)
    assert (1 - GAMMA) / (2 - GAMMA) == pytest.approx(D, abs=1e-15)  # one iteration matrix
    k = (-3 * GAMMA**2 + 4 * GAMMA - 2) / (12 * (2 - GAMMA))
    for z in (1e-2, -1e-2, 1e-2j):
        lte = stability_function(z) - np.exp(z)
        assert lte / z**3 == pytest.approx(-k, rel=0.05)  # leading error -k z^3, k != 0
    y = np.logspace(-3, 8, 500)
    assert np.max(np.abs(stability_function(1j * y))) <= 1 + 1e-12
    zs = -np.logspace(0, 12, 100)
    assert np.all(np.abs(stability_function(zs)) < 1)
    assert abs(stability_function(-1e12)) < 1e-11  # L-stable: R(z) ~ (2 + 2 sqrt 2)/z
    assert stability_function(-1e12) * -1e12 == pytest.approx(2 + 2 * math.sqrt(2), rel=1e-6)
    # error estimate: zero on linear f, and equal to minus the Bank et al. estimate
    assert E_N + E_Z + E_1 == pytest.approx(0.0, abs=1e-15)
    assert E_Z * GAMMA + E_1 == pytest.approx(0.0, abs=1e-15)
    bank = 2 * k * np.array([1 / GAMMA, -1 / (GAMMA * (1 - GAMMA)), 1 / (1 - GAMMA)])
    np.testing.assert_allclose([E_N, E_Z, E_1], -bank, rtol=1e-12)


# --- 1. order of accuracy with fixed steps --------------------------------------------------


def test_fixed_step_order_two():
    ns = [20, 40, 80, 160, 320]
    err = np.array(
        [abs(fixed_steps(forced, (0, 10), [1.0], n)[-1, 0] - forced_exact(10)) for n in ns]
    )
    order = observed_order(err, ns)
    assert np.all((order > 1.8) & (order < 2.2)), order
    err2 = np.array(
        [
            np.abs(
                fixed_steps(lambda t, y: OSC @ y, (0, 5), [1.0, 0.0], n, jac=OSC)[-1] - osc_exact(5)
            ).max()
            for n in ns
        ]
    )
    order2 = observed_order(err2, ns)
    assert np.all((order2 > 1.8) & (order2 < 2.2)), order2


def test_fixed_step_l_stable_on_prothero_robinson():
    """y' = -1e6 (y - cos t) + (-sin t), y = cos t: a big step damps the stiff error at once."""

    def f(t, y):
        return -1e6 * (y - np.cos(t)) - np.sin(t)

    ys = fixed_steps(f, (0, 2), [2.0], 20, jac=lambda t, y: np.array([[-1e6]]))  # h lambda = -1e5
    ts = np.linspace(0, 2, 21)
    # TR alone would carry the initial error 1 with factor ~ -1 per step; TR-BDF2 kills it
    assert abs(ys[1, 0] - np.cos(ts[1])) < 1e-3
    assert np.max(np.abs(ys[2:, 0] - np.cos(ts[2:]))) < 1e-3


# --- 2. stiff linear system -----------------------------------------------------------------


def test_stiff_linear_closed_form():
    """Eigenvalues -1 and -1e6: accurate, few steps, and the stiff mode is damped at once."""
    ts = np.linspace(0, 5, 51)
    kw = dict(method=TRBDF2, rtol=1e-6, atol=1e-10, jac=STIFF)
    sol = solve_ivp(lambda t, y: STIFF @ y, (0, 5), STIFF_Y0, t_eval=ts, **kw)
    assert sol.status == 0 and sol.success and sol.t.size == ts.size
    exact = stiff_exact(ts)
    err = np.abs(sol.y - exact).max(axis=0)
    assert err.max() < 1e-5 * np.abs(STIFF_Y0).max(), err.max()
    # relative to the decaying solution the error grows linearly in t (error per step control)
    rel = err[1:] / np.abs(exact[:, 1:]).max(axis=0)
    assert np.all(rel < 5e-5 * ts[1:]), rel
    stiff_part = (_Q.T @ sol.y)[1]
    assert np.abs(stiff_part[1:]).max() < 1e-9  # no ringing of the stiff mode (L-stability)
    assert sol.njev == 0 and sol.nlu < 200  # constant jac: never re-evaluated
    steps = solve_ivp(lambda t, y: STIFF @ y, (0, 5), STIFF_Y0, **kw).t.size
    assert steps < 2000, steps


def robertson(t, y):
    return np.array(
        [
            -0.04 * y[0] + 1e4 * y[1] * y[2],
            0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] ** 2,
            3e7 * y[1] ** 2,
        ]
    )


def test_robertson_filtered_error_estimate():
    """Robertson's stiff kinetics to t = 1e5: the filtered estimate allows long steps.

    (Unfiltered, the same run takes ~4e5 steps instead of ~200.)
    """
    span, y0, atol = (0, 1e5), [1.0, 0.0, 0.0], [1e-8, 1e-14, 1e-8]
    ref = solve_ivp(robertson, span, y0, method="Radau", rtol=1e-9, atol=1e-3 * np.array(atol))
    sol = solve_ivp(robertson, span, y0, method=TRBDF2, rtol=1e-4, atol=atol)
    assert sol.success and sol.t.size < 1000, sol.t.size
    np.testing.assert_allclose(sol.y[:, -1], ref.y[:, -1], rtol=2e-3)
    assert abs(sol.y[:, -1].sum() - 1) < 1e-12  # linear invariant kept by every stage


# --- 3. stiff Van der Pol against Radau ------------------------------------------------------

VDP_KW = dict(method=TRBDF2, rtol=1e-6, atol=1e-9)


@pytest.fixture(scope="module")
def vdp_reference():
    ref = solve_ivp(vdp, (0, 3000), [2.0, 0.0], method="Radau", rtol=1e-10, atol=1e-12, jac=vdp_jac)
    assert ref.success
    return ref.y[:, -1]


@pytest.fixture(scope="module")
def vdp_analytic():
    return solve_ivp(vdp, (0, 3000), [2.0, 0.0], jac=vdp_jac, **VDP_KW)


def test_van_der_pol_against_radau(vdp_reference, vdp_analytic):
    sol = vdp_analytic
    assert sol.success and sol.status == 0
    rel = abs(sol.y[0, -1] - vdp_reference[0]) / abs(vdp_reference[0])
    assert rel < 1e-3, rel
    assert sol.nlu < sol.t.size / 2 and sol.njev < sol.t.size / 4  # LU and J reused


# --- 4. finite-difference Jacobian ----------------------------------------------------------


def test_numerical_jacobian_matches_analytic(vdp_reference, vdp_analytic):
    num = solve_ivp(vdp, (0, 3000), [2.0, 0.0], **VDP_KW)
    assert num.success and num.njev > 0
    scale = abs(vdp_reference[0])
    assert abs(num.y[0, -1] - vdp_reference[0]) < 1e-3 * scale
    assert abs(num.y[0, -1] - vdp_analytic.y[0, -1]) < 1e-5 * scale  # measured 1.5e-8


# --- 5. tolerance proportionality -----------------------------------------------------------


def test_error_decreases_with_rtol():
    rtols = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
    ts = np.linspace(0, 10, 21)
    err = []
    for rtol in rtols:
        sol = solve_ivp(
            forced, (0, 10), [1.0], method=TRBDF2, rtol=rtol, atol=1e-3 * rtol, t_eval=ts
        )
        err.append(np.abs(sol.y[0] - forced_exact(ts)).max())
    err = np.array(err)
    assert np.all(err[1:] < err[:-1]), err
    slope = np.polyfit(np.log(rtols), np.log(err), 1)[0]
    assert 0.5 < slope < 1.1, slope  # between tol^(2/3) (error per step) and tol (per unit step)
    assert np.all(err < 300 * np.array(rtols)), err / np.array(rtols)  # measured 1.8 ... 83


# --- the solve_ivp contract -----------------------------------------------------------------


def test_dense_output_and_t_eval():
    ts = np.linspace(0, 10, 101)
    sol = solve_ivp(
        forced, (0, 10), [1.0], method=TRBDF2, rtol=1e-7, atol=1e-10, t_eval=ts, dense_output=True
    )
    assert sol.status == 0 and sol.message and sol.nfev > 0 and sol.nlu > 0
    np.testing.assert_allclose(sol.y[0], forced_exact(ts), atol=2e-5)
    np.testing.assert_allclose(sol.sol(ts)[0], sol.y[0], atol=1e-14)
    tm = np.linspace(0, 10, 997)
    np.testing.assert_allclose(sol.sol(tm)[0], forced_exact(tm), atol=2e-5)
    assert sol.sol(3.3).shape == (1,)


def test_backwards_and_max_step():
    sol = solve_ivp(
        lambda t, y: OSC @ y,
        (5, 0),
        osc_exact(5),
        method=TRBDF2,
        rtol=1e-8,
        atol=1e-10,
        max_step=0.05,
    )
    assert (
        sol.success
        and np.all(np.diff(sol.t) < 0)
        and np.all(np.abs(np.diff(sol.t)) <= 0.05 + 1e-15)
    )
    np.testing.assert_allclose(sol.y[:, -1], [1.0, 0.0], atol=1e-4)  # ~1600 steps of 1e-8


def test_rtol_floor_and_bad_jac():
    with pytest.warns(UserWarning, match="rtol"):
        solve_ivp(forced, (0, 0.1), [1.0], method=TRBDF2, rtol=1e-20)
    with pytest.raises(ValueError, match="shape"):
        solve_ivp(forced, (0, 1), [1.0], method=TRBDF2, jac=np.eye(2))


def test_failure_is_reported_not_raised():
    """y' = y^2 blows up at t = 1: status -1 and a message, as Radau gives."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        sol = solve_ivp(
            lambda t, y: y**2, (0, 2), [1.0], method=TRBDF2, rtol=1e-6, jac=lambda t, y: 2 * y[None]
        )
    assert sol.status == -1 and not sol.success and "step size" in sol.message
    assert 0.99 < sol.t[-1] < 1.0


# --- 6. the rotbeam model -------------------------------------------------------------------


def rotbeam_problem(N: int, start: str):
    """rhs, jac, initial state and period for the default beam at Omega_0 = 5 rad/s, f_d = 2 Hz.

    Built as rotbeam.integrate.steady_state builds them.
    """
    dl = build_scene({"drive": {"omega0": 5, "f_d": 2}}).dimensionless
    model = DiscreteElastica(dl, N)
    n = model.n

    def rhs(tau, z):
        acc = model.acceleration(z[:n], z[n:], dl.lam(tau), dl.lam_dot(tau))
        return np.concatenate([z[n:], acc])

    def jac(tau, z):
        return model.first_order_jacobian(z[:n], z[n:], dl.lam(tau), dl.lam_dot(tau))

    z0, _ = initial_state(model, start)
    return rhs, jac, z0, dl.period, n


def compare_with_radau(N, start, span, rtols):
    """Relative final-state differences (angles, all states) of TRBDF2 at `rtols` to Radau 1e-9."""
    rhs, jac, z0, P, n = rotbeam_problem(N, start)
    size = 0.05  # the response is ~0.05 rad: atol = rtol * size
    ref = solve_ivp(rhs, (0, span * P), z0, method="Radau", rtol=1e-9, atol=1e-9 * size, jac=jac)
    assert ref.success
    zr = ref.y[:, -1]
    out = []
    for rtol in rtols:
        sol = solve_ivp(rhs, (0, span * P), z0, method=TRBDF2, rtol=rtol, atol=rtol * size, jac=jac)
        assert sol.success
        d = np.abs(sol.y[:, -1] - zr)
        out.append((d[:n].max() / np.abs(zr[:n]).max(), d.max() / np.abs(zr).max()))
    return np.array(out)


def test_rotbeam_against_radau_two_periods():
    """N = 10 over 2 drive periods from the quasi-static state (rotbeam's start="quasistatic").

    At rtol 1e-6 the angles agree with Radau (rtol 1e-9) to 2e-4 (all states 7e-4; measured):
    TR-BDF2 holds the local error to rtol, and ~750 steps add it up.  At 1e-7 it is 5x closer.
    """
    err = compare_with_radau(10, "quasistatic", 2.0, [1e-6, 1e-7])
    assert err[0, 0] < 1e-3 and err[0, 1] < 2e-3, err
    assert np.all(err[1] < err[0] / 2), err


def test_rotbeam_from_straight_rest():
    """N = 10 from the straight beam at rest: the sudden load rings every mode (up to ~2200 in
    units of 1/T), which decays only like exp(-eta tau/2).  Over 1/50 period: angles agree with
    Radau to 1e-5 (measured), velocities, which carry the ringing, to 5e-3 of the state size.
    (Over the full 2 periods, too slow for a unit test: angles 2e-5, velocities 1e-2 at rtol 1e-6
    against Radau at 1e-10: the top modes' phase error adds up over ~1e5 steps.)
    """
    err = compare_with_radau(10, "rest", 0.02, [1e-6])
    assert err[0, 0] < 1e-4 and err[0, 1] < 1e-2, err


def test_no_private_scipy_import_and_same_jacobian():
    """trbdf2 carries its own copies of scipy's private ODE helpers: no import of a
    private scipy module remains, and the finite-difference Jacobian equals scipy's own while
    scipy still has it; a jac_sparsity structure only zeroes the entries outside it."""
    import ast
    import inspect

    import rotbeam.solve.trbdf2 as t

    tree = ast.parse(inspect.getsource(t))
    modules = [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    modules += [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    private = [m for m in modules if m and any(p.startswith("_") for p in m.split(".")[1:])]
    assert not private, private
    y, f = np.array([2.0, -0.3]), vdp(0.0, np.array([2.0, -0.3]))
    vec = lambda t_, ys: np.stack([vdp(t_, c) for c in ys.T], axis=1)  # noqa: E731
    J, factor = t.num_jac(vec, 0.0, y, f, 1e-6, None)
    np.testing.assert_allclose(J, vdp_jac(0.0, y), rtol=1e-5)
    try:
        from scipy.integrate._ivp.common import num_jac as scipy_num_jac
    except ImportError:  # gone from a newer scipy: nothing left to compare with
        pass
    else:
        J2, factor2 = scipy_num_jac(vec, 0.0, y, f, 1e-6, None)
        np.testing.assert_array_equal(J, J2)
        np.testing.assert_array_equal(factor, factor2)
    J3, _ = t.num_jac(vec, 0.0, y, f, 1e-6, None, sparsity=np.array([[0, 1], [1, 1]]))
    assert J3[0, 0] == 0 and J3[1, 0] == J[1, 0]
    sol = solve_ivp(vdp, (0, 1), [2.0, 0.0], method=TRBDF2, jac_sparsity=np.ones((2, 2)))
    assert sol.success
