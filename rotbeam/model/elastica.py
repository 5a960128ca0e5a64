r"""The discrete rotating elastica of Appendix A, re-derived from Eqs. (EOM1-3) and (BC).

Continuum model (dimensionless, time by T, see `rotbeam.params`), rotating frame, clamp at
(r_o, 0), position R(s) = (r_o + x, y):

    n_s + F = r_tt + eta r_t,        theta_ss - n_x sin(theta) + n_y cos(theta) = 0,
    F_x = lam^2 (r_o + x) + lam_t y + 2 lam y_t
    F_y = -lam_t (r_o + x) + lam^2 y - 2 lam x_t

i.e. centrifugal lam^2 R, Euler -lam_t e_z x R and Coriolis -2 lam e_z x r_t, each derived from
Eqs. (ForceW), (ForceE), (ForceC).  lam^2 (r_o + x) = C (1 - delta + delta x) and
lam_t / delta = E, so this is Eqs. (EOM1-2) with the Euler sign of Eq. (ForceE): the y-load is
-E (1 - delta + delta x) where Eq. (EOM2) prints +E; the x-load +delta E y agrees with Eq. (EOM1).
(The printed pair is not a force perpendicular to R; ours is.  RMS values do not depend on it.)

Grid: s_i = i ds, ds = 1/N.  Unknowns Theta = (theta_1 .. theta_{N-1}); theta_0 = 0 (clamp) and
theta_N = theta_{N-1} (theta_s(1) = 0 by a backward difference, Eq. Neumann BC).

* Positions, trapezoid rule (Eqs. numX, numY): x_i = ds/2 + (P cos Theta)_i, y_i = (P sin Theta)_i
  at nodes i = 1..N.  P is the paper's L extended by the tip row x_N = x_{N-1} + ds cos theta_{N-1}.
  (The printed "ds/2 + L c" is right: ds/2 is the clamp term cos theta_0 = 1 of every row.)
* Tension, trapezoid rule from s_i to 1 with n(1) = 0 (Eq. NumT): n_i = (Q g)_i,
  g = F - r_tt - eta r_t at nodes 1..N.  Q is the paper's U; we keep the tip node's own value
  g_N instead of the printed last column of 3s (which sets g_N = g_{N-1}, first order at the tip).
* Moment, central differences (Eq. Discrete_theta_ss): theta_ss = -K Theta with
  K = tridiag(-1, 2, -1) / ds^2, last diagonal entry 1 / ds^2.  The printed K has 1/ds; with 1/ds^2
  the units of K Theta and of the tension terms agree.

Substitution gives Eq. (discretizedEq)

    M Theta_tt + (eta M + 2 lam B) Theta_t + B Theta_t^2 + K Theta = f,
    W = Q P,   M_ij = W_ij cos(theta_i - theta_j),   B_ij = W_ij sin(theta_i - theta_j),
    f = -(sin Theta * Q F_x - cos Theta * Q F_y)  with the load parts of F only.

Departures from the printed appendix, beyond those above: (i) the n_y integrand of Eq. (NumT) has
+2 I y_t where Eq. (EOM2) gives -2 I x_t (we use -2 lam x_t); (ii) the first bracket of
Eq. (Disc_tension_x), 1 + (delta - 1) s - delta s^2/4, is not the integral of the centrifugal load:
int_s^1 lam^2 (r_o + s') ds' = lam^2 [r_o (1 - s) + (1 - s^2)/2], which the discrete Q P sums
reproduce exactly on the straight beam (tested); (iii) the velocity-squared matrix is
W_ij sin(theta_i - theta_j), antisymmetric, where the printed S~ is symmetric; (iv) the gyroscopic
term enters as 2 lam B Theta_t with the same B.  M is W "times" C~ element-wise, as printed.

Extension (effect `extension`, not in the paper, off by default; docs/model.md derives it).  The
centerline stretches by the local tension, r_s = (1 + eps) t(theta) with eps = N / (EA), s the
reference arc length.  In units of EI / L^2, eps = kappa n with kappa = EI / (EA L^2) =
(h/L)^2 / 12.  Mass per reference length, m = EI theta_s and n = int_s^1 g keep their form; the
moment balance becomes theta_ss + (1 + eps)(-n_x sin theta + n_y cos theta) = 0.  The strain is
quasi-static and frozen: eps(s) of the straight beam spinning steadily at lam_s, with
lam_s^2 = lam0^2 + alpha^2/2 the period mean of lam^2.  It is exact in eps
(`centrifugal_strain`, 14 % at the clamp at 165 rad/s for the Table 1 beam).  Then
* P becomes P diag(1 + eps_j): element lengths ds (1 + eps).  The clamp term is
  x0 = ds/2 (1 + eps_0), and the tip row carries ds (1 + eps_{N-1}) + ds/2 (1 + eps_N).  So x, y,
  y_m, the centrifugal and Euler loads and W = Q P (hence M, B) are those of the stretched beam.
  Q is unchanged: it integrates per reference length;
* K becomes diag(1 + eps)^-1 K (dividing the moment rows by 1 + eps).
eps depends on neither Theta nor time, so the Jacobians above hold as they stand with the
stretched P, W, K: they stay exact.  What is left out: the O(theta) and O(theta^2) parts of the
tension (deflection, Euler, inertia, damping; 1e-3 of n0 here), the modulation of eps by the
drive (relative 2 a / Omega_0, entering y_m at O(eps a / Omega_0)), axial inertia and
stretch-rate velocities (the first axial frequency, (pi/2) / sqrt(kappa) = 109 / T, is 22 times
a 9 Hz drive), Poisson thinning of the section, shear and rotary inertia (docs/model.md
estimates each).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from ..config.errors import RotbeamInputError
from ..config.parameters import check_value
from .params import Dimensionless, Effects


def check_N(N: int) -> int:
    """The number of grid intervals, checked against the registry (numerics.N)."""
    return check_value("numerics", "N", N)


def centrifugal_strain(s, hub_ratio: float, kappa: float, lam: float) -> np.ndarray:
    """Axial strain eps(s) of the straight extensible beam spinning steadily at lam, exact.

    n' = -lam^2 (r_o + x), x' = 1 + eps, eps = kappa n, n(1) = 0, x(0) = 0 give
    n'' + k^2 n = -lam^2 with k = |lam| sqrt(kappa), whose solution is
    1 + eps = [cos(k s) + k r_o sin(k (1 - s))] / cos(k), written below without cancellation;
    eps = kappa lam^2 [r_o (1 - s) + (1 - s^2)/2] (1 + O(k^2)).  No tensile equilibrium for
    k >= pi/2 (the stretch runs away).
    """
    k = abs(float(lam)) * math.sqrt(kappa)
    if not k < 0.5 * math.pi:
        raise RotbeamInputError(
            f"effects.extension: no stretched equilibrium at lam sqrt(kappa) = {k:.4g} >= pi/2 "
            f"(lam = Omega T = {lam:.4g}, kappa = (h/L)^2/12 = {kappa:.4g})"
        )
    s = np.asarray(s, dtype=float)
    a, b = 0.5 * k * (1.0 + s), 0.5 * k * (1.0 - s)
    return (2.0 * np.sin(a) * np.sin(b) + k * hub_ratio * np.sin(2.0 * b)) / math.cos(k)


@dataclass(frozen=True)
class Grid:
    """Operators of the N-interval grid (built once, reused for every evaluation)."""

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

    @classmethod
    def build(cls, N: int, strain: np.ndarray | None = None) -> Grid:
        """The grid; with `strain` (eps at nodes 0..N) the element lengths are ds (1 + eps)."""
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
        return cls(N=N, ds=ds, s=s, P=P, Q=Q, W=Q @ P, K=K, mid=mid, x0=x0, strain=strain)

    def positions(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """x, y at nodes 1..N (relative to the clamp); theta has shape (N-1,) or (N-1, m)."""
        x = self.x0 + self.P @ np.cos(theta)
        y = self.P @ np.sin(theta)
        return x, y

    def midspan(self, theta: np.ndarray) -> np.ndarray:
        """y(s = 1/2) from Theta of shape (N-1,) or (N-1, m) (linear interpolation for odd N)."""
        _, y = self.positions(theta)
        if self.mid >= 0:
            return y[self.mid]
        i = self.N // 2  # node i at s_i < 1/2 < s_{i+1}: rows i-1, i of y
        w = 0.5 * self.N - i
        return (1 - w) * y[i - 1] + w * y[i]

    def full_shape(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """s, x, y at all nodes 0..N (clamp included) for one Theta."""
        x, y = self.positions(theta)
        return (
            np.concatenate([[0.0], self.s]),
            np.concatenate([[0.0], x]),
            np.concatenate([[0.0], y]),
        )


class DiscreteElastica:
    """Right-hand side, Jacobians and static residual of the discrete model on one grid."""

    def __init__(
        self,
        N: int,
        hub_ratio: float,
        eta: float,
        effects: Effects | None = None,
        kappa: float = 0.0,
        lam_stretch: float = 0.0,
    ):
        """`kappa` = (h/L)^2 / 12 and `lam_stretch` (the rotation whose centrifugal tension
        stretches the beam) are read only with `effects.extension` (and `centrifugal`)."""
        self.hub_ratio = float(hub_ratio)
        self.effects = effects if effects is not None else Effects()
        strain = None
        if self.effects.extension and self.effects.centrifugal:
            if not (math.isfinite(kappa) and kappa > 0):
                raise RotbeamInputError(
                    f"effects.extension needs kappa = (h/L)^2 / 12 > 0, got {kappa!r}"
                )
            s = np.arange(N + 1) / check_N(N)
            strain = centrifugal_strain(s, self.hub_ratio, kappa, lam_stretch)
        self.grid = Grid.build(N, strain)
        self.n = self.grid.N - 1
        self.eta = float(eta) if self.effects.damping else 0.0

    @classmethod
    def from_dimensionless(cls, dl: Dimensionless, N: int, eta: float | None = None):
        """The model of one dimensionless scene (`eta` overrides the scene's damping)."""
        eta = dl.eta if eta is None else eta
        return cls(N, dl.hub_ratio, eta, dl.effects, dl.kappa, dl.lam_stretch)

    # --- loads ------------------------------------------------------------------------------
    def _loads(self, c, s, lam, lam_dot):
        """Nodal load parts of F_x, F_y (nodes 1..N) and nodal x, y."""
        g = self.grid
        x = g.x0 + g.P @ c
        y = g.P @ s
        fx = np.zeros_like(x)
        fy = np.zeros_like(y)
        ef = self.effects
        if ef.centrifugal:
            lam2 = lam * lam
            fx = fx + lam2 * (self.hub_ratio + x)
            if ef.softening:
                fy = fy + lam2 * y
        if ef.euler:
            fx = fx + lam_dot * y
            fy = fy - lam_dot * (self.hub_ratio + x)
        return fx, fy

    def load_torque(self, theta: np.ndarray, lam: float, lam_dot: float) -> np.ndarray:
        """L(Theta) = sin Theta * Q F_x - cos Theta * Q F_y (so that f = -L)."""
        c, s = np.cos(theta), np.sin(theta)
        fx, fy = self._loads(c, s, lam, lam_dot)
        Q = self.grid.Q
        return s * (Q @ fx) - c * (Q @ fy)

    def load_torque_jacobian(self, theta: np.ndarray, lam: float, lam_dot: float) -> np.ndarray:
        """dL/dTheta, exact (`load_torque_rows` at one instant)."""
        return self.load_torque_rows(theta[None], [lam], [lam_dot], jacobian=True)[1][0]

    def load_torque_rows(
        self, theta: np.ndarray, lam: np.ndarray, lam_dot: np.ndarray, jacobian: bool = False
    ):
        """`load_torque` at m instants at once: theta (m, n), lam and lam_dot (m,) -> (m, n);
        with `jacobian`, also the m Jacobians `load_torque_jacobian` (m, n, n)."""
        g, ef = self.grid, self.effects
        lam, lam_dot = np.asarray(lam, dtype=float), np.asarray(lam_dot, dtype=float)
        c, s = np.cos(theta), np.sin(theta)
        fx, fy = self._loads(c.T, s.T, lam, lam_dot)
        nx, ny = (g.Q @ fx).T, (g.Q @ fy).T
        torque = s * nx - c * ny
        if not jacobian:
            return torque
        # dL/dTheta = diag(C n_x + S n_y) + S W diag(a) - C W diag(b), from
        # d(F_x)/dTheta = P diag(a) = P (-lam^2 S + lam_dot C) and
        # d(F_y)/dTheta = P diag(b) = P (lam_dot S + [softening] lam^2 C)
        lam2, ld = (lam * lam)[:, None], lam_dot[:, None]
        a = np.zeros_like(theta)
        b = np.zeros_like(theta)
        if ef.centrifugal:
            a = a - lam2 * s
            if ef.softening:
                b = b + lam2 * c
        if ef.euler:
            a = a + ld * c
            b = b + ld * s
        J = s[:, :, None] * a[:, None, :] - c[:, :, None] * b[:, None, :]
        J *= g.W[None]
        idx = np.arange(self.n)
        J[:, idx, idx] += c * nx + s * ny
        return torque, J

    # --- static problem ---------------------------------------------------------------------
    def static_residual(self, theta: np.ndarray, lam: float, lam_dot: float) -> np.ndarray:
        return self.grid.K @ theta + self.load_torque(theta, lam, lam_dot)

    def static_jacobian(self, theta: np.ndarray, lam: float, lam_dot: float) -> np.ndarray:
        return self.grid.K + self.load_torque_jacobian(theta, lam, lam_dot)

    # --- dynamics ---------------------------------------------------------------------------
    def mass_and_gyro(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        c, s = np.cos(theta), np.sin(theta)
        W = self.grid.W
        M = (c[:, None] * W) * c[None, :] + (s[:, None] * W) * s[None, :]
        B = (s[:, None] * W) * c[None, :] - (c[:, None] * W) * s[None, :]
        return M, B

    def acceleration(self, theta, theta_t, lam, lam_dot):
        """Theta_tt from Eq. (discretizedEq); also returns the LU of M for Jacobians."""
        M, B = self.mass_and_gyro(theta)
        rhs = -self.grid.K @ theta - self.load_torque(theta, lam, lam_dot) - B @ (theta_t**2)
        if self.effects.coriolis:
            rhs -= 2.0 * lam * (B @ theta_t)
        lu = lu_factor(M, check_finite=False)
        acc = lu_solve(lu, rhs, check_finite=False) - self.eta * theta_t
        return acc, lu, B

    def first_order_jacobian(self, theta, theta_t, lam, lam_dot) -> np.ndarray:
        """Exact Jacobian of (Theta_t, Theta_tt) w.r.t. (Theta, Theta_t).

        With M a = r, r = -K Theta - L(Theta) - B v, v = Theta_t^2 (+ 2 lam Theta_t):
        d(M a)/dTheta = B diag(a) - diag(B a),  d(B v)/dTheta = diag(M v) - M diag(v).
        """
        n = self.n
        M, B = self.mass_and_gyro(theta)
        v = theta_t**2
        if self.effects.coriolis:
            v = v + 2.0 * lam * theta_t
        rhs = -self.grid.K @ theta - self.load_torque(theta, lam, lam_dot) - B @ v
        lu = lu_factor(M, check_finite=False)
        a0 = lu_solve(lu, rhs, check_finite=False)
        dr = -self.static_jacobian(theta, lam, lam_dot) + M * v[None, :] - B * a0[None, :]
        dr[np.diag_indices(n)] += -(M @ v) + B @ a0
        J = np.zeros((2 * n, 2 * n))
        J[:n, n:] = np.eye(n)
        J[n:, :n] = lu_solve(lu, dr, check_finite=False)
        dv = 2.0 * B * theta_t[None, :]
        if self.effects.coriolis:
            dv = dv + 2.0 * lam * B
        J[n:, n:] = -lu_solve(lu, dv, check_finite=False) - self.eta * np.eye(n)
        return J

    def first_order_rows(
        self, theta: np.ndarray, theta_t: np.ndarray, lam, lam_dot
    ) -> tuple[np.ndarray, np.ndarray]:
        """The first-order right-hand side (Theta_t, Theta_tt) (m, 2n) and its exact Jacobians
        (m, 2n, 2n) at m instants at once: theta, theta_t (m, n), lam and lam_dot (m,).  One
        batched pass instead of m calls: the Floquet monodromy needs them at every step.  The
        same formulas as `first_order_jacobian`, which stays the per-instant reference (its
        output is pinned to the bit by tests/test_extension.py); the two agree to round-off
        (tests/test_elastica.py).

        With M a = r, r = -K Theta - L(Theta) - B v, v = Theta_t^2 (+ 2 lam Theta_t):
        d(M a)/dTheta = B diag(a) - diag(B a),  d(B v)/dTheta = diag(M v) - M diag(v).
        """
        n, W, K = self.n, self.grid.W, self.grid.K
        lam, lam_dot = np.asarray(lam, dtype=float), np.asarray(lam_dot, dtype=float)
        c, s = np.cos(theta), np.sin(theta)
        M = c[:, :, None] * W * c[:, None, :] + s[:, :, None] * W * s[:, None, :]
        B = s[:, :, None] * W * c[:, None, :] - c[:, :, None] * W * s[:, None, :]
        v = theta_t**2
        if self.effects.coriolis:
            v = v + 2.0 * lam[:, None] * theta_t
        torque, dL = self.load_torque_rows(theta, lam, lam_dot, jacobian=True)
        Bv = np.einsum("mij,mj->mi", B, v)
        a0 = np.linalg.solve(M, (-(theta @ K.T) - torque - Bv)[..., None])[..., 0]
        idx = np.arange(n)
        dr = -(K[None] + dL) + M * v[:, None, :] - B * a0[:, None, :]
        dr[:, idx, idx] += -np.einsum("mij,mj->mi", M, v) + np.einsum("mij,mj->mi", B, a0)
        dv = 2.0 * B * theta_t[:, None, :]
        if self.effects.coriolis:
            dv = dv + 2.0 * lam[:, None, None] * B
        X = np.linalg.solve(M, np.concatenate([dr, dv], axis=2))
        J = np.zeros((theta.shape[0], 2 * n, 2 * n))
        J[:, idx, n + idx] = 1.0
        J[:, n:, :n] = X[:, :, :n]
        J[:, n:, n:] = -X[:, :, n:]
        J[:, n + idx, n + idx] -= self.eta
        F = np.concatenate([theta_t, a0 - self.eta * theta_t], axis=1)
        return F, J

    def tension(self, theta, theta_t, theta_tt, lam, lam_dot) -> tuple[np.ndarray, np.ndarray]:
        """Internal force n_x, n_y at nodes 1..N-1 (used in tests and for diagnostics)."""
        g = self.grid
        c, s = np.cos(theta), np.sin(theta)
        fx, fy = self._loads(c, s, lam, lam_dot)
        xt = -g.P @ (s * theta_t)
        yt = g.P @ (c * theta_t)
        xtt = -g.P @ (s * theta_tt + c * theta_t**2)
        ytt = g.P @ (c * theta_tt - s * theta_t**2)
        gx = fx - xtt - self.eta * xt
        gy = fy - ytt - self.eta * yt
        if self.effects.coriolis:
            gx = gx + 2 * lam * yt
            gy = gy - 2 * lam * xt
        return g.Q @ gx, g.Q @ gy
