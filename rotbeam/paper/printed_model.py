"""The discrete model of Appendix A *as printed*, misprint by misprint, beside our re-derivation.

`PrintedElastica` subclasses `rotbeam.model.elastica.DiscreteElastica` and switches on, one at a
time or together, what the printed appendix has where ours departs from it (`MISPRINTS`).  Every
solver takes such a model as it takes ours.  The misprints and what each does to the equations:
docs/reproduction.md.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..config.errors import RotbeamInputError
from ..model.elastica import DiscreteElastica
from ..model.params import Dimensionless

#: the printed appendix's misprints a model can switch on
MISPRINTS = ("bracket", "U3", "symS", "Kds")


class PrintedElastica(DiscreteElastica):
    """`DiscreteElastica` with some of the printed appendix's misprints switched on.

    Parameters
    ----------
    dl : Dimensionless
        The scene.
    N : int
        Grid intervals.
    misprints : tuple of str
        Any of `MISPRINTS`: "bracket" (the printed tension bracket), "U3" (the last column of
        3s in U), "symS" (the symmetric velocity-squared matrix), "Kds" (K with 1/ds).

    Raises
    ------
    RotbeamInputError
        For a misprint not in `MISPRINTS`.

    Notes
    -----
    With ``symS`` the Jacobians the solvers use stay those of the derivation's antisymmetric
    matrix: Newton converges more slowly on this model, to the same orbit.
    """

    def __init__(self, dl: Dimensionless, N: int, misprints: tuple[str, ...] = ()) -> None:
        super().__init__(dl, N)
        bad = [m for m in misprints if m not in MISPRINTS]
        if bad:
            raise RotbeamInputError(
                f"misprints = {bad!r}: unknown; allowed: {', '.join(MISPRINTS)}"
            )
        self.misprints = tuple(misprints)
        g = self.grid
        if "U3" in self.misprints:
            Q = g.Q.copy()
            Q[:, -2] += Q[:, -1]  # g_N taken equal to g_{N-1}: 2 + 1 = 3 in the last column
            Q[:, -1] = 0.0
            g = replace(g, Q=Q, W=Q @ g.P)
        if "Kds" in self.misprints:
            g = replace(g, K=g.K * g.ds)
        self.grid = g
        s = g.s[: self.n]  # nodes 1..N-1, where the tension is evaluated
        if "bracket" in self.misprints:
            self.extra = (1.0 - s**2 / 4.0) - (g.ds / 2.0) * (1.0 - s)
        else:
            self.extra = np.zeros(self.n)

    def at(self, dl: Dimensionless) -> PrintedElastica:
        """The same printed variant for another scene.

        Parameters
        ----------
        dl : Dimensionless
            The scene.

        Returns
        -------
        PrintedElastica
            The model of `dl` on the same grid, with the same misprints.
        """
        return PrintedElastica(dl, self.N, self.misprints)

    # the printed bracket adds lam^2 e to n_x and -lam_t e to n_y: torque s n_x - c n_y
    def load_torque_rows(
        self, theta: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray, jacobian: bool = False
    ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """`DiscreteElastica.load_torque_rows` with the printed bracket's extra tension.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles, shape (m, n).
        lam, lam_dot : numpy.ndarray
            Rotation rate Omega T and its rate of change at the m instants, shape (m,).
        jacobian : bool
            Also return dL/dTheta.

        Returns
        -------
        numpy.ndarray or tuple
            L, shape (m, n); with `jacobian`, (L, dL/dTheta of shape (m, n, n)).
        """
        out = super().load_torque_rows(theta, lam, lam_dot, jacobian=jacobian)
        if "bracket" not in self.misprints:
            return out
        lam = np.asarray(lam, dtype=float)[:, None]
        ld = np.asarray(lam_dot, dtype=float)[:, None]
        ef = self.effects
        ex = (lam * lam if ef.centrifugal else 0.0 * lam) * self.extra[None]
        ey = -(ld if ef.euler else 0.0 * ld) * self.extra[None]
        c, s = np.cos(theta), np.sin(theta)
        if not jacobian:
            return out + s * ex - c * ey
        torque, J = out
        idx = np.arange(self.n)
        J = J.copy()
        J[:, idx, idx] += c * ex + s * ey
        return torque + s * ex - c * ey, J

    def velocity_matrix_rows(self, theta: np.ndarray, B: np.ndarray) -> np.ndarray:
        """The matrix multiplying Theta_t^2: the printed symmetric W o S~ with ``symS``, else B.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles, shape (m, n).
        B : numpy.ndarray
            The derivation's antisymmetric matrix W_ij sin(theta_i - theta_j), shape (m, n, n).

        Returns
        -------
        numpy.ndarray
            Shape (m, n, n).
        """
        if "symS" not in self.misprints:
            return B
        d = theta[:, None, :] - theta[:, :, None]  # theta_j - theta_i
        upper = np.arange(self.n)[:, None] < np.arange(self.n)[None, :]
        S = np.where(upper[None], np.sin(d), np.sin(-d))
        idx = np.arange(self.n)
        S[:, idx, idx] = 0.0
        return self.grid.W[None] * S
