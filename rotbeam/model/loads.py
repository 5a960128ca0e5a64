"""Loads as parts of the discrete elastica: each load is one class that adds its term to the
residual and its blocks, attached to a `DiscreteElastica` in a list (after PyElastica's forcing
classes).

The interface, the table of parts and the term each adds: docs/model.md, "Loads as parts".
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .params import Effects

if TYPE_CHECKING:
    from .elastica import DiscreteElastica


class Load:
    """A load on the beam, one term of the residual R with its blocks.

    A load adds to the residual through one or more of the hooks below; each returns None where
    the load has no such term.  The model sums every part's term into R and its blocks
    dR/dTheta, dR/dTheta_t (`DiscreteElastica.load_torque_rows`, `GyroscopicModel`):

    * `forces` and `slopes`: nodal body forces F_x, F_y at nodes 1..N (rotating frame; per unit
      mass in units of L/T^2, which is per unit length of the beam in units of EI/L^3), which
      the model sums over the parts and turns into the torques
      L = sin Theta * Q F_x - cos Theta * Q F_y, with their slopes along the angles;
    * `torques`: torques on the angles' rows directly, with dT/dTheta;
    * `rows`: any other term in the angles and their rates, with dT/dTheta and dT/dTheta_t;
    * `gyroscopic`: g of a force g (y_t, -x_t) at every node, the term g B Theta_t;
    * `damping`: eta of a viscous force -eta r_t on the beam's own mass, eta Md Theta_t;
    * `euler_vector`: dR/d(lam_dot) on the straight beam, for a load linear in lam_dot.

    Attributes
    ----------
    requires : tuple of str
        The effects that must be on with this one for the default list to take it
        (`default_parts`).
    """

    requires: tuple[str, ...] = ()

    @property
    def name(self) -> str:
        """The part's name in messages: its class's name."""
        return type(self).__name__

    def forces(
        self,
        model: DiscreteElastica,
        x: np.ndarray,
        y: np.ndarray,
        lam: np.ndarray | float,
        lam_dot: np.ndarray | float,
    ) -> tuple[np.ndarray | None, np.ndarray | None]:
        """The part's nodal forces F_x, F_y at nodes 1..N.

        Parameters
        ----------
        model : DiscreteElastica
            The model the part is attached to (grid, hub ratio, scene).
        x, y : numpy.ndarray
            Node positions relative to the clamp, units of L, shape (N,) or (N, m).
        lam, lam_dot : numpy.ndarray or float
            Omega T and its rate of change: one value, or shape (m,) (broadcast along x's
            last axis).

        Returns
        -------
        tuple
            (F_x, F_y), each the shape of x or None (no such component), in units of L/T^2.
        """
        return None, None

    def slopes(
        self,
        model: DiscreteElastica,
        c: np.ndarray,
        s: np.ndarray,
        lam: np.ndarray,
        lam_dot: np.ndarray,
    ) -> tuple[np.ndarray | None, np.ndarray | None]:
        """a and b of the forces' slopes: d(F_x)/dTheta = P diag(a), d(F_y)/dTheta = P diag(b).

        For nodal forces linear in the positions with the same coefficients at every node,
        F_x = A_x x + B_x y + ..., a = -A_x sin Theta + B_x cos Theta (and b alike).

        Parameters
        ----------
        model : DiscreteElastica
            The model the part is attached to.
        c, s : numpy.ndarray
            cos Theta and sin Theta, shape (m, n).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change, shape (m,).

        Returns
        -------
        tuple
            (a, b), each shape (m, n) or None (zero).
        """
        return None, None

    def torques(
        self,
        model: DiscreteElastica,
        theta: np.ndarray,
        lam: np.ndarray,
        lam_dot: np.ndarray,
        jacobian: bool = False,
    ) -> tuple[np.ndarray, np.ndarray | None] | None:
        """Torques the part adds to the angles' rows directly, and their Jacobian.

        Parameters
        ----------
        model : DiscreteElastica
            The model the part is attached to.
        theta : numpy.ndarray
            Angles [rad], shape (m, n).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change, shape (m,).
        jacobian : bool
            Whether dT/dTheta is asked for.

        Returns
        -------
        tuple or None
            (T of shape (m, n), dT/dTheta of shape (m, n, n) or None for zero); None: no torque.
        """
        return None

    def rows(
        self,
        model: DiscreteElastica,
        theta: np.ndarray,
        theta_t: np.ndarray,
        lam: np.ndarray,
        lam_dot: np.ndarray,
        jacobian: bool = False,
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None] | None:
        """Any other term of the residual in the angles and their rates, with its blocks.

        Parameters
        ----------
        model : DiscreteElastica
            The model the part is attached to.
        theta, theta_t : numpy.ndarray
            Angles [rad] and their rates (1/T), shape (m, n) each.
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change, shape (m,).
        jacobian : bool
            Whether the blocks are asked for.

        Returns
        -------
        tuple or None
            (T, dT/dTheta, dT/dTheta_t): T of shape (m, n), the blocks (m, n, n) with
            `jacobian` (None: zero); None: no such term.
        """
        return None

    def gyroscopic(
        self, model: DiscreteElastica, lam: np.ndarray | float
    ) -> np.ndarray | float | None:
        """g of the gyroscopic force g (y_t, -x_t) per unit mass, whose term is g B Theta_t.

        Parameters
        ----------
        model : DiscreteElastica
            The model the part is attached to.
        lam : numpy.ndarray or float
            Omega T, shape (m,) or one value.

        Returns
        -------
        numpy.ndarray or float or None
            g, the shape of `lam` (units of 1/T); None: no such force.
        """
        return None

    def damping(self, model: DiscreteElastica) -> float | None:
        """eta of the viscous force -eta r_t per unit mass of the beam (not of a payload).

        Parameters
        ----------
        model : DiscreteElastica
            The model the part is attached to.

        Returns
        -------
        float or None
            eta in units of 1/T; None: no damping.
        """
        return None

    def euler_vector(self, model: DiscreteElastica) -> np.ndarray | None:
        """dR/d(lam_dot) at Theta = 0 in closed form, for a load linear in lam_dot.

        Parameters
        ----------
        model : DiscreteElastica
            The model the part is attached to.

        Returns
        -------
        numpy.ndarray or None
            Shape (n,); None: the part does not depend on lam_dot.
        """
        return None


class Centrifugal(Load):
    """The centrifugal load lam^2 (r_o + x) along the disk's radius (`effects.centrifugal`)."""

    def forces(self, model, x, y, lam, lam_dot):
        """F_x = lam^2 (r_o + x)."""
        return lam * lam * (model.hub_ratio + x), None

    def slopes(self, model, c, s, lam, lam_dot):
        """a = -lam^2 sin Theta."""
        return -(lam * lam)[:, None] * s, None


class Softening(Load):
    """The in-plane centrifugal softening lam^2 y across the radius (`effects.softening`, with
    the centrifugal load)."""

    requires = ("centrifugal",)

    def forces(self, model, x, y, lam, lam_dot):
        """F_y = lam^2 y."""
        return None, lam * lam * y

    def slopes(self, model, c, s, lam, lam_dot):
        """b = lam^2 cos Theta."""
        return None, (lam * lam)[:, None] * c


class Euler(Load):
    """The Euler load of the disk's angular acceleration, lam_dot (y, -(r_o + x)) on every
    node, and j / ds lam_dot on the last row from a payload's rotary inertia (`effects.euler`).
    """

    def forces(self, model, x, y, lam, lam_dot):
        """F_x = lam_dot y, F_y = -lam_dot (r_o + x)."""
        return lam_dot * y, -lam_dot * (model.hub_ratio + x)

    def slopes(self, model, c, s, lam, lam_dot):
        """a = lam_dot cos Theta, b = lam_dot sin Theta."""
        ld = lam_dot[:, None]
        return ld * c, ld * s

    def torques(self, model, theta, lam, lam_dot, jacobian=False):
        """j / ds lam_dot on the last row with a payload's rotary inertia (constant in Theta)."""
        if not model.rotary:
            return None
        torque = np.zeros_like(theta)
        torque[:, -1] = model.rotary * lam_dot
        return torque, None

    def euler_vector(self, model):
        """Q (r_o + x) on the straight beam, + j / ds on the last row (the rotary inertia)."""
        g = model.grid
        x = g.s if g.strain is None else g.positions(np.zeros(model.n))[0]
        q = g.Q @ (model.hub_ratio + x)
        if model.rotary:  # the payload's rotary inertia turns with the disk
            q[-1] += model.rotary
        return q


class Coriolis(Load):
    """The Coriolis load -2 lam e_z x r_t, the term 2 lam B Theta_t (`effects.coriolis`)."""

    def gyroscopic(self, model, lam):
        """g = 2 lam."""
        return 2.0 * lam


class Damping(Load):
    """Viscous damping -eta r_t per unit length of the beam, the term eta Md Theta_t
    (`effects.damping`; eta from the scene, Md the beam's own mass without a payload)."""

    def damping(self, model):
        """eta of the scene."""
        return float(model.dl.eta)


#: the effect that switches each standard part on, in the order the model sums them
PARTS: dict[str, type[Load]] = {
    "centrifugal": Centrifugal,
    "softening": Softening,
    "euler": Euler,
    "coriolis": Coriolis,
    "damping": Damping,
}


def default_parts(effects: Effects) -> tuple[Load, ...]:
    """The parts of a scene's effects: one per effect that is on (and whose `requires` are on).

    `extension` is not a load: it stretches the grid (`DiscreteElastica`).

    Parameters
    ----------
    effects : Effects
        The effects switched on.

    Returns
    -------
    tuple of Load
        In the order of `PARTS`.
    """
    on = set(effects.active())
    return tuple(cls() for name, cls in PARTS.items() if name in on and on.issuperset(cls.requires))


#: the parts the compiled kernel computes (`rotbeam.model.elastica_kernel`), the first four in
#: the order of its flags (CENTRIFUGAL .. CORIOLIS) and the damping through its eta
KERNEL_PARTS: tuple[type[Load], ...] = (Centrifugal, Softening, Euler, Coriolis, Damping)
