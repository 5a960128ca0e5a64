r"""The beam's `BranchProblem`: periodic orbits of the discrete elastica continued in f_d.

Unknowns x: the collocated orbit Theta at M equispaced phases j / M of the drive period,
(M, n) flattened (n = N - 1), exactly the unknowns of `rotbeam.solve.periodic.Collocation`, whose
residual and Jacobian are used as they are.  The parameter p is the drive frequency f_d in Hz;
every other number of the scene is fixed in physical units (Beam, Drive.omega0, Drive.amplitude,
Effects) and each p is turned into the dimensionless problem by `Dimensionless.from_physical`, so
the period (and with it the collocation instants tau_j and the Fourier matrix D) changes with p
while the phases j / M do not.  M stays fixed along a branch: `start_orbit` chooses it from the
harmonic tail at the branch's first point (`solve_periodic_adaptive`).

Floquet multipliers: `rotbeam.solve.floquet.beam_floquet` on the orbit and its spectral
derivative V = D Theta.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..model.base import DiscreteModel
from ..model.criterion import rms
from ..model.elastica import DiscreteElastica
from ..model.params import Beam, Dimensionless, Drive, Effects
from .continuation import Branch, BranchProblem, continue_branch
from .floquet import FloquetResult, beam_floquet
from .periodic import Collocation, solve_periodic_adaptive
from .spectral import trig_interpolate


@dataclass
class BeamBranchProblem(BranchProblem):
    """Collocated orbits of one model, parameter p = f_d [Hz]: every number of the scene but the
    drive frequency stays fixed in physical units."""

    model: DiscreteModel  #: the model at any f_d (its drive's frequency is replaced by p)
    T: float  #: time scale of the beam [s]: omega = 2 pi p T
    M: int  #: collocation instants (odd), fixed along the branch
    _cols: dict = field(default_factory=dict, repr=False)

    def dimensionless(self, f_d: float) -> Dimensionless:
        """The scene at drive frequency f_d [Hz]."""
        return replace(self.model.dl, omega=2.0 * math.pi * float(f_d) * self.T)

    def collocation(self, f_d: float) -> Collocation:
        """The collocation at f_d (the last few kept: residual, Jacobian and dR/dp reuse them)."""
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
        return self.collocation(p).residual(self._X(x)).ravel()

    def jacobian(self, x: np.ndarray, p: float) -> np.ndarray:
        col = self.collocation(p)
        return col.dense_jacobian(col.jacobian_blocks(self._X(x)))

    def floquet(self, x: np.ndarray, p: float) -> FloquetResult:
        col = self.collocation(p)
        X = self._X(x)
        return beam_floquet(col.model, X.T, (col.D @ X).T)

    def midspan(self, x: np.ndarray, p: float, samples: int = 64) -> np.ndarray:
        """y_m / L over one period at `samples` equispaced instants (trigonometric interpolant)."""
        col = self.collocation(p)
        return np.atleast_1d(col.model.midspan(trig_interpolate(self._X(x), samples).T))


@dataclass
class BeamBranch:
    """A continued branch of the beam with the quantities the figure and table need."""

    problem: BeamBranchProblem
    branch: Branch
    tail: float  #: harmonic tail of the start orbit (what fixed M)

    def rows(self) -> list[dict]:
        """One row per branch point: f_d [Hz], RMS of y_m / L, |mu|max, stability, the leading
        multiplier (real and imaginary parts), dp/ds."""
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
    beam: Beam,
    omega0: float,
    amplitude: float,
    f_d: float,
    effects: Effects | None = None,
    N: int = 10,
    tail_tol: float = 1e-5,
    M0: int = 17,
    M_max: int = 65,
) -> tuple[BeamBranchProblem, np.ndarray, float]:
    """The problem with M from the harmonic tail at f_d, and the converged orbit there."""
    effects = effects if effects is not None else Effects()
    dl = Dimensionless.from_physical(
        beam, Drive(omega0=omega0, f_d=f_d, amplitude=amplitude), effects
    )
    model = DiscreteElastica(dl, N)
    res = solve_periodic_adaptive(model, M0=M0, tail_tol=tail_tol, M_max=M_max)
    if not res.converged:
        raise RuntimeError(f"no periodic orbit at f_d = {f_d:g} Hz to start from: {res.message}")
    problem = BeamBranchProblem(model, beam.T, res.M)
    return problem, res.theta.T.ravel(), res.harmonic_tail


def beam_branch(
    beam: Beam,
    omega0: float,
    amplitude: float,
    f_range: tuple[float, float],
    effects: Effects | None = None,
    N: int = 10,
    tail_tol: float = 1e-5,
    ds: float = 0.02,
    ds_max: float = 0.1,
    max_points: int = 400,
    p_scale: float = 1.0,
    x_scale: float | None = None,
    on_point=None,
    direction: float = 1.0,
    stop=None,
) -> BeamBranch:
    """Pseudo-arclength continuation of the orbit at the low end of f_range [Hz] up in f_d
    (direction > 0), or of the orbit at the high end down (direction < 0); `stop(branch)`, if
    given, ends it early (`continue_branch`).

    The arclength weights: f_d by 1 / p_scale [1/Hz], the orbit by x_scale / sqrt(dim x) with
    x_scale = 1 / (RMS of the start orbit's Theta) by default, so a step ds moves the orbit by
    about ds times its own size or f_d by about ds p_scale.
    """
    lo, hi = min(f_range), max(f_range)
    f0 = lo if direction > 0 else hi
    problem, x0, tail = start_orbit(beam, omega0, amplitude, f0, effects, N, tail_tol)
    if x_scale is None:
        size = float(np.sqrt(np.mean(x0 * x0)))
        x_scale = 1.0 / size if size > 0 else 1.0
    br = continue_branch(problem, x0, f0, (lo, hi), ds=ds, ds_max=ds_max, max_points=max_points,
                         p_scale=p_scale, x_scale=x_scale, on_point=on_point,
                         direction=1.0 if direction > 0 else -1.0, stop=stop)  # fmt: skip
    return BeamBranch(problem, br, tail)
