r"""Branches of periodic orbits through folds: pseudo-arclength continuation in a parameter p.

Generic over a `BranchProblem` (a residual R(x, p) of collocated periodic orbits, its Jacobian
and the orbit's Floquet multipliers): `FirstOrderProblem` is one for any first-order ODE (the
Duffing oscillator in the tests), `rotbeam.solve.beam_branch` the beam's.  `continue_branch`
follows an orbit by Keller's method and marks the folds, period doublings and tori it passes.
Method: docs/stability.md, "Branches in f_d".
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla

from ..model.base import Residual
from .floquet import FloquetResult, orbit_floquet
from .newton import newton as solve_newton
from .periodic import SpectralCollocation


class BranchProblem:
    """What continuation needs of a family of periodic orbits: the collocation residual, its
    Jacobian and the orbit's Floquet multipliers, at a parameter p.  Subclasses implement
    `residual`, `jacobian` and `floquet`; `dR_dp` is a central difference."""

    def residual(self, x: np.ndarray, p: float) -> np.ndarray:
        """The collocation residual R(x, p), zero on a periodic orbit.

        Parameters
        ----------
        x : numpy.ndarray
            The collocation unknowns, flattened, shape (dim x,).
        p : float
            The parameter.

        Returns
        -------
        numpy.ndarray
            R, shape (dim x,).
        """
        raise NotImplementedError

    def jacobian(self, x: np.ndarray, p: float) -> np.ndarray:
        """The dense Jacobian dR/dx.

        Parameters
        ----------
        x : numpy.ndarray
            The collocation unknowns, shape (dim x,).
        p : float
            The parameter.

        Returns
        -------
        numpy.ndarray
            dR/dx, shape (dim x, dim x).
        """
        raise NotImplementedError

    def floquet(self, x: np.ndarray, p: float) -> FloquetResult:
        """The Floquet multipliers of the orbit x.

        Parameters
        ----------
        x : numpy.ndarray
            The collocation unknowns, shape (dim x,).
        p : float
            The parameter.

        Returns
        -------
        FloquetResult
            Its multipliers (`rotbeam.solve.floquet`).
        """
        raise NotImplementedError

    def dR_dp(self, x: np.ndarray, p: float) -> np.ndarray:
        """dR/dp by a central difference of step 1e-6 max(|p|, 1) (the residual is smooth in p).

        Parameters
        ----------
        x : numpy.ndarray
            The collocation unknowns, shape (dim x,).
        p : float
            The parameter.

        Returns
        -------
        numpy.ndarray
            dR/dp, shape (dim x,).
        """
        h = 1e-6 * max(abs(p), 1.0)
        return (self.residual(x, p + h) - self.residual(x, p - h)) / (2.0 * h)


class FirstOrderRows(Residual):
    """The rows R_j = z'_j - f(t_j, z_j; p) of a first-order system at the instants t_j, as a
    second-order residual with no mass: dR/dz = -J_j, dR/dz' = I, dR/dz'' = 0."""

    def __init__(self, problem: FirstOrderProblem, t: np.ndarray, Z: np.ndarray, Z_t: np.ndarray,
                 p: float) -> None:  # fmt: skip
        self.problem, self.t, self.Z, self.Z_t, self.p = problem, t, Z, Z_t, p

    @property
    def R(self) -> np.ndarray:
        """z' - f(t_j, z_j; p), shape (M, dim): evaluated where it is read (a Jacobian needs
        only the blocks)."""
        pr = self.problem
        F = np.array([pr.rhs(tj, zj, self.p) for tj, zj in zip(self.t, self.Z, strict=True)])
        return self.Z_t - F

    def mass(self) -> np.ndarray:
        """dR/dz'' = 0 at each instant.

        Returns
        -------
        numpy.ndarray
            Zeros, shape (M, dim, dim).
        """
        m, dim = self.Z.shape
        return np.zeros((m, dim, dim))

    def blocks(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """dR/dz = -J_j, dR/dz' = I and dR/dz'' = 0 at each instant.

        Returns
        -------
        dR_dz, dR_dz_t, mass : numpy.ndarray
            Shape (M, dim, dim) each.
        """
        pr = self.problem
        J = np.array([pr.jac(tj, zj, self.p) for tj, zj in zip(self.t, self.Z, strict=True)])
        m, dim = self.Z.shape
        return -J, np.broadcast_to(np.eye(dim), (m, dim, dim)), self.mass()

    def accelerate(self, theta_tt: np.ndarray) -> None:
        """Nothing moves: a first-order residual does not depend on z''.

        Parameters
        ----------
        theta_tt : numpy.ndarray
            Second derivatives, shape (M, dim) (unused).
        """


class FirstOrderProblem(BranchProblem):
    """Trigonometric collocation of z' = f(t, z; p) on M instants of the period P(p):
    R = D Z - f(t_j, Z_j; p), with dR/dZ = D (x) I - blockdiag(J_j) (`SpectralCollocation`
    of `FirstOrderRows`).

    The unknowns x are Z, the states at t_j = j P(p) / M, shape (M, dim), flattened.

    Parameters
    ----------
    rhs : callable
        rhs(t, z, p) -> f, shape (dim,).
    jac : callable
        jac(t, z, p) -> df/dz, shape (dim, dim).
    period : callable
        period(p) -> P, the orbit's period.
    dim : int
        Dimension of the state.
    M : int
        Collocation instants (odd).
    """

    def __init__(
        self,
        rhs: Callable[[float, np.ndarray, float], np.ndarray],
        jac: Callable[[float, np.ndarray, float], np.ndarray],
        period: Callable[[float], float],
        dim: int,
        M: int = 33,
    ) -> None:
        self.rhs, self.jac, self.period, self.dim, self.M = rhs, jac, period, dim, M
        self._last: tuple[float, SpectralCollocation] | None = None  # the last p's collocation

    def collocation(self, p: float) -> SpectralCollocation:
        """The collocation problem at the parameter p (its period P(p)); the last one is kept
        (the residual and the Jacobian at one point share it).

        Parameters
        ----------
        p : float
            The parameter.

        Returns
        -------
        SpectralCollocation
            Of the rows `FirstOrderRows` at M instants of P(p).
        """
        if self._last is not None and self._last[0] == p:
            return self._last[1]
        P = self.period(p)
        col = SpectralCollocation(lambda Z, Z_t, _: FirstOrderRows(self, col.tau, Z, Z_t, p), P,
                                  self.M)  # fmt: skip
        self._last = (p, col)
        return col

    def residual(self, x: np.ndarray, p: float) -> np.ndarray:
        """The collocation residual D Z - f(t_j, Z_j; p).

        Parameters
        ----------
        x : numpy.ndarray
            Z flattened, shape (M dim,).
        p : float
            The parameter.

        Returns
        -------
        numpy.ndarray
            R, shape (M dim,).
        """
        return self.collocation(p).residual(x.reshape(self.M, self.dim)).ravel()

    def jacobian(self, x: np.ndarray, p: float) -> np.ndarray:
        """dR/dZ = D (x) I - blockdiag(J_j), dense.

        Parameters
        ----------
        x : numpy.ndarray
            Z flattened, shape (M dim,).
        p : float
            The parameter.

        Returns
        -------
        numpy.ndarray
            Shape (M dim, M dim).
        """
        col = self.collocation(p)
        return col.dense_jacobian(col.jacobian_blocks(x.reshape(self.M, self.dim)))

    def floquet(self, x: np.ndarray, p: float) -> FloquetResult:
        """The Floquet multipliers of the orbit Z (`rotbeam.solve.floquet.orbit_floquet`).

        Parameters
        ----------
        x : numpy.ndarray
            Z flattened, shape (M dim,).
        p : float
            The parameter.

        Returns
        -------
        FloquetResult
            The multipliers (no defect: the right-hand side is not passed).
        """
        return orbit_floquet(
            lambda t, z: self.jac(t, z, p), x.reshape(self.M, self.dim), self.period(p)
        )

    def samples(self, z0_of_t: Callable[[np.ndarray], np.ndarray], p: float) -> np.ndarray:
        """The unknowns x of an orbit given as a function of time (e.g. a time-stepped orbit's
        dense output): a start for `continue_branch`.

        Parameters
        ----------
        z0_of_t : callable
            z0_of_t(t) for the instants t, shape (M,) -> the states, M dim values in all
            (reshaped to (M, dim)).
        p : float
            The parameter (it sets the period and so the instants).

        Returns
        -------
        numpy.ndarray
            x, shape (M dim,).
        """
        t = np.arange(self.M) * self.period(p) / self.M
        return np.asarray(z0_of_t(t)).reshape(self.M, self.dim).ravel()


def newton(
    problem: BranchProblem, x: np.ndarray, p: float, tol: float = 1e-10, maxiter: int = 30
) -> tuple[np.ndarray, bool]:
    """Newton on R(x, p) = 0 at fixed p, with dense solves and full steps: the first orbit of a
    branch (`rotbeam.solve.newton.newton`, undamped, the step against tol max(1, |x|)).

    Parameters
    ----------
    problem : BranchProblem
        The residual and its Jacobian.
    x : numpy.ndarray
        The start, shape (dim x,).
    p : float
        The parameter.
    tol : float
        Converged when the step is at most tol max(1, max |x|).
    maxiter : int
        Most Newton steps.

    Returns
    -------
    x : numpy.ndarray
        The last iterate.
    converged : bool
        Whether the step fell below the tolerance.
    """
    res = solve_newton(
        lambda z: problem.residual(z, p),
        lambda z, r: sla.solve(problem.jacobian(z, p), -r),
        x,
        tol,
        maxiter,
        damped=False,
        floor=1.0,
    )
    return res.x, res.converged


@dataclass
class BranchPoint:
    """One orbit on a branch, with its multipliers and the direction the branch takes in p."""

    p: float  #: the parameter
    x: np.ndarray  #: the orbit's collocation unknowns, flattened
    floquet: FloquetResult  #: its multipliers
    tangent_p: float  #: dp/ds

    @property
    def stable(self) -> bool:
        """Whether the orbit attracts (`FloquetResult.stable`)."""
        return self.floquet.stable


@dataclass
class Bifurcation:
    """A bifurcation detected between two consecutive points of a branch."""

    kind: str  #: "fold", "period doubling" or "torus"
    p: float  #: estimated parameter value
    index: int  #: branch point just after it


@dataclass
class Branch:
    """A continued branch: its points in the order followed, the bifurcations detected between
    them, and why the continuation stopped."""

    points: list[BranchPoint] = field(default_factory=list)
    bifurcations: list[Bifurcation] = field(default_factory=list)
    message: str = ""  #: why the continuation stopped

    def folds(self) -> list[float]:
        """The folds of the branch.

        Returns
        -------
        list of float
            The estimated p of every fold, in the order passed.
        """
        return [b.p for b in self.bifurcations if b.kind == "fold"]

    def first_unstable(self) -> int | None:
        """Index of the first point that is not stable (None: every point is)."""
        return next((k for k, pt in enumerate(self.points) if not pt.stable), None)

    def stable_start(self) -> list:
        """The points before the first one that is not stable (all of them if every one is)."""
        first = self.first_unstable()
        return self.points if first is None else self.points[:first]


def _counts(fl: FloquetResult) -> tuple[int, int]:
    """(real multipliers below -1, complex ones outside the unit circle)."""
    mu = fl.multipliers
    real = np.abs(mu.imag) <= 1e-7 * np.maximum(np.abs(mu), 1e-300)
    outside = np.abs(mu) > 1.0
    return int(np.sum(real & outside & (mu.real < 0))), int(np.sum(~real & outside))


def _tangent(problem: BranchProblem, x, p, prev: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Unit (weighted) tangent of the branch at (x, p), oriented along `prev`."""
    A = np.vstack([np.column_stack([problem.jacobian(x, p), problem.dR_dp(x, p)]), prev * w * w])
    rhs = np.zeros(A.shape[0])
    rhs[-1] = 1.0
    t = sla.solve(A, rhs)
    t /= np.linalg.norm(t * w)
    return t if np.dot(t * w * w, prev) >= 0 else -t


def _correct(problem: BranchProblem, y_pred, t, w, tol: float, maxiter: int = 8):
    """Newton on [R(y); t.W^2 (y - y_pred)] = 0 with full steps and the weighted step test
    max |w dy| <= tol (`rotbeam.solve.newton.newton`); returns (y, iterations) or
    (None, maxiter).  A corrector that wanders out of the problem's range (e.g. p <= 0, where
    the residual raises ValueError) has failed."""
    tw = t * w * w

    def residual(y: np.ndarray) -> np.ndarray:
        return np.append(problem.residual(y[:-1], y[-1]), np.dot(tw, y - y_pred))

    def direction(y: np.ndarray, G: np.ndarray) -> np.ndarray:
        x, p = y[:-1], y[-1]
        J = np.column_stack([problem.jacobian(x, p), problem.dR_dp(x, p)])
        return sla.solve(np.vstack([J, tw]), -G)

    res = solve_newton(residual, direction, y_pred.copy(), tol, maxiter, damped=False, weights=w)
    return (res.x, res.iterations) if res.converged else (None, maxiter)


def _most_negative(fl: FloquetResult) -> float:
    mu = fl.multipliers
    real = mu[(np.abs(mu.imag) <= 1e-7 * np.maximum(np.abs(mu), 1e-300)) & (mu.real < 0)]
    return float(np.min(real.real)) if real.size else 0.0


def _crossing_p(a: BranchPoint, b: BranchPoint) -> float:
    """p where the most negative real multiplier passes -1 (linear between a and b)."""
    ma, mb = _most_negative(a.floquet), _most_negative(b.floquet)
    if ma == mb or ma == 0.0 or mb == 0.0:
        return 0.5 * (a.p + b.p)
    return a.p + (-1.0 - ma) / (mb - ma) * (b.p - a.p)


def _fold_p(s: list[float], p: list[float]) -> float:
    """Vertex of the parabola through three (s, p) points (the fold's p)."""
    c = np.polyfit(np.asarray(s) - s[1], p, 2)
    if c[0] == 0.0:
        return p[1]
    sv = -c[1] / (2.0 * c[0])
    return float(np.polyval(c, sv))


def continue_branch(
    problem: BranchProblem,
    x0: np.ndarray,
    p0: float,
    p_range: tuple[float, float],
    ds: float,
    ds_max: float | None = None,
    max_points: int = 400,
    p_scale: float = 1.0,
    x_scale: float = 1.0,
    direction: float = 1.0,
    tol: float = 1e-9,
    on_point: Callable[[BranchPoint], None] | None = None,
    stop: Callable[[Branch], bool] | None = None,
) -> Branch:
    """Follow a periodic orbit in p by pseudo-arclength continuation, through folds.

    Keller's method with a weighted tangent; the step grows by 1.3 after a corrector that
    converged in at most 4 iterations and halves after a failure.  Folds, period doublings and
    tori are detected between consecutive points (docs/stability.md, "Branches in f_d").

    Parameters
    ----------
    problem : BranchProblem
        The family of orbits.
    x0 : numpy.ndarray
        An orbit at p0 or near it, shape (dim x,); Newton converges it first.
    p0 : float
        The parameter to start at.
    p_range : tuple of float
        The branch ends at the first point outside this interval (kept as the last point).
    ds : float
        First arclength step (weighted, see `x_scale`, `p_scale`).
    ds_max : float or None
        Largest step; None: 8 ds.
    max_points : int
        Most points on the branch, the first included.
    p_scale : float
        p enters the arclength divided by this.
    x_scale : float
        x enters it as x_scale times its RMS change (weights x_scale / sqrt(dim x)).
    direction : float
        Sign of the first step in p (> 0: increasing).
    tol : float
        Corrector tolerance on the weighted step (max-norm).
    on_point : callable or None
        on_point(point) after every new point.
    stop : callable or None
        stop(branch) after every new point: True ends the branch.

    Returns
    -------
    Branch
        The points with their multipliers and dp/ds, the bifurcations, and why it stopped
        (message; no points when Newton finds no orbit at p0).
    """
    branch = Branch()
    x, ok = newton(problem, np.asarray(x0, dtype=float), p0)
    if not ok:
        branch.message = f"no periodic orbit at p = {p0:g} from the given start"
        return branch
    w = np.append(np.full(x.size, x_scale / math.sqrt(x.size)), 1.0 / p_scale)
    prev = np.zeros(x.size + 1)
    prev[-1] = direction
    y = np.append(x, p0)
    t = _tangent(problem, x, p0, prev, w)
    ds_max = ds_max or 8.0 * ds
    arc = [0.0]
    branch.points.append(BranchPoint(p0, x, problem.floquet(x, p0), float(t[-1])))
    lo, hi = min(p_range), max(p_range)
    while len(branch.points) < max_points:
        y_new, iters = _correct(problem, y + ds * t, t, w, tol)
        if y_new is None:
            ds *= 0.5
            if ds < 1e-6 * ds_max:
                branch.message = f"step size collapsed at p = {y[-1]:.6g}"
                break
            continue
        t = _tangent(problem, y_new[:-1], y_new[-1], t, w)
        y = y_new
        arc.append(arc[-1] + ds)
        pt = BranchPoint(float(y[-1]), y[:-1].copy(), problem.floquet(y[:-1], y[-1]), float(t[-1]))
        branch.points.append(pt)
        if on_point is not None:
            on_point(pt)
        _detect(branch, arc)
        if not lo <= y[-1] <= hi:
            branch.message = f"left the range at p = {y[-1]:.6g}"
            break
        if stop is not None and stop(branch):
            branch.message = f"stopped as asked at p = {y[-1]:.6g}"
            break
        if iters <= 4:
            ds = min(ds * 1.3, ds_max)
    else:
        branch.message = f"stopped after {max_points} points"
    return branch


def _detect(branch: Branch, arc: list[float]) -> None:
    """Bifurcations between the last two points of the branch."""
    pts = branch.points
    if len(pts) < 2:
        return
    a, b = pts[-2], pts[-1]
    i = len(pts) - 1
    if a.tangent_p * b.tangent_p < 0.0:
        j = max(i - 1, 1)
        p = _fold_p(arc[j - 1 : j + 2], [q.p for q in pts[j - 1 : j + 2]]) if i >= 2 else b.p
        branch.bifurcations.append(Bifurcation("fold", p, i))
    (na, ca), (nb, cb) = _counts(a.floquet), _counts(b.floquet)
    if na != nb:
        branch.bifurcations.append(Bifurcation("period doubling", _crossing_p(a, b), i))
    if ca != cb:
        branch.bifurcations.append(Bifurcation("torus", 0.5 * (a.p + b.p), i))
