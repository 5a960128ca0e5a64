"""The quasi-static condition of the canonical damped oscillator (App. E of the paper).

The linear estimate f_d* ~ c_0 f_0 of the verdict rests on it: c_0 is the first frequency
ratio at which the oscillator's Delta RMS reaches the threshold, the smaller root of a
biquadratic; as zeta -> 0 it is sqrt(threshold) exactly, the printed table.  The derivation:
docs/model.md, "The canonical second-order system".
"""

from __future__ import annotations

import math

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
    out = 1.0 - np.sqrt((1.0 - c * c) ** 2 + (2.0 * z * c) ** 2)
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
