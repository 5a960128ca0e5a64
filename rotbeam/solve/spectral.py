"""Trigonometric (Fourier) tools on M equispaced instants of one period.

Shared by the periodic collocation (`rotbeam.periodic`) and the steady state it seeds
(`rotbeam.solve.steady`): differentiation, interpolation to other instants and the harmonic tail
that says whether M instants resolve the signal.
"""

from __future__ import annotations

import math

import numpy as np


def fourier_diff_matrix(M: int, period: float) -> np.ndarray:
    """First-derivative matrix on M equispaced points of a period (M odd: no Nyquist mode)."""
    if M % 2 == 0:
        raise ValueError("use an odd number of collocation points")
    h = 2.0 * math.pi / M
    j = np.arange(M)
    diff = j[:, None] - j[None, :]
    with np.errstate(divide="ignore"):
        D = 0.5 * (-1.0) ** diff / np.sin(diff * h / 2.0)
    D[diff == 0] = 0.0
    return D * (2.0 * math.pi / period)


def trig_interpolate(X: np.ndarray, m: int) -> np.ndarray:
    """Values at m equispaced instants of the trigonometric interpolant of X (M, ...), M odd."""
    M = X.shape[0]
    C = np.fft.rfft(X, axis=0)
    return np.fft.irfft(C, n=m, axis=0) * (m / M)


def harmonic_tail(X: np.ndarray) -> float:
    """Size of the upper half of the spectrum of X (M, ...) relative to the whole (0: exact)."""
    C = np.abs(np.fft.rfft(X, axis=0))
    total = float(np.sqrt(np.sum(C**2)))
    if total == 0.0:
        return 0.0
    k = C.shape[0]
    return float(np.sqrt(np.sum(C[k // 2 :] ** 2)) / total)
