"""The contract between a discrete model of the rotating beam and the solvers.

Every solver of rotbeam (collocation, time stepping, Floquet, continuation, the quasi-static
solver, the response classification) takes a `DiscreteModel` and uses nothing else of it than
what this class declares.  The equations and why they take this form: docs/model.md, "The
model contract".
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from .grid import Grid
from .params import Dimensionless, Effects
from .rows import matvec_rows


class DiscreteModel(ABC):
    """A discrete model of the beam on the rotating disk, as the solvers see it.

    The model is second order in the n angles Theta (time in units of T)::

        M(Theta) Theta_tt + eta Md(Theta) Theta_t + S(Theta) Theta_t^2 + 2 lam B(Theta) Theta_t
            + K Theta + L(Theta; lam, lam_dot) = 0,

    with the Coriolis term only when `effects.coriolis` is on and Md = M unless the model says
    otherwise (`damping_rows`: a payload has no damping of its own).  A subclass gives the mass and
    gyroscopic matrices M, B (`inertia_rows`), the stiffness K (`stiffness`), the loads L and
    their exact Jacobian (`load_torque_rows`), the scene it is built for (`dl`, with the drive
    lam(tau), lam_dot(tau)) and a copy of itself for another scene (`at`).  S, the matrix of the
    squared rates, is B unless the subclass says otherwise (`velocity_matrix_rows`).  From
    these the base class derives, once, what the solvers call: the first-order right-hand side
    and its Jacobian, the static residual, the linear operators and the outputs.

    Attributes
    ----------
    dl : Dimensionless
        The scene: dimensionless groups, effects and drive.
    grid : Grid
        Nodes, quadratures and outputs (y_m, tip) of the discretisation.
    n : int
        Number of angles (the state of the first-order system has 2 n entries).
    eta : float
        Damping applied (0 with `effects.damping` off).
    effects : Effects
        The loads the model computes.
    """

    dl: Dimensionless
    grid: Grid
    n: int
    eta: float
    effects: Effects

    # --- what a model must give ---------------------------------------------------------------
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

    @abstractmethod
    def at(self, dl: Dimensionless) -> DiscreteModel:
        """The same model (grid, structure) for another scene.

        Sweeps, continuation and the effect budget change the scene and keep the grid.

        Parameters
        ----------
        dl : Dimensionless
            The other scene.

        Returns
        -------
        DiscreteModel
            A model of the same class and grid for `dl`.
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

    def kernel(self) -> tuple[tuple | None, str]:
        """The model as a compiled kernel reads it, if it offers one (an optional accelerator
        of its right-hand side; `rotbeam.solve.elastica_rk` is the one rotbeam has).

        Returns
        -------
        arguments : tuple or None
            What the kernel reads, None where the model offers none for this scene.
        why_not : str
            '' with arguments, else why the model is left to the numpy path.
        """
        return None, f"{type(self).__name__} offers no compiled kernel"

    # --- the drive ------------------------------------------------------------------------------
    def drive_rows(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The drive lam = Omega T and lam_dot at many instants, for the row-wise methods.

        Parameters
        ----------
        tau : numpy.ndarray
            Instants in units of T, shape (m,).

        Returns
        -------
        lam, lam_dot : numpy.ndarray
            Dimensionless, shape (m,) each.
        """
        dl = self.dl
        return np.array([dl.lam(t) for t in tau]), np.array([dl.lam_dot(t) for t in tau])

    # --- first-order form -----------------------------------------------------------------------
    def velocity_vector(self, theta_t: np.ndarray, lam: np.ndarray | float) -> np.ndarray:
        """What B multiplies: v = Theta_t^2, plus 2 lam Theta_t with Coriolis on.

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
        if self.effects.coriolis:
            lam = np.asarray(lam, dtype=float)
            v = v + 2.0 * (lam[:, None] if lam.ndim else lam) * theta_t
        return v

    def acceleration(
        self, theta: np.ndarray, theta_t: np.ndarray, lam: float, lam_dot: float
    ) -> np.ndarray:
        """Theta_tt at one instant, from the equation of motion.

        The time stepper's right-hand side: the equation of motion (`DiscreteModel`) with
        M Theta_tt on the left, solved by one LU factorisation of M.

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Angles [rad] and their rates (units of 1/T), shape (n,).
        lam, lam_dot : float
            Rotation rate Omega T and its rate of change, dimensionless.

        Returns
        -------
        numpy.ndarray
            Theta_tt (units of 1/T^2), shape (n,).
        """
        rows = self.residual_rows(theta[None], theta_t[None], None, [lam], [lam_dot])
        return rows.solved(keep_lu=True)[0]

    def first_order_jvp(
        self,
        theta: np.ndarray,
        theta_t: np.ndarray,
        lam: float,
        lam_dot: float,
        p: np.ndarray,
        q: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The first-order right-hand side and its Jacobian times a vector, at one instant.

        What a tangent (variational) equation needs at every stage of a time step: J (p, q)
        without forming J, from the residual's directional derivative (`ResidualRows.apply`;
        docs/stability.md, "The tangent without the Jacobian"): one more solve with the mass
        matrix instead of 2 n of them.  Equal to `first_order_jacobian` @ (p, q) to
        round-off (exact for S = B, as that Jacobian).

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Angles and rates, shape (n,).
        lam, lam_dot : float
            Rotation rate and its rate of change.
        p, q : numpy.ndarray
            The direction's angle and rate parts, shape (n,) each.

        Returns
        -------
        F : numpy.ndarray
            (Theta_t, Theta_tt), shape (2 n,).
        Jv : numpy.ndarray
            dF/d(Theta, Theta_t) applied to (p, q), shape (2 n,).
        """
        rows = self.residual_rows(theta[None], theta_t[None], None, [lam], [lam_dot], True)
        acc = rows.solved(keep_lu=True)[0]
        dq = -rows.mass_solve(rows.apply(p[None], q[None]))[0]
        return np.concatenate([theta_t, acc]), np.concatenate([q, dq])

    def first_order_rows(
        self, theta: np.ndarray, theta_t: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """The first-order right-hand side (Theta_t, Theta_tt) and its exact Jacobian at m
        instants at once.

        Collocation, the implicit steppers and the Floquet monodromy need both at every step.
        Both follow from the residual (`residual_rows`), which is affine in Theta_tt: Theta_tt
        solves M Theta_tt = -R(Theta, Theta_t, 0), and its derivatives are -M^-1 (dR/dTheta,
        dR/dTheta_t) there (docs/model.md, "The model contract").

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Angles [rad] and rates (units of 1/T), shape (m, n).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change at the m instants, shape (m,).

        Returns
        -------
        F : numpy.ndarray
            (Theta_t, Theta_tt), shape (m, 2 n).
        J : numpy.ndarray
            dF/d(Theta, Theta_t), shape (m, 2 n, 2 n); exact for S = B (docs/model.md).
        """
        n = self.n
        rows = self.residual_rows(theta, theta_t, None, lam, lam_dot, True)
        acc = rows.solved()
        dq, dqt, mass = rows.blocks()
        X = np.linalg.solve(mass, np.concatenate([dq, dqt], axis=2))
        idx = np.arange(n)
        J = np.zeros((theta.shape[0], 2 * n, 2 * n))
        J[:, idx, n + idx] = 1.0
        J[:, n:, :] = -X
        return np.concatenate([theta_t, acc], axis=1), J

    def first_order_jacobian(
        self, theta: np.ndarray, theta_t: np.ndarray, lam: float, lam_dot: float
    ) -> np.ndarray:
        """`first_order_rows`' Jacobian at one instant.

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Angles [rad] and rates (units of 1/T), shape (n,).
        lam, lam_dot : float
            Omega T and its rate of change.

        Returns
        -------
        numpy.ndarray
            d(Theta_t, Theta_tt)/d(Theta, Theta_t), shape (2 n, 2 n).
        """
        return self.first_order_rows(theta[None], theta_t[None], [lam], [lam_dot])[1][0]

    # --- the equation of motion as a residual ----------------------------------------------------
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

        R = M (Theta_tt + eta Theta_t) + S Theta_t^2 + 2 lam B Theta_t + K Theta + L, with
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
        return ResidualRows(self, theta, theta_t, a, lam, lam_dot, Mm, Bm, v, damp, R, dL)

    # --- the static problem ---------------------------------------------------------------------
    def static_rows(
        self, theta: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray, jacobian: bool = False
    ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """Residual K Theta + L of the static equations at m instants, and its Jacobian.

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
        if not jacobian:
            return theta @ K.T + self.load_torque_rows(theta, lam, lam_dot)
        torque, dL = self.load_torque_rows(theta, lam, lam_dot, jacobian=True)
        dL += K[None]
        return theta @ K.T + torque, dL

    def linear_operators(self, lam: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The model linearised about the straight beam turning steadily at `lam`.

        Small vibrations obey mass Theta_tt + eta Md Theta_t + stiffness Theta = -euler lam_dot
        (the gyroscopic terms vanish on the straight beam): the natural frequencies and the
        linear forced response (`rotbeam.model.modes`) come from these.

        Parameters
        ----------
        lam : float
            Omega T, dimensionless.

        Returns
        -------
        mass, stiffness : numpy.ndarray
            M(0) and K + dL/dTheta(0; lam, 0), shape (n, n).
        euler : numpy.ndarray
            dL/d(lam_dot) at Theta = 0, shape (n,): the load per unit angular acceleration
            (zero with the Euler load off).
        """
        zero = np.zeros((1, self.n))
        mass = self.inertia_rows(zero)[0][0]
        stiffness = self.static_rows(zero, [lam], [0.0], jacobian=True)[1][0]
        return mass, stiffness, self.euler_load_vector()

    def euler_load_vector(self) -> np.ndarray:
        """The load per unit angular acceleration on the straight beam, dL/d(lam_dot) at Theta = 0.

        L is linear in lam_dot, so two evaluations of the loads give it.

        Returns
        -------
        numpy.ndarray
            Shape (n,), dimensionless (zero with the Euler load off).
        """
        zero = np.zeros((1, self.n))
        unit = self.load_torque_rows(zero, [0.0], [1.0])[0]
        return unit - self.load_torque_rows(zero, [0.0], [0.0])[0]

    # --- outputs --------------------------------------------------------------------------------
    def midspan(self, theta: np.ndarray) -> np.ndarray:
        """The midspan deflection y_m = y(s = 1/2), the paper's output (`Grid.midspan`).

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (n,) or (n, m).

        Returns
        -------
        numpy.ndarray
            y_m in units of L: a scalar array or shape (m,).
        """
        return self.grid.midspan(theta)

    def tip(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The tip position relative to the clamp (`Grid.tip`).

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (n,) or (n, m).

        Returns
        -------
        x, y : numpy.ndarray
            In units of L, along and across the clamp's direction: scalar arrays or shape (m,).
        """
        return self.grid.tip(theta)


class ResidualRows:
    """The residual of the equation of motion at m instants (`DiscreteModel.residual_rows`), and
    its derivatives from the same evaluation of the mass and gyroscopic matrices.

    Attributes
    ----------
    R : numpy.ndarray
        The residual, shape (m, n), dimensionless torques.
    """

    def __init__(self, model, theta, theta_t, a, lam, lam_dot, Mm, Bm, v, damp, R, dL=None):
        self.model, self.theta, self.theta_t, self.a = model, theta, theta_t, a
        self.lam, self.lam_dot = lam, lam_dot
        self.Mm, self.Bm, self.v, self.damp, self.R = Mm, Bm, v, damp, R
        self.dL = dL  #: the loads' Jacobian, when `residual_rows` was asked for it
        self._lu = None  #: the LU of the one mass matrix, once `mass_solve` has made it

    def mass_solve(self, rhs: np.ndarray) -> np.ndarray:
        """M^-1 rhs at each instant (by the LU `solved(keep_lu=True)` kept, if any).

        Parameters
        ----------
        rhs : numpy.ndarray
            Shape (m, n).

        Returns
        -------
        numpy.ndarray
            Shape (m, n).
        """
        if self._lu is not None:
            return lu_solve(self._lu, rhs[0], check_finite=False)[None]
        return np.linalg.solve(self.Mm, rhs[..., None])[..., 0]

    def apply(self, p: np.ndarray, q: np.ndarray) -> np.ndarray:
        """dR/dTheta p + dR/dTheta_t q at each instant without forming the blocks (the
        identities of `DiscreteModel.inertia_rows`; exact for S = B).

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
        if m.effects.coriolis:
            dv = dv + 2.0 * lam[:, None] * q
        out += matvec_rows(Bm, dv)
        if damp is None:
            out += m.eta * matvec_rows(Mm, q)
        else:
            Md, Bd = damp
            out += m.eta * (matvec_rows(Bd, V * p) - matvec_rows(Bd, V) * p)
            out += m.eta * matvec_rows(Md, q)
        return out

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
        if keep_lu and self.Mm.shape[0] == 1:
            self._lu = lu_factor(self.Mm[0], check_finite=False)
        self.a = -self.mass_solve(self.R)  # Theta_tt (+ eta Theta_t where the damping is eta M)
        self.R = np.zeros_like(self.R)
        if self.damp is None:
            return self.a - self.model.eta * self.theta_t
        return self.a

    def blocks(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """dR/dTheta, dR/dTheta_t and dR/dTheta_tt = M at each instant (exact for S = B: the
        identities of `DiscreteModel.inertia_rows` and the loads' own Jacobian).

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
        if m.effects.coriolis:
            dv = dv + 2.0 * self.lam[:, None]
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
        return Lj, Cj, Mm
