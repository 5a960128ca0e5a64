"""The periodic collocation of `rotbeam.solve.periodic` on any `DiscreteElastica` subclass.

Used for the printed-appendix variants (`rotbeam.model.elastica_printed`): the residual carries
the printed symmetric S~ when the model has it; the Jacobian stays ours, which only slows Newton
down (the Newton step and line search of `rotbeam.solve.periodic`).
"""

from __future__ import annotations

import numpy as np

from ..model.elastica import DiscreteElastica
from ..model.elastica_printed import PrintedElastica
from ..model.params import Dimensionless
from .periodic import Collocation, _line_search, _newton_step, linear_guess
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
        step, _, _ = _newton_step(col, col.jacobian_blocks(X), R, "auto")
        t, X, R, rn = _line_search(col, X, step, rn)
        if float(np.max(np.abs(t * step))) <= rtol * max(float(np.max(np.abs(X))), 1e-300):
            return X, True, harmonic_tail(X)
    return X, False, harmonic_tail(X)
