"""The elastica's structure of the residual: mass and gyroscopic matrices with M = W cos and
B = W sin, a constant stiffness and loads, and the residual's blocks from their identities.

The equation and the identities: docs/model.md, "The model contract".
"""

from __future__ import annotations

from abc import abstractmethod

import numpy as np

from .base import DiscreteModel, Residual
from .rows import matvec_rows


class GyroscopicModel(DiscreteModel):
    """A model whose residual has the rotating elastica's structure::

        R = M(Theta) Theta_tt + eta Md(Theta) Theta_t + S(Theta) Theta_t^2
            + g B(Theta) Theta_t + K Theta + L(Theta; lam, lam_dot),

    with the gyroscopic term only where the model has one (`gyroscopic_rows`: g = 2 lam of the
    Coriolis load) and Md = M unless the model says otherwise (`damping_rows`: a payload has no
    damping of its own).  A subclass gives M and B (`inertia_rows`), K (`stiffness`), the loads
    L and their exact Jacobian (`load_torque_rows`) and `at`; S is B unless it says otherwise
    (`velocity_matrix_rows`).  The residual and its blocks follow here (`residual_rows`),
    matrix-free where the identities allow.

    Attributes
    ----------
    eta : float
        Damping applied (0 without damping).
    """

    eta: float

    @property
    def damped(self) -> bool:
        """Whether any motion decays: eta > 0, or a load's linear damping (`DiscreteModel`)."""
        return self.eta > 0.0 or super().damped

    @abstractmethod
    def inertia_rows(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Mass and gyroscopic matrices at m instants.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles, shape (m, n).

        Returns
        -------
        M, B : numpy.ndarray
            Shape (m, n, n) each, with d(M a)/dTheta = B diag(a) - diag(B a) and
            d(B v)/dTheta = diag(M v) - M diag(v) for fixed vectors a, v.
        """

    @property
    @abstractmethod
    def stiffness(self) -> np.ndarray:
        """The bending stiffness K, shape (n, n)."""

    @abstractmethod
    def load_torque_rows(
        self, theta: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray, jacobian: bool = False
    ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """The loads L(Theta; lam, lam_dot) at m instants, and their exact Jacobians.

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

    def damping_rows(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """The mass matrix the damping acts on and its gyroscopic partner, when it is not M.

        The damping is per unit length of the beam; a payload adds mass without damping, so a
        model with one gives Md (and Bd, its partner as B is M's, for the Jacobian) here.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (m, n).

        Returns
        -------
        tuple of numpy.ndarray or None
            (Md, Bd), shape (m, n, n) each; None: the damping is eta M (the default).
        """
        return None

    def velocity_matrix_rows(self, theta: np.ndarray, B: np.ndarray) -> np.ndarray:
        """S, the matrix multiplying Theta_t^2, at m instants.

        The derivation gives S = B (the default); the printed appendix's symmetric matrix is
        the one model that says otherwise (`rotbeam.paper.printed_model`).  The Jacobians use B
        either way, so they are exact only for S = B.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (m, n).
        B : numpy.ndarray
            The gyroscopic matrices at the same instants, shape (m, n, n).

        Returns
        -------
        numpy.ndarray
            S, shape (m, n, n) (`B` itself by default).
        """
        return B

    def rate_load_rows(
        self,
        theta: np.ndarray,
        theta_t: np.ndarray,
        lam: np.ndarray,
        lam_dot: np.ndarray,
        jacobian: bool = False,
    ) -> tuple | None:
        """Loads beyond L, the gyroscopic and the damping terms, any function of the angles and
        their rates (a drag, say), with their blocks.

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Angles [rad] and their rates (1/T), shape (m, n) each.
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change at the m instants, shape (m,).
        jacobian : bool
            Also give the blocks.

        Returns
        -------
        tuple or None
            (T, dT/dTheta, dT/dTheta_t): T of shape (m, n), the blocks (m, n, n) with
            `jacobian` (None: zero); None (the default): no such load.
        """
        return None

    def gyroscopic_rows(self, lam: np.ndarray | float) -> np.ndarray | float | None:
        """g of the gyroscopic term g B Theta_t at m instants (2 lam of the Coriolis load).

        Parameters
        ----------
        lam : numpy.ndarray or float
            Omega T at the m instants, shape (m,), or one value.

        Returns
        -------
        numpy.ndarray or float or None
            g, the shape of `lam` (units of 1/T); None (the default): no gyroscopic term.
        """
        return None

    def velocity_vector(self, theta_t: np.ndarray, lam: np.ndarray | float) -> np.ndarray:
        """What B multiplies: v = Theta_t^2, plus g Theta_t with a gyroscopic term
        (`gyroscopic_rows`).

        Parameters
        ----------
        theta_t : numpy.ndarray
            Angular rates (units of 1/T), shape (m, n) or (n,).
        lam : numpy.ndarray or float
            Omega T at the m instants, shape (m,), or one value.

        Returns
        -------
        numpy.ndarray
            v, the shape of `theta_t`.
        """
        v = theta_t**2
        g = self.gyroscopic_rows(np.asarray(lam, dtype=float))
        if g is not None:
            v = v + (g[:, None] if np.ndim(g) else g) * theta_t
        return v

    def residual_rows(
        self,
        theta: np.ndarray,
        theta_t: np.ndarray,
        theta_tt: np.ndarray | None,
        lam: np.ndarray,
        lam_dot: np.ndarray,
        jacobian: bool = False,
    ) -> ResidualRows:
        """The equation of motion as a residual at m instants, with what its blocks reuse.

        R = M (Theta_tt + eta Theta_t) + S Theta_t^2 + g B Theta_t + K Theta + L, with
        eta Md Theta_t in place of eta M Theta_t where the damping has its own mass matrix
        (`damping_rows`): zero where (Theta, Theta_t, Theta_tt) is a motion of the model.  What
        collocation solves at its instants; `ResidualRows.blocks` gives dR/dTheta, dR/dTheta_t
        and dR/dTheta_tt = M (docs/model.md, "The model contract").

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Angles [rad] and their rates (1/T), shape (m, n) each.
        theta_tt : numpy.ndarray or None
            Accelerations (1/T^2), shape (m, n); None: R without its inertia term
            M (Theta_tt + eta Theta_t), the rows to solve for the accelerations
            (`ResidualRows.solved`).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change at the m instants, shape (m,).
        jacobian : bool
            Evaluate the loads' Jacobian with the loads (the blocks will be asked for: one
            evaluation of the loads instead of two).

        Returns
        -------
        ResidualRows
            ``R`` (dimensionless torques, shape (m, n)) and its blocks on demand.
        """
        lam, lam_dot = np.asarray(lam, dtype=float), np.asarray(lam_dot, dtype=float)
        Mm, Bm = self.inertia_rows(theta)
        v = self.velocity_vector(theta_t, lam)
        S = self.velocity_matrix_rows(theta, Bm)
        damp = self.damping_rows(theta)
        if theta_tt is None:  # the part without M (Theta_tt + eta Theta_t): `ResidualRows.solved`
            a = None
            R = matvec_rows(Bm, v) + theta @ self.stiffness.T
        else:
            a = theta_tt + self.eta * theta_t if damp is None else theta_tt
            R = matvec_rows(Mm, a) + matvec_rows(Bm, v) + theta @ self.stiffness.T
        if damp is not None:  # the damping's own mass matrix
            R += self.eta * matvec_rows(damp[0], theta_t)
        dL = None
        if jacobian:
            torque, dL = self.load_torque_rows(theta, lam, lam_dot, jacobian=True)
            R += torque
        else:
            R += self.load_torque_rows(theta, lam, lam_dot)
        if S is not Bm:  # a model whose squared rates carry another matrix than B
            R += matvec_rows(S - Bm, theta_t * theta_t)
        rate = self.rate_load_rows(theta, theta_t, lam, lam_dot, jacobian)
        if rate is not None:
            R += rate[0]
        return ResidualRows(
            self,
            theta,
            theta_t,
            a,
            lam,
            lam_dot,
            Mm,
            Bm,
            v,
            damp,
            R,
            dL,
            (rate,) if jacobian else None,
        )

    # --- the static problem, faster than the residual at rest -----------------------------------
    def static_rows(
        self, theta: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray, jacobian: bool = False
    ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """K Theta + L at m instants, and its Jacobian: the residual at rest
        (`DiscreteModel.static_rows`) without forming the mass matrices, equal to it to the bit.

        The quasi-static response is its root at every instant (time derivatives zero).

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (m, n).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change at the m instants, shape (m,).
        jacobian : bool
            Also return K + dL/dTheta, shape (m, n, n).

        Returns
        -------
        numpy.ndarray or tuple
            The residual (m, n), dimensionless torques; with `jacobian`, (residual, Jacobians).
        """
        K = self.stiffness
        rate = self.rate_load_rows(theta, np.zeros_like(theta), lam, lam_dot, jacobian)
        if not jacobian:
            R = theta @ K.T + self.load_torque_rows(theta, lam, lam_dot)
            return R if rate is None else R + rate[0]
        torque, dL = self.load_torque_rows(theta, lam, lam_dot, jacobian=True)
        dL += K[None]
        R = theta @ K.T + torque
        if rate is None:
            return R, dL
        if rate[1] is not None:
            dL += rate[1]
        return R + rate[0], dL


class ResidualRows(Residual):
    """The residual of a `GyroscopicModel` at m instants, and its derivatives from the same
    evaluation of the mass and gyroscopic matrices.

    Attributes
    ----------
    R : numpy.ndarray
        The residual, shape (m, n), dimensionless torques.
    """

    def __init__(
        self, model, theta, theta_t, a, lam, lam_dot, Mm, Bm, v, damp, R, dL=None, rate=None
    ):
        self.model, self.theta, self.theta_t, self.a = model, theta, theta_t, a
        self.lam, self.lam_dot = lam, lam_dot
        self.Mm, self.Bm, self.v, self.damp, self.R = Mm, Bm, v, damp, R
        self.dL = dL  #: the loads' Jacobian, when `residual_rows` was asked for it
        #: (the rate-dependent loads with their blocks,) once evaluated with them
        #: (`GyroscopicModel.rate_load_rows`); None: not yet
        self.rate = rate
        self._lu = None  #: the LU of the one mass matrix, once `keep_lu` has made it

    def mass(self) -> np.ndarray:
        """M at each instant (`Residual.mass`).

        Returns
        -------
        numpy.ndarray
            Shape (m, n, n).
        """
        return self.Mm

    def accelerate(self, theta_tt: np.ndarray) -> None:
        """Move the rows to the accelerations `theta_tt` (`Residual.accelerate`).

        Parameters
        ----------
        theta_tt : numpy.ndarray
            Accelerations (1/T^2), shape (m, n).
        """
        a = theta_tt + self.model.eta * self.theta_t if self.damp is None else theta_tt
        old = np.zeros_like(a) if self.a is None else self.a
        self.R = self.R + matvec_rows(self.Mm, a - old)
        self.a = a

    def apply(self, p: np.ndarray, q: np.ndarray) -> np.ndarray:
        """dR/dTheta p + dR/dTheta_t q at each instant without forming the blocks (the
        identities of `GyroscopicModel.inertia_rows`; exact for S = B).

        Parameters
        ----------
        p, q : numpy.ndarray
            Directions of the angles and of the rates, shape (m, n) each.

        Returns
        -------
        numpy.ndarray
            Shape (m, n), dimensionless torques.
        """
        m, V, a, lam = self.model, self.theta_t, self.a, self.lam
        Mm, Bm, v, damp = self.Mm, self.Bm, self.v, self.damp
        if self.dL is None:
            self.dL = m.load_torque_rows(self.theta, lam, self.lam_dot, jacobian=True)[1]
        out = p @ m.stiffness.T + matvec_rows(self.dL, p) - matvec_rows(Mm, v * p)
        out += matvec_rows(Bm, a * p) - (matvec_rows(Bm, a) - matvec_rows(Mm, v)) * p
        dv = 2.0 * V * q
        g = m.gyroscopic_rows(lam)
        if g is not None:
            dv = dv + g[:, None] * q
        out += matvec_rows(Bm, dv)
        if damp is None:
            out += m.eta * matvec_rows(Mm, q)
        else:
            Md, Bd = damp
            out += m.eta * (matvec_rows(Bd, V * p) - matvec_rows(Bd, V) * p)
            out += m.eta * matvec_rows(Md, q)
        rate = self._rate_blocks()
        if rate is not None:
            for block, x in zip(rate[1:], (p, q), strict=True):
                if block is not None:
                    out += matvec_rows(block, x)
        return out

    def _rate_blocks(self) -> tuple | None:
        """The rate-dependent loads' blocks at these rows, evaluated once (None: no such load)."""
        if self.rate is None:
            m = self.model
            self.rate = (m.rate_load_rows(self.theta, self.theta_t, self.lam, self.lam_dot, True),)
        return self.rate[0]

    def solved(self, keep_lu: bool = False) -> np.ndarray:
        """The accelerations that zero the residual at these angles and rates: the residual is
        affine in Theta_tt, R = M (Theta_tt + eta Theta_t) + R_0 (eta Md Theta_t in R_0 where
        the damping has its own mass matrix), so Theta_tt + eta Theta_t = -M^-1 R_0; `blocks`
        and `apply` are then taken there.  Valid on rows evaluated without Theta_tt
        (`residual_rows(..., None, ...)`).

        Parameters
        ----------
        keep_lu : bool
            At one instant, keep the mass matrix's LU for a tangent's solve (`mass_solve`).

        Returns
        -------
        numpy.ndarray
            Theta_tt (units of 1/T^2), shape (m, n).
        """
        self.keep_lu(keep_lu)
        self.a = -self.mass_solve(self.R)  # Theta_tt (+ eta Theta_t where the damping is eta M)
        self.R = np.zeros_like(self.R)
        if self.damp is None:
            return self.a - self.model.eta * self.theta_t
        return self.a

    def blocks(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """dR/dTheta, dR/dTheta_t and dR/dTheta_tt = M at each instant (exact for S = B: the
        identities of `GyroscopicModel.inertia_rows` and the loads' own Jacobian).

        Returns
        -------
        dR_dtheta, dR_dtheta_t, mass : numpy.ndarray
            Shape (m, n, n) each.
        """
        m, theta, V, a = self.model, self.theta, self.theta_t, self.a
        Mm, Bm, v, damp = self.Mm, self.Bm, self.v, self.damp
        n = m.n
        Ba = matvec_rows(Bm, a)
        Mv = matvec_rows(Mm, v)
        dv = 2.0 * V
        g = m.gyroscopic_rows(self.lam)
        if g is not None:
            dv = dv + g[:, None]
        Cj = m.eta * (Mm if damp is None else damp[0]) + Bm * dv[:, None, :]
        if self.dL is None:
            self.dL = m.load_torque_rows(theta, self.lam, self.lam_dot, jacobian=True)[1]
        Lj = self.dL + (m.stiffness[None] + Bm * a[:, None, :] - Mm * v[:, None, :])
        idx = np.arange(n)
        Lj[:, idx, idx] += Mv - Ba
        if damp is not None:  # d(eta Md V)/dTheta = eta (Bd diag(V) - diag(Bd V))
            Bd = damp[1]
            Lj += m.eta * (Bd * V[:, None, :])
            Lj[:, idx, idx] -= m.eta * matvec_rows(Bd, V)
        rate = self._rate_blocks()
        if rate is not None:
            if rate[1] is not None:
                Lj += rate[1]
            if rate[2] is not None:
                Cj = Cj + rate[2]
        return Lj, Cj, Mm
