"""Floquet multipliers from a collocation of the variational equation on equal intervals: the
product of the intervals' propagators (what a condensation of that collocation's Jacobian gives).

Radau IIA collocation is L-stable: the stiff bending modes, which it does not resolve, go to
zero, below the resolved slow modes that carry |mu|max; its |mu|max converges smoothly once
the intervals sample J(t) finely, where the exponential product's step ladder climbs to
hundreds of steps.  Its fixed-point offset misses the stiff part, so the certificate keeps the
exponentials (`rotbeam.solve.floquet`).  Gauss collocation (|R| -> 1 on the imaginary axis)
puts the stiff modes on the unit circle.  Derivation and measurements: docs/stability.md,
"Multipliers from a collocation".
"""

from __future__ import annotations

import math
import time
from typing import Literal

import numpy as np
from numpy.polynomial import legendre

from ..config.parameters import default
from ..model.base import DiscreteModel
from .floquet import FloquetResult, _product, beam_floquet, radius_of, trig_eval
from .timebudget import check_deadline

#: collocation points an interval (order 2 s of Gauss, 2 s - 1 of Radau IIA)
STAGES = 4
Kind = Literal["gauss", "radau"]


def collocation_tableau(
    kind: Kind, stages: int = STAGES
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The nodes, the integration matrix and the weights of s-point collocation on [0, 1].

    Parameters
    ----------
    kind : {"gauss", "radau"}
        Gauss-Legendre nodes (A-stable, |R(z)| -> 1 as z -> infinity along the imaginary axis)
        or Radau IIA nodes, the last at 1 (L-stable, R(z) -> 0).
    stages : int
        Collocation points an interval, >= 1.

    Returns
    -------
    c : numpy.ndarray
        The nodes, shape (s,), increasing in (0, 1].
    A : numpy.ndarray
        a_ij = int_0^{c_i} l_j(t) dt with l_j the Lagrange polynomials of the nodes, shape
        (s, s).
    b : numpy.ndarray
        The weights b_j = int_0^1 l_j(t) dt, shape (s,): A's last row for Radau.
    """
    if kind == "radau":  # roots of P_s - P_{s-1} on [-1, 1], the last at 1
        coef = np.zeros(stages + 1)
        coef[stages], coef[stages - 1] = 1.0, -1.0
        x = np.sort(np.real(legendre.legroots(coef)))
    else:
        x = legendre.leggauss(stages)[0]
    c = (x + 1.0) / 2.0
    A = np.zeros((stages, stages + 1))  # the last column: int_0^1 l_j, the weights b
    for j in range(stages):
        others = np.delete(c, j)
        primitive = np.polyint(np.poly1d(others, r=True) / np.prod(c[j] - others))
        A[:, j] = primitive(c) - primitive(0.0)
        A[j, stages] = primitive(1.0) - primitive(0.0)
    return c, A[:, :stages], A[:, stages]


def collocated_monodromy(
    model: DiscreteModel,
    theta: np.ndarray,
    theta_t: np.ndarray,
    intervals: int,
    kind: Kind = "radau",
    stages: int = STAGES,
) -> tuple[np.ndarray, np.ndarray]:
    """The monodromy and one-period defect of a collocated orbit by s-point collocation of its
    variational equation on equal intervals: the product of the intervals' propagators.

    Each interval's stage rates solve one system of s n, the angles eliminated
    (docs/stability.md, "Multipliers from a collocation").

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive; the period is its `dl.period`.
    theta, theta_t : numpy.ndarray
        The orbit at M equispaced instants of the period, the first at tau = 0, shape (M, n).
    intervals : int
        Equal intervals over the period.
    kind : {"gauss", "radau"}
        The collocation nodes (`collocation_tableau`).
    stages : int
        Collocation points an interval.

    Returns
    -------
    Phi : numpy.ndarray
        The monodromy, shape (2 n, 2 n).
    defect : numpy.ndarray
        The one-period defect of the orbit's interpolant, shape (2 n,).
    """
    n, period = model.n, model.dl.period
    h = period / intervals
    c, A, b = collocation_tableau(kind, stages)
    t = ((np.arange(intervals)[:, None] + c[None, :]) * h).ravel()
    Z = np.concatenate([theta, theta_t], axis=1)
    Zs = trig_eval(Z, period, t)
    lam, lam_dot = model.drive_rows(t)
    F, J = model.first_order_rows(Zs[:, :n], Zs[:, n:], lam, lam_dot)
    g = (F[:, n:] - trig_eval(Z, period, t, derivative=1)[:, n:]).reshape(intervals, stages, n)
    Xq = J[:, n:, :n].reshape(intervals, stages, n, n)
    Xv = J[:, n:, n:].reshape(intervals, stages, n, n)
    # blocks (i, k) of h A X_v + h^2 A X_q A: a_ik X_v,k and sum_j a_ij a_jk X_q,j
    AA = (A[:, :, None] * A[None, :, :]).transpose(0, 2, 1)  # AA[i, k, j] = a_ij a_jk
    quad = np.tensordot(Xq, AA, axes=([1], [2])).transpose(0, 3, 4, 1, 2)  # (., i, k, n, n)
    blocks = h * A[None, :, :, None, None] * Xv[:, None, :, :, :] + h * h * quad
    G = -blocks.transpose(0, 1, 3, 2, 4).reshape(intervals, stages * n, stages * n)
    G[:, np.arange(stages * n), np.arange(stages * n)] += 1.0
    AXq = A[None, :, :, None, None] * Xq[:, None, :, :, :]  # a_ij X_q,j
    rhs = np.zeros((intervals, stages, n, 2 * n + 1))
    rhs[..., :n] = h * AXq.sum(axis=2)
    rhs[:, :, np.arange(n), n + np.arange(n)] = 1.0
    rhs[..., 2 * n] = h * np.einsum("ij,kja->kia", A, g)
    V = np.linalg.solve(G, rhs.reshape(intervals, stages * n, 2 * n + 1))
    V = V.reshape(intervals, stages, n, 2 * n + 1)
    start_q = np.zeros((n, 2 * n + 1))
    start_q[:, :n] = np.eye(n)
    start_v = np.zeros((n, 2 * n + 1))
    start_v[:, n : 2 * n] = np.eye(n)
    Q = start_q + h * np.einsum("ij,kjab->kiab", A, V)  # the stage angles
    acc = Xq @ Q + Xv @ V
    acc[..., 2 * n] += g
    steps = np.zeros((intervals, 2 * n + 1, 2 * n + 1))  # augmented, as the exponentials
    steps[:, :n] = start_q + h * np.einsum("i,kiab->kab", b, V)
    steps[:, n : 2 * n] = start_v + h * np.einsum("i,kiab->kab", b, acc)
    steps[:, 2 * n, 2 * n] = 1.0
    return _product(steps)


#: the interval counts `collocated_multipliers` takes in turn, each checked against the one
#: before, from the first whose 4 n collocation points are at least the orbit's M instants
COLLOCATION_INTERVALS = (16, 32, 64, 128, 256, 512, 1024)

#: the largest intervals x angles a count may have: 128 intervals at N = 40, 256 at N = 20, 1024
#: at N = 6 (measured on one core: 0.20, 0.10 and 0.11 s a product, against 0.58, 0.11 and
#: 0.03 s for the exponential ladder's 1012 steps)
COLLOCATION_WORK = 8192

#: how far (relative) |mu|max must stand above exp(-c P / 2), the modulus every mode of a
#: uniformly damped beam shares but for its orbit's coupling, for the collocation to report it:
#: a mode the collocation does not resolve lies in that cluster (docs/stability.md)
CLUSTER_MARGIN = 1e-4

#: how the result says where its multipliers come from
COLLOCATED_METHOD = "Radau IIA collocation (4 points an interval): stiff modes annihilated"


def uniform_decay(model: DiscreteModel) -> float | None:
    """exp(-c P / 2), the modulus every Floquet multiplier of the straight beam shares, when the
    model's damping is c times its mass; None when it is not (a payload's damping, which leaves
    out the tip mass, is not).

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.

    Returns
    -------
    float or None
        The shared modulus over one drive period (1 without damping), or None.
    """
    _, damping, mass = model.straight_blocks(float(model.dl.lam0))
    c = float(np.trace(damping) / np.trace(mass))
    if np.max(np.abs(damping - c * mass)) > 1e-12 * np.max(np.abs(mass)):
        return None
    return math.exp(-0.5 * c * model.dl.period)


def above_cluster(decay: float | None, radius: float) -> bool:
    """Whether a |mu|max stands more than CLUSTER_MARGIN above `uniform_decay`, the cluster in
    which a mode the collocation does not resolve may lie (False where the damping is not
    uniform and no cluster is known).

    Parameters
    ----------
    decay : float or None
        The model's `uniform_decay` (None: not uniformly damped).
    radius : float
        A |mu|max, or a bound on it.

    Returns
    -------
    bool
        True where the collocation's |mu|max can be reported.
    """
    return decay is not None and radius >= decay * (1.0 + CLUSTER_MARGIN)


def collocated_multipliers(
    model: DiscreteModel,
    theta: np.ndarray,
    theta_t: np.ndarray,
    mu_tol: float = default("numerics", "floquet_tol"),
) -> FloquetResult | None:
    """|mu|max of a collocated orbit by Radau IIA collocation, resolved to `mu_tol`: the interval
    counts of COLLOCATION_INTERVALS in turn (up to COLLOCATION_WORK intervals x angles), each
    kept when its |mu|max and the count's before it differ by at most `mu_tol` and a tenth of
    its distance from 1.

    The collocation annihilates the modes it does not resolve.  Its |mu|max is therefore
    reported only where it stands above the cluster those modes lie in (`above_cluster`: more
    than CLUSTER_MARGIN above `uniform_decay`, for a uniformly damped model, where that cluster
    is known).  The result carries no defect: the offset of an L-stable product misses
    the stiff modes' part, so it is no certificate (docs/stability.md, "Multipliers from a
    collocation").

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    theta, theta_t : numpy.ndarray
        The orbit at M equispaced instants of the period, the first at tau = 0, shape (M, n).
    mu_tol : float
        How closely |mu|max is resolved (`Numerics.floquet_tol`).

    Returns
    -------
    FloquetResult or None
        The kept product (`radius` its |mu|max, `coarse` the count before it, `method`
        COLLOCATED_METHOD, `steps` its intervals); None when no two counts agree, the kept
        |mu|max lies within the cluster, the damping is not uniform or the orbit has more
        instants than 4 points an interval can take (the caller goes on with the exponential
        product).
    """
    t0 = time.perf_counter()
    decay = uniform_decay(model)
    if decay is None:
        return None
    previous = None
    for count in COLLOCATION_INTERVALS:
        if 4 * count < theta.shape[0]:
            continue
        if count * model.n > COLLOCATION_WORK:
            break
        check_deadline()
        Phi, _ = collocated_monodromy(model, theta, theta_t, count)
        current = radius_of(Phi, count)
        current.method = COLLOCATED_METHOD
        if previous is not None:
            current.coarse = previous
            if current.spread <= min(mu_tol, 0.1 * abs(1.0 - current.max_abs)):
                if not above_cluster(decay, current.max_abs):
                    return None
                current.seconds = time.perf_counter() - t0
                return current
        previous = current
    return None


def resolved_multipliers(
    model: DiscreteModel,
    theta: np.ndarray,
    theta_t: np.ndarray,
    mu_tol: float = default("numerics", "floquet_tol"),
) -> FloquetResult:
    """The multipliers of a periodic orbit given by its samples, |mu|max resolved to `mu_tol`,
    where no fixed-point offset is asked for (a branch point, an orbit time stepping settled on).

    They are the Radau collocation's where its |mu|max stands above the cluster
    (`collocated_multipliers`), else the exponential ladder's (`beam_floquet`).  The ladder
    still compares the offsets of two step counts: inside the cluster two counts can agree on
    |mu|max and both miss it by more than `mu_tol`, and the offsets tell (docs/stability.md,
    "Multipliers from a collocation").

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    theta, theta_t : numpy.ndarray
        The orbit at M equispaced instants of the period, the first at tau = 0, shape (M, n).
    mu_tol : float
        How closely |mu|max is resolved (`Numerics.floquet_tol`).

    Returns
    -------
    FloquetResult
        The multipliers (with the orbit's defect, where they come from the exponentials).
    """
    collocated = collocated_multipliers(model, theta, theta_t, mu_tol)
    if collocated is not None:
        return collocated
    return beam_floquet(model, theta, theta_t, mu_tol=mu_tol)
