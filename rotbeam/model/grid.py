"""The grid of the discrete model: nodes, the position and tension quadratures, the bending
stiffness and the outputs read off the angles (docs/model.md, "The discrete model")."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..config.errors import RotbeamInputError
from ..config.parameters import check_value


def check_N(N: int) -> int:
    """The number of grid intervals, checked against the registry (numerics.N).

    Parameters
    ----------
    N : int
        Grid intervals.

    Returns
    -------
    int
        N as an int.

    Raises
    ------
    RotbeamInputError
        If N is not an integer in the registry's range.
    """
    return check_value("numerics", "N", N)


def centrifugal_strain(
    s: np.ndarray | float, hub_ratio: float, kappa: float, lam: float, tip_mass: float = 0.0
) -> np.ndarray:
    """Axial strain eps(s) of the straight extensible beam spinning steadily at lam, exact.

    The `extension` effect stretches the grid by it.  n' = -lam^2 (r_o + x), x' = 1 + eps,
    eps = kappa n, x(0) = 0 and the payload's pull n(1) = mu lam^2 (r_o + x(1)) give
    u = 1 + eps with u'' = -k^2 u, k = |lam| sqrt(kappa), u'(0) = -k^2 r_o, u(1) + mu u'(1) = 1,
    whose solution is evaluated without cancellation in its numerator:
    eps = [2 sin(a) sin(b) + k r_o sin(2b) + mu k (sin k + k r_o cos(2b))] / (cos k - mu k sin k),
    a = k (1 + s) / 2, b = k (1 - s) / 2;
    eps = kappa lam^2 [r_o (1 - s) + (1 - s^2)/2 + mu (r_o + 1)] (1 + O(k^2)) (docs/model.md,
    "Axial stretching").

    Parameters
    ----------
    s : numpy.ndarray or float
        Reference arc length in units of L, in [0, 1], any shape.
    hub_ratio : float
        r_o = R_o / L, dimensionless.
    kappa : float
        EI / (EA L^2) = (h/L)^2 / 12, dimensionless.
    lam : float
        The steady rotation Omega T that stretches the beam, dimensionless.
    tip_mass : float
        mu = m / (rho A L) of a payload at s = 1, dimensionless, >= 0: its centrifugal pull
        adds to the tension.

    Returns
    -------
    numpy.ndarray
        eps(s), dimensionless, the shape of `s`.

    Raises
    ------
    RotbeamInputError
        For k at or beyond the axial limit k_c (cos k_c = mu k_c sin k_c; pi/2 without a
        payload): no tensile equilibrium (the stretch runs away).
    """
    k = abs(float(lam)) * math.sqrt(kappa)
    mu = float(tip_mass)
    denominator = math.cos(k) - mu * k * math.sin(k)
    if not (k < 0.5 * math.pi and denominator > 0):
        raise RotbeamInputError(_axial_limit_message(k, lam, kappa, mu))
    s = np.asarray(s, dtype=float)
    a, b = 0.5 * k * (1.0 + s), 0.5 * k * (1.0 - s)
    numerator = 2.0 * np.sin(a) * np.sin(b) + k * hub_ratio * np.sin(2.0 * b)
    if mu:
        numerator = numerator + mu * k * (math.sin(k) + k * hub_ratio * np.cos(2.0 * b))
    return numerator / denominator


def _axial_limit(mu: float) -> float:
    """k_c, the first root of cos k = mu k sin k in (0, pi/2) for mu > 0, by bisection
    (cos k - mu k sin k falls from 1 to -mu pi/2 on [0, pi/2])."""
    lo, hi = 0.0, 0.5 * math.pi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if math.cos(mid) - mu * mid * math.sin(mid) > 0:
            lo = mid
        else:
            hi = mid
    return lo


def _axial_limit_message(k: float, lam: float, kappa: float, mu: float) -> str:
    """The one-line refusal of a rotation at or beyond the axial limit, naming k and its bound."""
    bound = "pi/2"
    if mu:
        bound = f"{_axial_limit(mu):.6g} (the root of cos k = mu k sin k at tip mass mu = {mu:.4g})"
    return (
        f"effects.extension: no stretched equilibrium at lam sqrt(kappa) = {k:.6g} >= {bound} "
        f"(lam = Omega T = {lam:.4g}, kappa = (h/L)^2/12 = {kappa:.4g})"
    )


@dataclass(frozen=True)
class Grid:
    """Operators of the N-interval grid (built once, reused for every evaluation).

    Nodes s_i = i / N; the angles Theta sit at nodes 1..N-1 (theta_0 = 0 at the clamp,
    theta_N = theta_{N-1} at the free end).  P and Q are the trapezoid quadratures of the
    positions and of the tension, K the bending stiffness; build it with `build`
    (docs/model.md, "The discrete model").
    """

    N: int
    ds: float
    s: np.ndarray  #: nodes 1..N
    P: np.ndarray  #: (N, N-1): positions at nodes 1..N from cos/sin of Theta
    Q: np.ndarray  #: (N-1, N): int_{s_i}^1 of nodal values at 1..N
    W: np.ndarray  #: (N-1, N-1) = Q P
    K: np.ndarray  #: (N-1, N-1) bending stiffness
    mid: int  #: index of the node used for y_m (or -1: interpolate)
    x0: float  #: the clamp node's share of every x: ds/2 (1 + eps_0)
    strain: np.ndarray | None = None  #: eps at nodes 0..N (extension), None: inextensible
    #: the beam's own Q and W (no payload): what damping acts on; None: Q and W themselves
    Q_beam: np.ndarray | None = None
    W_beam: np.ndarray | None = None

    @classmethod
    def build(cls, N: int, strain: np.ndarray | None = None, tip_mass: float = 0.0) -> Grid:
        """The grid of N intervals.

        Parameters
        ----------
        N : int
            Grid intervals.
        strain : numpy.ndarray or None
            eps at nodes 0..N: element lengths ds (1 + eps) (the extension effect).
        tip_mass : float
            A point mass at node N, m / (rho A L): the tension quadrature Q gains it in its last
            column (the tip's load and inertia reach every node's tension), W = Q P with it.
            Q sums mass per reference length, so the column is the same on a stretched grid
            (P carries the stretch).

        Returns
        -------
        Grid

        Raises
        ------
        RotbeamInputError
            If N is out of range.
        ValueError
            If `strain` does not have shape (N + 1,).
        """
        N = check_N(N)
        n = N - 1
        ds = 1.0 / N
        s = ds * np.arange(1, N + 1)
        P = np.zeros((N, n))
        for i in range(1, N):  # node i, angles 1..i
            P[i - 1, : i - 1] = ds
            P[i - 1, i - 1] = ds / 2
        P[N - 1] = P[N - 2]
        P[N - 1, n - 1] += ds  # tip: theta_N = theta_{N-1}
        Q = np.zeros((n, N))
        for i in range(1, N):  # tension at node i from nodes i..N
            Q[i - 1, i - 1] = ds / 2
            Q[i - 1, i : N - 1] = ds
            Q[i - 1, N - 1] = ds / 2
        K = (2.0 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)) / ds**2
        K[-1, -1] = 1.0 / ds**2
        mid = N // 2 - 1 if N % 2 == 0 else -1
        x0 = ds / 2
        if strain is not None:
            strain = np.array(strain, dtype=float)
            if strain.shape != (N + 1,):
                raise ValueError(f"strain must have shape ({N + 1},), got {strain.shape}")
            x0 = x0 * (1.0 + strain[0])
            P = P * (1.0 + strain[1:N])[None, :]
            P[N - 1, n - 1] = ds * (1.0 + strain[N - 1]) + ds / 2 * (1.0 + strain[N])
            K = K / (1.0 + strain[1:N])[:, None]
        Q_beam = W_beam = None
        if tip_mass:
            Q_beam, W_beam = Q, Q @ P
            Q = Q.copy()
            Q[:, N - 1] += tip_mass
            # the last row's curvature reaches s = 1, where the tip's force sets theta_ss(1):
            # half of its torque again keeps the scheme second order (docs/model.md, payload)
            Q[n - 1, N - 1] += 0.5 * tip_mass
        return cls(N=N, ds=ds, s=s, P=P, Q=Q, W=Q @ P, K=K, mid=mid, x0=x0, strain=strain,
                   Q_beam=Q_beam, W_beam=W_beam)  # fmt: skip

    def positions(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Node positions from the angles, by the trapezoid quadrature P.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad] at nodes 1..N-1, shape (N-1,) or (m, N-1) at m instants.

        Returns
        -------
        x, y : numpy.ndarray
            At nodes 1..N relative to the clamp, in units of L, shape (N,) or (m, N).
        """
        x = self.x0 + np.cos(theta) @ self.P.T
        y = np.sin(theta) @ self.P.T
        return x, y

    def midspan(self, theta: np.ndarray) -> np.ndarray:
        """y_m = y(s = 1/2) from Theta of shape (N-1,) or (m, N-1).

        Parameters
        ----------
        theta : numpy.ndarray
            Angles at nodes 1..N-1, one row per instant.

        Returns
        -------
        numpy.ndarray
            y(1/2) in units of L: the node value for even N, linear interpolation for odd N.
        """
        _, y = self.positions(theta)
        return self.at_midspan(y)

    def midspan_rate(self, theta: np.ndarray, theta_t: np.ndarray) -> np.ndarray:
        """The midspan velocity dy_m/dtau, interpolated as `midspan`.

        Parameters
        ----------
        theta, theta_t : numpy.ndarray
            Angles [rad] and their rates (units of 1/T), shape (N-1,) or (m, N-1).

        Returns
        -------
        numpy.ndarray
            dy_m/dtau in units of L/T: a scalar array or shape (m,).
        """
        return self.at_midspan((np.cos(theta) * theta_t) @ self.P.T)

    def at_midspan(self, nodal: np.ndarray) -> np.ndarray:
        """A nodal quantity at s = 1/2: the node's value for even N, linear interpolation for odd.

        Parameters
        ----------
        nodal : numpy.ndarray
            Values at nodes 1..N (the last axis), shape (N,) or (m, N).

        Returns
        -------
        numpy.ndarray
            The value at s = 1/2: a scalar array or shape (m,).
        """
        if self.mid >= 0:
            return nodal[..., self.mid]
        i = self.N // 2  # node i at s_i < 1/2 < s_{i+1}: columns i-1, i
        w = 0.5 * self.N - i
        return (1 - w) * nodal[..., i - 1] + w * nodal[..., i]

    def tip(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The position of the free end (node N) relative to the clamp.

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (N-1,) or (m, N-1).

        Returns
        -------
        x, y : numpy.ndarray
            In units of L: scalar arrays or shape (m,).
        """
        x, y = self.positions(theta)
        return x[..., -1], y[..., -1]

    def full_shape(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The whole centerline, clamp included, for one Theta (figures and animations).

        Parameters
        ----------
        theta : numpy.ndarray
            Angles [rad], shape (N-1,).

        Returns
        -------
        s, x, y : numpy.ndarray
            Reference arc length and position relative to the clamp at nodes 0..N, in units
            of L, shape (N + 1,) each.
        """
        x, y = self.positions(theta)
        return (
            np.concatenate([[0.0], self.s]),
            np.concatenate([[0.0], x]),
            np.concatenate([[0.0], y]),
        )
