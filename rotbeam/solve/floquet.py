r"""Floquet multipliers of a periodic orbit: the monodromy of the variational equations.

For a first-order system z' = f(t, z) with a periodic orbit z*(t) of period P, a perturbation
obeys y' = J(t) y, J(t) = df/dz (t, z*(t)); its fundamental matrix over one period is the
monodromy Phi, and its eigenvalues mu are the Floquet multipliers.  The orbit attracts every
nearby state when max |mu| < 1; a real mu through +1 is a fold (or pitchfork), through -1 a
period doubling, a complex pair through |mu| = 1 a Neimark-Sacker (torus) bifurcation.

How.  Phi is the product over S equal steps of exp(h J(t_s)), J frozen at each step's midpoint
(the exponential midpoint rule, the second-order Magnus integrator), with the orbit between
the collocation instants taken from its trigonometric interpolant.  The fast bending modes are
propagated exactly by the exponential of their frozen part, so the error is O(h^2) uniformly in
the stiffness (Hochbruck & Lubich, SIAM J. Numer. Anal. 41 (2003) 945).  The fourth-order
Magnus step with its commutator term h^2 [J_2, J_1] overflows here: the commutator carries the
stiffness (measured: |mu| = 7.5 for a stable orbit at S = 17).

The step count.  The first try takes FIRST_STEPS = 12 steps; every third of its exponentials,
cubed, is the step of the same rule on 4 steps (its midpoint is theirs), so a coarse monodromy
comes with two matrix products a step and no new exponential.  The first try stands when the
two agree (`first_try_stands`: |mu|max to SPREAD_TOL, the fixed-point offset to 1 %); else the
full S = 2 M steps (M the collocation instants, at least 32) are taken.  Calm orbits, most of a
sweep, need no more than 12 steps: their J(t) varies slowly over the period.  Measured at the
benchmark scenes and on a Fig. 7 grid column (docs/stability.md, `python3 -m
rotbeam.paper.floquet_steps`): a kept first try is within 3e-6 of |mu|max converged in S, the
full count within 1e-4 (6e-5 at the resonant Omega_0 = 5 rad/s, 7 Hz, which takes it).
Why not Hill's method: the Floquet exponents would be eigenvalues of the (M n)-sized
collocation pencil (2535 unknowns at N = 40, M = 65), a dense eigenproblem of 5070 with
spurious exponents to sort out; why not solve_ivp of the matrix ODE: (2n)^2 = 6084 unknowns in
an implicit stepper.  Here the cost is S Jacobians and S 79 x 79 matrix exponentials.

The defect.  Given the right-hand side too, the same pass measures how far the orbit is from a
true periodic solution (the certificate of `rotbeam.solve.stability.monodromy_certificate`).  Let
x(t) be the interpolant, r(t) = x' - f(t, x) its residual (zero at the collocation instants,
not between them).  The solution from x(0) is x + e with e' = J e - r + O(e^2), e(0) = 0, so the
one-period map moves x(0) by delta = e(P) = -int_0^P Phi(P, s) r(s) ds.  Each step propagates e
exactly for J and r frozen at the midpoint: the exponential of the augmented matrix
[[h J, -h r], [0, 0]] is [[exp(h J), -h phi1(h J) r], [0, 1]], so the stiff modes see r / |lambda|,
not h r (one 79 x 79 exponential instead of 78 x 78).  The fixed point of the period map is then
x(0) + w with (I - Phi) w = delta, to first order in delta.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla

from ..model.base import DiscreteModel

#: an orbit counts as stable when its largest |mu| is below 1 - STABLE_MARGIN: the monodromy is
#: accurate to ~1e-6 here (tests), far below the margins the verdicts rest on
STABLE_MARGIN = 1e-6

#: the monodromy's first try (a multiple of 3): enough for an orbit whose Jacobian varies slowly
#: over the period, the common case (docs/stability.md)
FIRST_STEPS = 12

#: the first try stands when its |mu|max and the coarse product's differ by at most this ...
SPREAD_TOL = 1e-5
#: ... and their fixed-point offsets by this much of the offset or of the orbit's size
OFFSET_RTOL = 1e-2
OFFSET_ATOL = 1e-8


@dataclass
class FloquetResult:
    """Multipliers of one periodic orbit, largest |mu| first."""

    multipliers: np.ndarray  #: complex, sorted by decreasing modulus
    monodromy: np.ndarray  #: (2n, 2n) fundamental matrix over one period
    steps: int  #: Magnus steps over the period
    seconds: float
    method: str = "exponential midpoint (Magnus-2) product of matrix exponentials"
    defect: np.ndarray | None = None  #: one-period map minus identity at the orbit's start
    #: the same rule on a third of the steps (every third step's exponential cubed), whose
    #: distance from this one estimates its error; None when the steps were fixed or full
    coarse: FloquetResult | None = None
    #: (w,) once `fixed_point_offset` has solved for it: the acceptance of a first try and the
    #: certificate both ask
    _offset: tuple = field(default=(), init=False, repr=False, compare=False)

    @property
    def spread(self) -> float:
        """| |mu|max - coarse |mu|max |: an error estimate (0 without a coarse product)."""
        return abs(self.max_abs - self.coarse.max_abs) if self.coarse is not None else 0.0

    def fixed_point_offset(self) -> np.ndarray | None:
        """w with (I - Phi) w = defect: how far the orbit's start is from the true periodic
        state, to first order (None without a defect, or when 1 is a multiplier)."""
        if not self._offset:
            self._offset = (self._solve_offset(),)
        return self._offset[0]

    def _solve_offset(self) -> np.ndarray | None:
        if self.defect is None or not self.stable:
            return None
        return np.linalg.solve(np.eye(self.monodromy.shape[0]) - self.monodromy, self.defect)

    @property
    def max_abs(self) -> float:
        return float(np.abs(self.multipliers[0])) if self.multipliers.size else 0.0

    @property
    def stable(self) -> bool:
        return self.max_abs < 1.0 - STABLE_MARGIN

    @property
    def unstable(self) -> bool:
        """A multiplier outside the unit circle: perturbations grow.  Neither stable nor
        unstable is neutral (|mu|max = 1: an undamped model), which is not left or flagged."""
        return self.max_abs > 1.0 + STABLE_MARGIN

    def describe(self) -> str:
        mu = self.multipliers[0] if self.multipliers.size else 0.0
        kind = "real" if abs(np.imag(mu)) <= 1e-9 * max(abs(mu), 1e-300) else "complex pair"
        return f"|mu|max = {self.max_abs:.6f} ({kind}, {'stable' if self.stable else 'UNSTABLE'})"

    def crossing(self) -> str:
        """What the leading multiplier does if it leaves the unit circle: fold, period doubling
        or torus (Neimark-Sacker); '' when stable."""
        if self.stable:
            return ""
        mu = self.multipliers[0]
        if abs(mu.imag) > 1e-6 * abs(mu):
            return "torus"
        return "fold" if mu.real > 0 else "period doubling"

    def as_dict(self) -> dict:
        return {"floquet_max": self.max_abs, "stable": self.stable}


def _step_exponentials(steps_data, h: float) -> np.ndarray:
    """exp of each step's augmented matrix [[h J, -h r], [0, 0]], (S, dim + 1, dim + 1)."""
    out = []
    for J, r in steps_data:
        dim = J.shape[0]
        A = np.zeros((dim + 1, dim + 1))
        A[:dim, :dim] = h * J
        A[:dim, dim] = -h * r
        out.append(sla.expm(A))
    return np.array(out)


def _product(E: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(Phi, e(P)) from the steps' augmented exponentials, the first step first."""
    dim = E.shape[1] - 1
    Phi, e = E[0, :dim, :dim], E[0, :dim, dim].copy()
    for Ek in E[1:]:
        Phi, e = Ek[:dim, :dim] @ Phi, Ek[:dim, :dim] @ e + Ek[:dim, dim]
    return Phi, e


def _coarse_product(E: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(Phi, e(P)) of the rule on a third of the steps: step k of 3h has its midpoint at the
    midpoint of fine step 3k + 1, so its exponential is that step's cubed (two products, no
    new exponential)."""
    return _product(np.array([Ek @ Ek @ Ek for Ek in E[1::3]]))


def multipliers_of(
    Phi: np.ndarray, steps: int, seconds: float, defect: np.ndarray | None = None
) -> FloquetResult:
    mu = np.linalg.eigvals(Phi)
    mu = mu[np.argsort(-np.abs(mu), kind="stable")]
    return FloquetResult(mu, Phi, steps, seconds, defect=defect)


def trig_eval(X: np.ndarray, period: float, t: np.ndarray, derivative: int = 0) -> np.ndarray:
    """The trigonometric interpolant of X (M equispaced samples of one period, M odd, axis 0)
    and its `derivative`-th time derivative at the instants t: (len(t), ...)."""
    M = X.shape[0]
    C = np.fft.rfft(X, axis=0) / M  # c_0, c_1 .. c_{(M-1)/2}
    k = np.arange(C.shape[0])
    w = 2.0 * math.pi / period
    E = np.exp(1j * w * np.outer(np.asarray(t, dtype=float), k)) * (1j * w * k) ** derivative
    E[:, 1:] *= 2.0
    if M % 2 == 0:  # the Nyquist term is counted once
        E[:, -1] *= 0.5
    return np.real(np.tensordot(E, C, axes=(1, 0)))


def first_try_stands(first: FloquetResult, size: float) -> bool:
    """Whether the first try's |mu|max and fixed-point offset are as good as the full step
    count's: |mu|max within SPREAD_TOL of the coarse product's and within a tenth of its distance
    from 1 (the spread cannot move the stability verdict), and the offset (I - Phi)^-1 defect
    within OFFSET_RTOL of the coarse one's or OFFSET_ATOL of the orbit's size (the certificate
    compares it with 1e-4 of the response).  The entries of Phi may still be off by more: a
    stiff mode's phase over the period moves them and not |mu| (tests/test_floquet.py)."""
    if first.spread > min(SPREAD_TOL, 0.1 * abs(1.0 - first.max_abs)):
        return False
    w, w_coarse = first.fixed_point_offset(), first.coarse.fixed_point_offset()
    if w is None or w_coarse is None:
        return first.defect is None
    gap = float(np.max(np.abs(w - w_coarse)))
    return gap <= OFFSET_RTOL * float(np.max(np.abs(w))) + OFFSET_ATOL * size


def default_steps(M: int) -> int:
    """The full step count: 2 M (at least 32), M the orbit's collocation instants."""
    return max(2 * M, 32)


def _steps_data(jac, Z, period, steps, rhs, rows) -> tuple[np.ndarray, np.ndarray, bool]:
    """(J (S, dim, dim), r (S, dim), has_defect) at the midpoints of `steps` equal steps: the
    Jacobian and the interpolant's residual (zero without a right-hand side)."""
    t = (np.arange(steps) + 0.5) * (period / steps)
    Zs = trig_eval(Z, period, t)
    if rows is not None:
        F, Js = rows(t, Zs)
        return Js, trig_eval(Z, period, t, derivative=1) - F, True
    Js = np.array([jac(tk, zk) for tk, zk in zip(t, Zs, strict=True)])
    if rhs is None:
        return Js, np.zeros(Zs.shape), False
    F = np.array([rhs(tk, zk) for tk, zk in zip(t, Zs, strict=True)])
    return Js, trig_eval(Z, period, t, derivative=1) - F, True


def _monodromy(jac, Z, period, steps, rhs, rows, coarse: bool):
    """(Phi, defect, coarse (Phi, defect) or None) over `steps` steps."""
    Js, r, has_defect = _steps_data(jac, Z, period, steps, rhs, rows)
    E = _step_exponentials(zip(Js, r, strict=True), period / steps)
    Phi, defect = _product(E)
    low = _coarse_product(E) if coarse else None
    if not has_defect:  # the residual column was zero: no defect to report
        defect = None
        low = (low[0], None) if low is not None else None
    return Phi, defect, low


def orbit_floquet(
    jac: Callable[[float, np.ndarray], np.ndarray] | None,
    Z: np.ndarray,
    period: float,
    steps: int | None = None,
    rhs: Callable[[float, np.ndarray], np.ndarray] | None = None,
    rows: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]] | None = None,
) -> FloquetResult:
    """Multipliers of the orbit whose states at M equispaced instants are Z (M, dim), for the
    system with Jacobian jac(t, z); the orbit between the instants is Z's trigonometric
    interpolant.  With the right-hand side rhs(t, z) the result also carries the interpolant's
    one-period `defect` (module docstring).  `rows(t, Z)` -> (f (S, dim), J (S, dim, dim))
    gives both at every step at once instead of jac and rhs (the beam's batched
    `first_order_rows`).

    `steps` fixes the step count.  Without it the monodromy first tries FIRST_STEPS steps and
    keeps them when the coarse product (a third of the steps, from the same exponentials) agrees
    with it (`first_try_stands`); otherwise it takes `default_steps(M)`."""
    t0 = time.perf_counter()
    if steps is not None:
        Phi, defect, _ = _monodromy(jac, Z, period, steps, rhs, rows, coarse=False)
        return multipliers_of(Phi, steps, time.perf_counter() - t0, defect)
    Phi, defect, low = _monodromy(jac, Z, period, FIRST_STEPS, rhs, rows, coarse=True)
    first = multipliers_of(Phi, FIRST_STEPS, 0.0, defect)
    first.coarse = multipliers_of(low[0], FIRST_STEPS // 3, 0.0, low[1])
    if first_try_stands(first, float(np.max(np.abs(Z)))):
        first.seconds = time.perf_counter() - t0
        return first
    full = default_steps(Z.shape[0])
    Phi, defect, _ = _monodromy(jac, Z, period, full, rhs, rows, coarse=False)
    return multipliers_of(Phi, full, time.perf_counter() - t0, defect)


def beam_floquet(
    model: DiscreteModel,
    theta: np.ndarray,
    theta_t: np.ndarray,
    steps: int | None = None,
) -> FloquetResult:
    """Multipliers of the beam's orbit sampled at M equispaced instants of the drive period,
    theta and theta_t (n, M), with the model's exact Jacobians (`first_order_rows`, all steps
    in one batch), and the orbit's one-period defect."""
    n, dl = model.n, model.dl

    def rows(t: np.ndarray, Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        lam, lam_dot = model.drive_rows(t)
        return model.first_order_rows(Z[:, :n], Z[:, n:], lam, lam_dot)

    Z = np.concatenate([theta, theta_t], axis=0).T
    return orbit_floquet(None, Z, dl.period, steps, rows=rows)


def sampled_beam_floquet(
    model: DiscreteModel, theta: np.ndarray, steps: int | None = None
) -> FloquetResult:
    """Multipliers of a time-stepped periodic orbit from its angles at m equispaced instants of
    one period (n, m); the velocities are the samples' spectral derivative."""
    X, dl = theta.T, model.dl
    if X.shape[0] % 2 == 0:  # an odd count: no Nyquist term, whose derivative is undefined
        X = trig_eval(X, dl.period, np.arange(X.shape[0] + 1) * dl.period / (X.shape[0] + 1))
    V = trig_eval(X, dl.period, np.arange(X.shape[0]) * dl.period / X.shape[0], derivative=1)
    return beam_floquet(model, X.T, V.T, steps)
