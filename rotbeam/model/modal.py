"""The modal reduced model: the discrete elastica projected on its lowest modes under rotation.

The n coordinates q are the amplitudes of the first n linear modes Phi of the full model
turning steadily at the drive's mean rate; the angles are Theta = Phi q and the equations are
the full residual projected on the same modes (Galerkin), Phi' R(Phi q, Phi q_t, Phi q_tt) = 0.
The derivation, what it keeps and what it costs: docs/model.md, "The modal reduced model".
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import eig

from ..config.errors import RotbeamInputError
from .base import DiscreteModel, Kernel, Residual
from .params import Dimensionless


def mode_basis(model: DiscreteModel, lam: float, count: int) -> np.ndarray:
    """The first `count` linear modes of a model on the straight beam turning steadily at `lam`.

    Right eigenvectors of (stiffness, mass) of `DiscreteModel.linear_operators`, ordered by
    frequency, each scaled to unit modal mass phi' M phi = 1 and signed so that its largest
    angle is positive.

    Parameters
    ----------
    model : DiscreteModel
        The full model.
    lam : float
        Omega T, dimensionless.
    count : int
        How many modes, in [1, model.n].

    Returns
    -------
    numpy.ndarray
        Phi, shape (model.n, count), real.

    Raises
    ------
    RotbeamInputError
        For `count` out of range.
    """
    if not (isinstance(count, int | np.integer) and 1 <= count <= model.n):
        raise RotbeamInputError(
            f"numerics.modes = {count!r}: allowed 1 to {model.n} (the full model's N - 1)"
        )
    mass, stiffness, _ = model.linear_operators(lam)
    w2, vectors = eig(stiffness, mass)
    order = np.argsort(np.real(w2))[:count]
    phi = np.real(vectors[:, order])
    phi /= np.sqrt(np.einsum("ik,ij,jk->k", phi, mass, phi))
    sign = np.sign(phi[np.argmax(np.abs(phi), axis=0), np.arange(count)])
    return phi * sign


class ModalModel(DiscreteModel):
    """The Galerkin projection of a full model on its first n modes under rotation.

    Theta = Phi q with Phi the full model's first n linear modes at the drive's mean rate lam0
    (`mode_basis`); the residual is Phi' R_full(Phi q, Phi q_t, Phi q_tt) and its blocks are the
    full blocks projected, Phi' (dR/dTheta) Phi and so on.  Every load, the payload and every
    nonlinearity of the full model stay in it exactly; only the motion is confined to n modes.
    With n = N - 1 it is the full model in other coordinates.

    Parameters
    ----------
    full : DiscreteModel
        The model projected (the discrete elastica of the scene).
    modes : int
        n, the number of modes, in [1, full.n].

    Raises
    ------
    RotbeamInputError
        For `modes` out of range.
    """

    def __init__(self, full: DiscreteModel, modes: int) -> None:
        self.full = full
        self.dl = full.dl
        self.grid = full.grid
        self.phi = mode_basis(full, float(full.dl.lam0), modes)
        self.n = int(modes)

    def at(self, dl: Dimensionless) -> ModalModel:
        """The modal model of another scene: the full model's `at`, projected on its own modes.

        Parameters
        ----------
        dl : Dimensionless
            The scene.

        Returns
        -------
        ModalModel
            The same number of modes of the same full model for `dl`.
        """
        return ModalModel(self.full.at(dl), self.n)

    @property
    def label(self) -> str:
        """'3 modes of N = 40', for messages."""
        return f"{self.n} mode{'s' if self.n > 1 else ''} of {self.full.label}"

    @property
    def damped(self) -> bool:
        """Whether the full model is damped."""
        return self.full.damped

    def kernel(self, tangent: bool = True) -> tuple[Kernel | None, str]:
        """The full model's compiled march with its right-hand side projected on the modes
        (`rotbeam.model.elastica_kernel.rates` with Phi): where the full model offers one
        without a tangent; never with a tangent.

        Parameters
        ----------
        tangent : bool
            Whether the march will carry a tangent.

        Returns
        -------
        kernel : Kernel or None
            The march and the full model's arrays with Phi last, or None.
        why_not : str
            '' with arguments, else the reason.
        """
        if tangent:
            return None, "the modal model's tangent is not in the kernel"
        kernel, why_not = self.full.kernel(tangent=False)
        if kernel is None:
            return None, why_not
        phi = np.ascontiguousarray(self.phi, dtype=float)
        return Kernel(kernel.advance, kernel.rates, (*kernel.arguments[:-1], phi)), ""

    def residual_rows(
        self,
        theta: np.ndarray,
        theta_t: np.ndarray,
        theta_tt: np.ndarray | None,
        lam: np.ndarray,
        lam_dot: np.ndarray,
        jacobian: bool = False,
    ) -> ModalRows:
        """Phi' R_full(Phi q, Phi q_t, Phi q_tt) at m instants (`DiscreteModel.residual_rows`).

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Modal amplitudes q and their rates (1/T), shape (m, n) each.
        theta_tt : numpy.ndarray or None
            Modal accelerations (1/T^2), shape (m, n); None: zero, the rows to solve.
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change at the m instants, shape (m,).
        jacobian : bool
            The blocks will be asked for.

        Returns
        -------
        ModalRows
            The projected residual, shape (m, n), and its blocks.
        """
        up = self.phi.T
        acc = np.zeros_like(theta) if theta_tt is None else theta_tt
        inner = self.full.residual_rows(theta @ up, theta_t @ up, acc @ up, lam, lam_dot, jacobian)
        return ModalRows(inner, self.phi)

    def static_rows(
        self, theta: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray, jacobian: bool = False
    ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """The full model's static residual projected (`DiscreteModel.static_rows`).

        Parameters
        ----------
        theta : numpy.ndarray
            Modal amplitudes, shape (m, n).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change, shape (m,).
        jacobian : bool
            Also return the projected Jacobian, shape (m, n, n).

        Returns
        -------
        numpy.ndarray or tuple
            The residual (m, n); with `jacobian`, (residual, Jacobians).
        """
        phi = self.phi
        out = self.full.static_rows(theta @ phi.T, lam, lam_dot, jacobian)
        if not jacobian:
            return out @ phi
        return out[0] @ phi, phi.T @ out[1] @ phi

    def euler_load_vector(self) -> np.ndarray:
        """The full model's load per unit angular acceleration, projected.

        Returns
        -------
        numpy.ndarray
            Shape (n,).
        """
        return self.phi.T @ self.full.euler_load_vector()

    def beam_angles(self, theta: np.ndarray) -> np.ndarray:
        """Theta = Phi q on the full model's grid.

        Parameters
        ----------
        theta : numpy.ndarray
            Modal amplitudes q, shape (n,) or (m, n) at m instants.

        Returns
        -------
        numpy.ndarray
            Angles [rad], shape (N - 1,) or (m, N - 1).
        """
        return np.asarray(theta, dtype=float) @ self.phi.T


class ModalRows(Residual):
    """A full model's residual rows projected on the modes Phi (`ModalModel.residual_rows`).

    Parameters
    ----------
    inner : Residual
        The full model's rows at Theta = Phi q.
    phi : numpy.ndarray
        The modes, shape (N - 1, n).
    """

    def __init__(self, inner: Residual, phi: np.ndarray) -> None:
        self.inner, self.phi = inner, phi
        self.R = inner.R @ phi

    def _project(self, A: np.ndarray) -> np.ndarray:
        """Phi' A Phi at each instant, shape (m, n, n)."""
        return self.phi.T @ A @ self.phi

    def mass(self) -> np.ndarray:
        """Phi' M Phi at each instant (`Residual.mass`).

        Returns
        -------
        numpy.ndarray
            Shape (m, n, n).
        """
        return self._project(self.inner.mass())

    def blocks(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The full blocks projected (`Residual.blocks`).

        Returns
        -------
        dR_dq, dR_dq_t, mass : numpy.ndarray
            Shape (m, n, n) each.
        """
        dq, dqt, mass = self.inner.blocks()
        return self._project(dq), self._project(dqt), self._project(mass)

    def accelerate(self, theta_tt: np.ndarray) -> None:
        """Move the full rows to Theta_tt = Phi q_tt (`Residual.accelerate`).

        Parameters
        ----------
        theta_tt : numpy.ndarray
            Modal accelerations, shape (m, n).
        """
        self.inner.accelerate(theta_tt @ self.phi.T)
        self.R = self.inner.R @ self.phi

    def apply(self, p: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Phi' (dR/dTheta Phi p + dR/dTheta_t Phi q), matrix-free as the full rows allow.

        Parameters
        ----------
        p, q : numpy.ndarray
            Directions of the amplitudes and of their rates, shape (m, n) each.

        Returns
        -------
        numpy.ndarray
            Shape (m, n).
        """
        up = self.phi.T
        return self.inner.apply(p @ up, q @ up) @ self.phi
