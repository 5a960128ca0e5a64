r"""The beam's `BranchProblem`: periodic orbits of the discrete elastica continued in f_d.

The unknowns are the collocated orbit Theta at M equispaced phases of the drive period (those of
`rotbeam.solve.periodic.Collocation`, whose residual and Jacobian it uses as they are), the
parameter is f_d in Hz with every other number of the scene fixed in physical units, and M
stays fixed along a branch.  `beam_branch` follows the orbit at one end of a frequency range.
Details: docs/stability.md, "Branches in f_d".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..model.base import DiscreteModel
from ..model.criterion import rms
from ..model.params import Dimensionless
from .collocated_floquet import resolved_multipliers
from .continuation import Branch, BranchProblem, continue_branch
from .floquet import FloquetResult
from .periodic import Collocation, solve_periodic_adaptive
from .spectral import trig_interpolate


@dataclass
class BeamBranchProblem(BranchProblem):
    """Collocated orbits of one model, parameter p = f_d [Hz]: every number of the scene but the
    drive frequency stays fixed in physical units.

    The unknowns x are Theta at the phases j / M of the drive period, shape (M, n) flattened
    (n = N - 1); the period, and with it the collocation instants and the Fourier matrix D,
    changes with f_d while the phases do not.
    """

    model: DiscreteModel  #: the model at any f_d (its drive's frequency is replaced by p)
    T: float  #: time scale of the beam [s]: omega = 2 pi p T
    M: int  #: collocation instants (odd), fixed along the branch
    _cols: dict = field(default_factory=dict, repr=False)

    def dimensionless(self, f_d: float) -> Dimensionless:
        """The scene at another drive frequency.

        Parameters
        ----------
        f_d : float
            Drive frequency [Hz].

        Returns
        -------
        Dimensionless
            The model's scene with omega = 2 pi f_d T.
        """
        return replace(self.model.dl, omega=2.0 * math.pi * float(f_d) * self.T)

    def collocation(self, f_d: float) -> Collocation:
        """The collocation problem at a drive frequency (the last four are kept: the residual,
        Jacobian and dR/dp at one point reuse them).

        Parameters
        ----------
        f_d : float
            Drive frequency [Hz].

        Returns
        -------
        Collocation
            M equispaced instants of the drive period, for the model at that frequency.
        """
        key = float(f_d)
        col = self._cols.get(key)
        if col is None:
            if len(self._cols) >= 4:
                self._cols.pop(next(iter(self._cols)))
            col = self._cols[key] = Collocation(self.model.at(self.dimensionless(key)), self.M)
        return col

    def _X(self, x: np.ndarray) -> np.ndarray:
        return np.asarray(x, dtype=float).reshape(self.M, self.model.n)

    def residual(self, x: np.ndarray, p: float) -> np.ndarray:
        """The collocation residual (`Collocation.residual`), flattened.

        Parameters
        ----------
        x : numpy.ndarray
            Theta [rad], shape (M n,).
        p : float
            Drive frequency f_d [Hz].

        Returns
        -------
        numpy.ndarray
            R, shape (M n,) (dimensionless torques).
        """
        return self.collocation(p).residual(self._X(x)).ravel()

    def jacobian(self, x: np.ndarray, p: float) -> np.ndarray:
        """The dense collocation Jacobian (`Collocation.dense_jacobian`).

        Parameters
        ----------
        x : numpy.ndarray
            Theta [rad], shape (M n,).
        p : float
            Drive frequency f_d [Hz].

        Returns
        -------
        numpy.ndarray
            dR/dx, shape (M n, M n).
        """
        col = self.collocation(p)
        return col.dense_jacobian(col.jacobian_blocks(self._X(x)))

    def floquet(self, x: np.ndarray, p: float) -> FloquetResult:
        """The Floquet multipliers of the orbit, |mu|max resolved to `Numerics.floquet_tol`
        (`rotbeam.solve.collocated_floquet.resolved_multipliers`: the Radau collocation's
        where they stand above the cluster, where the exponential ladder's 1012 steps can be
        5e-3 off on the large orbits past a fold; docs/stability.md, "Branches in f_d").

        Parameters
        ----------
        x : numpy.ndarray
            Theta [rad], shape (M n,).
        p : float
            Drive frequency f_d [Hz].

        Returns
        -------
        FloquetResult
            The multipliers (and the orbit's defect, where they come from the exponentials).
        """
        col = self.collocation(p)
        X = self._X(x)
        return resolved_multipliers(col.model, X, col.D @ X)

    def midspan(self, x: np.ndarray, p: float, samples: int = 64) -> np.ndarray:
        """The midspan deflection over one period, from the orbit's trigonometric interpolant.

        Parameters
        ----------
        x : numpy.ndarray
            Theta [rad], shape (M n,).
        p : float
            Drive frequency f_d [Hz].
        samples : int
            Equispaced instants of the period.

        Returns
        -------
        numpy.ndarray
            y_m / L at those instants, shape (samples,).
        """
        col = self.collocation(p)
        return np.atleast_1d(col.model.midspan(trig_interpolate(self._X(x), samples)))


@dataclass
class BeamBranch:
    """A continued branch of the beam with the quantities the figure and table need."""

    problem: BeamBranchProblem
    branch: Branch
    tail: float  #: harmonic tail of the start orbit (what fixed M)

    def rows(self) -> list[dict]:
        """The branch as table rows, one per point in the order followed.

        Returns
        -------
        list of dict
            index, f_d [Hz], rms_ym (RMS of y_m / L), floquet_max (|mu|max), mu_re and mu_im
            (the leading multiplier), stable, crossing (`FloquetResult.crossing`) and
            tangent_p (d f_d / ds).
        """
        out = []
        for k, pt in enumerate(self.branch.points):
            mu = pt.floquet.multipliers[0]
            out.append(
                {"index": k, "f_d": pt.p, "rms_ym": rms(self.problem.midspan(pt.x, pt.p)),
                 "floquet_max": pt.floquet.max_abs, "mu_re": float(mu.real),
                 "mu_im": float(mu.imag), "stable": bool(pt.stable),
                 "crossing": pt.floquet.crossing(), "tangent_p": pt.tangent_p}
            )  # fmt: skip
        return out


def start_orbit(
    model: DiscreteModel,
    T: float,
    f_d: float,
    tail_tol: float = 1e-5,
    M0: int = 17,
    M_max: int = 65,
) -> tuple[BeamBranchProblem, np.ndarray, float]:
    """The first orbit of a branch, and the problem with M chosen from its harmonic tail.

    Parameters
    ----------
    model : DiscreteModel
        The model of the scene (any drive frequency: it is replaced by `f_d`).
    T : float
        The beam's time scale [s]: the drive's omega = 2 pi f_d T.
    f_d : float
        Drive frequency of the first orbit [Hz].
    tail_tol : float
        Harmonic tail the first orbit must reach (`solve_periodic_adaptive`).
    M0 : int
        First number of collocation instants.
    M_max : int
        Finest M.

    Returns
    -------
    problem : BeamBranchProblem
        The model, its time scale T [s] and M.
    x0 : numpy.ndarray
        The orbit Theta [rad], shape (M n,) flattened.
    tail : float
        Its harmonic tail.

    Raises
    ------
    RuntimeError
        When collocation finds no orbit at f_d.
    """
    problem = BeamBranchProblem(model, T, M0)
    at = model.at(problem.dimensionless(f_d))
    res = solve_periodic_adaptive(at, M0=M0, tail_tol=tail_tol, M_max=M_max)
    if not res.converged:
        raise RuntimeError(f"no periodic orbit at f_d = {f_d:g} Hz to start from: {res.message}")
    return BeamBranchProblem(at, T, res.M), res.theta.ravel(), res.harmonic_tail


def beam_branch(
    model: DiscreteModel,
    T: float,
    f_range: tuple[float, float],
    tail_tol: float = 1e-5,
    ds: float = 0.02,
    ds_max: float = 0.1,
    max_points: int = 400,
    p_scale: float = 1.0,
    x_scale: float | None = None,
    on_point=None,
    direction: float = 1.0,
    stop=None,
    M: int | None = None,
) -> BeamBranch:
    """Pseudo-arclength continuation of the orbit at the low end of f_range up in f_d
    (direction > 0), or of the orbit at the high end down (direction < 0).

    The arclength weights: f_d by 1 / p_scale [1/Hz], the orbit by x_scale / sqrt(dim x) with
    x_scale = 1 / (RMS of the start orbit's Theta) by default, so a step ds moves the orbit by
    about ds times its own size or f_d by about ds p_scale.

    Parameters
    ----------
    model : DiscreteModel
        The model of the scene (its drive frequency is replaced along the branch).
    T : float
        The beam's time scale [s]: the drive's omega = 2 pi f_d T.
    f_range : tuple of float
        (f_lo, f_hi) [Hz]: the branch starts at one end and stops outside the range.
    tail_tol : float
        Harmonic tail that fixes M at the first orbit (`start_orbit`).
    ds : float
        First arclength step.
    ds_max : float
        Largest arclength step.
    max_points : int
        Most points on the branch.
    p_scale : float
        Scale of f_d in the arclength [Hz].
    x_scale : float or None
        Weight of the orbit in the arclength; None: 1 / RMS of the start orbit.
    on_point : callable or None
        on_point(point) after every new `BranchPoint`.
    direction : float
        > 0: from f_lo upwards; < 0: from f_hi downwards.
    stop : callable or None
        stop(branch) after every new point: True ends the branch early.
    M : int or None
        Collocation instants (odd) of the whole branch; None: from the start orbit's harmonic
        tail (`start_orbit`).

    Returns
    -------
    BeamBranch
        The problem, the branch (`continue_branch`) and the start orbit's harmonic tail.

    Raises
    ------
    RuntimeError
        When collocation finds no orbit at the starting end.
    """
    lo, hi = min(f_range), max(f_range)
    f0 = lo if direction > 0 else hi
    if M is None:
        problem, x0, tail = start_orbit(model, T, f0, tail_tol)
    else:
        problem, x0, tail = start_orbit(model, T, f0, tail_tol, M0=M, M_max=M)
    if x_scale is None:
        size = float(np.sqrt(np.mean(x0 * x0)))
        x_scale = 1.0 / size if size > 0 else 1.0
    br = continue_branch(problem, x0, f0, (lo, hi), ds=ds, ds_max=ds_max, max_points=max_points,
                         p_scale=p_scale, x_scale=x_scale, on_point=on_point,
                         direction=1.0 if direction > 0 else -1.0, stop=stop)  # fmt: skip
    return BeamBranch(problem, br, tail)
