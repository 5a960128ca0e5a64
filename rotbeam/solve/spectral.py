"""Trigonometric (Fourier) tools on M equispaced instants of one period.

Shared by the periodic collocation (`rotbeam.solve.periodic`) and the steady state it seeds
(`rotbeam.solve.steady`): differentiation, interpolation to other instants and the harmonic tail
that says whether M instants resolve the signal.
"""

from __future__ import annotations

import math

import numpy as np


def fourier_diff_matrix(M: int, period: float) -> np.ndarray:
    """The Fourier (spectral) first-derivative matrix on M equispaced points of a period:
    exact for trigonometric polynomials of degree < M / 2.

    Parameters
    ----------
    M : int
        Number of points, odd (no Nyquist mode).
    period : float
        The period, in any time unit.

    Returns
    -------
    numpy.ndarray
        D, shape (M, M): (D X)_j is dX/dt at t_j = j period / M, per unit of that time.

    Raises
    ------
    ValueError
        For an even M.
    """
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
    """The trigonometric interpolant of equispaced samples, resampled at another count.

    Fewer instants than samples keep the harmonics below m / 2 (a low-pass, not an alias; for an
    even m, half the cosine of harmonic m / 2).  For an even M the Nyquist harmonic M / 2 is a
    cosine counted once: on more instants it enters with half its weight, as the interpolant of
    least oscillation has it.

    Parameters
    ----------
    X : numpy.ndarray
        M equispaced samples of one period along axis 0, shape (M, ...).
    m : int
        Number of equispaced instants wanted (the first at the same time as X's).

    Returns
    -------
    numpy.ndarray
        The interpolant at the m instants, shape (m, ...).
    """
    M = X.shape[0]
    C = np.fft.rfft(X, axis=0)
    if M % 2 == 0 and m > M:
        C[M // 2] *= 0.5
    return np.fft.irfft(C, n=m, axis=0) * (m / M)


def highest_harmonic(X: np.ndarray, tol: float) -> int:
    """The highest harmonic a periodic signal carries above a share of its size.

    Parameters
    ----------
    X : numpy.ndarray
        M equispaced samples of one period along axis 0, shape (M, ...).
    tol : float
        The share: a harmonic counts when its 2-norm (over the other axes) exceeds tol times
        the 2-norm of the whole spectrum, the mean included (as `harmonic_tail` measures).

    Returns
    -------
    int
        k >= 1 of the highest such harmonic, 0 for a constant (or zero) signal.
    """
    C = np.abs(np.fft.rfft(np.reshape(X, (X.shape[0], -1)), axis=0))
    size = np.sqrt(np.sum(C**2, axis=1))
    above = np.flatnonzero(size[1:] > tol * float(np.sqrt(np.sum(size**2))))
    return int(above[-1]) + 1 if above.size else 0


def harmonic_tail(X: np.ndarray) -> float:
    """Whether M instants resolve a periodic signal: the size of the upper half of its spectrum
    relative to the whole.

    Parameters
    ----------
    X : numpy.ndarray
        M equispaced samples of one period along axis 0, shape (M, ...).

    Returns
    -------
    float
        The 2-norm of the harmonics k >= (M // 2 + 1) // 2 over the 2-norm of all (0 for a zero
        signal).
    """
    C = np.abs(np.fft.rfft(X, axis=0))
    total = float(np.sqrt(np.sum(C**2)))
    if total == 0.0:
        return 0.0
    k = C.shape[0]
    return float(np.sqrt(np.sum(C[k // 2 :] ** 2)) / total)


def periodic_rates(
    theta: np.ndarray, period: float, axis: int = 0
) -> tuple[np.ndarray, np.ndarray]:
    """Rates and accelerations of a periodic series, spectrally (the derivative of its
    trigonometric interpolant; an even count's Nyquist harmonic is dropped).

    Parameters
    ----------
    theta : numpy.ndarray
        m equispaced samples of one period along `axis`: shape (m, ...) for axis 0.
    period : float
        The period, in units of T.
    axis : int
        The axis of the instants.

    Returns
    -------
    theta_t, theta_tt : numpy.ndarray
        d/dtau and d^2/dtau^2, the shape of `theta`.
    """
    theta = np.asarray(theta, dtype=float)
    m = theta.shape[axis]
    C = np.fft.rfft(theta, axis=axis)
    w = 2.0 * math.pi / period * np.arange(C.shape[axis])
    if m % 2 == 0:
        w[-1] = 0.0
    w = np.expand_dims(w, tuple(range(1, theta.ndim - axis % theta.ndim)))
    first = np.fft.irfft(1j * w * C, n=m, axis=axis)
    second = np.fft.irfft(-(w**2) * C, n=m, axis=axis)
    return first, second
