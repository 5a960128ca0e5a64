r"""The discrete model of Appendix A *as printed*, misprint by misprint, beside our re-derivation.

`PrintedElastica` subclasses `rotbeam.model.elastica.DiscreteElastica` and switches on, one at a
time or together, what the printed appendix has where `rotbeam.model.elastica` departs from it:

* ``bracket``: the first bracket of Eqs. (Disc_tension_x/y), 1 + (delta - 1) s - delta s^2/4,
  taken literally.  As printed, n_x = C [bracket] + U L delta C c~ + ..., i.e. (units of
  `rotbeam.model.params`, C = lam^2 / delta) the centrifugal tension is lam^2 [bracket] / delta +
  lam^2 Q P cos(Theta), where the integral of lam^2 (r_o + x) is lam^2 [r_o (1 - s) +
  Q (ds/2 + P cos Theta)].  The difference is an extra tension lam^2 e(s) with
  e(s) = (1 - s^2/4) - (ds/2)(1 - s) (nonzero at the free end, where n must vanish); the Euler
  bracket of n_y adds the same e(s) times -lam_t.  Both enter the load torque.
* ``U3``: the last column of 3s in U (the tip node's value g_N replaced by g_{N-1}).
* ``symS``: the velocity-squared matrix W o S~ with the printed *symmetric* S~,
  S~_ij = sin(theta_max(i,j) - theta_min(i,j)), where the derivation gives the antisymmetric
  W_ij sin(theta_i - theta_j).
* ``Kds``: K with 1/ds instead of 1/ds^2 (bending stiffness divided by N).

The fourth printed slip, +2 I y_t in the n_y integrand of Eq. (NumT), only acts with Coriolis on
(the paper switches Coriolis off): see `rotbeam.paper.c_hypotheses` ("printed_ny_coriolis").

Every solver takes such a model as it takes ours (`rotbeam.model.base.DiscreteModel`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..config.errors import RotbeamInputError
from ..model.elastica import DiscreteElastica
from ..model.params import Dimensionless

MISPRINTS = ("bracket", "U3", "symS", "Kds")


class PrintedElastica(DiscreteElastica):
    """`DiscreteElastica` with the printed appendix's misprints in `misprints` switched on.

    Parameters
    ----------
    dl : Dimensionless
        The scene.
    N : int
        Grid intervals.
    misprints : tuple of str
        Any of MISPRINTS.

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
        """The same printed variant for the scene `dl`."""
        return PrintedElastica(dl, self.N, self.misprints)

    # the printed bracket adds lam^2 e to n_x and -lam_t e to n_y: torque s n_x - c n_y
    def load_torque_rows(self, theta, lam, lam_dot, jacobian=False):
        """`DiscreteElastica.load_torque_rows` with the printed bracket's extra tension."""
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
        """The matrix multiplying Theta_t^2: the printed symmetric W o S~ with ``symS``, else B."""
        if "symS" not in self.misprints:
            return B
        d = theta[:, None, :] - theta[:, :, None]  # theta_j - theta_i
        upper = np.arange(self.n)[:, None] < np.arange(self.n)[None, :]
        S = np.where(upper[None], np.sin(d), np.sin(-d))
        idx = np.arange(self.n)
        S[:, idx, idx] = 0.0
        return self.grid.W[None] * S
