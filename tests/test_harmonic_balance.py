"""The one harmonic balance (`rotbeam.solve.periodic.SpectralCollocation`) against the other
spectral solves in the package: the one-mode surrogate's Galerkin solve of its Hill equation in
Fourier space, and the first-order collocation of continuation (`FirstOrderProblem`)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla

from rotbeam.model.base import Residual
from rotbeam.model.params import Beam, Dimensionless, Drive, Harmonic
from rotbeam.model.surrogate import SurrogateModel
from rotbeam.solve.continuation import FirstOrderProblem
from rotbeam.solve.periodic import SpectralCollocation
from rotbeam.solve.spectral import fourier_diff_matrix


class HillRows(Residual):
    """The surrogate's equation in its tip deflection q, written in the test alone:
    q'' + c q' + (k_b + lam^2 (k_c - sigma m_soft)) / m q + F_e lam_dot / m = 0."""

    def __init__(self, sur: SurrogateModel, lam, lam_dot, q, q_t, q_tt) -> None:
        self.k = (sur.k_b + lam * lam * (sur.k_c - sur.sigma * sur.m_soft)) / sur.m
        self.c, self.q = sur.damping, q
        self.R = q_tt + self.c * q_t + self.k[:, None] * q + (sur.F_e / sur.m) * lam_dot[:, None]

    def mass(self) -> np.ndarray:
        return np.ones((self.q.shape[0], 1, 1))

    def blocks(self):
        m = self.q.shape[0]
        return self.k[:, None, None], np.full((m, 1, 1), self.c), self.mass()

    def accelerate(self, theta_tt) -> None:
        raise NotImplementedError


def _collocated_q(sur: SurrogateModel, M: int) -> tuple[np.ndarray, np.ndarray]:
    """q at the M instants of one drive period: the linear problem is one Newton step from 0."""
    dl = sur.dl
    tau = np.arange(M) * dl.period / M
    lam = np.array([dl.lam(t) for t in tau])
    lam_dot = np.array([dl.lam_dot(t) for t in tau])
    col = SpectralCollocation(lambda q, q_t, q_tt: HillRows(sur, lam, lam_dot, q, q_t, q_tt),
                              dl.period, M)  # fmt: skip
    zero = np.zeros((M, 1))
    R = col.residual(zero)
    J = col.dense_jacobian(col.jacobian_blocks(zero))
    return tau, -sla.solve(J, R.ravel())


@pytest.mark.parametrize(
    "drive",
    [
        Drive(5.0, 1.0, 7.0),  # the reference scene, next to resonance
        Drive(20.0, 1.0, 2.5),  # stiffened, below resonance
        Drive(20.0, 1.0, 2.5, harmonics=(Harmonic(1, 1.0), Harmonic(3, 0.5, 0.7))),
    ],
)
def test_surrogate_hill_solve_is_the_collocated_one(drive):
    """The surrogate's banded Galerkin solve in Fourier space and the collocation of the same
    Hill equation at M = 65 instants give the same q(tau) to 1e-10 of its size: two
    discretisations of one periodic problem, both spectral (the error falls from 1e-4 or more
    at M = 5 to round-off by M = 17)."""
    sur = SurrogateModel.from_dimensionless(Dimensionless.from_physical(Beam(), drive))
    tau, q = _collocated_q(sur, 65)
    expected = sur.midspan_series(tau) / sur.phi_mid
    assert np.max(np.abs(q - expected)) <= 1e-11 * np.max(np.abs(expected))
    tau5, q5 = _collocated_q(sur, 5)  # too few instants: the check tells them apart
    assert np.max(np.abs(q5 - sur.midspan_series(tau5) / sur.phi_mid)) > 1e-5 * np.max(
        np.abs(expected)
    )


def _pendulum(t, z, p):
    return np.array([z[1], -0.1 * z[1] - np.sin(z[0]) + p * np.cos(t)])


def _pendulum_jac(t, z, p):
    return np.array([[0.0, 1.0], [-np.cos(z[0]), -0.1]])


def test_first_order_collocation_is_d_kron_i_minus_blockdiag():
    """FirstOrderProblem through SpectralCollocation: R = D Z - f(t_j, Z_j) and
    dR/dZ = D (x) I - blockdiag(J_j), written out here from the Fourier matrix."""
    M, P, p = 15, 2.0 * np.pi, 0.3
    pr = FirstOrderProblem(_pendulum, _pendulum_jac, lambda _: P, 2, M=M)
    x = np.random.default_rng(3).normal(size=2 * M)
    Z = x.reshape(M, 2)
    t = np.arange(M) * P / M
    D = fourier_diff_matrix(M, P)
    F = np.array([_pendulum(tj, zj, p) for tj, zj in zip(t, Z, strict=True)])
    assert np.allclose(pr.residual(x, p), (D @ Z - F).ravel(), rtol=0, atol=1e-13)
    J = np.kron(D, np.eye(2))
    for j in range(M):
        J[2 * j : 2 * j + 2, 2 * j : 2 * j + 2] -= _pendulum_jac(t[j], Z[j], p)
    assert np.allclose(pr.jacobian(x, p), J, rtol=0, atol=1e-13)


def test_first_order_collocation_finds_the_forced_pendulum_orbit():
    """Newton on the first-order collocation lands on the orbit that time stepping settles on
    (the damped, weakly forced pendulum: one attracting period-2 pi orbit)."""
    from scipy.integrate import solve_ivp

    M, P, p = 33, 2.0 * np.pi, 0.3
    pr = FirstOrderProblem(_pendulum, _pendulum_jac, lambda _: P, 2, M=M)
    sol = solve_ivp(_pendulum, (0, 80 * P), [0.0, 0.0], args=(p,), rtol=1e-11, atol=1e-12,
                    dense_output=True)  # fmt: skip
    settled = sol.sol(79 * P + np.arange(M) * P / M).T.ravel()
    x = np.zeros(2 * M)
    for _ in range(20):
        x = x - np.linalg.solve(pr.jacobian(x, p), pr.residual(x, p))
    assert np.max(np.abs(pr.residual(x, p))) < 1e-10
    assert np.max(np.abs(x - settled)) < 1e-7
