r"""Periodic steady state by trigonometric collocation (harmonic balance in the time domain).

The steady response to a drive of period P is sought directly as Theta at M equally spaced
instants tau_j = j P / M, with time derivatives by the Fourier (spectral) differentiation matrix
D (exact for trigonometric polynomials of degree < M/2).  The residual of Eq. (discretizedEq)

    R_j = M(Theta_j) (A_j + eta V_j) + B(Theta_j) (V_j^2 + 2 lam_j V_j [Coriolis]) + K Theta_j
          + L(Theta_j; lam_j, lam_t_j),        V = D Theta,  A = D^2 Theta,

is driven to zero by Newton with the exact block Jacobian
J[j, k] = delta_jk dR_j/dTheta_j + D_jk dR_j/dV_j + (D^2)_jk M(Theta_j).

The cost does not depend on the damping (no transient to wait for).  It finds *a* periodic
solution, not necessarily the one the beam settles on: `rotbeam.integrate.steady_state` with
start="periodic" uses it as the initial state and keeps integrating until its transient criterion
holds, so an unstable or wrong orbit is left behind rather than reported.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from .elastica import DiscreteElastica
from .modes import linear_forced_response
from .params import Dimensionless


def fourier_diff_matrix(M: int, period: float) -> np.ndarray:
    """First-derivative matrix on M equispaced points of a period (M odd: no Nyquist mode)."""
    if M % 2 == 0:
        raise ValueError("use an odd number of collocation points")
    h = 2.0 * math.pi / M
    j = np.arange(M)
    diff = j[:, None] - j[None, :]
    with np.errstate(divide="ignore"):
        D = 0.5 * (-1.0) ** diff / np.sin(diff * h / 2.0)
    D[diff == 0] = 0.0
    return D * (2.0 * math.pi / period)


@dataclass
class PeriodicResult:
    tau: np.ndarray  #: collocation instants over one period
    theta: np.ndarray  #: (N-1, M)
    theta_t: np.ndarray  #: (N-1, M)
    converged: bool
    iterations: int
    residual: float
    harmonic_tail: float  #: size of the upper half of the spectrum relative to the whole
    M: int
    message: str


class Collocation:
    """Residual and Jacobian of the collocated periodic problem for one scene and grid."""

    def __init__(self, dl: Dimensionless, N: int, M: int):
        self.dl = dl
        self.model = DiscreteElastica(N, dl.hub_ratio, dl.eta, dl.effects)
        self.M = M
        self.tau = np.arange(M) * dl.period / M
        self.D = fourier_diff_matrix(M, dl.period)
        self.D2 = self.D @ self.D
        self.lam = np.array([dl.lam(t) for t in self.tau])
        self.lam_dot = np.array([dl.lam_dot(t) for t in self.tau])

    def _mass_gyro(self, X):
        c, s = np.cos(X), np.sin(X)  # (M, n)
        W = self.model.grid.W
        Mm = c[:, :, None] * W[None] * c[:, None, :] + s[:, :, None] * W[None] * s[:, None, :]
        Bm = s[:, :, None] * W[None] * c[:, None, :] - c[:, :, None] * W[None] * s[:, None, :]
        return Mm, Bm

    def residual(self, X: np.ndarray, jacobian: bool = False):
        """X: (M, n).  Returns R (M, n) and, if asked, J (M n, M n)."""
        m = self.model
        n, M = m.n, self.M
        V = self.D @ X
        A = self.D2 @ X
        Mm, Bm = self._mass_gyro(X)
        v = V * V
        if m.effects.coriolis:
            v = v + 2.0 * self.lam[:, None] * V
        a = A + m.eta * V
        R = np.einsum("jik,jk->ji", Mm, a) + np.einsum("jik,jk->ji", Bm, v) + X @ m.grid.K.T
        for j in range(M):
            R[j] += m.load_torque(X[j], self.lam[j], self.lam_dot[j])
        if not jacobian:
            return R
        J = np.zeros((M, n, M, n))
        Ba = np.einsum("jik,jk->ji", Bm, a)
        Mv = np.einsum("jik,jk->ji", Mm, v)
        dv = 2.0 * V
        if m.effects.coriolis:
            dv = dv + 2.0 * self.lam[:, None]
        Cj = m.eta * Mm + Bm * dv[:, None, :]
        J += self.D2[:, None, :, None] * Mm[:, :, None, :]
        J += self.D[:, None, :, None] * Cj[:, :, None, :]
        idx = np.arange(n)
        for j in range(M):
            loc = m.static_jacobian(X[j], self.lam[j], self.lam_dot[j])
            loc += Bm[j] * a[j][None, :] - Mm[j] * v[j][None, :]
            loc[idx, idx] += -Ba[j] + Mv[j]
            J[j, :, j, :] += loc
        return R, J.reshape(M * n, M * n)


def _tail(X: np.ndarray) -> float:
    C = np.abs(np.fft.rfft(X, axis=0))
    total = float(np.sqrt(np.sum(C**2)))
    if total == 0.0:
        return 0.0
    k = C.shape[0]
    return float(np.sqrt(np.sum(C[k // 2 :] ** 2)) / total)


def linear_guess(dl: Dimensionless, N: int, tau: np.ndarray) -> np.ndarray:
    amp, _ = linear_forced_response(dl, N)
    return np.real(amp[None, :] * np.exp(1j * dl.omega * tau)[:, None])


def solve_periodic(
    dl: Dimensionless,
    N: int = 40,
    M: int = 33,
    guess: np.ndarray | None = None,
    rtol: float = 1e-10,
    maxiter: int = 40,
) -> PeriodicResult:
    """Newton on the collocated periodic problem; `guess` is (M, N-1) or None (linear guess)."""
    col = Collocation(dl, N, M)
    X = linear_guess(dl, N, col.tau) if guess is None else np.array(guess, dtype=float)
    R = col.residual(X)
    rn = float(np.max(np.abs(R)))
    it = 0
    converged = rn == 0.0
    msg = "exact" if converged else "no convergence"
    while not converged and it < maxiter:
        it += 1
        R, J = col.residual(X, jacobian=True)
        try:
            step = -sla.solve(J, R.ravel(), check_finite=False).reshape(X.shape)
        except (np.linalg.LinAlgError, ValueError):
            msg = "singular collocation Jacobian"
            break
        t = 1.0
        while True:
            Xt = X + t * step
            Rt = col.residual(Xt)
            rt = float(np.max(np.abs(Rt)))
            if np.isfinite(rt) and (rt < rn or t < 1e-3):
                break
            t *= 0.5
        X, R, rn = Xt, Rt, rt
        if not np.isfinite(rn):
            msg = "residual not finite"
            break
        scale = max(float(np.max(np.abs(X))), 1e-300)
        if float(np.max(np.abs(t * step))) <= rtol * scale:
            converged, msg = True, f"converged in {it} iterations"
    V = col.D @ X
    return PeriodicResult(
        tau=col.tau,
        theta=X.T.copy(),
        theta_t=V.T.copy(),
        converged=converged,
        iterations=it,
        residual=rn,
        harmonic_tail=_tail(X),
        M=M,
        message=msg,
    )


def trig_interpolate(X: np.ndarray, m: int) -> np.ndarray:
    """Values at m equispaced instants of the trigonometric interpolant of X (M, ...), M odd."""
    M = X.shape[0]
    C = np.fft.rfft(X, axis=0)
    return np.fft.irfft(C, n=m, axis=0) * (m / M)


def _amplitude_continuation(dl: Dimensionless, N: int, M: int, rtol: float, steps: int = 6):
    """Follow the orbit from a small drive amplitude up to the real one (large responses)."""
    from dataclasses import replace

    X = None
    for k in range(1, steps + 1):
        res = solve_periodic(replace(dl, alpha=dl.alpha * k / steps), N, M, guess=X, rtol=rtol)
        if not res.converged:
            return None
        X = res.theta.T
    res.message += f" (amplitude continuation in {steps} steps)"
    return res


def solve_periodic_adaptive(
    dl: Dimensionless,
    N: int = 40,
    M0: int = 17,
    tail_tol: float = 1e-5,
    M_max: int = 65,
    rtol: float = 1e-10,
    guess: np.ndarray | None = None,
) -> PeriodicResult:
    """`solve_periodic` with M doubled (2M - 1) until the harmonic tail is below `tail_tol`.

    `guess` (M', N-1) from a neighbouring scene (continuation) is resampled to M points.
    """
    M = M0 if M0 % 2 else M0 + 1
    if guess is not None:
        guess = np.asarray(guess, dtype=float)
        M = max(M, guess.shape[0] if guess.shape[0] % 2 else guess.shape[0] + 1)
        if guess.shape[0] != M:
            guess = trig_interpolate(guess, M)
    res = solve_periodic(dl, N, M, guess=guess, rtol=rtol)
    if not res.converged and guess is not None:
        res = solve_periodic(dl, N, M, rtol=rtol)
    if not res.converged:
        res = _amplitude_continuation(dl, N, M, rtol) or res
    while res.converged and res.harmonic_tail > tail_tol and 2 * M - 1 <= M_max:
        guess = trig_interpolate(res.theta.T, 2 * M - 1)
        M = 2 * M - 1
        res = solve_periodic(dl, N, M, guess=guess, rtol=rtol)
    if res.converged and res.harmonic_tail > tail_tol:
        res.message += f"; harmonic tail {res.harmonic_tail:.2g} > {tail_tol:g} at M={M}"
    return res
