"""The quasi-static condition of the canonical damped oscillator (App. E of the paper).

c_0 is the first frequency ratio at which the oscillator's Delta RMS reaches the threshold, the
smaller root of a biquadratic; as zeta -> 0 it is sqrt(threshold) exactly, the printed table.
The same oscillator forced by every harmonic of a periodic drive gives the verdict's linear
estimate of f_d* (`first_crossing`).  The derivations: docs/model.md, "The canonical
second-order system" and "The verdict and the linear estimate of f_d*".
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..config.checks import check_threshold
from ..config.errors import RotbeamInputError


def _check_zeta(zeta: float) -> float:
    if isinstance(zeta, bool) or not isinstance(zeta, (int, float, np.floating)):
        raise RotbeamInputError(f"damping ratio zeta must be a number >= 0, got {zeta!r}")
    z = float(zeta)
    if not (math.isfinite(z) and z >= 0.0):
        raise RotbeamInputError(f"damping ratio zeta must be finite and >= 0, got {zeta!r}")
    return z


def inverse_gain2(r: float | np.ndarray, zeta: float) -> float | np.ndarray:
    """1 / |H(r)|^2 = (1 - r^2)^2 + (2 zeta r)^2: the canonical oscillator's static-to-dynamic
    amplitude ratio, squared, at the frequency ratio r (H(r) = 1 / (1 - r^2 + 2 i zeta r)).

    Parameters
    ----------
    r : float or numpy.ndarray
        Frequency ratio f / f_n, dimensionless, any shape.
    zeta : float
        Damping ratio, dimensionless (not checked here: the callers check it).

    Returns
    -------
    float or numpy.ndarray
        The shape of `r`, dimensionless.
    """
    return (1.0 - r * r) ** 2 + (2.0 * zeta * r) ** 2


def delta_rms_canonical(c0: float | np.ndarray, zeta: float) -> float | np.ndarray:
    """Signed Delta RMS of the canonical oscillator, 1 - sqrt((1 - c0^2)^2 + (2 zeta c0)^2).

    App. E's expression for u'' + 2 zeta u' + u = cos(c0 tau): >= 0 below resonance, where
    the dynamic amplitude exceeds the static one.  Eq. (Delta_RMS) takes its absolute value,
    which differs only where A_dyn < A_QS (far above resonance, or on the lag branch of an
    overdamped oscillator).

    Parameters
    ----------
    c0 : float or numpy.ndarray
        Frequency ratio f / f_n, dimensionless, any shape.
    zeta : float
        Damping ratio, dimensionless, >= 0.

    Returns
    -------
    float or numpy.ndarray
        Delta RMS (dimensionless, signed), a float for a scalar `c0`, else the shape of `c0`.

    Raises
    ------
    RotbeamInputError
        If `zeta` is not a finite number >= 0.
    """
    z = _check_zeta(zeta)
    c = np.asarray(c0, dtype=float)
    out = 1.0 - np.sqrt(inverse_gain2(c, z))
    return float(out) if np.ndim(out) == 0 else out


def biquadratic_residual(c0: float, zeta: float, threshold: float) -> float:
    """The biquadratic of Eq. (c_0), zero where the oscillator's Delta RMS equals the threshold.

    c0^4 + (4 zeta^2 - 2) c0^2 + (1 - (1 - threshold)^2): a check of `c0_root` (its root) and
    of the printed equation (the constant 0.19 at threshold 0.1).

    Parameters
    ----------
    c0 : float
        Frequency ratio f / f_n, dimensionless.
    zeta : float
        Damping ratio, dimensionless.
    threshold : float
        Delta RMS threshold, dimensionless.

    Returns
    -------
    float
        The residual, dimensionless.
    """
    c2 = c0 * c0
    return c2 * c2 + (4.0 * zeta * zeta - 2.0) * c2 + (1.0 - (1.0 - threshold) ** 2)


def c0_root(zeta: float, threshold: float = 0.10) -> float:
    """App. E's c_0: the first frequency ratio f / f_n at which Delta RMS reaches `threshold`.

    The smallest positive root of the biquadratic, X = c0^2 = C / (B + sqrt(B^2 - C)) with
    B = 1 - 2 zeta^2 and C = threshold (2 - threshold), written without cancellation.  The
    verdict's linear estimate is f_d* ~ c_0 f_0.

    Parameters
    ----------
    zeta : float
        Damping ratio, dimensionless, >= 0.
    threshold : float
        Delta RMS threshold, dimensionless, in (0, 1).

    Returns
    -------
    float
        c_0, dimensionless.

    Raises
    ------
    RotbeamInputError
        If `zeta` or `threshold` is out of range, or the damping is so high that the response
        never exceeds the static one by the threshold: (1 - 2 zeta^2)^2 < threshold
        (2 - threshold) (the verdict then uses the lag branch).
    """
    z = _check_zeta(zeta)
    t = check_threshold(threshold)
    B = 1.0 - 2.0 * z * z
    C = t * (2.0 - t)
    disc = B * B - C
    if B <= 0.0 or disc < 0.0:
        peak = 2.0 * z * math.sqrt(1.0 - z * z) if z < 1.0 / math.sqrt(2.0) else 1.0
        raise RotbeamInputError(
            f"no c0 reaches Delta RMS = {t} at zeta = {z}: the response never exceeds the "
            f"quasi-static one by that much (max of 1 - sqrt(...) is {1.0 - peak:.4g}); "
            f"a root needs (1 - 2 zeta^2)^2 >= threshold (2 - threshold)"
        )
    # smaller root X = B - sqrt(disc), written without cancellation
    X = C / (B + math.sqrt(disc))
    return math.sqrt(X)


def c0_limit(threshold: float = 0.10) -> float:
    """The undamped limit of c_0: sqrt(threshold), exactly (no small-threshold approximation).

    The paper's c_0 table is this root (docs/model.md, "The canonical second-order system").

    Parameters
    ----------
    threshold : float
        Delta RMS threshold, dimensionless, in (0, 1).

    Returns
    -------
    float
        c_0 at zeta = 0, dimensionless.

    Raises
    ------
    RotbeamInputError
        If `threshold` is not in (0, 1).
    """
    return math.sqrt(check_threshold(threshold))


def lag_root(zeta: float, threshold: float = 0.10) -> float:
    """The frequency ratio f / f_n at which the oscillator's response lags its static one by the
    threshold: the |.| branch of App. E's Delta RMS that overdamped oscillators cross.

    sqrt((1 - c^2)^2 + (2 zeta c)^2) = 1 + threshold, i.e. c^4 - 2 B c^2 + 1 - (1 + t)^2 = 0
    with B = 1 - 2 zeta^2, whose constant term is negative: one positive root in c^2, written
    without cancellation for either sign of B (docs/model.md, "The verdict and the linear
    estimate of f_d*").

    Parameters
    ----------
    zeta : float
        Damping ratio, dimensionless, >= 0.
    threshold : float
        Delta RMS threshold, dimensionless, in (0, 1).

    Returns
    -------
    float
        The ratio c, dimensionless.

    Raises
    ------
    RotbeamInputError
        If `zeta` or `threshold` is out of range.
    """
    z = _check_zeta(zeta)
    t = check_threshold(threshold)
    B = 1.0 - 2.0 * z * z
    C = 1.0 - (1.0 + t) ** 2  # < 0: one positive root in c^2
    root = math.sqrt(B * B - C)
    return math.sqrt(B + root) if B >= 0 else math.sqrt(-C / (root - B))


def _loads(orders: np.ndarray | tuple, loads: np.ndarray | tuple) -> tuple[np.ndarray, np.ndarray]:
    """Harmonic orders k >= 1 and squared load amplitudes w_k > 0, checked."""
    k = np.asarray(orders, dtype=float).ravel()
    f = np.asarray(loads, dtype=float).ravel()
    if k.size == 0 or k.size != f.size:
        raise RotbeamInputError(
            f"harmonic orders and loads must be non-empty and of one length, got {k.size} "
            f"orders and {f.size} loads"
        )
    if not (np.all(np.isfinite(k)) and np.all(k > 0) and np.all(np.isfinite(f))):
        raise RotbeamInputError(
            f"harmonic orders must be finite and > 0 and loads finite, got orders "
            f"{k.tolist()} and loads {f.tolist()}"
        )
    top = float(np.max(np.abs(f)))
    if not top > 0:
        raise RotbeamInputError("every load is 0: Delta RMS is undefined without a load")
    w = (f / top) ** 2  # only the ratios matter: scaled, a tiny load does not underflow
    return k[w > 0], w[w > 0]


def delta_rms_harmonics(
    ratio: float | np.ndarray, orders: np.ndarray | tuple, loads: np.ndarray | tuple, zeta: float
) -> float | np.ndarray:
    """Signed Delta RMS of the canonical oscillator forced by several harmonics at once.

    u'' + 2 zeta u' + u = sum_k F_k cos(k c tau + phi_k): harmonic k of the steady response is
    F_k H(k c) with H(r) = 1 / (1 - r^2 + 2 i zeta r), its quasi-static response F_k; distinct
    harmonics are orthogonal over the period, so RMS^2 = sum of squared amplitudes / 2 and
    Delta RMS = 1 - sqrt(sum F_k^2 / sum F_k^2 |H(k c)|^2), whatever the phases.  One harmonic
    k = 1 gives `delta_rms_canonical`.  >= 0 where the dynamic response exceeds the static one;
    Eq. (Delta_RMS) is its absolute value.  A load exactly at an undamped resonance gives 1.

    Parameters
    ----------
    ratio : float or numpy.ndarray
        The fundamental's frequency ratio c = f / f_n, dimensionless, > 0, any shape.
    orders : array_like
        Harmonic orders k > 0 (distinct), one per load.
    loads : array_like
        Load amplitudes F_k (any common unit; only their ratios matter); at least one nonzero.
    zeta : float
        Damping ratio, dimensionless, >= 0.

    Returns
    -------
    float or numpy.ndarray
        Delta RMS (dimensionless, signed), a float for a scalar `ratio`, else its shape.

    Raises
    ------
    RotbeamInputError
        If `zeta` is not a finite number >= 0, or the orders and loads are empty, of different
        lengths, not > 0 and finite, or all zero.
    """
    z = _check_zeta(zeta)
    k, w = _loads(orders, loads)
    c = np.asarray(ratio, dtype=float)
    r = c[..., None] * k
    gain2 = inverse_gain2(r, z)
    with np.errstate(divide="ignore"):
        dynamic = np.sum(w / gain2, axis=-1)  # sum F_k^2 |H|^2: inf at an undamped resonance
    out = 1.0 - np.sqrt(np.sum(w) / dynamic)
    return float(out) if np.ndim(out) == 0 else out


#: The scan of `first_crossing`: log-spaced steps of this relative size times zeta, within
#: SCAN_STEP_RANGE, so that a resonance peak (relative width ~2 zeta) spans several steps.
SCAN_STEP_PER_ZETA = 0.5
SCAN_STEP_RANGE = (1e-3, 0.05)


def first_crossing(
    orders: np.ndarray | tuple, loads: np.ndarray | tuple, zeta: float, threshold: float = 0.10
) -> float:
    """The lowest frequency ratio c = f / f_n at which |Delta RMS| of the oscillator forced by
    several harmonics (`delta_rms_harmonics`) reaches the threshold.

    A log scan upwards from a ratio where |Delta RMS| is below the threshold to
    sqrt(2 (1 + t)) / k_min, where every harmonic lies so far above resonance that
    |Delta RMS| > t (the crossing lies below it), with each harmonic's resonance (r = 1 and the
    peak of |H|) among the scanned points; then brentq on the first step that crosses, to
    round-off.  For one harmonic k it is c_0 / k where App. E's c_0 exists, else `lag_root` / k
    (docs/model.md, "The verdict and the linear estimate of f_d*").

    Parameters
    ----------
    orders : array_like
        Harmonic orders k > 0, one per load.
    loads : array_like
        Load amplitudes F_k (any common unit); at least one nonzero.
    zeta : float
        Damping ratio, dimensionless, >= 0.
    threshold : float
        Delta RMS threshold, dimensionless, in (0, 1).

    Returns
    -------
    float
        The ratio c of the fundamental, dimensionless.

    Raises
    ------
    RotbeamInputError
        If `zeta`, `threshold`, the orders or the loads are out of range (`delta_rms_harmonics`).
    """
    from scipy.optimize import brentq

    z = _check_zeta(zeta)
    t = check_threshold(threshold)
    k, w = _loads(orders, loads)

    def excess(c: float | np.ndarray) -> float | np.ndarray:
        return np.abs(delta_rms_harmonics(c, k, np.sqrt(w), z)) - t

    grid = _scan_grid(k, z, t, excess)
    g = excess(grid)
    i = int(np.argmax(g >= 0.0))  # the first point does not cross, the last does
    if g[i] == 0.0:
        return float(grid[i])
    return float(brentq(excess, grid[i - 1], grid[i], xtol=1e-300, rtol=4 * np.finfo(float).eps))


def _scan_grid(
    k: np.ndarray, zeta: float, t: float, excess: Callable[[float], float]
) -> np.ndarray:
    """The ratios `first_crossing` scans: log-spaced from below the first crossing to
    sqrt(2 (1 + t)) / k_min (|H| <= 1 / (1 + 2 t) for every harmonic there), with every
    harmonic's resonance r = 1 and peak r = sqrt(1 - 2 zeta^2) among them."""
    lo, hi = math.sqrt(t) / k.max(), math.sqrt(2.0 * (1.0 + t)) / k.min()
    for _ in range(40):  # |Delta RMS| ~ r^2 for r -> 0: a few decades below sqrt(t) suffice
        if excess(lo) < 0.0:
            break
        lo /= 10.0
    else:
        raise RotbeamInputError(f"|Delta RMS| stays above threshold {t} down to ratio {lo:.3g}")
    step = min(max(SCAN_STEP_PER_ZETA * zeta, SCAN_STEP_RANGE[0]), SCAN_STEP_RANGE[1])
    n = int(math.ceil(math.log(hi / lo) / math.log1p(step))) + 1
    peaks = [1.0] + ([math.sqrt(1.0 - 2.0 * zeta * zeta)] if 2.0 * zeta * zeta < 1.0 else [])
    resonances = np.outer(peaks, 1.0 / k).ravel()
    grid = np.unique(np.concatenate([np.geomspace(lo, hi, n), resonances]))
    return grid[(grid >= lo) & (grid <= hi)]
