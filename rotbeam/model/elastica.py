"""The discrete rotating elastica: Appendix A of the paper, re-derived, as a `DiscreteModel`.

The grid, the quadratures and the derivation of M, B, K and the loads: docs/model.md, "The
discrete model", which lists the departures from the printed appendix; the payload: "A payload
at the tip".
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..config.errors import RotbeamInputError
from .base import Kernel
from .grid import Grid, centrifugal_strain, check_N
from .gyroscopic import GyroscopicModel
from .loads import KERNEL_PARTS, Load, default_parts
from .params import Dimensionless


class DiscreteElastica(GyroscopicModel):
    """The rotating elastica on an N-interval grid: its beam and a list of loads.

    The model every run of rotbeam uses: the beam is M = W cos, B = W sin with W = Q P and the
    bending stiffness K, in units of EI/L^2 with time in units of T; the loads are parts
    (`rotbeam.model.loads`: centrifugal, softening, Euler, Coriolis, damping, or any `Load`),
    their nodal forces summed by the tension quadrature.  With `extension` the grid is the
    stretched one (stretched by the tip mass's pull too): a property of the beam, not a load;
    with a payload Q carries the tip mass and the last angle's row its rotary inertia.

    Parameters
    ----------
    dl : Dimensionless
        The scene (groups, effects, drive, payload).
    N : int
        Grid intervals; the model has n = N - 1 angles.
    parts : sequence of Load or None
        The loads; None: one for each effect of `dl.effects` that is on (`default_parts`).
    extra : sequence of Load
        Loads added after `parts` (`with_parts`); `at` keeps them.

    Raises
    ------
    RotbeamInputError
        For N out of range, `extension` without kappa > 0, or a rotation too fast for a
        stretched equilibrium (with a tip mass, whose pull adds to the tension, sooner).
    """

    def __init__(
        self,
        dl: Dimensionless,
        N: int,
        parts: Sequence[Load] | None = None,
        extra: Sequence[Load] = (),
    ) -> None:
        self.dl = dl
        self.N = check_N(N)
        self.hub_ratio = float(dl.hub_ratio)
        self.effects = dl.effects
        strain = None
        if self.effects.extension and self.effects.centrifugal:
            kappa = dl.kappa
            if not (math.isfinite(kappa) and kappa > 0):
                raise RotbeamInputError(
                    f"effects.extension needs kappa = (h/L)^2 / 12 > 0, got {kappa!r}"
                )
            s = np.arange(self.N + 1) / self.N
            strain = centrifugal_strain(s, self.hub_ratio, kappa, dl.lam_stretch, dl.tip_mass)
        self.grid = Grid.build(self.N, strain, dl.tip_mass)
        self.n = self.N - 1
        self.given = None if parts is None else tuple(parts)
        self.extra = tuple(extra)
        #: the loads, summed in this order
        self.parts = (default_parts(dl.effects) if parts is None else self.given) + self.extra
        self.eta = self._damping_rate()
        #: the payload's rotary inertia on the last angle's row, J / (rho A L^3) / ds, divided
        #: by that row's 1 + eps like the row's curvature (the stretched grid's K)
        self.rotary = dl.tip_inertia / self.grid.ds
        if strain is not None:
            self.rotary /= 1.0 + strain[self.N - 1]

    def at(self, dl: Dimensionless) -> DiscreteElastica:
        """The model of another scene on the same grid size.

        Parameters
        ----------
        dl : Dimensionless
            The scene.

        Returns
        -------
        DiscreteElastica
            The model of `dl` with the same N and the same explicit and extra parts (the
            parts of the effects are those of `dl.effects`).
        """
        return DiscreteElastica(dl, self.N, self.given, self.extra)

    def with_parts(self, *loads: Load) -> DiscreteElastica:
        """The same model with more loads attached.

        Parameters
        ----------
        *loads : Load
            Loads added after the model's own parts.

        Returns
        -------
        DiscreteElastica
            A new model of the same scene and grid; `at` keeps `loads`.
        """
        return DiscreteElastica(self.dl, self.N, self.given, self.extra + tuple(loads))

    def _damping_rate(self) -> float:
        """eta: the sum of the parts' viscous damping rates (0.0 without damping)."""
        eta = 0.0
        for part in self.parts:
            rate = part.damping(self)
            if rate is not None:
                eta += rate
        return eta

    def rate_load_rows(
        self,
        theta: np.ndarray,
        theta_t: np.ndarray,
        lam: np.ndarray,
        lam_dot: np.ndarray,
        jacobian: bool = False,
    ) -> tuple | None:
        """The sum of the parts' other terms (`Load.rows`), with their blocks.

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
            (T, dT/dTheta, dT/dTheta_t), blocks None where zero; None where no part has such a
            term.
        """
        total = None
        for part in self.parts:
            term = part.rows(self, theta, theta_t, lam, lam_dot, jacobian)
            if term is None:
                continue
            if total is None:
                total = list(term)
                continue
            for k, x in enumerate(term):
                if x is not None:
                    total[k] = x if total[k] is None else total[k] + x
        return None if total is None else tuple(total)

    def gyroscopic_rows(self, lam: np.ndarray | float) -> np.ndarray | float | None:
        """g of the gyroscopic term g B Theta_t: the sum of the parts' (2 lam of Coriolis).

        Parameters
        ----------
        lam : numpy.ndarray or float
            Omega T at the m instants, shape (m,), or one value.

        Returns
        -------
        numpy.ndarray or float or None
            g, the shape of `lam`; None where no part has a gyroscopic force.
        """
        g = None
        for part in self.parts:
            term = part.gyroscopic(self, lam)
            if term is not None:
                g = term if g is None else g + term
        return g

    @property
    def stiffness(self) -> np.ndarray:
        """K = tridiag(-1, 2, -1) / ds^2 (stretched: divided by 1 + eps), shape (n, n)."""
        return self.grid.K

    def inertia_rows(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """M_ij = W_ij cos(theta_i - theta_j) and B_ij = W_ij sin(theta_i - theta_j) at m instants.

        W = Q P; a payload's rotary inertia j / ds adds to M's last diagonal entry.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (m, n).

        Returns
        -------
        M, B : numpy.ndarray
            Shape (m, n, n) each, dimensionless.
        """
        M, B = self._cos_sin_rows(theta, self.grid.W)
        if self.rotary:
            M[:, -1, -1] += self.rotary
        return M, B

    def damping_rows(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """With a payload, the beam's own M and B (W without the tip mass, M without the
        rotary inertia): the damping stays per unit length of the beam.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (m, n).

        Returns
        -------
        tuple of numpy.ndarray or None
            (Md, Bd), shape (m, n, n) each, with a payload; None without one (eta M).
        """
        W = self._damping_weights()
        return None if W is None else self._cos_sin_rows(theta, W)

    def _damping_weights(self) -> np.ndarray | None:
        """The W the damping's mass is made of with a payload (W without the tip mass; W itself
        with a rotary inertia alone), None without a payload (the damping acts on M)."""
        if self.grid.W_beam is None and not self.rotary:
            return None
        return self.grid.W if self.grid.W_beam is None else self.grid.W_beam

    @staticmethod
    def _cos_sin_rows(theta: np.ndarray, W: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """W_ij cos(theta_i - theta_j) and W_ij sin(theta_i - theta_j) at m instants, from the
        angle-difference identities (outer products of cos and sin, formed in place)."""
        c, s = np.cos(theta), np.sin(theta)
        M = c[:, :, None] * c[:, None, :]
        M += s[:, :, None] * s[:, None, :]
        M *= W
        B = s[:, :, None] * c[:, None, :]
        B -= c[:, :, None] * s[:, None, :]
        B *= W
        return M, B

    @property
    def label(self) -> str:
        """'N = 40': the grid, for messages."""
        return f"N = {self.N}"

    def kernel(self, tangent: bool = True) -> tuple[Kernel | None, str]:
        """The compiled DOP853 march of `rotbeam.model.elastica_kernel`: its right-hand side for
        the standard parts (`rotbeam.model.loads.KERNEL_PARTS`, each at most once; extension
        too: it only changes the grid's operators) under a drive of harmonics or a move; without
        a tangent, also with a payload (its rotary inertia and its undamped mass).  A subclass
        such as the printed appendix, another drive law, a payload with a tangent or no numba
        leave the model to the numpy path.

        Parameters
        ----------
        tangent : bool
            Whether the march will carry a tangent.

        Returns
        -------
        kernel : Kernel or None
            The march and (W, K, P, Q, par, harm, knots, cubic, Wd, Phi), or None where it
            does not cover the model.
        why_not : str
            '' with arguments, else the reason.
        """
        if type(self) is not DiscreteElastica:
            return None, f"the kernel is DiscreteElastica's, not {type(self).__name__}'s"
        Wd = self._damping_weights()
        if Wd is not None and tangent:
            return None, "a payload (tip mass or inertia) is not in the kernel's tangent"
        flags, why_not = self._kernel_flags()
        if flags is None:
            return None, why_not
        drive, why_not = _kernel_drive(self.dl.law)
        if drive is None:
            return None, why_not
        try:
            import numba  # noqa: F401
        except ImportError:
            return None, "numba is not installed"
        g = self.grid
        par = np.array([g.x0, self.hub_ratio, self.eta, self.dl.law.mean, *flags, self.rotary],
                       dtype=float)  # fmt: skip
        mats = (np.ascontiguousarray(m, dtype=float) for m in (g.W, g.K, g.P, g.Q))
        Wd = np.ascontiguousarray(np.zeros((0, 0)) if Wd is None else Wd, dtype=float)
        from . import elastica_kernel  # here: numba loads with the first compiled run only

        arguments = (*mats, par, *drive, Wd, np.zeros((self.n, 0)))
        return Kernel(elastica_kernel.advance, elastica_kernel.rates, arguments), ""

    def euler_load_vector(self) -> np.ndarray:
        """dL/d(lam_dot) at Theta = 0, in closed form: the sum of the parts' (`Load.euler_vector`;
        the Euler load's is the straight beam's lever arm summed by Q, Q (r_o + s), plus a
        payload's rotary inertia on the last row).

        Returns
        -------
        numpy.ndarray
            Shape (n,), dimensionless (zero without a load that depends on lam_dot).
        """
        q = np.zeros(self.n)
        for part in self.parts:
            term = part.euler_vector(self)
            if term is not None:
                q = q + term
        return q

    def _kernel_flags(self) -> tuple[list[bool] | None, str]:
        """The kernel's flags of its parts (centrifugal, softening, euler, coriolis), or None and
        why the kernel does not cover the parts."""
        kinds = [type(p) for p in self.parts]
        unknown = [p.name for p in self.parts if type(p) not in KERNEL_PARTS]
        if unknown:
            return None, f"the kernel does not know the part(s) {', '.join(unknown)}"
        if len(set(kinds)) < len(kinds):
            return None, "the kernel takes each standard part once"
        on = [cls in kinds for cls in KERNEL_PARTS[:4]]
        if on[1] and not on[0]:
            return None, "the kernel's softening goes with the centrifugal load"
        return on, ""

    def _loads(self, c, s, lam, lam_dot):
        """The parts' nodal forces F_x, F_y (nodes 1..N) from cos and sin of the angles, summed
        in the order of the parts."""
        g = self.grid
        x = g.x0 + g.P @ c
        y = g.P @ s
        pairs = (part.forces(self, x, y, lam, lam_dot) for part in self.parts)
        return _summed(pairs, np.zeros_like(x), np.zeros_like(y))

    def _slopes(self, c, s, lam, lam_dot):
        """a, b of the summed forces' slopes, d(F_x)/dTheta = P diag(a) and
        d(F_y)/dTheta = P diag(b), shape (m, n) each."""
        pairs = (part.slopes(self, c, s, lam, lam_dot) for part in self.parts)
        return _summed(pairs, np.zeros_like(c), np.zeros_like(c))

    def load_torque_rows(
        self, theta: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray, jacobian: bool = False
    ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """L = sin Theta * Q F_x - cos Theta * Q F_y at m instants, and dL/dTheta (exact).

        F sums the parts' nodal forces (`Load.forces`: centrifugal, softening, Euler, ...); the
        parts' own torques follow (`Load.torques`: the payload's rotary inertia's j / ds lam_dot
        on the last row with the Euler load).

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (m, n).
        lam, lam_dot : numpy.ndarray
            Omega T and its rate of change at the m instants, shape (m,).
        jacobian : bool
            Also return the Jacobians, shape (m, n, n).

        Returns
        -------
        numpy.ndarray or tuple
            L (m, n), dimensionless torques; with `jacobian`, (L, dL/dTheta).
        """
        g = self.grid
        lam, lam_dot = np.asarray(lam, dtype=float), np.asarray(lam_dot, dtype=float)
        c, s = np.cos(theta), np.sin(theta)
        fx, fy = self._loads(c.T, s.T, lam, lam_dot)
        nx, ny = (g.Q @ fx).T, (g.Q @ fy).T
        torque = s * nx - c * ny
        own = [p.torques(self, theta, lam, lam_dot, jacobian) for p in self.parts]
        own = [term for term in own if term is not None]
        for term in own:
            torque = torque + term[0]
        if not jacobian:
            return torque
        # dL/dTheta = diag(C n_x + S n_y) + S W diag(a) - C W diag(b), from
        # d(F_x)/dTheta = P diag(a) and d(F_y)/dTheta = P diag(b) (`Load.slopes`)
        a, b = self._slopes(c, s, lam, lam_dot)
        J = s[:, :, None] * a[:, None, :] - c[:, :, None] * b[:, None, :]
        J *= g.W[None]
        idx = np.arange(self.n)
        J[:, idx, idx] += c * nx + s * ny
        for term in own:
            if term[1] is not None:
                J += term[1]
        return torque, J

    def tension(
        self,
        theta: np.ndarray,
        theta_t: np.ndarray,
        theta_tt: np.ndarray,
        lam: float,
        lam_dot: float,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Internal force n_x, n_y at nodes 1..N-1 at one instant (a diagnostic).

        n = Q g with g = F - r_tt - eta r_t (+ the parts' gyroscopic force), the rotating
        frame's components, without the half of the tip's force that the last row's moment
        balance carries (Q's half torque); the tests check the straight beam's centrifugal
        tension and the extension's strain with it.

        Parameters
        ----------
        theta, theta_t, theta_tt : numpy.ndarray
            Angles [rad] and their first two time derivatives (units of 1/T, 1/T^2), shape (n,).
        lam, lam_dot : float
            Rotation rate Omega T and its rate of change, dimensionless.

        Returns
        -------
        n_x, n_y : numpy.ndarray
            Shape (n,), units of EI / L^2.
        """
        g = self.grid
        c, s = np.cos(theta), np.sin(theta)
        fx, fy = self._loads(c, s, lam, lam_dot)
        xt = -g.P @ (s * theta_t)
        yt = g.P @ (c * theta_t)
        xtt = -g.P @ (s * theta_tt + c * theta_t**2)
        ytt = g.P @ (c * theta_tt - s * theta_t**2)
        gx, gy = fx - xtt, fy - ytt
        rate = self.gyroscopic_rows(lam)  # the gyroscopic force rate (y_t, -x_t)
        if rate is not None:
            gx = gx + rate * yt
            gy = gy - rate * xt
        Qd = g.Q if g.Q_beam is None else g.Q_beam  # the payload has no damping of its own
        nx, ny = g.Q @ gx - self.eta * (Qd @ xt), g.Q @ gy - self.eta * (Qd @ yt)
        if self.dl.tip_mass:  # the last row's half torque belongs to the moment scheme
            nx[-1] -= 0.5 * self.dl.tip_mass * gx[-1]
            ny[-1] -= 0.5 * self.dl.tip_mass * gy[-1]
        return nx, ny


def _summed(pairs, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """a + the sum of the pairs' first parts, b + the sum of their second, in order (a part's
    None adds nothing)."""
    for pa, pb in pairs:
        if pa is not None:
            a = a + pa
        if pb is not None:
            b = b + pb
    return a, b


def _kernel_drive(law) -> tuple[tuple | None, str]:
    """The kernel's drive arrays (harm, knots, cubic) of a harmonic law or a move's spline, or
    None and why not."""
    from .drive import HarmonicLaw, MoveLaw

    if isinstance(law, HarmonicLaw):
        harm = np.array([[k * law.omega, a, ph] for k, a, ph in law.terms], dtype=float)
        return (harm.reshape(-1, 3), np.zeros(0), np.zeros((4, 0))), ""
    if isinstance(law, MoveLaw):
        curve = law.spline
        return (np.zeros((0, 3)), np.ascontiguousarray(curve.x, dtype=float),
                np.ascontiguousarray(curve.c, dtype=float)), ""  # fmt: skip
    return None, f"the kernel's drive is a sum of harmonics or a move, not a {type(law).__name__}"
