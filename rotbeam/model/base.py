"""The contract between a discrete model of the rotating beam and the solvers.

Every solver of rotbeam (collocation, time stepping, Floquet, continuation, the quasi-static
solver, the response classification) takes a `DiscreteModel` and uses nothing else of it than
what this class declares: one required method, the residual of the equation of motion over a
batch of instants with its blocks.  The equations and why they take this form: docs/model.md,
"The model contract".
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from scipy.linalg import eig, lu_factor, lu_solve

from .grid import Grid
from .params import Dimensionless
from .rows import matvec_rows


class DiscreteModel(ABC):
    """A discrete model of the beam on the rotating disk, as the solvers see it.

    A model is its residual: n generalised coordinates Theta (time in units of T) obey

        R(Theta, Theta_t, Theta_tt; lam, lam_dot) = 0

    at every instant, R affine in Theta_tt with the mass matrix M = dR/dTheta_tt.  A subclass
    gives R and its blocks dR/dTheta, dR/dTheta_t and M at m instants at once (`residual_rows`),
    the scene it is built for (`dl`, with the drive lam(tau), lam_dot(tau)) and a copy of itself
    for another scene (`at`).  From these the base class derives, once, what the solvers call:
    the first-order right-hand side and its Jacobian, the matrix-free tangent, the static
    residual and the operators of the linearised straight beam (frequencies, forced response,
    slowest decay).  A model may offer faster equivalents (`static_rows`, `kernel`), tested equal
    to what its residual gives.

    Attributes
    ----------
    dl : Dimensionless
        The scene: dimensionless groups, effects and drive.
    grid : Grid
        The beam's nodes and quadratures, on which `beam_angles` gives the angles.
    n : int
        Number of coordinates (the state of the first-order system has 2 n entries).
    """

    dl: Dimensionless
    grid: Grid
    n: int

    # --- what a model must give ---------------------------------------------------------------
    @abstractmethod
    def residual_rows(
        self,
        theta: np.ndarray,
        theta_t: np.ndarray,
        theta_tt: np.ndarray | None,
        lam: np.ndarray,
        lam_dot: np.ndarray,
        jacobian: bool = False,
    ) -> Residual:
        """The equation of motion as a residual at m instants, with its blocks on demand.

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Coordinates and their rates (1/T), shape (m, n) each.
        theta_tt : numpy.ndarray or None
            Accelerations (1/T^2), shape (m, n); None: the rows to solve for the accelerations
            (`Residual.solved`).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change at the m instants, shape (m,).
        jacobian : bool
            The blocks will be asked for (a model may evaluate them with R).

        Returns
        -------
        Residual
            ``R`` (dimensionless torques, shape (m, n)) and its blocks.
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

    @property
    def label(self) -> str:
        """The model's name and size in a message, e.g. 'N = 40'."""
        return f"{type(self).__name__} of n = {self.n}"

    @property
    def damped(self) -> bool:
        """Whether any motion decays: the linear damping (`linear_damping`) is not zero."""
        return bool(np.any(self.linear_damping(float(self.dl.lam0))))

    def kernel(self, tangent: bool = True) -> tuple[Kernel | None, str]:
        """A compiled time stepper of the model's first-order form, if it offers one (an optional
        accelerator, tested equal to the residual; `rotbeam.model.elastica_kernel` is the one
        rotbeam has).

        Parameters
        ----------
        tangent : bool
            Whether the march will carry a tangent (a classification's); without, a kernel may
            cover more models.

        Returns
        -------
        kernel : Kernel or None
            The compiled march and what it reads, None where the model offers none.
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
        return self.dl.law.rows(tau)

    # --- first-order form -----------------------------------------------------------------------
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
        inverse = rows.mass_inverse()  # for the accelerations and the 2 n columns below
        acc = rows.solved()
        dq, dqt, _ = rows.blocks()
        X = inverse @ np.concatenate([dq, dqt], axis=2)
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

    # --- the static problem ---------------------------------------------------------------------
    def static_rows(
        self, theta: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray, jacobian: bool = False
    ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """The residual at rest (zero rates and accelerations) at m instants, and its Jacobian.

        The quasi-static response is its root at every instant.

        Parameters
        ----------
        theta : numpy.ndarray
            Coordinates, shape (m, n).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change at the m instants, shape (m,).
        jacobian : bool
            Also return dR/dTheta there, shape (m, n, n).

        Returns
        -------
        numpy.ndarray or tuple
            The residual (m, n), dimensionless torques; with `jacobian`, (residual, Jacobians).
        """
        zero = np.zeros_like(theta)
        rows = self.residual_rows(theta, zero, zero, lam, lam_dot, jacobian)
        if not jacobian:
            return rows.R
        return rows.R, rows.blocks()[0]

    def linear_operators(self, lam: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The model linearised about the straight beam turning steadily at `lam`.

        Small vibrations obey mass Theta_tt + damping Theta_t + stiffness Theta = -euler lam_dot
        (`linear_damping`; the gyroscopic terms vanish on the straight beam): the natural
        frequencies and the linear forced response (`rotbeam.model.modes`) come from these.

        Parameters
        ----------
        lam : float
            Omega T, dimensionless.

        Returns
        -------
        mass, stiffness : numpy.ndarray
            dR/dTheta_tt and dR/dTheta at rest on the straight beam (lam_dot = 0), shape (n, n).
        euler : numpy.ndarray
            dR/d(lam_dot) at Theta = 0, shape (n,): the load per unit angular acceleration
            (zero with the Euler load off).
        """
        stiffness, _, mass = self.straight_blocks(lam)
        return mass, stiffness, self.euler_load_vector()

    def straight_blocks(self, lam: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The residual's blocks on the straight beam at rest turning steadily at `lam`, from
        one evaluation: the linearised stiffness, damping and mass.

        Parameters
        ----------
        lam : float
            Omega T, dimensionless.

        Returns
        -------
        stiffness, damping, mass : numpy.ndarray
            dR/dTheta, dR/dTheta_t and dR/dTheta_tt at Theta = 0 (lam_dot = 0), shape (n, n)
            each.
        """
        zero = np.zeros((1, self.n))
        dq, dqt, mass = self.residual_rows(zero, zero, zero, [lam], [0.0], True).blocks()
        return dq[0], dqt[0], mass[0]

    def euler_load_vector(self) -> np.ndarray:
        """The load per unit angular acceleration on the straight beam, dR/d(lam_dot) at Theta = 0.

        R is affine in lam_dot, so two evaluations of the residual at rest give it.

        Returns
        -------
        numpy.ndarray
            Shape (n,), dimensionless (zero with the Euler load off).
        """
        zero = np.zeros((1, self.n))
        unit = self.static_rows(zero, [0.0], [1.0])[0]
        return unit - self.static_rows(zero, [0.0], [0.0])[0]

    def linear_damping(self, lam: float) -> np.ndarray:
        """dR/dTheta_t on the straight beam at rest turning at `lam`: the linear damping.

        Parameters
        ----------
        lam : float
            Omega T, dimensionless.

        Returns
        -------
        numpy.ndarray
            Shape (n, n) (zero without damping).
        """
        return self.straight_blocks(lam)[1]

    def first_mode_decay(self, lam: float) -> tuple[float, float]:
        """The first mode of the straight beam turning at `lam` and its modal damping.

        psi' C phi / psi' M phi with phi, psi the first mode's right and left eigenvectors of
        (stiffness, mass) and C the linear damping (`linear_damping`): to first order in the
        damping the mode decays as exp(-c tau / 2).

        Parameters
        ----------
        lam : float
            Omega T, dimensionless.

        Returns
        -------
        w1 : float
            The first angular frequency, in units of 1/T.
        c : float
            The modal damping coefficient, in units of 1/T (0 without damping).
        """
        stiffness, damping, mass = self.straight_blocks(lam)
        w2, left, right = eig(stiffness, mass, left=True, right=True)
        k = int(np.argmin(np.real(w2)))
        phi, psi = right[:, k], left[:, k].conj()
        c = float(np.real((psi @ damping @ phi) / (psi @ mass @ phi)))
        return float(np.sqrt(max(float(np.real(w2[k])), 0.0))), c

    # --- outputs --------------------------------------------------------------------------------
    def beam_angles(self, theta: np.ndarray) -> np.ndarray:
        """The angles of the beam on `grid` from the model's coordinates (the coordinates
        themselves unless the model says otherwise).

        Parameters
        ----------
        theta : numpy.ndarray
            Coordinates, shape (n,) or (m, n) at m instants.

        Returns
        -------
        numpy.ndarray
            Angles [rad] at the grid's nodes 1..N-1, shape (N - 1,) or (m, N - 1).
        """
        return np.asarray(theta, dtype=float)

    def midspan(self, theta: np.ndarray) -> np.ndarray:
        """The midspan deflection y_m = y(s = 1/2), the paper's output (`Grid.midspan`).

        Parameters
        ----------
        theta : numpy.ndarray
            Coordinates, shape (n,) or (m, n) at m instants.

        Returns
        -------
        numpy.ndarray
            y_m in units of L: a scalar array or shape (m,).
        """
        return self.grid.midspan(self.beam_angles(theta))

    def tip(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The tip position relative to the clamp (`Grid.tip`).

        Parameters
        ----------
        theta : numpy.ndarray
            Coordinates, shape (n,) or (m, n) at m instants.

        Returns
        -------
        x, y : numpy.ndarray
            In units of L, along and across the clamp's direction: scalar arrays or shape (m,).
        """
        return self.grid.tip(self.beam_angles(theta))


class Residual(ABC):
    """The residual of a model's equation of motion at m instants (`DiscreteModel.residual_rows`)
    and its derivatives.

    A model gives R, the mass matrices, the blocks and how the rows move to other accelerations;
    the solve for the accelerations and the directional derivative follow here.

    Attributes
    ----------
    R : numpy.ndarray
        The residual, shape (m, n), dimensionless torques.
    """

    R: np.ndarray
    _lu: tuple | None = None
    _inverse: np.ndarray | None = None

    @abstractmethod
    def mass(self) -> np.ndarray:
        """dR/dTheta_tt = M at each instant.

        Returns
        -------
        numpy.ndarray
            Shape (m, n, n).
        """

    @abstractmethod
    def blocks(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """dR/dTheta, dR/dTheta_t and dR/dTheta_tt = M at each instant.

        Returns
        -------
        dR_dtheta, dR_dtheta_t, mass : numpy.ndarray
            Shape (m, n, n) each.
        """

    @abstractmethod
    def accelerate(self, theta_tt: np.ndarray) -> None:
        """Move the rows to the accelerations `theta_tt` (R and the blocks follow).

        Parameters
        ----------
        theta_tt : numpy.ndarray
            Accelerations (1/T^2), shape (m, n).
        """

    def keep_lu(self, keep: bool) -> None:
        """At one instant, factor the mass matrix once for `mass_solve` (a tangent's solve).

        Parameters
        ----------
        keep : bool
            Whether to keep the LU (rows of more than one instant keep none).
        """
        if keep and self.R.shape[0] == 1:
            self._lu = lu_factor(self.mass()[0], check_finite=False)

    def mass_inverse(self) -> np.ndarray:
        """M^-1 at each instant, computed once and kept: `mass_solve` then applies it.

        The first-order Jacobian multiplies the 2 n columns of the blocks by it: with the
        inverse that takes half the time of numpy's batched solve at n = 39, 2e-13 apart at the
        mass matrix's condition 7e4.

        Returns
        -------
        numpy.ndarray
            Shape (m, n, n).
        """
        if self._inverse is None:
            self._inverse = np.linalg.inv(self.mass())
        return self._inverse

    def mass_solve(self, rhs: np.ndarray) -> np.ndarray:
        """M^-1 rhs at each instant (by the LU `solved(keep_lu=True)` or the inverse
        `mass_inverse` kept, if any).

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
        if self._inverse is not None:
            return matvec_rows(self._inverse, rhs)
        return np.linalg.solve(self.mass(), rhs[..., None])[..., 0]

    def solved(self, keep_lu: bool = False) -> np.ndarray:
        """The accelerations that zero the residual at these coordinates and rates.

        R is affine in Theta_tt with slope M, so on rows evaluated at zero accelerations
        Theta_tt = -M^-1 R; the rows then move there (`accelerate`), where `blocks` and `apply`
        are taken.  Valid on rows evaluated without Theta_tt (`residual_rows(..., None, ...)`).

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
        acc = -self.mass_solve(self.R)
        self.accelerate(acc)
        return acc

    def apply(self, p: np.ndarray, q: np.ndarray) -> np.ndarray:
        """dR/dTheta p + dR/dTheta_t q at each instant.

        Parameters
        ----------
        p, q : numpy.ndarray
            Directions of the coordinates and of the rates, shape (m, n) each.

        Returns
        -------
        numpy.ndarray
            Shape (m, n), dimensionless torques.
        """
        dq, dqt, _ = self.blocks()
        return matvec_rows(dq, p) + matvec_rows(dqt, q)


class Kernel:
    """A compiled time stepper a model offers (`DiscreteModel.kernel`): its march and the arrays
    it reads.

    Parameters
    ----------
    advance : callable
        ``advance(y, stops, h, rtol, atol, tangent, arguments, saved, counts)`` ->
        ``(status, h)``: DOP853 through the stops in place (the state and, with `tangent`, its
        tangent).
    rates : callable
        ``rates(t, y, out, tangent, *arguments)``: the first-order right-hand side in place.
    arguments : tuple
        What both read after their own arguments.
    """

    def __init__(self, advance, rates, arguments: tuple) -> None:
        self.advance, self.rates, self.arguments = advance, rates, arguments
