"""The model contract, run over every model (as scipy's tests run over every method).

A model gives one thing, its residual R(q, q_t, q_tt; lam, lam_dot) with blocks; what the base
class derives from it (the first-order form and its Jacobian, the matrix-free tangent, the
static residual, the linearised operators) is checked here against finite differences of the
residual itself, for the discrete elastica (bare, and with a payload and Coriolis) and for its
modal reduced model (a few modes, and every mode).
"""

from __future__ import annotations

import numpy as np
import pytest

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.modal import ModalModel
from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.runs.scene import Scene
from rotbeam.solve.numerics import Numerics

N = 9


def _scene(payload: bool, coriolis: bool) -> Scene:
    beam = Beam(tip_mass=0.004, tip_inertia=2e-7) if payload else Beam()
    effects = Effects(coriolis=coriolis)
    return Scene(beam, Drive(omega0=6.0, amplitude=2.0, f_d=4.0), effects, Numerics(N=N))


def _models() -> dict:
    bare = DiscreteElastica(_scene(False, False).dimensionless, N)
    loaded = DiscreteElastica(_scene(True, True).dimensionless, N)
    return {
        "elastica": bare,
        "elastica, payload, Coriolis": loaded,
        "modal 3, payload, Coriolis": ModalModel(loaded, 3),
        "modal, every mode": ModalModel(bare, N - 1),
    }


MODELS = _models()


@pytest.fixture(params=list(MODELS), ids=list(MODELS))
def model(request):
    return MODELS[request.param]


def _state(model, m: int = 3, seed: int = 1):
    rng = np.random.default_rng(seed)
    n = model.n
    theta = 0.3 * rng.standard_normal((m, n))
    theta_t = rng.standard_normal((m, n))
    theta_tt = rng.standard_normal((m, n))
    lam = 0.4 + rng.random(m)
    lam_dot = rng.standard_normal(m)
    return theta, theta_t, theta_tt, lam, lam_dot


def _fd_columns(f, x: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """d f / d x by central differences, row by row: shape (m, len(f), n)."""
    m, n = x.shape
    cols = []
    for k in range(n):
        e = np.zeros_like(x)
        e[:, k] = h
        cols.append((f(x + e) - f(x - e)) / (2 * h))
    return np.stack(cols, axis=2)


def _close(a, b, rel=1e-6):
    scale = max(float(np.max(np.abs(b))), 1.0)
    assert np.max(np.abs(a - b)) <= rel * scale, np.max(np.abs(a - b)) / scale


def test_blocks_are_the_residuals_derivatives(model):
    th, tt, ta, lam, ld = _state(model)
    dq, dqt, mass = model.residual_rows(th, tt, ta, lam, ld, True).blocks()

    def R(a, b, c):
        return model.residual_rows(a, b, c, lam, ld).R

    _close(dq, _fd_columns(lambda x: R(x, tt, ta), th))
    _close(dqt, _fd_columns(lambda x: R(th, x, ta), tt))
    _close(mass, _fd_columns(lambda x: R(th, tt, x), ta))


def test_first_order_form_solves_the_residual_and_its_jacobian_is_its_derivative(model):
    th, tt, _, lam, ld = _state(model)
    n = model.n
    F, J = model.first_order_rows(th, tt, lam, ld)
    assert np.array_equal(F[:, :n], tt)
    scale = np.max(np.abs(model.residual_rows(th, tt, np.zeros_like(th), lam, ld).R))
    solved = model.residual_rows(th, tt, F[:, n:], lam, ld).R
    assert np.max(np.abs(solved)) <= 1e-12 * scale

    def acc(z):
        return model.first_order_rows(z[:, :n], z[:, n:], lam, ld)[0]

    _close(J, _fd_columns(acc, np.concatenate([th, tt], axis=1)))
    one = model.acceleration(th[0], tt[0], lam[0], ld[0])
    _close(one, F[0, n:], 1e-12)


def test_tangent_is_the_jacobian_times_the_direction(model):
    th, tt, _, lam, ld = _state(model, m=1)
    rng = np.random.default_rng(7)
    p, q = rng.standard_normal(model.n), rng.standard_normal(model.n)
    F, Jv = model.first_order_jvp(th[0], tt[0], lam[0], ld[0], p, q)
    Fr, J = model.first_order_rows(th, tt, lam, ld)
    _close(F, Fr[0], 1e-12)
    _close(Jv, J[0] @ np.concatenate([p, q]), 1e-10)


def test_static_residual_is_the_residual_at_rest(model):
    th, _, _, lam, ld = _state(model)
    zero = np.zeros_like(th)
    R, dR = model.static_rows(th, lam, ld, jacobian=True)
    _close(R, model.residual_rows(th, zero, zero, lam, ld).R, 1e-12)
    _close(dR, _fd_columns(lambda x: model.static_rows(x, lam, ld), th))


def test_linear_operators_are_the_residual_linearised_on_the_straight_beam(model):
    lam = 0.7
    mass, stiffness, euler = model.linear_operators(lam)
    damping = model.linear_damping(lam)
    zero = np.zeros((1, model.n))

    def R(a, b, c, ld=0.0):
        return model.residual_rows(a, b, c, [lam], [ld]).R

    _close(stiffness, _fd_columns(lambda x: R(x, zero, zero), zero)[0])
    _close(damping, _fd_columns(lambda x: R(zero, x, zero), zero)[0])
    _close(mass, _fd_columns(lambda x: R(zero, zero, x), zero)[0])
    _close(euler, (R(zero, zero, zero, 1e-3) - R(zero, zero, zero, -1e-3))[0] / 2e-3)


@pytest.mark.parametrize("lam", [0.0, 0.7])
def test_first_mode_decay_is_the_damped_eigenproblems_first_mode(model, lam):
    """The first mode's frequency and modal damping (first order in the damping) against the
    slowest pair s of the damped linear problem s^2 M + s C + K = 0, solved in companion form:
    w1 = |s| and c = -2 Re s to second order in the damping; exactly for the bare beam, whose
    damping is proportional to its mass (C = eta M, so c = eta)."""
    w1, c = model.first_mode_decay(lam)
    stiffness, damping, mass = model.straight_blocks(lam)
    n = model.n
    companion = np.block(
        [
            [np.zeros((n, n)), np.eye(n)],
            [-np.linalg.solve(mass, stiffness), -np.linalg.solve(mass, damping)],
        ]
    )
    s = np.linalg.eigvals(companion)
    s = s[np.imag(s) > 0]
    s1 = s[np.argmin(np.abs(s))]
    assert abs(w1 - abs(s1)) <= 1e-5 * w1
    assert abs(c + 2.0 * s1.real) <= 1e-4 * c
    if np.allclose(damping, model.dl.eta * mass, rtol=0, atol=1e-12 * np.max(np.abs(mass))):
        assert c == pytest.approx(model.dl.eta, rel=1e-10)
