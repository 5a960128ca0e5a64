r"""Quasi-static condition of the canonical second-order system (App. E of the paper).

For u'' + 2 zeta u' + u = (F0/k) cos(c0 tau) the steady amplitudes are
A_dyn = (F0/k) / sqrt((1 - c0^2)^2 + (2 zeta c0)^2) and A_QS = F0/k, so Eq. (Delta_RMS) gives

    Delta RMS = (A_dyn - A_QS) / A_dyn = 1 - sqrt((1 - c0^2)^2 + (2 zeta c0)^2)    (c0 < 1 side).

Setting it to a threshold t gives the biquadratic (Eq. c_0, printed for t = 0.1 as "+0.19")

    c0^4 + (4 zeta^2 - 2) c0^2 + (1 - (1 - t)^2) = 0,

i.e. with X = c0^2, B = 1 - 2 zeta^2 and C = t (2 - t) = 1 - (1 - t)^2:
X = B -+ sqrt(B^2 - C).  The smaller root is the first crossing.  At zeta = 0, B = 1 and
sqrt(1 - C) = 1 - t, so X = t exactly: c0(zeta -> 0) = sqrt(t), with no small-t approximation.
The paper's table (0.02 -> 0.1414, ..., 0.10 -> 0.3162) is therefore the exact zeta = 0 root.
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
    """Signed App. E expression 1 - sqrt((1 - c0^2)^2 + (2 zeta c0)^2) (>= 0 below resonance).

    Eq. (Delta_RMS) takes |.|, which differs only where A_dyn < A_QS (far above resonance).
    """
    z = _check_zeta(zeta)
    c = np.asarray(c0, dtype=float)
    out = 1.0 - np.sqrt((1.0 - c * c) ** 2 + (2.0 * z * c) ** 2)
    return float(out) if np.ndim(out) == 0 else out


def biquadratic_residual(c0: float, zeta: float, threshold: float) -> float:
    """c0^4 + (4 zeta^2 - 2) c0^2 + (1 - (1 - threshold)^2), zero at a critical c0."""
    c2 = c0 * c0
    return c2 * c2 + (4.0 * zeta * zeta - 2.0) * c2 + (1.0 - (1.0 - threshold) ** 2)


def c0_root(zeta: float, threshold: float = 0.10) -> float:
    """Smallest positive root c0 of the biquadratic: the first frequency ratio f/f_n at which
    Delta RMS reaches `threshold`.  Raises if damping is so high that it never does."""
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
    """Exact zeta -> 0 root of the biquadratic: c0 = sqrt(threshold) (see module docstring)."""
    return math.sqrt(check_threshold(threshold))
