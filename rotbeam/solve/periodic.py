r"""Periodic steady state by trigonometric collocation (harmonic balance in the time domain).

The orbit of the drive period is sought directly as Theta at M equally spaced instants, with
time derivatives by the Fourier differentiation matrix, and the collocated equations of motion
are solved by damped Newton (dense LU for small problems, else GMRES preconditioned by the
time-averaged Jacobian).  The cost does not depend on the damping, and the result is *a*
periodic solution, which `rotbeam.solve.steady` then checks.  The residual, its Jacobian and
the solver: docs/numerics.md, "Trigonometric collocation".
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla

from ..model.base import DiscreteModel, Residual
from ..model.modes import linear_forced_response
from ..model.rows import matvec_rows
from .krylov import gmres
from .newton import newton
from .spectral import fourier_diff_matrix, harmonic_tail, trig_interpolate


@dataclass
class PeriodicResult:
    """A collocated periodic orbit and how Newton got there (times in units of T, angles in
    rad)."""

    tau: np.ndarray  #: (M,) collocation instants over one period
    theta: np.ndarray  #: (M, n) the model's coordinates at the instants
    theta_t: np.ndarray  #: (M, n) d theta / d tau, the spectral derivative
    converged: bool  #: Newton met its step tolerance
    iterations: int  #: Newton steps
    residual: float  #: max |R| at the last iterate
    harmonic_tail: float  #: size of the upper half of the spectrum relative to the whole
    M: int  #: collocation instants
    message: str  #: how Newton ended
    krylov_iterations: int = 0  #: GMRES iterations in all Newton steps (0: dense solves)


class SpectralCollocation:
    """Residual and Jacobian of a periodic problem R(X, D X, D^2 X) = 0 collocated at M
    equally spaced instants of its period: the one harmonic balance of the package.

    D is the Fourier differentiation matrix of the period, exact on the M-point trigonometric
    polynomials; the rows R and their blocks (dR/dX, dR/dX_t, dR/dX_tt) at the instants come
    from `rows`, a second-order residual over a batch of instants (`rotbeam.model.base.Residual`:
    a first-order system is one with dR/dX_tt = 0).  `Collocation` is this for a model's
    equation of motion under its drive; `rotbeam.solve.continuation.FirstOrderProblem` for
    z' = f(t, z; p).

    Parameters
    ----------
    rows : callable
        rows(X, X_t, X_tt) -> Residual at the instants, each argument of shape (M, n).
    period : float
        The period (the time unit of the rows).
    M : int
        Collocation instants tau_j = j period / M (odd).
    """

    def __init__(
        self,
        rows: Callable[[np.ndarray, np.ndarray, np.ndarray], Residual],
        period: float,
        M: int,
    ) -> None:
        self.rows_at = rows
        self.period = period
        self.M = M
        self.tau = np.arange(M) * period / M
        self.D = fourier_diff_matrix(M, period)
        self.D2 = self.D @ self.D
        self._cache: tuple | None = None

    def _rows(self, X: np.ndarray) -> Residual:
        """The residual rows at the instants, with the rates and accelerations by the Fourier
        differentiation matrix; cached for the last X, which the residual and the Jacobian
        share."""
        if self._cache is not None and self._cache[0] is X:
            return self._cache[1]
        rows = self.rows_at(X, self.D @ X, self.D2 @ X)
        self._cache = (X, rows)
        return rows

    def residual(self, X: np.ndarray) -> np.ndarray:
        """The residual of the equations of motion at the collocation instants.

        Parameters
        ----------
        X : numpy.ndarray
            Theta [rad] at the instants, shape (M, n).

        Returns
        -------
        numpy.ndarray
            R_j (dimensionless torques), shape (M, n); zero on a collocated orbit.
        """
        return self._rows(X).R

    def jacobian_blocks(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The Jacobian at X as three block sets: J = diag(L_j) + diag(C_j) D + diag(M_j) D^2
        (reusing the residual's work when X was its last argument).

        Parameters
        ----------
        X : numpy.ndarray
            Theta [rad] at the instants, shape (M, n).

        Returns
        -------
        L : numpy.ndarray
            dR_j / dTheta_j, shape (M, n, n).
        C : numpy.ndarray
            dR_j / dV_j, shape (M, n, n).
        Mm : numpy.ndarray
            The mass matrices M(Theta_j), shape (M, n, n).
        """
        return self._rows(X).blocks()

    def dense_jacobian(self, blocks: tuple[np.ndarray, np.ndarray, np.ndarray]) -> np.ndarray:
        """The block Jacobian as one dense matrix (for small problems and tests).

        Parameters
        ----------
        blocks : tuple of numpy.ndarray
            (L, C, Mm) from `jacobian_blocks`.

        Returns
        -------
        numpy.ndarray
            Shape (M n, M n), unknowns ordered instant by instant.
        """
        Lj, Cj, Mm = blocks
        M, n = self.M, Lj.shape[-1]
        J = self.D2[:, None, :, None] * Mm[:, :, None, :]
        J = J + self.D[:, None, :, None] * Cj[:, :, None, :]
        for j in range(M):
            J[j, :, j, :] += Lj[j]
        return J.reshape(M * n, M * n)

    def jacobian_times(
        self, blocks: tuple[np.ndarray, np.ndarray, np.ndarray], Y: np.ndarray
    ) -> np.ndarray:
        """J Y without forming J: O(M n^2 + M^2 n).

        Parameters
        ----------
        blocks : tuple of numpy.ndarray
            (L, C, Mm) from `jacobian_blocks`.
        Y : numpy.ndarray
            Shape (M, n).

        Returns
        -------
        numpy.ndarray
            J Y, shape (M, n).
        """
        Lj, Cj, Mm = blocks
        return matvec_rows(Lj, Y) + matvec_rows(Cj, self.D @ Y) + matvec_rows(Mm, self.D2 @ Y)

    def averaged_inverse(self, blocks: tuple[np.ndarray, np.ndarray, np.ndarray]):
        """Solver of the time-averaged (block-circulant) Jacobian, diagonal in Fourier space.

        D is exact on the M-point trigonometric polynomials, so with the blocks replaced by their
        means the Jacobian decouples into one n x n complex system per harmonic k:
        (L + i w_k C - w_k^2 M) Y_k = R_k, w_k = 2 pi k / P.  A preconditioner for GMRES.

        Parameters
        ----------
        blocks : tuple of numpy.ndarray
            (L, C, Mm) from `jacobian_blocks`; their means over the instants are used.

        Returns
        -------
        callable
            solve(R) -> Y, both of shape (M, n): the averaged Jacobian's inverse applied to R.
        """
        Lb, Cb, Mb = (b.mean(axis=0) for b in blocks)
        M = self.M
        w = 2.0 * math.pi * np.arange(M // 2 + 1) / self.period
        blocks_k = Lb[None] + 1j * w[:, None, None] * Cb[None] - (w * w)[:, None, None] * Mb[None]
        inv = np.linalg.inv(blocks_k)  # one batched call; a preconditioner needs no pivoted LU

        def solve(R: np.ndarray) -> np.ndarray:
            F = np.fft.rfft(R, axis=0)
            return np.fft.irfft(matvec_rows(inv, F), n=M, axis=0)

        return solve


class Collocation(SpectralCollocation):
    """The collocated periodic problem of one model under its drive: its residual rows
    (`DiscreteModel.residual_rows`) at M instants of the drive period.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive (period `dl.period`, dimensionless).
    M : int
        Collocation instants tau_j = j P / M (odd).
    """

    def __init__(self, model: DiscreteModel, M: int) -> None:
        self.model = model
        self.dl = dl = model.dl
        super().__init__(self._model_rows, dl.period, M)
        self.lam, self.lam_dot = model.drive_rows(self.tau)

    def _model_rows(self, X: np.ndarray, X_t: np.ndarray, X_tt: np.ndarray) -> Residual:
        return self.model.residual_rows(X, X_t, X_tt, self.lam, self.lam_dot)


@dataclass(frozen=True)
class Neighbour:
    """The converged orbit of a nearby scene, where continuation starts (a sweep's previous
    point): the same model at another drive frequency.

    The angles are kept at equispaced phases of the drive period, so the orbit serves as a
    start at any frequency as it is.
    """

    theta: np.ndarray  #: (M, n) angles [rad] at the phases j / M of the drive period
    omega: float  #: its drive frequency 2 pi f_d T (dimensionless)

    @property
    def M(self) -> int:
        """Its collocation instants."""
        return self.theta.shape[0]

    def at(self, M: int) -> np.ndarray:
        """The orbit at M instants (its trigonometric interpolant resampled).

        Parameters
        ----------
        M : int
            Instants (odd).

        Returns
        -------
        numpy.ndarray
            Theta [rad] at the phases j / M, shape (M, n).
        """
        return self.theta if self.M == M else trig_interpolate(self.theta, M)

    def coarse(self) -> Neighbour:
        """The same orbit on the grid of N // 2 intervals (every second node; N even).

        Returns
        -------
        Neighbour
            Angles at the coarse grid's nodes.
        """
        return Neighbour(self.theta[:, 1::2], self.omega)


def as_neighbour(guess: np.ndarray | Neighbour | None, omega: float) -> Neighbour | None:
    """A guess as a `Neighbour`: an array of angles (M, n) is one at the drive frequency
    `omega` (no slope, no state).

    Parameters
    ----------
    guess : numpy.ndarray, Neighbour or None
        The guess.
    omega : float
        The frequency a bare array is taken to be at (the scene's own).

    Returns
    -------
    Neighbour or None
        The guess as a Neighbour (without a state for an array).
    """
    if guess is None or isinstance(guess, Neighbour):
        return guess
    return Neighbour(np.asarray(guess, dtype=float), omega)


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
        return _dense_step(col, blocks, R), 0, None
    inv = inv if inv is not None else col.averaged_inverse(blocks)
    solved = gmres(
        lambda y: col.jacobian_times(blocks, y.reshape(shape)).ravel(),
        lambda r: inv(r.reshape(shape)).ravel(),
        -R.ravel(),
        rtol=1e-4,
        restart=60,
        maxiter=20,
    )
    x = solved.x
    if not solved.converged or not np.all(np.isfinite(x)):
        if size <= 8 * DENSE_MAX:  # GMRES stalled: fall back to the exact dense solve
            return _dense_step(col, blocks, R), solved.iterations, None
        if not np.all(np.isfinite(x)):
            raise np.linalg.LinAlgError("GMRES gave a non-finite step")
    return x.reshape(shape), solved.iterations, inv


def _dense_step(col: Collocation, blocks, R: np.ndarray) -> np.ndarray:
    """The exact Newton step -J^-1 R by LU of the dense block Jacobian, shaped as R."""
    J = col.dense_jacobian(blocks)
    return -sla.solve(J, R.ravel(), check_finite=False).reshape(R.shape)


class _NewtonDirections:
    """The Newton steps of one solve: `_newton_step` with the preconditioner kept between steps
    (rebuilt when GMRES needs more than twice the iterations of its first use) and the GMRES
    iterations counted."""

    def __init__(self, col: Collocation, linear: str) -> None:
        self.col, self.linear = col, linear
        self.inv = None
        self.first_krylov = self.krylov_iterations = 0

    def __call__(self, X: np.ndarray, R: np.ndarray) -> np.ndarray:
        blocks = self.col.jacobian_blocks(X)
        step, krylov, self.inv = _newton_step(self.col, blocks, R, self.linear, self.inv)
        self.krylov_iterations += krylov
        if krylov > 2 * max(self.first_krylov, 5):
            self.inv = None  # the preconditioner went stale: rebuild it at the next step
        self.first_krylov = self.first_krylov or krylov
        return step


def linear_guess(model: DiscreteModel, tau: np.ndarray) -> np.ndarray:
    """The linearised model's harmonic response: the start of Newton without a neighbouring
    orbit.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    tau : numpy.ndarray
        Instants (units of T), shape (m,).

    Returns
    -------
    numpy.ndarray
        Theta [rad] at tau, shape (m, n).
    """
    w = model.dl.omega
    out = np.zeros((np.size(tau), model.n))
    for k, amp in linear_forced_response(model).items():
        out += np.real(amp[None, :] * np.exp(1j * (k * w) * tau)[:, None])
    return out


def solve_periodic(
    model: DiscreteModel,
    M: int = 33,
    guess: np.ndarray | None = None,
    rtol: float = 1e-10,
    maxiter: int = 40,
    linear: str = "auto",
) -> PeriodicResult:
    """The periodic orbit of `model` collocated at M instants, by Newton.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive (the orbit has the drive's period).
    M : int
        Collocation instants, odd.
    guess : numpy.ndarray or None
        Start (M, n); None: the linearised response (`linear_guess`).
    rtol : float
        Newton's relative step tolerance.
    maxiter : int
        Most Newton steps.
    linear : str
        How the Newton systems are solved: "dense" (LU of the (M n)^2 Jacobian), "krylov"
        (GMRES, matrix-free, preconditioned by the time-averaged Jacobian) or "auto" (dense
        when M n is small).

    Returns
    -------
    PeriodicResult
        The orbit at the M instants, its rates, whether Newton converged and the harmonic tail.

    Raises
    ------
    ValueError
        For another `linear`.
    """
    if linear not in LINEAR_SOLVERS:
        raise ValueError(f"linear must be one of {LINEAR_SOLVERS}, got {linear!r}")
    col = Collocation(model, M)
    X = linear_guess(model, col.tau) if guess is None else np.array(guess, dtype=float)
    directions = _NewtonDirections(col, linear)
    res = newton(col.residual, directions, X, rtol, maxiter, contraction=True)
    message = "singular collocation Jacobian" if res.message == "singular Jacobian" else res.message
    return PeriodicResult(
        tau=col.tau,
        theta=res.x.copy(),
        theta_t=col.D @ res.x,
        converged=res.converged,
        iterations=res.iterations,
        krylov_iterations=directions.krylov_iterations,
        residual=res.norm,
        harmonic_tail=harmonic_tail(res.x),
        M=M,
        message=message,
    )


#: Newton steps of a refinement (2 M - 1 instants from the interpolant of a converged orbit on
#: M): one from an orbit M resolves meets its tolerance in 2-7 (measured on five sweep lines and
#: 25 scenes alone near resonances); one that has not by then started from an orbit that is no
#: coarse image of any (5 rad/s, 6.85 Hz, N = 40: the linear guess's orbit on 17 instants,
#: harmonic tail 8.6e-2, whose refinement crawls 23 steps and fails)
REFINE_MAXITER = 12


def refined(model: DiscreteModel, res: PeriodicResult, rtol: float = 1e-10) -> PeriodicResult:
    """The orbit solved again on 2M - 1 instants, from its trigonometric interpolant, in at most
    REFINE_MAXITER Newton steps.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    res : PeriodicResult
        The orbit on M instants.
    rtol : float
        Newton's relative step tolerance.

    Returns
    -------
    PeriodicResult
        The orbit on 2M - 1 instants.
    """
    M = 2 * res.M - 1
    guess = trig_interpolate(res.theta, M)
    return solve_periodic(model, M, guess=guess, rtol=rtol, maxiter=REFINE_MAXITER)


def _amplitude_continuation(model: DiscreteModel, M: int, rtol: float, steps: int = 6):
    """Follow the orbit from a small drive amplitude up to the real one (large responses)."""
    dl = model.dl
    X = None
    for k in range(1, steps + 1):
        scaled = model.at(dl.scaled_drive(k / steps))
        res = solve_periodic(scaled, M, guess=X, rtol=rtol)
        if not res.converged:
            return None
        X = res.theta
    res.message += f" (amplitude continuation in {steps} steps)"
    return res


#: where a scene's own start and the amplitude continuation fail (next to a resonance peak),
#: its orbit is reached as an upward sweep reaches it: solved at the first of these fractions
#: of its drive frequency and continued through the others to its own ...
FREQUENCY_PATH = (0.9, 0.95, 0.98)
#: ... and where that branch ends at a fold short of f_d (past the end of the lower branch of
#: a resonance curve bent to lower frequencies, where the resonant orbit is the only one), as
#: a downward sweep reaches it
FREQUENCY_PATH_ABOVE = (1.1, 1.05, 1.02)


def _frequency_continuation(
    model: DiscreteModel,
    M0: int,
    tail_tol: float,
    M_max: int,
    rtol: float,
    path: tuple[float, ...],
) -> PeriodicResult | None:
    """The orbit continued in the drive frequency along `path` (fractions of f_d, each step
    `solve_periodic_adaptive` from the previous orbit, as a sweep's points); None where a step
    does not converge."""
    dl = model.dl
    seed = None
    for fraction in (*path, 1.0):
        at = model if fraction == 1.0 else model.at(replace(dl, omega=fraction * dl.omega))
        res = solve_periodic_adaptive(at, M0, tail_tol, M_max, rtol, guess=seed, by_frequency=False)
        if not res.converged:
            return None
        seed = Neighbour(res.theta, at.dl.omega)
    res.message += f" (continued in the frequency from {path[0]:g} f_d)"
    return res


#: the frequency substeps of `continued`: the step from the neighbour is halved, at most this
#: many times (down to 1/16 of it), while Newton fails
SUBSTEP_HALVINGS = 4
#: Newton steps a substep may take before it counts as failed (from a near orbit Newton meets
#: its tolerance in 3-6)
SUBSTEP_MAXITER = 12
#: Newton steps of the start from the neighbour on its own number of instants: near a fold the
#: damped Newton crawls (10 rad/s, 7.54 Hz, N = 20 from 7.17 Hz: 54 steps, 0.45 s), still far
#: cheaper than the time stepping that replaces a failed orbit
NEIGHBOUR_MAXITER = 60


def continued(model: DiscreteModel, seed: Neighbour, M0: int, rtol: float) -> PeriodicResult | None:
    """The orbit of `model` continued from a neighbouring scene's, at M0 instants where it is
    found there.

    Newton starts from the neighbour's orbit at M0 instants, then at the neighbour's own
    number when that is larger; where neither converges, the frequency is approached from the
    neighbour's in substeps, halved while Newton fails (`SUBSTEP_HALVINGS`).  A fold of the
    branch between the two frequencies stops all of them: the orbit followed does not reach
    this frequency.

    Parameters
    ----------
    model : DiscreteModel
        The model at the frequency wanted.
    seed : Neighbour
        The neighbour's orbit.
    M0 : int
        First number of instants (odd).
    rtol : float
        Newton's relative step tolerance.

    Returns
    -------
    PeriodicResult or None
        The orbit Newton converged to; None when it converged nowhere.
    """
    omega = model.dl.omega
    res = solve_periodic(model, M0, guess=seed.at(M0), rtol=rtol)
    if res.converged:
        return res
    M = max(M0, seed.M)
    if M > M0:
        res = solve_periodic(model, M, guess=seed.at(M), rtol=rtol, maxiter=NEIGHBOUR_MAXITER)
        if res.converged:
            return res
    X, w = seed.at(M), seed.omega
    step = (omega - w) / 2.0
    for _ in range(SUBSTEP_HALVINGS):
        while abs(omega - w) > 1e-12 * abs(omega):
            target = omega if abs(step) >= abs(omega - w) else w + step
            at = model if target == omega else model.at(replace(model.dl, omega=target))
            res = solve_periodic(at, M, guess=X, rtol=rtol, maxiter=SUBSTEP_MAXITER)
            if not res.converged:
                break
            X, w = res.theta, target
            if target == omega:
                return res
        step /= 2.0
    return None


def _on(model: DiscreteModel, res: PeriodicResult, M0: int, rtol: float) -> PeriodicResult:
    """The orbit `res` solved again on M0 instants from its interpolant; `res` itself where
    Newton does not converge there (M0 does not resolve it)."""
    if res.M == M0:
        return res
    coarse = solve_periodic(model, M0, guess=trig_interpolate(res.theta, M0), rtol=rtol)
    return coarse if coarse.converged else res


def solve_periodic_adaptive(
    model: DiscreteModel,
    M0: int = 17,
    tail_tol: float = 1e-5,
    M_max: int = 129,
    rtol: float = 1e-10,
    guess: np.ndarray | Neighbour | None = None,
    by_frequency: bool = True,
) -> PeriodicResult:
    """`solve_periodic` with M refined (2M - 1) until the harmonic tail is below `tail_tol`.

    M starts at M0 whatever the guess: an orbit continued on more instants is solved again on
    M0 from its interpolant (`_on`), so that the sizes taken are those a solve without a guess
    takes and a sweep's orbits are the scenes' own; where the refinement from M0 fails (near a
    fold), the continued orbit stands.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    M0 : int
        First number of instants (made odd).
    tail_tol : float
        Harmonic tail to reach.
    M_max : int
        Finest M.
    rtol : float
        Newton's relative step tolerance.
    guess : numpy.ndarray, Neighbour or None
        An orbit (M', n) of a neighbouring scene, or a `Neighbour`: continuation
        (`continued`); where no continued orbit converges and refines, the scene is solved
        as without a guess: from the linear guess, then by continuation in the amplitude,
        then in the frequency from below (`FREQUENCY_PATH`), then from above
        (`FREQUENCY_PATH_ABOVE`).
    by_frequency : bool
        Whether a scene solved alone may be reached by continuation in the frequency (False
        on the path of that continuation itself).

    Returns
    -------
    PeriodicResult
        The last orbit; its message says when the tail stayed above `tail_tol` at M_max.
    """
    M = M0 if M0 % 2 else M0 + 1
    seed = as_neighbour(guess, model.dl.omega)
    res = continued(model, seed, M, rtol) if seed is not None else None
    resolved = None  # a continued orbit on more instants than M, kept in case M cannot refine
    if res is not None and res.M != M:
        resolved, res = res, _on(model, res, M, rtol)
    alone = res is None
    if alone:
        res = solve_periodic(model, M, rtol=rtol)
    if not res.converged:
        res = _amplitude_continuation(model, M, rtol) or res
    while res.converged and res.harmonic_tail > tail_tol and 2 * res.M - 1 <= M_max:
        finer = refined(model, res, rtol)
        if not finer.converged and resolved is not None and resolved.M > res.M:
            # near a fold the orbit landed on M0 is too coarse to refine from: keep the one the
            # neighbour's instants resolved (10 rad/s, 7.54 Hz, N = 20: M = 65, tail 2.8e-4)
            finer, resolved = resolved, None
        res = finer
    if not res.converged and not alone:  # the continued orbit did not refine: solve alone
        return solve_periodic_adaptive(model, M0, tail_tol, M_max, rtol, by_frequency=by_frequency)
    if not res.converged and alone and by_frequency:  # next to a resonance peak
        for path in (FREQUENCY_PATH, FREQUENCY_PATH_ABOVE):
            reached = _frequency_continuation(model, M0, tail_tol, M_max, rtol, path)
            if reached is not None:
                res = reached
                break
    if res.converged and res.harmonic_tail > tail_tol:
        res.message += f"; harmonic tail {res.harmonic_tail:.2g} > {tail_tol:g} at M={res.M}"
    return res
