"""The periodic collocation of `rotbeam.solve.periodic` on any `DiscreteElastica` subclass.

Used for the printed-appendix variants (`rotbeam.model.elastica_printed`): the residual carries
the printed symmetric S~ when the model has it; the Jacobian stays ours, which only slows Newton
down (inexact Newton, GMRES preconditioned by the time-averaged Jacobian, dense LU when GMRES
stalls).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
from scipy.sparse.linalg import LinearOperator, gmres

from ..model.elastica import DiscreteElastica
from ..model.elastica_printed import PrintedElastica
from ..model.params import Dimensionless
from .periodic import Collocation, linear_guess
from .spectral import harmonic_tail


class PrintedCollocation(Collocation):
    """`Collocation` whose residual is that of `model` (ours or a `PrintedElastica`)."""

    def __init__(self, dl: Dimensionless, model: DiscreteElastica, M: int):
        super().__init__(dl, model.grid.N, M)
        self.model = model

    def residual(self, X: np.ndarray) -> np.ndarray:
        R = super().residual(X)
        m = self.model
        if isinstance(m, PrintedElastica) and "symS" in m.misprints:
            V = self.D @ X
            for j in range(X.shape[0]):
                _, B = m.mass_and_gyro(X[j])
                R[j] += (m.velocity_matrix(X[j]) - B) @ (V[j] ** 2)
        return R


def _inexact_newton_step(col: PrintedCollocation, X: np.ndarray, R: np.ndarray) -> np.ndarray:
    """GMRES on J step = -R (time-averaged preconditioner); dense LU when GMRES stalls."""
    blocks = col.jacobian_blocks(X)
    inv = col.averaged_inverse(blocks)
    size, shape = R.size, R.shape
    op = LinearOperator(
        (size, size), lambda v: col.jacobian_times(blocks, v.reshape(shape)).ravel()
    )
    pre = LinearOperator((size, size), lambda r: inv(r.reshape(shape)).ravel())
    step, info = gmres(op, -R.ravel(), rtol=1e-6, atol=0.0, restart=60, maxiter=20, M=pre)
    if info != 0:
        step = -sla.solve(col.dense_jacobian(blocks), R.ravel())
    return step.reshape(shape)


def _backtrack(col: PrintedCollocation, X: np.ndarray, step: np.ndarray, rn: float):
    """Halve the step until the residual's max norm drops (or the step is 1e-3 of Newton's)."""
    t = 1.0
    while True:
        Xt = X + t * step
        Rt = col.residual(Xt)
        rt = float(np.max(np.abs(Rt)))
        if np.isfinite(rt) and (rt < rn or t < 1e-3):
            return Xt, Rt, rt, t
        t *= 0.5


def periodic_orbit(
    dl: Dimensionless,
    model: DiscreteElastica,
    M: int = 33,
    guess: np.ndarray | None = None,
    rtol: float = 1e-10,
    maxiter: int = 30,
) -> tuple[np.ndarray, bool, float]:
    """Collocated periodic orbit X (M, n) of `model`: (X, converged, harmonic tail)."""
    col = PrintedCollocation(dl, model, M)
    X = linear_guess(dl, model.grid.N, col.tau) if guess is None else np.array(guess, float)
    R = col.residual(X)
    rn = float(np.max(np.abs(R)))
    for _ in range(maxiter):
        step = _inexact_newton_step(col, X, R)
        X, R, rn, t = _backtrack(col, X, step, rn)
        if float(np.max(np.abs(t * step))) <= rtol * max(float(np.max(np.abs(X))), 1e-300):
            return X, True, harmonic_tail(X)
    return X, False, harmonic_tail(X)
