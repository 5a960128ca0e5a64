"""Quasi-static response: static equilibrium under the instantaneous loads (time derivatives
zero), by Newton with the exact Jacobian of the model's static equations."""

from __future__ import annotations

from dataclasses import dataclass
from itertools import pairwise

import numpy as np

from ..model.base import DiscreteModel
from ..model.rows import matvec_rows
from .newton import newton, step_converged


class QuasiStaticError(RuntimeError):
    """Newton did not converge, even with load bisection; the message says where."""


@dataclass
class StaticResult:
    """One static equilibrium: the angles and how Newton got there."""

    theta: np.ndarray  #: angles [rad], shape (n,)
    converged: bool
    iterations: int  #: Newton steps (of the last solve)
    residual: float  #: max |residual| (dimensionless torques)
    message: str


def _newton(model: DiscreteModel, lam, lam_dot, theta, rtol, maxiter) -> StaticResult:
    lam_, lam_dot_ = [lam], [lam_dot]

    def residual(th: np.ndarray) -> np.ndarray:
        return model.static_rows(th[None], lam_, lam_dot_)[0]

    def direction(th: np.ndarray, r: np.ndarray) -> np.ndarray:
        return np.linalg.solve(model.static_rows(th[None], lam_, lam_dot_, True)[1][0], -r)

    res = newton(residual, direction, theta, rtol, maxiter)
    return StaticResult(res.x, res.converged, res.iterations, res.norm, res.message)


def solve_static(
    model: DiscreteModel,
    lam: float,
    lam_dot: float,
    theta0: np.ndarray | None = None,
    rtol: float = 1e-11,
    maxiter: int = 30,
) -> StaticResult:
    """The static equilibrium under constant loads, by Newton; with a load ramp if it stalls.

    Where Newton from `theta0` does not converge, the loads are ramped from zero (lam by
    sqrt(t), lam_dot by t) in 4, 16, ... 4096 steps, each from the last equilibrium.

    Parameters
    ----------
    model : DiscreteModel
        The model (its static equations and effects).
    lam : float
        Dimensionless angular velocity Omega T.
    lam_dot : float
        Its rate d lam / d tau (the Euler load).
    theta0 : numpy.ndarray or None
        Start, shape (n,); None: the straight beam.
    rtol : float
        Newton's relative step tolerance.
    maxiter : int
        Most Newton steps of one solve.

    Returns
    -------
    StaticResult
        The angles and whether (and how) Newton converged.
    """
    guess = np.zeros(model.n) if theta0 is None else np.array(theta0, dtype=float)
    res = _newton(model, lam, lam_dot, guess, rtol, maxiter)
    if res.converged:
        return res
    # continuation from the previous guess' loads is unknown here: ramp the loads from zero
    theta = np.zeros(model.n)
    steps = 4
    while steps <= 4096:
        ok = True
        theta = np.zeros(model.n)
        for k in range(1, steps + 1):
            t = k / steps
            sub = _newton(model, lam * np.sqrt(t), lam_dot * t, theta, rtol, maxiter)
            if not sub.converged:
                ok = False
                break
            theta = sub.theta
        if ok:
            return StaticResult(theta, True, sub.iterations, sub.residual, f"ramped in {steps}")
        steps *= 4
    return StaticResult(theta, False, maxiter, res.residual, "no convergence after load ramp")


#: chord Newton (one Jacobian) in `batched_static` while all angles stay below this (rad)
CHORD_MAX_ANGLE = 0.1

#: the chord with one Jacobian for all instants stops once a step shrinks by less than this
#: factor (then each instant gets its own Jacobian)
CHORD_CONTRACTION = 0.5

#: the chord's iterates are mixed with this many earlier ones (Anderson acceleration, each
#: instant its own weights): 6-8 residuals of all instants instead of 8-14 (docs/numerics.md)
ANDERSON_DEPTH = 2


def anderson_mix(history: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """The next iterate of a fixed-point iteration x -> g(x) = x + f(x) from its last ones,
    at many independent instants at once (Anderson acceleration, type II).

    With d = len(history) - 1 differences dF_i = f_(i+1) - f_i and dG_i = g_(i+1) - g_i, each
    instant takes gamma minimising |f_last - sum gamma_i dF_i| (its d x d normal equations,
    regularised by 1e-12 of their trace) and returns g_last - sum gamma_i dG_i.  On a linear
    contraction this is GMRES on the iteration's residual (Walker and Ni, SIAM J. Numer. Anal.
    49, 2011): the chord's error components that contract slowest are removed first.

    Parameters
    ----------
    history : list of tuple of numpy.ndarray
        (g(x_k), f(x_k)) of the last iterations, oldest first, each of shape (m, n).

    Returns
    -------
    numpy.ndarray
        The mixed iterate, shape (m, n); g of the last iteration where there is no earlier one
        or an instant's normal equations are singular.
    """
    g_last, f_last = history[-1]
    if len(history) < 2:
        return g_last
    dG = [newer[0] - older[0] for older, newer in pairwise(history)]
    dF = [newer[1] - older[1] for older, newer in pairwise(history)]
    d = len(dF)
    gram, rhs = np.empty((f_last.shape[0], d, d)), np.empty((f_last.shape[0], d))
    for i in range(d):  # row by row: a third less time than einsum over the stacked arrays
        rhs[:, i] = np.einsum("mn,mn->m", dF[i], f_last)
        for j in range(i, d):
            gram[:, i, j] = gram[:, j, i] = np.einsum("mn,mn->m", dF[i], dF[j])
    gram += (1e-12 * np.trace(gram, axis1=1, axis2=2) + 1e-300)[:, None, None] * np.eye(d)
    try:
        gamma = np.linalg.solve(gram, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError:
        return g_last
    mixed = g_last.copy()
    with np.errstate(invalid="ignore", over="ignore"):
        for i in range(d):
            mixed -= gamma[:, i, None] * dG[i]
    return mixed if np.all(np.isfinite(mixed)) else g_last


def shared_chord(
    model: DiscreteModel,
    lam: np.ndarray,
    lam_dot: np.ndarray,
    rtol: float = 1e-11,
    maxiter: int = 30,
) -> tuple[np.ndarray, bool]:
    """Static equilibria at many (lam, lam_dot) by chord iterations with one Jacobian for all:
    the straight beam's at the root mean square of lam and no angular acceleration, one LU.

    The instants' Jacobians differ from it by the load's variation over the drive and, at
    second order, by the angles; where that is small (all but the largest responses) the
    iterations contract by 10-20x a step, and each costs one residual of all instants and one
    triangular solve instead of m Jacobians.  Each iterate is mixed with the ANDERSON_DEPTH
    before it (`anderson_mix`).

    Parameters
    ----------
    model : DiscreteModel
        The model.
    lam, lam_dot : numpy.ndarray
        Dimensionless angular velocity and its rate at each instant, shape (m,).
    rtol : float
        Relative step tolerance, met by every instant.
    maxiter : int
        Most iterations.

    Returns
    -------
    theta : numpy.ndarray
        The last iterate, shape (m, n).
    converged : bool
        Whether every instant met rtol; False as soon as a step shrinks by less than
        CHORD_CONTRACTION (the Jacobian is too far off) or an iterate is not finite.
    """
    import scipy.linalg as sla

    theta = np.zeros((lam.size, model.n))
    lam_rms = float(np.sqrt(np.mean(np.square(lam))))
    J = model.static_rows(np.zeros((1, model.n)), [lam_rms], [0.0], jacobian=True)[1][0]
    try:
        lu = sla.lu_factor(J, check_finite=True)
    except (ValueError, np.linalg.LinAlgError):
        return theta, False
    previous = np.inf
    history: list[tuple[np.ndarray, np.ndarray]] = []
    for _ in range(maxiter):
        r = model.static_rows(theta, lam, lam_dot)
        step = -sla.lu_solve(lu, r.T, check_finite=False).T
        theta = theta + step
        size = float(np.max(np.abs(step)))
        if not np.all(np.isfinite(theta)) or size > CHORD_CONTRACTION * previous:
            return theta, False
        previous = size
        if step_converged(step, theta, rtol, axis=-1):
            return theta, True
        history = [*history, (theta, step)][-(ANDERSON_DEPTH + 1) :]
        theta = anderson_mix(history)
    return theta, False


def batched_static(
    model: DiscreteModel,
    lam: np.ndarray,
    lam_dot: np.ndarray,
    rtol: float = 1e-11,
    maxiter: int = 12,
) -> np.ndarray | None:
    """Static equilibria at many (lam, lam_dot) at once: Newton from the straight beam, all
    instants in one batched solve.  The same residual and Jacobian as `solve_static`
    (vectorised).

    First the chord with one Jacobian for all instants (`shared_chord`); where it does not
    contract, Newton with each instant's own Jacobian from where it stopped.  While every
    angle stays below CHORD_MAX_ANGLE that Jacobian is kept (chord Newton): it changes only at
    second order in Theta (1 % at 0.1 rad), so the iterations contract almost as fast as
    Newton's and skip most of the cost, the assembly and inversion of the m Jacobians.  Larger
    angles get plain Newton.

    Parameters
    ----------
    model : DiscreteModel
        The model.
    lam : numpy.ndarray
        Dimensionless angular velocity Omega T at each instant, shape (m,).
    lam_dot : numpy.ndarray
        Its rate d lam / d tau, shape (m,).
    rtol : float
        Newton's relative step tolerance, met by every instant.
    maxiter : int
        Most Newton steps after the shared chord.

    Returns
    -------
    numpy.ndarray or None
        Angles [rad], shape (m, n); None unless every instant converges (callers then take the
        robust path) or when a Jacobian is singular or an iterate not finite.
    """
    theta, converged = shared_chord(model, lam, lam_dot, rtol)
    if converged:
        return theta
    if not np.all(np.isfinite(theta)):
        theta = np.zeros((lam.size, model.n))

    def residual(th: np.ndarray) -> np.ndarray:
        return model.static_rows(th, lam, lam_dot)

    res = newton(residual, _BatchedDirections(model, lam, lam_dot), theta, rtol, maxiter,
                 damped=False, axis=-1)  # fmt: skip
    return res.x if res.converged else None


class _BatchedDirections:
    """The Newton steps of `batched_static`: each instant's own Jacobian, inverted at once;
    kept (chord Newton) while every angle stays below CHORD_MAX_ANGLE, fresh at every step
    above."""

    def __init__(self, model: DiscreteModel, lam: np.ndarray, lam_dot: np.ndarray) -> None:
        self.model, self.lam, self.lam_dot = model, lam, lam_dot
        self.inverse = None

    def __call__(self, theta: np.ndarray, r: np.ndarray) -> np.ndarray:
        if self.inverse is None or float(np.max(np.abs(theta))) > CHORD_MAX_ANGLE:
            J = self.model.static_rows(theta, self.lam, self.lam_dot, jacobian=True)[1]
            self.inverse = np.linalg.inv(J)
        return -matvec_rows(self.inverse, r)


def quasistatic_series(model: DiscreteModel, taus: np.ndarray, rtol: float = 1e-11) -> np.ndarray:
    """Theta(tau) of the quasi-static response at the instants `taus`.

    First all instants at once (`batched_static`); if any instant does not converge, the
    robust path: continuation in time, each instant starting Newton from the previous solution,
    a failed instant approached by bisecting the time step (`_bisected`).

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    taus : numpy.ndarray
        Instants [units of T], shape (m,).
    rtol : float
        Newton's relative step tolerance.

    Returns
    -------
    numpy.ndarray
        Angles, shape (m, n).

    Raises
    ------
    QuasiStaticError
        Where an instant has no equilibrium that Newton reaches.
    """
    taus = np.asarray(taus, dtype=float)
    lam, lam_dot = model.drive_rows(taus)
    if taus.size:
        fast = batched_static(model, lam, lam_dot, rtol)
        if fast is not None:
            return fast
    out = np.empty((taus.size, model.n))
    theta = None
    tau_prev = None
    for j, tau in enumerate(taus):
        res = solve_static(model, lam[j], lam_dot[j], theta, rtol)
        if not res.converged and tau_prev is not None:
            res = _bisected(model, tau_prev, tau, theta, rtol) or res
        if not res.converged:
            raise QuasiStaticError(
                f"quasi-static Newton did not converge at tau={tau:.6g} "
                f"(lam={lam[j]:.6g}, lam_dot={lam_dot[j]:.6g}): {res.message}"
            )
        theta, tau_prev = res.theta, tau
        out[j] = theta
    return out


def _bisected(
    model: DiscreteModel, tau_prev: float, tau: float, theta: np.ndarray, rtol: float
) -> StaticResult | None:
    """The equilibrium at `tau` reached from the one at `tau_prev` in 64 small steps (None if a
    step fails)."""
    dl = model.dl
    for k in range(1, 65):
        tk = tau_prev + (tau - tau_prev) * k / 64
        sub = solve_static(model, dl.lam(tk), dl.lam_dot(tk), theta, rtol)
        if not sub.converged:
            return None
        theta = sub.theta
    return StaticResult(theta, True, 0, 0.0, "bisected")
