r"""Periodic steady state by trigonometric collocation (harmonic balance in the time domain).

The steady response to a drive of period P is sought directly as Theta at M equally spaced
instants tau_j = j P / M, with time derivatives by the Fourier (spectral) differentiation matrix
D (exact for trigonometric polynomials of degree < M/2).  The residual of Eq. (discretizedEq)

    R_j = M(Theta_j) (A_j + eta V_j) + B(Theta_j) (V_j^2 + 2 lam_j V_j [Coriolis]) + K Theta_j
          + L(Theta_j; lam_j, lam_t_j),        V = D Theta,  A = D^2 Theta,

is driven to zero by Newton with the exact block Jacobian
J[j, k] = delta_jk dR_j/dTheta_j + D_jk dR_j/dV_j + (D^2)_jk M(Theta_j).

The cost does not depend on the damping (no transient to wait for).  It finds *a* periodic
solution, not necessarily the one the beam settles on: `rotbeam.solve.steady.steady_state` with
start="periodic" uses it as the initial state and keeps integrating until its transient criterion
holds, so an unstable or wrong orbit is left behind rather than reported.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from ..model.elastica import DiscreteElastica
from ..model.modes import linear_forced_response
from ..model.params import Dimensionless
from .spectral import fourier_diff_matrix, harmonic_tail, trig_interpolate


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
    krylov_iterations: int = 0  #: GMRES iterations in all Newton steps (0: dense solves)


class Collocation:
    """Residual and Jacobian of the collocated periodic problem for one scene and grid."""

    def __init__(self, dl: Dimensionless, N: int, M: int):
        self.dl = dl
        self.model = DiscreteElastica.from_dimensionless(dl, N)
        self.M = M
        self.tau = np.arange(M) * dl.period / M
        self.D = fourier_diff_matrix(M, dl.period)
        self.D2 = self.D @ self.D
        self.lam = np.array([dl.lam(t) for t in self.tau])
        self.lam_dot = np.array([dl.lam_dot(t) for t in self.tau])
        self._cache: tuple | None = None

    def _mass_gyro(self, X):
        """M and B at every instant: W cos(Theta_i - Theta_k), W sin(Theta_i - Theta_k)."""
        c, s = np.cos(X), np.sin(X)
        cc, ss = c[:, :, None] * c[:, None, :], s[:, :, None] * s[:, None, :]
        sc, cs = s[:, :, None] * c[:, None, :], c[:, :, None] * s[:, None, :]
        W = self.model.grid.W[None]
        cc += ss
        sc -= cs
        return W * cc, W * sc

    def _state(self, X: np.ndarray):
        """Everything the residual and the Jacobian share at X; cached for the last X."""
        if self._cache is not None and self._cache[0] is X:
            return self._cache[1]
        V = self.D @ X
        A = self.D2 @ X
        Mm, Bm = self._mass_gyro(X)
        v = V * V
        if self.model.effects.coriolis:
            v = v + 2.0 * self.lam[:, None] * V
        st = (V, A, Mm, Bm, v)
        self._cache = (X, st)
        return st

    def residual(self, X: np.ndarray) -> np.ndarray:
        """X: (M, n) -> R (M, n)."""
        m = self.model
        V, A, Mm, Bm, v = self._state(X)
        a = A + m.eta * V
        R = np.einsum("jik,jk->ji", Mm, a) + np.einsum("jik,jk->ji", Bm, v) + X @ m.grid.K.T
        R += m.load_torque_rows(X, self.lam, self.lam_dot)
        return R

    def jacobian_blocks(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The Jacobian at X as (M, n, n) block sets: J = diag(L_j) + diag(C_j) D + diag(M_j) D^2
        (reusing the residual's work when X was its last argument)."""
        m = self.model
        n = m.n
        V, A, Mm, Bm, v = self._state(X)
        a = A + m.eta * V
        Ba = np.einsum("jik,jk->ji", Bm, a)
        Mv = np.einsum("jik,jk->ji", Mm, v)
        dv = 2.0 * V
        if m.effects.coriolis:
            dv = dv + 2.0 * self.lam[:, None]
        Cj = m.eta * Mm + Bm * dv[:, None, :]
        _, Lj = m.load_torque_rows(X, self.lam, self.lam_dot, jacobian=True)
        Lj += m.grid.K[None] + Bm * a[:, None, :] - Mm * v[:, None, :]
        idx = np.arange(n)
        Lj[:, idx, idx] += Mv - Ba
        return Lj, Cj, Mm

    def dense_jacobian(self, blocks) -> np.ndarray:
        """(M n, M n) matrix of the block Jacobian (for small problems and tests)."""
        Lj, Cj, Mm = blocks
        M, n = self.M, self.model.n
        J = self.D2[:, None, :, None] * Mm[:, :, None, :]
        J = J + self.D[:, None, :, None] * Cj[:, :, None, :]
        for j in range(M):
            J[j, :, j, :] += Lj[j]
        return J.reshape(M * n, M * n)

    def jacobian_times(self, blocks, Y: np.ndarray) -> np.ndarray:
        """J Y without forming J: O(M n^2 + M^2 n)."""
        Lj, Cj, Mm = blocks
        return (
            np.einsum("jik,jk->ji", Lj, Y)
            + np.einsum("jik,jk->ji", Cj, self.D @ Y)
            + np.einsum("jik,jk->ji", Mm, self.D2 @ Y)
        )

    def averaged_inverse(self, blocks):
        """Solver of the time-averaged (block-circulant) Jacobian, diagonal in Fourier space.

        D is exact on the M-point trigonometric polynomials, so with the blocks replaced by their
        means the Jacobian decouples into one n x n complex system per harmonic k:
        (L + i w_k C - w_k^2 M) Y_k = R_k, w_k = 2 pi k / P.  A preconditioner for GMRES.
        """
        Lb, Cb, Mb = (b.mean(axis=0) for b in blocks)
        M = self.M
        w = 2.0 * math.pi * np.arange(M // 2 + 1) / self.dl.period
        blocks_k = Lb[None] + 1j * w[:, None, None] * Cb[None] - (w * w)[:, None, None] * Mb[None]
        inv = np.linalg.inv(blocks_k)  # one batched call; a preconditioner needs no pivoted LU

        def solve(R: np.ndarray) -> np.ndarray:
            F = np.fft.rfft(R, axis=0)
            return np.fft.irfft(np.einsum("kij,kj->ki", inv, F), n=M, axis=0)

        return solve


LINEAR_SOLVERS = ("auto", "dense", "krylov")
DENSE_MAX = 200  #: "auto": dense LU up to this many unknowns (GMRES 2.5x faster at 663, 6x at 2535)


def _newton_step(col: Collocation, blocks, R: np.ndarray, linear: str, inv=None):
    """Solve J step = -R to relative accuracy 1e-4 (an inexact Newton step: Newton still
    converges, in fewer Krylov iterations).  Returns the step, the GMRES iterations spent (0 for
    dense) and the preconditioner used (`inv`, if given, is reused: it is only a preconditioner,
    and the time-averaged Jacobian changes little between Newton iterations)."""
    shape = R.shape
    size = R.size
    if linear == "dense" or (linear == "auto" and size <= DENSE_MAX):
        J = col.dense_jacobian(blocks)
        return -sla.solve(J, R.ravel(), check_finite=False).reshape(shape), 0, None
    from scipy.sparse.linalg import LinearOperator, gmres

    def matvec(y: np.ndarray) -> np.ndarray:
        return col.jacobian_times(blocks, y.reshape(shape)).ravel()

    op = LinearOperator((size, size), matvec)
    inv = inv if inv is not None else col.averaged_inverse(blocks)
    pre = LinearOperator((size, size), lambda r: inv(r.reshape(shape)).ravel())
    count = [0]

    def tick(_):
        count[0] += 1

    b = -R.ravel()
    x, info = gmres(op, b, rtol=1e-4, atol=0.0, restart=60, maxiter=20, M=pre,
                    callback=tick, callback_type="pr_norm")  # fmt: skip
    if info != 0 or not np.all(np.isfinite(x)):
        if size <= 8 * DENSE_MAX:  # GMRES stalled: fall back to the exact dense solve
            J = col.dense_jacobian(blocks)
            return -sla.solve(J, R.ravel(), check_finite=False).reshape(shape), count[0], None
        if not np.all(np.isfinite(x)):
            raise np.linalg.LinAlgError("GMRES gave a non-finite step")
    return x.reshape(shape), count[0], inv


def linear_guess(dl: Dimensionless, N: int, tau: np.ndarray) -> np.ndarray:
    amp, _ = linear_forced_response(dl, N)
    return np.real(amp[None, :] * np.exp(1j * dl.omega * tau)[:, None])


def _line_search(
    col: Collocation, X: np.ndarray, step: np.ndarray, rn: float
) -> tuple[float, np.ndarray, np.ndarray, float]:
    """Halve the Newton step until the residual's max-norm falls below rn (or t < 1e-3); returns
    (t, X + t step, its residual, its max-norm)."""
    t = 1.0
    while True:
        Xt = X + t * step
        Rt = col.residual(Xt)
        rt = float(np.max(np.abs(Rt)))
        if np.isfinite(rt) and (rt < rn or t < 1e-3):
            return t, Xt, Rt, rt
        t *= 0.5


def solve_periodic(
    dl: Dimensionless,
    N: int = 40,
    M: int = 33,
    guess: np.ndarray | None = None,
    rtol: float = 1e-10,
    maxiter: int = 40,
    linear: str = "auto",
) -> PeriodicResult:
    """Newton on the collocated periodic problem; `guess` is (M, N-1) or None (linear guess).

    `linear` solves the Newton systems: "dense" (LU of the (M n)^2 Jacobian), "krylov" (GMRES,
    matrix-free, preconditioned by the time-averaged Jacobian) or "auto" (dense when M n is small).
    """
    if linear not in LINEAR_SOLVERS:
        raise ValueError(f"linear must be one of {LINEAR_SOLVERS}, got {linear!r}")
    gmres_iterations = first_krylov = 0
    inv = None
    col = Collocation(dl, N, M)
    X = linear_guess(dl, N, col.tau) if guess is None else np.array(guess, dtype=float)
    R = col.residual(X)
    rn = float(np.max(np.abs(R)))
    it = 0
    converged = rn == 0.0
    msg = "exact" if converged else "no convergence"
    while not converged and it < maxiter:
        it += 1
        blocks = col.jacobian_blocks(X)
        try:
            step, krylov, inv = _newton_step(col, blocks, R, linear, inv)
        except (np.linalg.LinAlgError, ValueError):
            msg = "singular collocation Jacobian"
            break
        gmres_iterations += krylov
        if krylov > 2 * max(first_krylov, 5):
            inv = None  # the preconditioner went stale: rebuild it at the next step
        first_krylov = first_krylov or krylov
        t, X, R, rn = _line_search(col, X, step, rn)
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
        krylov_iterations=gmres_iterations,
        residual=rn,
        harmonic_tail=harmonic_tail(X),
        M=M,
        message=msg,
    )


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
    M_max: int = 129,
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
