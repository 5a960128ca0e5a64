"""The discrete elastica's time stepping compiled with numba: the first-order right-hand side
and its tangent J v (the kernel of `DiscreteElastica.acceleration` and
`DiscreteModel.first_order_jvp`), and the embedded Runge-Kutta method of Dormand and Prince
of order 8(5, 3) around it (scipy's `DOP853`: its tableau, error norm and step control).

Imported only where a run uses it (`DiscreteElastica.kernel`), so that numba loads with the
first time-stepped run and never with a command that does not step.  Both live in
this one file because numba's cache tracks the file of the function it compiles, not the files
of the functions it calls.  Which models the kernel covers, how it is checked against the numpy
model, and what it gains: docs/stability.md, "What a classification period costs".
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import dop853_table as _dop

_S = _dop.N_STAGES  # 12 stages, and the last stage's f at the new point for the error estimate
_A = np.ascontiguousarray(_dop.A)
_B = np.ascontiguousarray(_dop.B)
_C = np.ascontiguousarray(_dop.C)
_E3 = np.ascontiguousarray(_dop.E3)
_E5 = np.ascontiguousarray(_dop.E5)
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0
_EXPONENT = -1.0 / 8.0  # -1 / (error estimator order 7 + 1)

#: the kernel's flags and numbers, in `par`
X0, HUB, ETA, LAM0, CENTRIFUGAL, SOFTENING, EULER, CORIOLIS, ROTARY = range(9)


@njit(cache=True)
def _drive(t, par, harm, knots, cubic):
    """lam and lam_dot: with knots, the piecewise cubic cubic[:, k] on [knots[k], knots[k+1]]
    (scipy's `PPoly` form, as `MoveLaw`'s spline), its end values outside; else lam0 + sum
    alpha_k sin(k omega t + phase_k), as `HarmonicLaw`."""
    if knots.size:
        last = knots.size - 2
        x = min(max(t, knots[0]), knots[last + 1])
        k = 0
        while k < last and x >= knots[k + 1]:
            k += 1
        d = x - knots[k]
        lam = ((cubic[0, k] * d + cubic[1, k]) * d + cubic[2, k]) * d + cubic[3, k]
        lam_dot = 0.0
        if knots[0] <= t <= knots[last + 1]:
            lam_dot = (3.0 * cubic[0, k] * d + 2.0 * cubic[1, k]) * d + cubic[2, k]
        return lam, lam_dot
    lam = par[LAM0]
    lam_dot = 0.0
    for r in range(harm.shape[0]):
        lam = lam + harm[r, 1] * math.sin(harm[r, 0] * t + harm[r, 2])
    for r in range(harm.shape[0]):
        lam_dot = lam_dot + harm[r, 1] * harm[r, 0] * math.cos(harm[r, 0] * t + harm[r, 2])
    return lam, lam_dot


@njit(cache=True)
def _lu(A, piv):
    """LU factors of A in place, partial pivoting."""
    n = A.shape[0]
    for k in range(n):
        p = k
        big = abs(A[k, k])
        for i in range(k + 1, n):
            if abs(A[i, k]) > big:
                big, p = abs(A[i, k]), i
        piv[k] = p
        if p != k:
            for j in range(n):
                A[k, j], A[p, j] = A[p, j], A[k, j]
        for i in range(k + 1, n):
            A[i, k] /= A[k, k]
            f = A[i, k]
            for j in range(k + 1, n):
                A[i, j] -= f * A[k, j]


@njit(cache=True)
def _lu_solve(A, piv, b):
    """b <- A^-1 b from `_lu`'s factors."""
    n = A.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            b[k], b[p] = b[p], b[k]
    for i in range(n):
        acc = b[i]
        for j in range(i):
            acc -= A[i, j] * b[j]
        b[i] = acc
    for i in range(n - 1, -1, -1):
        acc = b[i]
        for j in range(i + 1, n):
            acc -= A[i, j] * b[j]
        b[i] = acc / A[i, i]


@njit(cache=True)
def rates(t, y, out, tangent, W, K, P, Q, par, harm, knots, cubic, Wd, Phi):
    """out <- (Theta_t, Theta_tt) of the state y[:2n], and with `tangent` also
    J (p, q) of the direction y[2n:4n] in out[2n:4n]; with modes Phi, (q_t, q_tt) of the
    modal state y = (q, q_t), the residual projected on Phi (`ModalModel`, no tangent).

    One function of ~110 lines by design: the state's rates and the tangent's share every
    intermediate sum of one compiled pass (split, each part would recompute them).

    Parameters
    ----------
    t : float
        tau.
    y : numpy.ndarray
        (Theta, Theta_t), or (Theta, Theta_t, p, q) with `tangent`; with modes, (q, q_t).
    out : numpy.ndarray
        The rates, the shape of y.
    tangent : bool
        Whether y carries a direction (never with modes or a payload).
    W, K, P, Q : numpy.ndarray
        The grid's operators (`Grid`).
    par : numpy.ndarray
        x0, hub ratio, eta, lam0, the effects centrifugal, softening, euler, coriolis (1.0
        on, 0.0 off) and a payload's rotary inertia j / ds, at the indices X0 .. ROTARY.
    harm : numpy.ndarray
        (k omega, alpha_k, phase_k) of the drive's harmonics, shape (m, 3).
    knots, cubic : numpy.ndarray
        A move's spline (`_drive`): breakpoints (k + 1,) and coefficients (4, k); knots of
        size 0 for a drive of harmonics.
    Wd : numpy.ndarray
        The matrix the damping's mass is made of with a payload (`damping_rows`), shape (n, n);
        shape (0, 0): the damping acts on M.
    Phi : numpy.ndarray
        The modes of a modal model, shape (n, m); shape (n, 0): the full model.
    """
    n = W.shape[0]
    nn = P.shape[0]
    m = Phi.shape[1]
    lam, lam_dot = _drive(t, par, harm, knots, cubic)
    lam2 = lam * lam
    hub, eta = par[HUB], par[ETA]
    cen, soft = par[CENTRIFUGAL] != 0.0, par[SOFTENING] != 0.0
    eul, cor = par[EULER] != 0.0, par[CORIOLIS] != 0.0
    th = np.empty(n)
    tht = np.empty(n)
    if m:
        for i in range(n):
            a = 0.0
            b = 0.0
            for k in range(m):
                a += Phi[i, k] * y[k]
                b += Phi[i, k] * y[m + k]
            th[i] = a
            tht[i] = b
    else:
        th[:] = y[:n]
        tht[:] = y[n : 2 * n]
    c = np.empty(n)
    s = np.empty(n)
    for i in range(n):
        c[i] = math.cos(th[i])
        s[i] = math.sin(th[i])
    M = np.empty((n, n))
    B = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            M[i, j] = c[i] * W[i, j] * c[j] + s[i] * W[i, j] * s[j]
            B[i, j] = s[i] * W[i, j] * c[j] - c[i] * W[i, j] * s[j]
    M[n - 1, n - 1] += par[ROTARY]
    fx = np.zeros(nn)
    fy = np.zeros(nn)
    for k in range(nn):
        xk = par[X0]
        yk = 0.0
        for j in range(n):
            xk += P[k, j] * c[j]
            yk += P[k, j] * s[j]
        if cen:
            fx[k] += lam2 * (hub + xk)
            if soft:
                fy[k] += lam2 * yk
        if eul:
            fx[k] += lam_dot * yk
            fy[k] -= lam_dot * (hub + xk)
    nx = Q @ fx
    ny = Q @ fy
    v = np.empty(n)  # what B multiplies: Theta_t^2 (+ 2 lam Theta_t)
    for i in range(n):
        w = tht[i]
        v[i] = w * w + (2.0 * lam * w if cor else 0.0)
    a0 = np.empty(n)
    for i in range(n):
        acc = -(s[i] * nx[i] - c[i] * ny[i])
        for j in range(n):
            acc -= K[i, j] * th[j] + B[i, j] * v[j]
        a0[i] = acc
    if eul:  # the payload's rotary inertia turns with the disk
        a0[n - 1] -= par[ROTARY] * lam_dot
    own = Wd.shape[0] > 0  # the damping's own mass (a payload's is undamped)
    if own:
        for i in range(n):
            acc = 0.0
            for j in range(n):
                acc += (c[i] * c[j] + s[i] * s[j]) * Wd[i, j] * tht[j]
            a0[i] -= eta * acc
    damp = 0.0 if own else eta
    k = m if m else n  # the unknowns solved for: q_tt, or Theta_tt
    if m:  # Phi' M Phi q_tt = Phi' a0: the Galerkin projection
        MPhi = M @ Phi
        LU = np.ascontiguousarray(Phi.T @ MPhi)
        rhs = Phi.T @ a0
    else:
        LU = M.copy()
        rhs = a0
    piv = np.empty(k, dtype=np.int64)
    _lu(LU, piv)
    _lu_solve(LU, piv, rhs)
    for i in range(k):
        out[i] = y[k + i]
        out[k + i] = rhs[i] - damp * y[k + i]
    if m or not tangent:
        return
    # J (p, q) = (q, M^-1 (dr p - dv q) - eta q): docs/stability.md, "The tangent without the
    # Jacobian"; dL p = S W (a p) - C W (b p) + (C n_x + S n_y) p
    d = 2 * n
    ap = np.empty(n)
    bp = np.empty(n)
    for j in range(n):
        a = 0.0
        b = 0.0
        if cen:
            a -= lam2 * s[j]
            if soft:
                b += lam2 * c[j]
        if eul:
            a += lam_dot * c[j]
            b += lam_dot * s[j]
        ap[j] = a * y[d + j]
        bp[j] = b * y[d + j]
    r = np.empty(n)
    for i in range(n):
        p = y[d + i]
        acc = -(c[i] * nx[i] + s[i] * ny[i]) * p
        mv = 0.0
        ba = 0.0
        for j in range(n):
            acc -= K[i, j] * y[d + j] + s[i] * W[i, j] * ap[j] - c[i] * W[i, j] * bp[j]
            pj = y[d + j]
            qj = y[d + n + j]
            acc += M[i, j] * v[j] * pj - B[i, j] * a0[j] * pj
            acc -= 2.0 * B[i, j] * y[n + j] * qj + (2.0 * lam * B[i, j] * qj if cor else 0.0)
            mv += M[i, j] * v[j]
            ba += B[i, j] * a0[j]
        r[i] = acc + (ba - mv) * p
    _lu_solve(LU, piv, r)
    for i in range(n):
        out[d + i] = y[d + n + i]
        out[d + n + i] = r[i] - eta * y[d + n + i]


@njit(cache=True)
def _rms(x):
    return math.sqrt(np.sum(x * x) / x.size)


@njit(cache=True)
def _initial_step(t, y, f, t_end, rtol, atol, tangent, model):
    """scipy's `select_initial_step` for order 7 (Hairer, Norsett and Wanner, II.4)."""
    length = abs(t_end - t)
    scale = atol + np.abs(y) * rtol
    d0 = _rms(y / scale)
    d1 = _rms(f / scale)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, length)
    f1 = np.empty(y.size)
    rates(t + h0, y + h0 * f, f1, tangent, *model)
    d2 = _rms((f1 - f) / scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, length)


@njit(cache=True)
def advance(y, stops, h, rtol, atol, tangent, model, saved, counts):
    """DOP853 from stops[0] through every later stop, as scipy's `DOP853` steps.

    One loop of ~70 lines by design: step, error norm, step-size control and the stops in
    one compiled loop, so that no Python runs between steps.

    Parameters
    ----------
    y : numpy.ndarray
        The state (with `tangent`, state and direction) at stops[0]; overwritten with the one
        at the last stop reached.
    stops : numpy.ndarray
        Increasing instants; a step never crosses one.
    h : float
        The first step to try; <= 0: scipy's initial-step estimate.
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances, the shape of y.
    tangent : bool
        Whether y carries a direction (`rates`).
    model : tuple
        What `rates` reads after `tangent`: W, K, P, Q, par, harm, knots, cubic, Wd, Phi.
    saved : numpy.ndarray
        saved[k - 1] <- y at stops[k], shape (stops.size - 1, y.size).
    counts : numpy.ndarray
        counts[0:3] += right-hand-side evaluations, accepted steps, rejected steps.

    Returns
    -------
    status : int
        0 when every stop was reached; k > 0 when the step fell below scipy's minimum (10
        spacings of doubles at t) in the interval ending at stops[k].
    h : float
        The step the controller proposes next.
    """
    d = y.size
    Ks = np.zeros((_S + 1, d))
    f = np.empty(d)
    rates(stops[0], y, f, tangent, *model)
    counts[0] += 1
    t = stops[0]
    if h <= 0.0:
        h = _initial_step(t, y, f, stops[stops.size - 1], rtol, atol, tangent, model)
        counts[0] += 1
    y_new = np.empty(d)
    dy = np.empty(d)
    for k in range(1, stops.size):
        t_end = stops[k]
        while t < t_end:
            min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
            h = max(h, min_step)
            rejected = False
            while True:
                if h < min_step:
                    return k, h
                t_new = min(t + h, t_end)
                clipped = t + h > t_end
                step = t_new - t
                Ks[0] = f
                for st in range(1, _S):
                    dy[:] = 0.0
                    for j in range(st):
                        dy += _A[st, j] * Ks[j]
                    rates(t + _C[st] * step, y + step * dy, Ks[st], tangent, *model)
                dy[:] = 0.0
                for j in range(_S):
                    dy += _B[j] * Ks[j]
                y_new[:] = y + step * dy
                rates(t_new, y_new, Ks[_S], tangent, *model)
                counts[0] += _S
                e5 = 0.0
                e3 = 0.0
                for i in range(d):
                    sc = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
                    x5 = 0.0
                    x3 = 0.0
                    for j in range(_S + 1):
                        x5 += _E5[j] * Ks[j, i]
                        x3 += _E3[j] * Ks[j, i]
                    e5 += (x5 / sc) ** 2
                    e3 += (x3 / sc) ** 2
                if e5 == 0.0 and e3 == 0.0:
                    err = 0.0
                else:
                    err = step * e5 / math.sqrt((e5 + 0.01 * e3) * d)
                if err < 1.0:
                    factor = (
                        _MAX_FACTOR if err == 0.0 else min(_MAX_FACTOR, _SAFETY * err**_EXPONENT)
                    )
                    if rejected:
                        factor = min(1.0, factor)
                    # a step cut short by a stop leaves the controller's proposal standing
                    h = h if clipped else step * factor
                    counts[1] += 1
                    break
                fac = _SAFETY * err**_EXPONENT
                h = step * (fac if fac > _MIN_FACTOR else _MIN_FACTOR)  # NaN error: MIN_FACTOR
                rejected = True
                counts[2] += 1
            t = t_new
            y[:] = y_new
            f[:] = Ks[_S]
        saved[k - 1] = y
    return 0, h
