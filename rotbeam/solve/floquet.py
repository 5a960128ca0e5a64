"""Floquet multipliers of a periodic orbit: the monodromy of the variational equations.

The monodromy Phi is a product of matrix exponentials exp(h J) over S steps of the period (the
exponential midpoint rule, second-order Magnus), with J the exact Jacobian on the orbit's
trigonometric interpolant; its eigenvalues are the multipliers, and max |mu| < 1 means the orbit
attracts.  The same pass propagates the interpolant's residual: the one-period defect behind the
certificate of `rotbeam.solve.certify`.  A first try of FIRST_STEPS steps stands when a coarse
product from the same exponentials agrees with it; otherwise the step counts of STEP_LADDER are
taken in turn, each checked against the one before, until one stands.  Definitions, derivation,
step counts and checks: docs/stability.md, "How the multipliers are computed" and "The
monodromy certificate".
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla

from ..config.parameters import default
from ..model.base import DiscreteModel
from .spectral import periodic_rates, trig_interpolate
from .timebudget import check_deadline

#: an orbit counts as stable when its largest |mu| is below 1 - STABLE_MARGIN: the monodromy is
#: accurate to ~1e-6 here (tests), far below the margins the verdicts rest on
STABLE_MARGIN = 1e-6

#: the monodromy's first try (a multiple of 3): enough for an orbit whose Jacobian varies slowly
#: over the period, the common case (docs/stability.md)
FIRST_STEPS = 12

#: the most instants an orbit may have for the first try to stand on its own: its FIRST_STEPS
#: midpoints sample J(t) without aliasing only where the orbit's harmonics are below
#: FIRST_STEPS (M <= 2 FIRST_STEPS - 1; in practice the orbits of M0 = 17 instants).  A finer
#: orbit starts the ladder at once, the first try its first check: at N = 16, 36.67 rad/s,
#: 13.7 Hz (M = 129, the tip swinging 1 rad) 12 and 4 steps agree on |mu|max 1.198 and 1.202,
#: an unstable verdict, where the orbit's is 0.941 (docs/stability.md)
FIRST_TRY_MAX_INSTANTS = 2 * FIRST_STEPS - 1

#: the step counts after a first try that does not stand: each is checked against the one before
#: and kept when the two agree.  Consecutive counts are coprime (3 S + 1): the exponential
#: midpoint rule's error peaks at step counts that alias a mode's frequency onto a low harmonic
#: of the orbit, a count's aliases are those of its divisors too, and two coprime counts share
#: none below their product (docs/stability.md, "How the multipliers are computed")
STEP_LADDER = (FIRST_STEPS, 37, 112, 337, 1012)

#: a product stands when its |mu|max and the one it is checked against differ by at most this
#: (the registry's numerics.floquet_tol, what a reported |mu|max carries by default) ...
SPREAD_TOL = default("numerics", "floquet_tol")
#: ... and their fixed-point offsets by this much of the offset or of the orbit's size
OFFSET_RTOL = 1e-2
OFFSET_ATOL = 1e-8

#: numerics.floquet_tol of an orbit whose multipliers no result reports: |mu|max stays as
#: resolved as its stability verdict and certificate needed (a spread of 1 always stands)
VERDICT_ONLY = 1.0


@dataclass
class FloquetResult:
    """Multipliers of one periodic orbit, largest |mu| first, with the monodromy they come from.

    `orbit_floquet` and its beam versions make it; `max_abs`, `stable` and `crossing` give the
    verdict, and `fixed_point_offset` the distance to the true periodic state that the
    certificate of `rotbeam.solve.certify` asks for.  Times are those of the system the
    monodromy was built for (dimensionless tau, in units of T, for the beam).
    """

    monodromy: np.ndarray  #: (2n, 2n) fundamental matrix over one period
    steps: int  #: Magnus steps over the period
    seconds: float  #: time the computation took [s] (time.perf_counter)
    method: str = "exponential midpoint (Magnus-2) product of matrix exponentials"
    defect: np.ndarray | None = None  #: one-period map minus identity at the orbit's start
    #: the product this one was checked against: the same rule on a third of the steps (every
    #: third step's exponential cubed) for a first try, the count of STEP_LADDER before it
    #: after that; their distance estimates the error.  None when the steps were fixed
    coarse: FloquetResult | None = None
    #: max |mu| as `spectral_radius` gives it (the step ladder's products: every verdict and
    #: check asks for |mu|max alone); None: the leading eigenvalue's modulus (a fixed count)
    radius: float | None = None
    #: (w,) once `fixed_point_offset` has solved for it: the acceptance of a first try and the
    #: certificate both ask
    _offset: tuple = field(default=(), init=False, repr=False, compare=False)
    #: (mu,) once `multipliers` has computed them
    _multipliers: tuple = field(default=(), init=False, repr=False, compare=False)

    @property
    def multipliers(self) -> np.ndarray:
        """The eigenvalues of the monodromy, complex, sorted by decreasing modulus: computed
        when first asked (a crossing, a branch, the push off an unstable orbit), not for a
        verdict, which needs |mu|max alone (`max_abs`).  Of a Radau collocation's product
        (`method`, `rotbeam.solve.collocated_floquet`) they are the slow modes' and near-zeros
        for the stiff modes it annihilates."""
        if not self._multipliers:
            mu = np.linalg.eigvals(self.monodromy) if self.monodromy.size else np.zeros(0, complex)
            self._multipliers = (mu[np.argsort(-np.abs(mu), kind="stable")],)
        return self._multipliers[0]

    @property
    def spread(self) -> float:
        """| |mu|max - coarse |mu|max |: an error estimate (0 without a coarse product)."""
        return abs(self.max_abs - self.coarse.max_abs) if self.coarse is not None else 0.0

    def fixed_point_offset(self) -> np.ndarray | None:
        """How far the orbit's start is from the true periodic state, to first order in the
        defect: w with (I - Phi) w = defect (solved once, then kept).

        Returns
        -------
        numpy.ndarray or None
            w, shape (dim,), in the units of the state (angles, then rates); None without a
            defect or when the orbit is not stable (I - Phi may then be singular).
        """
        if not self._offset:
            self._offset = (self._solve_offset(),)
        return self._offset[0]

    def _solve_offset(self) -> np.ndarray | None:
        if self.defect is None or not self.stable:
            return None
        return np.linalg.solve(np.eye(self.monodromy.shape[0]) - self.monodromy, self.defect)

    @property
    def max_abs(self) -> float:
        """The largest |mu|: `radius` where it is set, else the leading multiplier's modulus (0
        for an empty monodromy)."""
        if self.radius is not None:
            return self.radius
        return float(np.abs(self.multipliers[0])) if self.multipliers.size else 0.0

    @property
    def stable(self) -> bool:
        """Whether max |mu| < 1 - STABLE_MARGIN: every small perturbation shrinks each period."""
        return self.max_abs < 1.0 - STABLE_MARGIN

    @property
    def unstable(self) -> bool:
        """A multiplier outside the unit circle: perturbations grow.  Neither stable nor
        unstable is neutral (|mu|max = 1: an undamped model), which is not left or flagged."""
        return self.max_abs > 1.0 + STABLE_MARGIN

    def describe(self) -> str:
        """|mu|max and the verdict in words, for messages (`crossing` says how an orbit that is
        not stable loses its stability).

        Returns
        -------
        str
            '|mu|max = 0.888269 (stable)', or '(UNSTABLE)' where the orbit is not stable.
        """
        return f"|mu|max = {self.max_abs:.6f} ({'stable' if self.stable else 'UNSTABLE'})"

    def crossing(self) -> str:
        """How the orbit loses stability, from where its leading multiplier leaves the circle.

        Returns
        -------
        str
            "fold" (a real mu > 1), "period doubling" (a real mu < -1), "torus" (a complex
            pair: Neimark-Sacker), or '' when the orbit is stable.
        """
        if self.stable:
            return ""
        mu = self.multipliers[0]
        if abs(mu.imag) > 1e-6 * abs(mu):
            return "torus"
        return "fold" if mu.real > 0 else "period doubling"

    def as_dict(self) -> dict:
        """The columns a result row carries.

        Returns
        -------
        dict
            floquet_max (float, the largest |mu|) and stable (bool).
        """
        return {"floquet_max": self.max_abs, "stable": self.stable}


def _step_exponentials(Js: np.ndarray, r: np.ndarray, h: float) -> np.ndarray:
    """exp of each step's augmented matrix [[h J, -h r], [0, 0]] in one batched call,
    (S, dim + 1, dim + 1) from J (S, dim, dim) and r (S, dim)."""
    S, dim = r.shape
    A = np.zeros((S, dim + 1, dim + 1))
    A[:, :dim, :dim] = h * Js
    A[:, :dim, dim] = -h * r
    return sla.expm(A)


def _product(
    E: np.ndarray, start: tuple[np.ndarray, np.ndarray] | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """(Phi, e(P)) from the steps' augmented exponentials, the first step first, continuing
    the product `start` of the steps before them (None: the first steps)."""
    dim = E.shape[1] - 1
    if start is None:
        Phi, e = E[0, :dim, :dim], E[0, :dim, dim].copy()
        E = E[1:]
    else:
        Phi, e = start
    for Ek in E:
        Phi, e = Ek[:dim, :dim] @ Phi, Ek[:dim, :dim] @ e + Ek[:dim, dim]
    return Phi, e


def _coarse_product(
    E: np.ndarray, start: tuple[np.ndarray, np.ndarray] | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """(Phi, e(P)) of the rule on a third of the steps: step k of 3h has its midpoint at the
    midpoint of fine step 3k + 1, so its exponential is that step's cubed (two products, no
    new exponential).  E starts at a step whose index is a multiple of 3."""
    E3 = E[1::3]
    return _product(E3 @ E3 @ E3, start)


#: squarings behind `spectral_radius`: ||Phi^k||^(1/k) at k = 2^32 is above |mu|max by at most
#: log(kappa n) / k (kappa the condition of Phi's eigenvector basis, 2.6e5 at N = 40: 4e-9);
#: the rounding of the first squarings leaves it within about 1e-8 (tests/test_floquet.py)
RADIUS_SQUARINGS = 32


def spectral_radius(Phi: np.ndarray) -> float:
    """max |mu| of a square matrix without its eigenvalues: ||Phi^k||^(1/k) at k = 2^32, by
    repeated squaring rescaled at each step (Gelfand's formula).

    The largest |mu| is all a product that only checks another needs (`first_try_stands`),
    and at 78 x 78 this costs a third of an eigenvalue solve.  It needs no gap between the
    moduli (at a calm orbit all 78 multipliers share one, exp(-eta P / 2): docs/stability.md),
    only that log of the eigenvector basis's condition be small against 2^32.  It is accurate to
    about 1e-8 (the rounding of the first squarings), against 1e-11 for the eigenvalues: enough
    for a check at SPREAD_TOL, not for a reported |mu|max.

    Parameters
    ----------
    Phi : numpy.ndarray
        The matrix, shape (dim, dim), finite.

    Returns
    -------
    float
        Its spectral radius (0 for a nilpotent matrix).

    Raises
    ------
    numpy.linalg.LinAlgError
        For a matrix with an entry that is not finite (as `numpy.linalg.eigvals`).
    """
    X = np.array(Phi, dtype=float)
    if not np.all(np.isfinite(X)):
        raise np.linalg.LinAlgError("spectral_radius: the matrix has an entry that is not finite")
    log_radius, weight = 0.0, 1.0  # X = Phi^(2^j) / (the scales so far), log weighted by 2^-j
    for _ in range(RADIUS_SQUARINGS):
        scale = float(np.max(np.abs(X)))
        if scale == 0.0:
            return 0.0
        log_radius += weight * math.log(scale)
        X *= 1.0 / scale
        X = X @ X
        weight *= 0.5
    scale = float(np.max(np.abs(X)))
    return 0.0 if scale == 0.0 else math.exp(log_radius + weight * math.log(scale))


def radius_of(Phi: np.ndarray, steps: int, defect: np.ndarray | None = None) -> FloquetResult:
    """A product of the step ladder: its largest |mu| by `spectral_radius`, the multipliers
    left until they are asked for (`FloquetResult.multipliers`).

    Parameters
    ----------
    Phi : numpy.ndarray
        The monodromy, shape (dim, dim).
    steps : int
        Magnus steps it was built from.
    defect : numpy.ndarray or None
        The orbit's one-period defect, shape (dim,), if measured.

    Returns
    -------
    FloquetResult
        Phi, `radius` set.
    """
    return FloquetResult(Phi, steps, 0.0, defect=defect, radius=spectral_radius(Phi))


def trig_eval(X: np.ndarray, period: float, t: np.ndarray, derivative: int = 0) -> np.ndarray:
    """The trigonometric interpolant of equispaced samples, or a time derivative of it, at any
    instants: the orbit between its collocation instants.

    Parameters
    ----------
    X : numpy.ndarray
        M equispaced samples of one period along axis 0, shape (M, ...), the first at t = 0;
        M odd (an even M counts its Nyquist term once).
    period : float
        The period, in the units of t.
    t : numpy.ndarray
        Instants, shape (m,), in the units of `period` (any, not only within one period).
    derivative : int
        Order of the time derivative (0: the values).

    Returns
    -------
    numpy.ndarray
        The interpolant's `derivative`-th derivative at t, shape (m, ...).
    """
    M = X.shape[0]
    C = np.fft.rfft(X, axis=0) / M  # c_0, c_1 .. c_{(M-1)/2}
    k = np.arange(C.shape[0])
    w = 2.0 * math.pi / period
    E = np.exp(1j * w * np.outer(np.asarray(t, dtype=float), k)) * (1j * w * k) ** derivative
    E[:, 1:] *= 2.0
    if M % 2 == 0:  # the Nyquist term is counted once
        E[:, -1] *= 0.5
    return np.real(np.tensordot(E, C, axes=(1, 0)))


def top_stands_apart(fl: FloquetResult, cluster: float, mu_tol: float) -> bool:
    """Whether a product tells |mu|max apart from the other moduli: it lies within `mu_tol` of
    `cluster` (a calm orbit, whose moduli all lie there), or more than `mu_tol` above every
    other multiplier but its complex conjugate.

    Two step counts can agree on |mu|max to `mu_tol` and both miss it where two moduli above
    the cluster lie closer than that: the counts' errors swap their order (docs/stability.md,
    "How the multipliers are computed").

    Parameters
    ----------
    fl : FloquetResult
        The product.
    cluster : float
        The modulus every multiplier shares but for the orbit's coupling (a uniformly damped
        beam's exp(-c P / 2): `rotbeam.solve.collocated_floquet.uniform_decay`).
    mu_tol : float
        How closely |mu|max is resolved.

    Returns
    -------
    bool
        True where |mu|max stands apart (or at the cluster); False where the next modulus lies
        within `mu_tol` of it.
    """
    if fl.max_abs - cluster <= mu_tol:
        return True
    mu = fl.multipliers
    top, rest = mu[0], mu[1:]
    if rest.size and abs(top.imag) > 1e-12 * abs(top):  # its conjugate shares its modulus
        rest = np.delete(rest, int(np.argmin(np.abs(rest - np.conj(top)))))
    return not rest.size or bool(abs(top) - np.max(np.abs(rest)) > mu_tol)


def first_try_stands(
    first: FloquetResult,
    size: float,
    offset_atol: float | None = None,
    mu_tol: float = SPREAD_TOL,
    cluster: float | None = None,
) -> bool:
    """Whether a product's |mu|max and fixed-point offset are as good as a finer step count's,
    judged by their distance from the product it was checked against (`coarse`).

    |mu|max must lie within `mu_tol` (SPREAD_TOL, what a reported |mu|max carries) of the
    coarse product's and within a tenth of its distance from 1 (the spread cannot move the
    stability verdict), and the offset
    (I - Phi)^-1 defect within OFFSET_RTOL of the coarse one's or `offset_atol` (OFFSET_ATOL of
    the orbit's size unless given; infinite where the certificate weighs the offsets' gap
    itself).  The entries of Phi may still
    be off by more: a stiff mode's phase over the period moves them and not |mu|
    (tests/test_floquet.py; docs/stability.md, "How the multipliers are computed").

    Parameters
    ----------
    first : FloquetResult
        The product, with its `coarse` product set.
    size : float
        The orbit's size, max |z| over its samples (in the units of the state).
    offset_atol : float or None
        The absolute tolerance of the offsets' gap (max-norm, units of the state); None:
        OFFSET_ATOL * size; inf: the offsets are not compared.
    mu_tol : float
        The tolerance of |mu|max's spread; inf: only the verdict's (a tenth of the distance
        from 1).
    cluster : float or None
        Where every modulus lies but for the orbit's coupling; where given, |mu|max must also
        stand apart from the next modulus (`top_stands_apart`).

    Returns
    -------
    bool
        True when the product stands; False when a finer step count is needed.
    """
    if first.spread > min(mu_tol, 0.1 * abs(1.0 - first.max_abs)):
        return False
    if cluster is not None and not top_stands_apart(first, cluster, mu_tol):
        return False
    if offset_atol == math.inf:
        return True
    w, w_coarse = first.fixed_point_offset(), first.coarse.fixed_point_offset()
    if w is None or w_coarse is None:
        return first.defect is None
    gap = float(np.max(np.abs(w - w_coarse)))
    atol = OFFSET_ATOL * size if offset_atol is None else offset_atol
    return gap <= OFFSET_RTOL * float(np.max(np.abs(w))) + atol


def _steps_data(jac, Z, period, t, rhs, rows) -> tuple[np.ndarray, np.ndarray, bool]:
    """(J (S, dim, dim), r (S, dim), has_defect) at the steps' midpoints t (S,): the Jacobian
    and the interpolant's residual (zero without a right-hand side)."""
    Zs = trig_eval(Z, period, t)
    if rows is not None:
        F, Js = rows(t, Zs)
        return Js, trig_eval(Z, period, t, derivative=1) - F, True
    Js = np.array([jac(tk, zk) for tk, zk in zip(t, Zs, strict=True)])
    if rhs is None:
        return Js, np.zeros(Zs.shape), False
    F = np.array([rhs(tk, zk) for tk, zk in zip(t, Zs, strict=True)])
    return Js, trig_eval(Z, period, t, derivative=1) - F, True


#: steps whose Jacobians and exponentials are made at once (a multiple of 3, for the coarse
#: product): the product goes on block by block, so a long pass keeps its arrays in cache
#: (1.4x faster at 1012 steps than all at once)
BLOCK = 63


def _monodromy(jac, Z, period, steps, rhs, rows, coarse: bool):
    """(Phi, defect, coarse (Phi, defect) or None) over `steps` steps."""
    t = (np.arange(steps) + 0.5) * (period / steps)
    fine = low = None
    for first in range(0, steps, BLOCK):
        check_deadline()
        Js, r, has_defect = _steps_data(jac, Z, period, t[first : first + BLOCK], rhs, rows)
        E = _step_exponentials(Js, r, period / steps)
        fine = _product(E, fine)
        low = _coarse_product(E, low) if coarse else None
    Phi, defect = fine
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
    after: FloquetResult | None = None,
    offset_atol: float | None = None,
    mu_tol: float = SPREAD_TOL,
    cluster: float | None = None,
) -> FloquetResult:
    """Floquet multipliers of a periodic orbit of a first-order system z' = f(t, z), given by
    its states at M equispaced instants of the period.

    The orbit between the instants is Z's trigonometric interpolant (`trig_eval`).  Without
    `steps` the monodromy first tries FIRST_STEPS steps and keeps them when the orbit has at
    most FIRST_TRY_MAX_INSTANTS instants and the coarse product (a third of the steps, from the
    same exponentials) agrees with it (`first_try_stands`); otherwise it takes the counts of
    STEP_LADDER in turn, each checked against the one before, until one stands or the ladder
    ends (docs/stability.md, "How the multipliers are computed").

    Parameters
    ----------
    jac : callable or None
        jac(t, z) -> df/dz, shape (dim, dim); None when `rows` is given.
    Z : numpy.ndarray
        The orbit at t_j = j P / M, j = 0 .. M-1, shape (M, dim).
    period : float
        The period P, in the system's time unit.
    steps : int or None
        A fixed number of Magnus steps; None: the first try, then the ladder.
    rhs : callable or None
        rhs(t, z) -> f, shape (dim,).  With it the result also carries the interpolant's
        one-period `defect` (docs/stability.md, "The monodromy certificate").
    rows : callable or None
        rows(t, Z) -> (f (S, dim), J (S, dim, dim)) at S instants at once, in place of jac and
        rhs (the beam's batched `first_order_rows`).
    after : FloquetResult or None
        A pass of the same orbit already made: the ladder goes on from the first count above
        its steps, checked against it (what an ambiguous certificate asks for).
    offset_atol : float or None
        How far the fixed-point offsets of two counts may differ for the finer to stand
        (`first_try_stands`).
    mu_tol : float
        How far their |mu|max may differ (`first_try_stands`).
    cluster : float or None
        Where every modulus lies but for the orbit's coupling: |mu|max must also stand apart
        from the next modulus (`top_stands_apart`); None: no such check.

    Returns
    -------
    FloquetResult
        The multipliers, the monodromy, the steps taken and, with rhs or rows, the defect; the
        product it was checked against is its `coarse` (None for a fixed count).
    """
    t0 = time.perf_counter()
    if steps is not None:
        Phi, defect, _ = _monodromy(jac, Z, period, steps, rhs, rows, coarse=False)
        return FloquetResult(Phi, steps, time.perf_counter() - t0, defect=defect)
    size = float(np.max(np.abs(Z)))
    previous = after
    if previous is None:
        resolved = Z.shape[0] <= FIRST_TRY_MAX_INSTANTS
        Phi, defect, low = _monodromy(jac, Z, period, FIRST_STEPS, rhs, rows, coarse=resolved)
        previous = radius_of(Phi, FIRST_STEPS, defect)
        if resolved:  # the first try may stand, checked against its coarse product
            previous.coarse = radius_of(low[0], FIRST_STEPS // 3, low[1])
            if first_try_stands(previous, size, offset_atol, mu_tol, cluster):
                previous.seconds = time.perf_counter() - t0
                return previous
    for count in (S for S in STEP_LADDER if S > previous.steps):
        Phi, defect, _ = _monodromy(jac, Z, period, count, rhs, rows, coarse=False)
        current = radius_of(Phi, count, defect)
        current.coarse = _alone(previous)
        previous = current
        if first_try_stands(current, size, offset_atol, mu_tol, cluster):
            break
    previous.seconds = time.perf_counter() - t0
    return previous


def _alone(fl: FloquetResult) -> FloquetResult:
    """`fl` without the product it was checked against (a ladder keeps one comparison)."""
    out = FloquetResult(fl.monodromy, fl.steps, fl.seconds, fl.method, fl.defect, radius=fl.radius)
    out._offset, out._multipliers = fl._offset, fl._multipliers
    return out


def beam_floquet(
    model: DiscreteModel,
    theta: np.ndarray,
    theta_t: np.ndarray,
    steps: int | None = None,
    after: FloquetResult | None = None,
    offset_atol: float | None = None,
    mu_tol: float = SPREAD_TOL,
    cluster: float | None = None,
) -> FloquetResult:
    """Floquet multipliers and one-period defect of a collocated orbit of the beam.

    The Jacobians and right-hand sides of all steps come from the model in one batch
    (`first_order_rows`); the state is z = (Theta, Theta_t), dim = 2 n.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive; the period is its `dl.period` (dimensionless, units of T).
    theta : numpy.ndarray
        Angles [rad] at M equispaced instants of the drive period, the first at tau = 0,
        shape (M, n).
    theta_t : numpy.ndarray
        Their rates d theta / d tau at the same instants, shape (M, n).
    steps : int or None
        A fixed number of Magnus steps; None: the first try, then the ladder
        (`orbit_floquet`).
    after : FloquetResult or None
        A pass of the same orbit already made, for the ladder to go on from.
    offset_atol : float or None
        How far two counts' fixed-point offsets may differ (`first_try_stands`).
    mu_tol : float
        How far their |mu|max may differ (`first_try_stands`).
    cluster : float or None
        Where every modulus lies but for the orbit's coupling (`top_stands_apart`).

    Returns
    -------
    FloquetResult
        The multipliers, the (2 n, 2 n) monodromy and the defect.
    """
    n, dl = model.n, model.dl

    def rows(t: np.ndarray, Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        lam, lam_dot = model.drive_rows(t)
        return model.first_order_rows(Z[:, :n], Z[:, n:], lam, lam_dot)

    Z = np.concatenate([theta, theta_t], axis=1)
    return orbit_floquet(None, Z, dl.period, steps, None, rows, after, offset_atol, mu_tol, cluster)


def sampled_orbit(model: DiscreteModel, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A time-stepped periodic orbit as the multipliers take it: its angles over one period on
    an odd number of instants and their spectral derivative.

    An even count m is first resampled to m + 1 instants (no Nyquist term, whose derivative is
    undefined).

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive (period `dl.period`, dimensionless).
    theta : numpy.ndarray
        Angles [rad] at m equispaced instants of one drive period, the first at a whole number
        of periods, shape (m, n).

    Returns
    -------
    theta : numpy.ndarray
        The angles [rad] at m or m + 1 (odd) equispaced instants, shape (M, n).
    theta_t : numpy.ndarray
        Their rates d theta / d tau at the same instants, shape (M, n).
    """
    X = np.asarray(theta, dtype=float)
    if X.shape[0] % 2 == 0:  # an odd count: no Nyquist term, whose derivative is undefined
        X = trig_interpolate(X, X.shape[0] + 1)
    return X, periodic_rates(X, model.dl.period)[0]
