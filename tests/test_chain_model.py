"""Self-checks of the independent rigid-link chain model against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import solve

try:
    from chain_model import (
        ChainModel,
        chain_natural_frequencies,
        chain_static_shape,
        chain_steady_rms,
    )
except ImportError:  # tests/ imported as a package
    from tests.chain_model import (
        ChainModel,
        chain_natural_frequencies,
        chain_static_shape,
        chain_steady_rms,
    )

DELTA = 0.258
R_O = 1.0 / DELTA - 1.0
BETA1_SQ = 1.875104068711961**2  # first clamped-free eigenvalue, 3.5160152...
BETA2_SQ = 4.694091132974175**2


def _errors(values: list[float], exact: float) -> np.ndarray:
    return np.abs(np.array(values) - exact)


def test_first_frequency_converges_second_order() -> None:
    """(a) Non-rotating, undamped: omega_1 -> 1.8751^2 with error ~ O(h^2)."""
    freqs = [chain_natural_frequencies(n, lam=0.0, delta=DELTA, n_modes=2) for n in (20, 40, 80)]
    err1 = _errors([f[0] for f in freqs], BETA1_SQ)
    err2 = _errors([f[1] for f in freqs], BETA2_SQ)
    assert err1[-1] < 5e-4
    assert abs(freqs[-1][0] - 3.51602) < 5e-4
    for err in (err1, err2):
        ratios = err[:-1] / err[1:]
        assert np.all((ratios > 3.5) & (ratios < 4.5)), ratios


def test_uniform_clamp_spring_would_be_first_order() -> None:
    """Documents why the clamp spring is 2/h: with 1/h the chain converges only O(h)."""
    errs = _errors(
        [ChainModel(n, DELTA, clamp_spring=1.0).linear_modes()[0] for n in (20, 40, 80)],
        BETA1_SQ,
    )
    ratios = errs[:-1] / errs[1:]
    assert np.all((ratios > 1.8) & (ratios < 2.2)), ratios


def test_rotation_stiffens_first_mode() -> None:
    """Centrifugal stiffening raises omega_1; in-plane softening lowers it by ~lam^2."""
    lam = 2.0
    w0 = chain_natural_frequencies(40, lam=0.0)[0]
    w_soft = chain_natural_frequencies(40, lam=lam, softening=True)[0]
    w_nosoft = chain_natural_frequencies(40, lam=lam, softening=False)[0]
    assert w0 < w_soft < w_nosoft
    # softening load lam^2 y is mass-proportional: omega^2 drops by exactly lam^2
    assert w_nosoft**2 - w_soft**2 == pytest.approx(lam**2, rel=1e-8)


@pytest.mark.parametrize("n", [20, 80])
@pytest.mark.parametrize("softening", [True, False])
def test_static_straight_beam_axial_force(n: int, softening: bool) -> None:
    """(b) Steady rotation keeps the beam straight; clamp tension = lam^2 (r_o + 1/2)."""
    lam = 3.0
    x, y = chain_static_shape(lam, 0.0, DELTA, n_links=n, softening=softening)
    s = np.linspace(0.0, 1.0, n + 1)
    assert np.max(np.abs(y)) < 1e-12
    assert np.max(np.abs(x - s)) < 1e-12
    model = ChainModel(n, DELTA, softening=softening, damping=False)
    # Newton from a perturbed shape must return to the straight (stable) state
    phi = model.static_angles(lam, 0.0, phi0=0.05 * np.sin(np.arange(n)))
    assert np.max(np.abs(phi)) < 1e-12
    force, moment = model.clamp_reaction(phi, lam, 0.0)
    exact = lam**2 * (R_O + 0.5)
    assert force[0] == pytest.approx(exact, rel=0.1 / n**2)
    assert abs(force[1]) < 1e-12 * exact
    assert abs(moment) < 1e-12 * exact


def _linear_cantilever(s: np.ndarray, e: float) -> np.ndarray:
    """w'''' = q, q = -e (r_o + s); w(0) = w'(0) = 0, w''(1) = w'''(1) = 0."""
    uniform = R_O * (6 * s**2 - 4 * s**3 + s**4) / 24.0  # q = 1
    linear = (20 * s**2 - 10 * s**3 + s**5) / 120.0  # q = s
    return -e * (uniform + linear)


def test_small_euler_load_matches_linear_cantilever() -> None:
    """(c) lam = 0, lamdot = e: y(s) -> linear cantilever deflection, error O(h^2)."""
    e = 1e-6
    errs = []
    for n in (20, 40, 80):
        x, y = chain_static_shape(0.0, e, DELTA, n_links=n)
        s = np.linspace(0.0, 1.0, n + 1)
        errs.append(np.max(np.abs(y - _linear_cantilever(s, e))) / e)
    errs_arr = np.array(errs)
    ratios = errs_arr[:-1] / errs_arr[1:]
    assert np.all((ratios > 3.5) & (ratios < 4.5)), ratios
    assert errs_arr[-1] < 1e-3 * abs(_linear_cantilever(np.array(1.0), 1.0))


def test_deflected_static_moment_balance() -> None:
    """Large static deflection: clamp spring moment = moment of the loads about the clamp."""
    n = 40
    model = ChainModel(n, DELTA, damping=False)
    lam, lamdot = 1.5, 2.0
    phi = model.static_angles(lam, lamdot)
    assert abs(phi[-1]) > 0.3  # genuinely nonlinear
    _, moment = model.clamp_reaction(phi, lam, lamdot)
    assert moment == pytest.approx(model.clamp_spring * phi[0] / model.h, rel=1e-10)


def test_jacobian_matches_finite_differences() -> None:
    """Analytic Jacobian of the first-order system against central differences."""
    rng = np.random.default_rng(1)
    for flags in ({"coriolis": True}, {"coriolis": True, "softening": False}):
        model = ChainModel(7, DELTA, eta=0.3, **flags)
        z = 0.5 * rng.normal(size=14)
        jac = model.jac(z, 1.3, 0.7)
        fd = np.empty_like(jac)
        eps = 1e-6
        for j in range(14):
            dz = np.zeros(14)
            dz[j] = eps
            fd[:, j] = (model.rhs(z + dz, 1.3, 0.7) - model.rhs(z - dz, 1.3, 0.7)) / (2 * eps)
        assert np.max(np.abs(jac - fd)) < 1e-7 * np.max(np.abs(jac))


def test_jacobi_integral_conserved() -> None:
    """Constant lam, no Euler/damping (Coriolis on): T + V - U_centrifugal is conserved."""
    n, lam = 4, 2.0
    model = ChainModel(n, DELTA, euler=False, coriolis=True, damping=False)
    s = (np.arange(n) + 0.5) / n
    z0 = np.concatenate([0.4 * s, -1.5 * s**2])
    sol = solve_ivp(
        lambda t, z: model.rhs(z, lam, 0.0),
        (0.0, 1.0),
        z0,
        method="Radau",
        rtol=1e-8,
        atol=1e-10,
        jac=lambda t, z: model.jac(z, lam, 0.0),
    )
    assert sol.success
    e0 = model.energy(z0, lam)
    drift = max(abs(model.energy(z, lam) - e0) for z in sol.y.T)
    assert np.max(np.abs(sol.y[:n, -1] - z0[:n])) > 0.05  # it actually moved
    assert drift < 1e-9 * abs(e0)


@pytest.mark.parametrize("lam0", [0.0, 1.0])
def test_steady_rms_matches_linear_frequency_response(lam0: float) -> None:
    """Tiny alpha: time-integrated steady RMS = linear frequency response of the chain."""
    n, eta, alpha, omega = 10, 1.0, 1e-4, 3.0
    res = chain_steady_rms(lam0, alpha, omega, DELTA, eta, n_links=n, samples_per_period=64)
    model = ChainModel(n, DELTA, eta=eta)
    zero = np.zeros(n)
    mass = model.mass_matrix(zero)
    dq_dphi, dq_du = model.dq(zero, zero, lam0, 0.0)
    load = model.generalized_forces(zero, zero, lam0, 1.0) - model.generalized_forces(
        zero, zero, lam0, 0.0
    )  # dQ/dlamdot; lamdot = alpha omega Re(e^{i omega tau})
    dyn = model.K - dq_dphi - 1j * omega * dq_du - omega**2 * mass
    phi_hat = solve(dyn, alpha * omega * load)
    y_hat = model.h * np.sum(phi_hat[: n // 2])
    rms_lin = abs(y_hat) / math.sqrt(2.0)
    assert res["rms"] == pytest.approx(rms_lin, rel=1e-4)
    assert len(res["tau"]) == 4 * 64
    assert res["tip"].shape == (2, 4 * 64)


def test_steady_state_independent_of_start() -> None:
    """Start at rest straight vs at rest in the tau = 0 static equilibrium: same steady RMS."""
    kw = {"n_links": 4, "samples_per_period": 16, "rtol": 1e-7, "atol": 1e-9}
    a = chain_steady_rms(0.5, 0.2, 3.5, DELTA, 3.0, start="rest", **kw)
    b = chain_steady_rms(0.5, 0.2, 3.5, DELTA, 3.0, start="static", **kw)
    assert a["rms"] > 1e-2
    assert a["rms"] == pytest.approx(b["rms"], rel=1e-6)
