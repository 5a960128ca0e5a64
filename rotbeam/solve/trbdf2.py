# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, rotbeam contributors.  The helpers below "Helpers of scipy's own implicit
# solvers" (validate_first_step, validate_max_step, warn_extraneous, validate_tol, norm,
# select_initial_step, num_jac) are adapted from SciPy (scipy/integrate/_ivp/common.py, SciPy
# 1.17), Copyright (c) 2001-2002 Enthought, Inc. 2003, SciPy Developers, BSD-3-Clause: see
# LICENSES/scipy.txt.
"""TR-BDF2: a one-step, second-order, L-stable implicit integrator for `solve_ivp`.

This is the method of MATLAB's ode23tb (M. E. Hosea and L. F. Shampine, "Analysis and
implementation of TR-BDF2", Appl. Numer. Math. 20 (1996) 21-37), written as a
`scipy.integrate.OdeSolver` so that ``solve_ivp(fun, t_span, y0, method=TRBDF2, ...)`` behaves
like ``method="Radau"`` (same options, status, message, nfev/njev/nlu, dense output, t_eval).
A step needs one real n x n LU per step size and about five f evaluations; being second order
it suits modest accuracies.  The method, its derivation, error estimate and step control:
docs/numerics.md, "TR-BDF2".
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any
from warnings import warn

import numpy as np
from scipy.integrate import DenseOutput, OdeSolver
from scipy.linalg import lu_factor, lu_solve
from scipy.sparse import issparse

GAMMA = 2.0 - np.sqrt(2.0)  #: TR stage ends at t_n + GAMMA h
D = GAMMA / 2.0  #: diagonal coefficient of both stages
A_Z = 1.0 / (GAMMA * (2.0 - GAMMA))  #: BDF2 weight of z
A_Y = -((1.0 - GAMMA) ** 2) / (GAMMA * (2.0 - GAMMA))  #: BDF2 weight of y_n
W = A_Z * D  #: RK weight of f_n and f_z (sqrt(2)/4)
#: local error estimate e = h (E_N f_n + E_Z f_z + E_1 f_{n+1}) (Hosea & Shampine)
E_N, E_Z, E_1 = (4.0 * W - 1.0) / 3.0, -1.0 / 3.0, 2.0 * D / 3.0

NEWTON_MAXITER = 4  #: simplified Newton iterations per stage
MIN_FACTOR = 0.2  #: smallest step-size ratio
MAX_FACTOR = 5.0  #: largest step-size ratio
SAFETY = 0.9


def stability_function(z: complex | np.ndarray) -> complex | np.ndarray:
    """The stability function R(z), y_{n+1} = R(h lambda) y_n for y' = lambda y (for checks of
    the coefficients).

    Parameters
    ----------
    z : complex or numpy.ndarray
        h lambda, any shape.

    Returns
    -------
    complex or numpy.ndarray
        R(z) = (A_Z (1 + D z) / (1 - D z) + A_Y) / (1 - D z), complex, the shape of z.
    """
    z = np.asarray(z, dtype=complex)
    tr = (1.0 + D * z) / (1.0 - D * z)
    return (A_Z * tr + A_Y) / (1.0 - D * z)


def _newton(
    fun: Callable[[float, np.ndarray], np.ndarray],
    t: float,
    psi: np.ndarray,
    dh: float,
    x0: np.ndarray,
    LU: Any,
    scale: np.ndarray,
    tol: float,
    rate0: float | None = None,
) -> tuple[bool, int, np.ndarray, float | None]:
    """Solve x - dh f(t, x) = psi by simplified Newton with a fixed LU of I - dh J.

    Same rate-based convergence test as scipy's Radau.  `rate0`, the rate seen earlier with
    the same LU, lets the first iteration be accepted if its correction is 10 times below the
    tolerance (as ode23tb does).  Returns (converged, iterations, x, rate).
    """
    x = x0.copy()
    dx_norm_old = None
    rate = None
    converged = False
    k = 0
    for k in range(NEWTON_MAXITER):
        fx = fun(t, x)
        if not np.all(np.isfinite(fx)):
            break
        dx = lu_solve(LU, psi + dh * fx - x, overwrite_b=True)
        dx_norm = norm(dx / scale)
        if dx_norm_old is not None:
            rate = dx_norm / dx_norm_old
        if rate is not None and (
            rate >= 1 or rate ** (NEWTON_MAXITER - k) / (1 - rate) * dx_norm > tol
        ):
            break
        x += dx
        if rate is None and rate0 is not None and rate0 < 1:
            if rate0 / (1 - rate0) * dx_norm < 0.1 * tol:
                converged = True
                break
        if dx_norm == 0 or (rate is not None and rate / (1 - rate) * dx_norm < tol):
            converged = True
            break
        dx_norm_old = dx_norm
    return converged, k + 1, x, rate


class HermiteDenseOutput(DenseOutput):
    """Cubic Hermite interpolant on [t_old, t] from the end values and slopes of a step."""

    def __init__(
        self,
        t_old: float,
        t: float,
        y_old: np.ndarray,
        f_old: np.ndarray,
        y: np.ndarray,
        f: np.ndarray,
    ) -> None:
        super().__init__(t_old, t)
        self.h = t - t_old
        self.y_old = y_old
        self.dy = y - y_old
        self.hf_old = self.h * f_old
        self.hf = self.h * f

    def _call_impl(self, t: np.ndarray) -> np.ndarray:
        x = (np.asarray(t) - self.t_old) / self.h
        # y(x) = y0 + x dy + x (1-x) [ (1-x) h f0 - x h f1 + (2x - 1) dy ]
        if x.ndim == 0:
            return (
                self.y_old
                + x * self.dy
                + x * (1 - x) * ((1 - x) * self.hf_old - x * self.hf + (2 * x - 1) * self.dy)
            )
        c = x * (1 - x)
        return (
            self.y_old[:, None]
            + self.dy[:, None] * x
            + self.hf_old[:, None] * (c * (1 - x))
            - self.hf[:, None] * (c * x)
            + self.dy[:, None] * (c * (2 * x - 1))
        )


class TRBDF2(OdeSolver):
    """TR-BDF2 (ode23tb) for stiff problems; use as ``solve_ivp(..., method=TRBDF2)``.

    Options as for Radau: rtol, atol, jac (callable, array or None for finite differences),
    jac_sparsity (a structure for the finite differences: the entries outside it are set to
    zero, all n columns are still differenced; matrices are dense), max_step, first_step,
    vectorized.  Second order, L-stable; one real LU of I - d h J per step size
    (docs/numerics.md, "TR-BDF2").
    """

    def __init__(
        self,
        fun: Callable[[float, np.ndarray], np.ndarray],
        t0: float,
        y0: np.ndarray,
        t_bound: float,
        max_step: float = np.inf,
        rtol: float = 1e-3,
        atol: float | np.ndarray = 1e-6,
        jac: Callable | np.ndarray | None = None,
        jac_sparsity: Any = None,
        vectorized: bool = False,
        first_step: float | None = None,
        **extraneous: Any,
    ) -> None:
        warn_extraneous(extraneous)
        super().__init__(fun, t0, y0, t_bound, vectorized)
        self.y_old = None
        self.max_step = validate_max_step(max_step)
        self.rtol, self.atol = validate_tol(rtol, atol, self.n)
        self.f = self.fun(self.t, self.y)
        if first_step is None:
            self.h_abs = select_initial_step(
                self.fun, self.t, self.y, t_bound, self.max_step, self.f, self.direction,
                2, self.rtol, self.atol,
            )  # fmt: skip
        else:
            self.h_abs = validate_first_step(first_step, t0, t_bound)
        self.newton_tol = max(10 * EPS / rtol, min(0.03, rtol**0.5))
        self.sol = None
        self.jac_factor = None
        self.jac, self.J = self._validate_jac(jac, jac_sparsity)
        self.I = np.identity(self.n)
        self.LU = None  #: LU of I - d h J for h = LU_h
        self.LU_h = None
        self.rate = None
        self.current_jac = True

    def _lu(self, h: float) -> Any:
        """LU of the iteration matrix I - d h J shared by both stages."""
        self.nlu += 1
        return lu_factor(self.I - (D * h) * self.J, overwrite_a=True)

    def _validate_jac(self, jac: Any, sparsity: Any) -> tuple[Callable | None, np.ndarray]:
        """Jacobian as (callable that re-evaluates it or None if constant, dense matrix)."""
        t0, y0 = self.t, self.y
        if jac is None:
            if sparsity is not None:  # a structure only: J is dense (see num_jac below)
                sparsity = sparsity.toarray() if issparse(sparsity) else np.asarray(sparsity)

            def jac_wrapped(t, y, f):
                self.njev += 1
                J, self.jac_factor = num_jac(
                    self.fun_vectorized, t, y, f, self.atol, self.jac_factor, sparsity
                )
                return J.toarray() if issparse(J) else np.asarray(J, dtype=float)

            J = jac_wrapped(t0, y0, self.f)
        elif callable(jac):

            def jac_wrapped(t, y, _=None):
                self.njev += 1
                J = jac(t, y)
                return J.toarray().astype(float) if issparse(J) else np.asarray(J, dtype=float)

            J = jac_wrapped(t0, y0)
        else:
            J = jac.toarray().astype(float) if issparse(jac) else np.asarray(jac, dtype=float)
            jac_wrapped = None
        if J.shape != (self.n, self.n):
            raise ValueError(
                f"`jac` is expected to have shape {(self.n, self.n)}, but actually has {J.shape}."
            )
        return jac_wrapped, J

    def _stages(
        self,
        t: float,
        y: np.ndarray,
        f: np.ndarray,
        h: float,
        LU: Any,
        rate0: float | None = None,
    ) -> tuple[bool, int, float | None, np.ndarray, np.ndarray]:
        """Both implicit stages of one step: (converged, max iterations, last rate, z, y_new)."""
        dh = D * h
        scale = self.atol + self.rtol * np.abs(y)
        # TR predictor: the previous step's interpolant extrapolated (y_n on the first step)
        z0 = y if self.sol is None else self.sol(t + GAMMA * h)
        ok, it1, z, rate1 = _newton(
            self.fun, t + GAMMA * h, y + dh * f, dh, z0, LU, scale, self.newton_tol, rate0
        )
        if not ok:
            return False, it1, rate1, z, y
        rate0 = rate1 if rate1 is not None else rate0
        hfz = (z - y) / D - h * f
        # BDF2 predictor: quadratic through y_n and z with slope f_z at z, taken at t_n + h
        s = 1.0 - GAMMA
        y0 = z + s * hfz + (s / GAMMA) ** 2 * (y - z + GAMMA * hfz)
        ok, it2, y_new, rate2 = _newton(
            self.fun, t + h, A_Z * z + A_Y * y, dh, y0, LU, scale, self.newton_tol, rate0
        )
        return ok, max(it1, it2), rate2 if rate2 is not None else rate0, z, y_new

    def _error(
        self, y: np.ndarray, f: np.ndarray, h: float, z: np.ndarray, y_new: np.ndarray, LU: Any
    ) -> np.ndarray:
        """Stiffness-filtered local error estimate (I - d h J)^-1 e."""
        hf_z = (z - y) / D - h * f
        hf_1 = (y_new - A_Z * z - A_Y * y) / D
        e = E_N * h * f + E_Z * hf_z + E_1 * hf_1
        return lu_solve(LU, e, overwrite_b=True)

    def _step_impl(self) -> tuple[bool, str | None]:
        t, y, f = self.t, self.y, self.f
        max_step, atol, rtol = self.max_step, self.atol, self.rtol
        min_step = 10 * np.abs(np.nextafter(t, self.direction * np.inf) - t)
        h_abs = min(max(self.h_abs, min_step), max_step)
        current_jac = self.current_jac
        rejected = False
        while True:
            if h_abs < min_step:
                return False, self.TOO_SMALL_STEP
            h = h_abs * self.direction
            t_new = t + h
            if self.direction * (t_new - self.t_bound) > 0:
                t_new = self.t_bound
            h = t_new - t
            h_abs = np.abs(h)
            if self.LU is None or h != self.LU_h:
                self.LU, self.LU_h = self._lu(h), h
                self.rate = None  # convergence rate seen with this LU
            converged, n_iter, rate, z, y_new = self._stages(t, y, f, h, self.LU, self.rate)
            self.rate = rate
            if not converged:
                if not current_jac and self.jac is not None:
                    self.J = self.jac(t, y, f)
                    current_jac = True
                    self.LU = None
                    continue
                h_abs *= 0.5
                rejected = True
                continue
            err = self._error(y, f, h, z, y_new, self.LU)
            scale = atol + np.maximum(np.abs(y), np.abs(y_new)) * rtol
            err_norm = norm(err / scale)
            if err_norm > 1:
                h_abs *= max(MIN_FACTOR, SAFETY * err_norm ** (-1 / 3))
                rejected = True
                continue
            break

        recompute_jac = self.jac is not None and n_iter > 2 and (rate or 0.0) > 1e-3
        with np.errstate(divide="ignore"):
            factor = min(MAX_FACTOR, SAFETY * err_norm ** (-1 / 3))
        if rejected:
            factor = min(1.0, factor)
        if not recompute_jac and factor < 1.2:
            factor = 1.0  # keep h and with it the LU
        f_new = self.fun(t_new, y_new)
        if recompute_jac:
            self.J = self.jac(t_new, y_new, f_new)
            self.LU = None
            current_jac = True
        elif self.jac is not None:
            current_jac = False
        self.h_abs = h_abs * factor
        self.current_jac = current_jac
        self.y_old, self.t_old = y, t
        self.t, self.y, self.f = t_new, y_new, f_new
        self.sol = HermiteDenseOutput(t, t_new, y, f, y_new, f_new)
        return True, None

    def _dense_output_impl(self) -> HermiteDenseOutput:
        return self.sol


def fixed_steps(
    fun: Callable[[float, np.ndarray], np.ndarray],
    t_span: tuple[float, float],
    y0: np.ndarray,
    n_steps: int,
    jac: Callable | np.ndarray | None = None,
    newton_rtol: float = 1e-12,
) -> np.ndarray:
    """States at n_steps + 1 equally spaced instants taken with constant-h TR-BDF2 steps.

    For convergence-order checks: the stages are the solver's own, Newton is iterated to
    `newton_rtol` (with a fresh Jacobian per step), and there is no error control.

    Parameters
    ----------
    fun : callable
        fun(t, y) -> y', shape (n,).
    t_span : tuple of float
        (t0, t1).
    y0 : numpy.ndarray
        State at t0, shape (n,).
    n_steps : int
        Number of equal steps.
    jac : callable, numpy.ndarray or None
        The Jacobian as for `TRBDF2` (None: finite differences).
    newton_rtol : float
        Tolerance of the stage iterations (used as rtol and atol of the solver).

    Returns
    -------
    numpy.ndarray
        The states at t0 + i h, i = 0 .. n_steps, shape (n_steps + 1, n).

    Raises
    ------
    RuntimeError
        When Newton does not converge in a step.
    """
    t0, t1 = map(float, t_span)
    h = (t1 - t0) / n_steps
    y0 = np.asarray(y0, dtype=float)
    s = TRBDF2(fun, t0, y0, t1, rtol=newton_rtol, atol=newton_rtol, jac=jac, first_step=abs(h))
    out = [s.y.copy()]
    for i in range(n_steps):
        t = t0 + i * h
        if s.jac is not None:
            s.J = s.jac(t, s.y, s.f)
        ok, _, _, _, y_new = s._stages(t, s.y, s.f, h, s._lu(h))
        if not ok:
            raise RuntimeError(f"Newton did not converge in step {i} at t={t:g}")
        s.y = y_new
        s.f = s.fun(t + h, y_new)
        out.append(y_new.copy())
    return np.array(out)


# Helpers of scipy's own implicit solvers (scipy/integrate/_ivp/common.py, scipy 1.17), copied
# because that module is private and may change without notice.  Copyright (c) 2001-2002
# Enthought, Inc. 2003, SciPy Developers; BSD 3-clause licence (LICENSES/scipy.txt).  Changes:
# num_jac has only the dense path, and a `jac_sparsity` structure zeroes the entries outside it
# instead of grouping columns (the same values, n evaluations of f instead of fewer).
EPS = np.finfo(float).eps
NUM_JAC_DIFF_REJECT = EPS**0.875
NUM_JAC_DIFF_SMALL = EPS**0.75
NUM_JAC_DIFF_BIG = EPS**0.25
NUM_JAC_MIN_FACTOR = 1e3 * EPS
NUM_JAC_FACTOR_INCREASE = 10
NUM_JAC_FACTOR_DECREASE = 0.1


def validate_first_step(first_step: float, t0: float, t_bound: float) -> float:
    """The first step, checked: positive and within the interval.

    Parameters
    ----------
    first_step : float
        The step asked for.
    t0, t_bound : float
        The interval of integration.

    Returns
    -------
    float
        first_step.

    Raises
    ------
    ValueError
        When it is not positive or exceeds |t_bound - t0|.
    """
    if first_step <= 0:
        raise ValueError("`first_step` must be positive.")
    if first_step > np.abs(t_bound - t0):
        raise ValueError("`first_step` exceeds bounds.")
    return first_step


def validate_max_step(max_step: float) -> float:
    """The largest step, checked: positive.

    Parameters
    ----------
    max_step : float
        The step asked for.

    Returns
    -------
    float
        max_step.

    Raises
    ------
    ValueError
        When it is not positive.
    """
    if max_step <= 0:
        raise ValueError("`max_step` must be positive.")
    return max_step


def warn_extraneous(extraneous: dict[str, Any]) -> None:
    """Warn about options the solver does not use.

    Parameters
    ----------
    extraneous : dict
        The unused keyword arguments.
    """
    if extraneous:
        warn(
            "The following arguments have no effect for a chosen solver: "
            f"{', '.join(f'`{x}`' for x in extraneous)}.",
            stacklevel=3,
        )


def validate_tol(rtol: float, atol: float | np.ndarray, n: int) -> tuple[float, np.ndarray]:
    """The tolerances, checked: rtol raised to 100 eps with a warning, atol non-negative.

    Parameters
    ----------
    rtol : float
        Relative tolerance.
    atol : float or numpy.ndarray
        Absolute tolerance, scalar or shape (n,).
    n : int
        Size of the state.

    Returns
    -------
    rtol : float
        At least 100 eps.
    atol : numpy.ndarray
        atol as an array.

    Raises
    ------
    ValueError
        When atol has the wrong shape or a negative entry.
    """
    if np.any(rtol < 100 * EPS):
        warn(
            "At least one element of `rtol` is too small. "
            f"Setting `rtol = np.maximum(rtol, {100 * EPS})`.",
            stacklevel=3,
        )
        rtol = np.maximum(rtol, 100 * EPS)
    atol = np.asarray(atol)
    if atol.ndim > 0 and atol.shape != (n,):
        raise ValueError("`atol` has wrong shape.")
    if np.any(atol < 0):
        raise ValueError("`atol` must be positive.")
    return rtol, atol


def norm(x: np.ndarray) -> float:
    """The RMS norm.

    Parameters
    ----------
    x : numpy.ndarray
        Any shape.

    Returns
    -------
    float
        ||x||_2 / sqrt(x.size).
    """
    return np.linalg.norm(x) / x.size**0.5


def select_initial_step(
    fun: Callable[[float, np.ndarray], np.ndarray],
    t0: float,
    y0: np.ndarray,
    t_bound: float,
    max_step: float,
    f0: np.ndarray,
    direction: float,
    order: int,
    rtol: float,
    atol: float | np.ndarray,
) -> float:
    """Initial step of Hairer, Norsett & Wanner, Solving ODEs I, Sec. II.4.

    Parameters
    ----------
    fun : callable
        fun(t, y) -> y'.
    t0 : float
        Initial time.
    y0 : numpy.ndarray
        Initial state, shape (n,).
    t_bound : float
        End of the interval.
    max_step : float
        Largest step allowed.
    f0 : numpy.ndarray
        fun(t0, y0).
    direction : float
        +1 or -1, the direction of integration.
    order : int
        Order of the error estimate (2 for TR-BDF2).
    rtol : float
        Relative tolerance.
    atol : float or numpy.ndarray
        Absolute tolerance.

    Returns
    -------
    float
        The absolute size of the first step.
    """
    if y0.size == 0:
        return np.inf
    interval_length = abs(t_bound - t0)
    if interval_length == 0.0:
        return 0.0
    scale = atol + np.abs(y0) * rtol
    d0 = norm(y0 / scale)
    d1 = norm(f0 / scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval_length)
    f1 = fun(t0 + h0 * direction, y0 + h0 * direction * f0)
    d2 = norm((f1 - f0) / scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1 / (order + 1))
    return min(100 * h0, h1, interval_length, max_step)


def num_jac(
    fun: Callable[[float, np.ndarray], np.ndarray],
    t: float,
    y: np.ndarray,
    f: np.ndarray,
    threshold: float | np.ndarray,
    factor: np.ndarray | None,
    sparsity: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Forward-difference Jacobian of the vectorized `fun`, with the step factor of each column
    adapted from call to call to keep the difference well above its round-off.

    Parameters
    ----------
    fun : callable
        fun(t, Y) -> F for states in the columns of Y, shape (n, k) -> (n, k).
    t : float
        Time.
    y : numpy.ndarray
        State, shape (n,).
    f : numpy.ndarray
        fun(t, y), shape (n,).
    threshold : float or numpy.ndarray
        Smallest |y| a difference step is scaled by (the absolute tolerance).
    factor : numpy.ndarray or None
        Step factors of the columns from the last call, shape (n,); None: sqrt(eps).
    sparsity : numpy.ndarray or None
        A dense structure, shape (n, n): entries where it is zero are set to zero.

    Returns
    -------
    J : numpy.ndarray
        The Jacobian, shape (n, n).
    factor : numpy.ndarray
        The step factors for the next call, shape (n,).
    """
    y = np.asarray(y)
    n = y.shape[0]
    if n == 0:
        return np.empty((0, 0)), factor
    factor = np.full(n, EPS**0.5) if factor is None else factor.copy()
    f_sign = 2 * (np.real(f) >= 0).astype(float) - 1
    y_scale = f_sign * np.maximum(threshold, np.abs(y))
    h = (y + factor * y_scale) - y
    for i in np.nonzero(h == 0)[0]:
        while h[i] == 0:
            factor[i] *= 10
            h[i] = (y[i] + factor[i] * y_scale[i]) - y[i]

    h_vecs = np.diag(h)
    f_new = fun(t, y[:, None] + h_vecs)
    diff = f_new - f[:, None]
    max_ind = np.argmax(np.abs(diff), axis=0)
    r = np.arange(n)
    max_diff = np.abs(diff[max_ind, r])
    scale = np.maximum(np.abs(f[max_ind]), np.abs(f_new[max_ind, r]))
    diff_too_small = max_diff < NUM_JAC_DIFF_REJECT * scale
    if np.any(diff_too_small):
        (ind,) = np.nonzero(diff_too_small)
        new_factor = NUM_JAC_FACTOR_INCREASE * factor[ind]
        h_new = (y[ind] + new_factor * y_scale[ind]) - y[ind]
        h_vecs[ind, ind] = h_new
        f_new = fun(t, y[:, None] + h_vecs[:, ind])
        diff_new = f_new - f[:, None]
        max_ind = np.argmax(np.abs(diff_new), axis=0)
        r = np.arange(ind.shape[0])
        max_diff_new = np.abs(diff_new[max_ind, r])
        scale_new = np.maximum(np.abs(f[max_ind]), np.abs(f_new[max_ind, r]))
        update = max_diff[ind] * scale_new < max_diff_new * scale[ind]
        if np.any(update):
            (update,) = np.nonzero(update)
            update_ind = ind[update]
            factor[update_ind] = new_factor[update]
            h[update_ind] = h_new[update]
            diff[:, update_ind] = diff_new[:, update]
            scale[update_ind] = scale_new[update]
            max_diff[update_ind] = max_diff_new[update]
    diff /= h
    factor[max_diff < NUM_JAC_DIFF_SMALL * scale] *= NUM_JAC_FACTOR_INCREASE
    factor[max_diff > NUM_JAC_DIFF_BIG * scale] *= NUM_JAC_FACTOR_DECREASE
    factor = np.maximum(factor, NUM_JAC_MIN_FACTOR)
    if sparsity is not None:
        diff = np.where(sparsity != 0, diff, 0.0)
    return diff, factor
