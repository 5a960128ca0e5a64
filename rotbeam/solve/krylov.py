"""Restarted GMRES with a left preconditioner: the linear solve inside the collocation's Newton.

The algorithm and its tolerance control are scipy's `scipy.sparse.linalg.gmres` (scipy 1.12+,
itself after the Templates' GMRESREVCOM); the Arnoldi step orthogonalises with two matrix
products against the basis (classical Gram-Schmidt, repeated when the first pass cancels, the
"twice is enough" rule) and the Givens rotations run on Python floats, so that one iteration
costs its matrix-vector product and preconditioner solve and little else (docs/numerics.md,
"The periodic orbit").
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

#: a second Gram-Schmidt pass runs when the first leaves less than this part of the vector's
#: norm (Daniel, Gragg, Kaufman and Stewart 1976: 1 / sqrt 2)
REORTHOGONALISE = 1.0 / math.sqrt(2.0)


@dataclass(frozen=True)
class KrylovResult:
    """What `gmres` returns: the solution and whether it met its tolerance."""

    x: np.ndarray  #: the last iterate, shape (n,)
    iterations: int  #: Arnoldi steps taken over all restarts
    converged: bool  #: ||b - A x|| <= rtol ||b|| (the true residual, not the preconditioned)
    residual: float  #: ||b - A x|| / ||b|| at the last restart (0 for b = 0)


def gmres(
    matvec: Callable[[np.ndarray], np.ndarray],
    psolve: Callable[[np.ndarray], np.ndarray],
    b: np.ndarray,
    rtol: float = 1e-5,
    restart: int = 20,
    maxiter: int = 10,
) -> KrylovResult:
    """Solve A x = b by GMRES(restart) preconditioned on the left by P (P^-1 A x = P^-1 b).

    The inner iteration stops where the preconditioned residual estimate is below its share of
    the tolerance; each restart then measures the true residual and tightens or relaxes that
    share as scipy's gmres does, so that the answer meets ||b - A x|| <= rtol ||b|| when
    `converged`.

    Parameters
    ----------
    matvec : callable
        matvec(v) -> A v, shapes (n,) -> (n,).
    psolve : callable
        psolve(r) -> P^-1 r, shapes (n,) -> (n,): the preconditioner's solve.
    b : numpy.ndarray
        Right-hand side, shape (n,), real.
    rtol : float
        Relative tolerance of the true residual, in (0, 1).
    restart : int
        Arnoldi steps between restarts (at most n).
    maxiter : int
        Restarts at most.

    Returns
    -------
    KrylovResult
        x from x0 = 0, the Arnoldi steps taken, whether ||b - A x|| <= rtol ||b||, and the last
        measured relative residual.
    """
    b = np.asarray(b, dtype=float)
    n = b.size
    bnorm = float(np.linalg.norm(b))
    x = np.zeros(n)
    if bnorm == 0.0:
        return KrylovResult(x, 0, True, 0.0)
    atol = rtol * bnorm
    eps = float(np.finfo(float).eps)
    restart = min(restart, n)
    ptol_factor = 1.0
    ptol = float(np.linalg.norm(psolve(b))) * min(ptol_factor, rtol)
    V = np.empty((restart + 1, n))
    r, rnorm, total = b.copy(), bnorm, 0
    for _ in range(maxiter):
        steps, presid, breakdown = _arnoldi_cycle(matvec, psolve, r, V, ptol, eps)
        total += steps.count
        x += steps.solution() @ V[: steps.count]
        r = b - matvec(x)
        rnorm = float(np.linalg.norm(r))
        if rnorm <= atol or breakdown:
            break
        if presid <= ptol:  # the inner estimate passed but the true residual did not
            ptol_factor = max(eps, 0.25 * ptol_factor)
        else:
            ptol_factor = min(1.0, 1.5 * ptol_factor)
        ptol = presid * min(ptol_factor, atol / rnorm)
    return KrylovResult(x, total, rnorm <= atol, rnorm / bnorm)


class _Hessenberg:
    """The least-squares problem of one Arnoldi cycle, kept triangular by Givens rotations as
    the columns arrive (Python floats: the cycle's columns are short)."""

    def __init__(self, beta: float) -> None:
        self.R: list[list[float]] = []  #: the rotated columns, column j of length j + 1
        self.rotations: list[tuple[float, float]] = []
        self.g = [beta]  #: the rotated right-hand side beta e_1

    @property
    def count(self) -> int:
        """Columns taken so far."""
        return len(self.R)

    def add(self, column: list[float], below: float) -> float:
        """Append the column (h_0j .. h_jj) with subdiagonal `below`; return the residual norm
        estimate |g_{j+1}|."""
        for k, (c, s) in enumerate(self.rotations):
            column[k], column[k + 1] = (
                c * column[k] + s * column[k + 1],
                -s * column[k] + c * column[k + 1],
            )
        top = column[-1]
        mag = math.hypot(top, below)
        c, s = (1.0, 0.0) if mag == 0.0 else (top / mag, below / mag)
        column[-1] = mag
        self.rotations.append((c, s))
        self.R.append(column)
        gj = self.g[-1]
        self.g[-1] = c * gj
        self.g.append(-s * gj)
        return abs(self.g[-1])

    def solution(self) -> np.ndarray:
        """y minimising ||beta e_1 - H y||: back substitution on the rotated columns (a zero
        pivot leaves its component 0, a pseudo-solve as scipy's)."""
        m = self.count
        R = np.zeros((m, m))
        for j, column in enumerate(self.R):
            R[: j + 1, j] = column
        g = np.array(self.g[:m])
        if np.all(np.diag(R) != 0.0):
            return sla.solve_triangular(R, g, check_finite=False)
        y = np.zeros(m)
        for i in range(m - 1, -1, -1):
            if R[i, i] != 0.0:
                y[i] = (g[i] - R[i, i + 1 :] @ y[i + 1 :]) / R[i, i]
        return y


def _arnoldi_cycle(matvec, psolve, r, V, ptol, eps) -> tuple[_Hessenberg, float, bool]:
    """One cycle from the residual r: the basis in V's rows, the triangular problem, the last
    preconditioned residual estimate, and whether the Krylov space became invariant (the
    exact solution lies in it)."""
    v0 = psolve(r)
    beta = float(np.linalg.norm(v0))
    V[0] = v0 / beta
    hess = _Hessenberg(beta)
    presid, breakdown = beta, False
    for j in range(V.shape[0] - 1):
        w = psolve(matvec(V[j]))
        w_norm = float(np.linalg.norm(w))
        basis = V[: j + 1]
        h = basis @ w
        w -= h @ basis
        below = float(np.linalg.norm(w))
        if below < REORTHOGONALISE * w_norm:
            dh = basis @ w
            w -= dh @ basis
            h += dh
            below = float(np.linalg.norm(w))
        breakdown = below <= eps * w_norm
        V[j + 1] = w if breakdown else w / below
        presid = hess.add(h.tolist(), 0.0 if breakdown else below)
        if presid <= ptol or breakdown:
            break
    return hess, presid, breakdown
