"""The RMS criterion of Sec. 5: RMS (Eq. RMS), Delta RMS (Eq. Delta_RMS), spectra, f_d*.

Quasi-static is good enough where Delta RMS = |RMS_dyn - RMS_QS| / RMS_dyn of the midspan
deflection stays below a threshold; f_d* is where it first reaches it along a line of drive
frequencies.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..config.checks import check_threshold


def rms(y: np.ndarray) -> float:
    """Root mean square of uniformly sampled values (Eq. RMS).

    Parameters
    ----------
    y : numpy.ndarray
        Samples over whole periods, any shape (y_m in units of L, in rotbeam).

    Returns
    -------
    float
        sqrt(mean(y^2)), in the unit of `y`.

    Raises
    ------
    ValueError
        For an empty series.
    """
    y = np.asarray(y, dtype=float)
    if y.size == 0:
        raise ValueError("rms of an empty series")
    return float(np.sqrt(np.mean(y * y)))


def delta_rms(rms_dynamic: float, rms_quasistatic: float) -> float:
    """|RMS_dyn - RMS_QS| / RMS_dyn (Eq. Delta_RMS): the paper's measure of inertia's share.

    Parameters
    ----------
    rms_dynamic, rms_quasistatic : float
        RMS of the dynamic and the quasi-static response, in one unit.

    Returns
    -------
    float
        Delta RMS, dimensionless; 0 when both are zero (no load), inf when only the dynamic
        one is.
    """
    if rms_dynamic == 0.0:
        return 0.0 if rms_quasistatic == 0.0 else float("inf")
    return abs(rms_dynamic - rms_quasistatic) / rms_dynamic


def power_spectrum(tau: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum of a uniformly sampled series, its mean removed.

    Parameters
    ----------
    tau : numpy.ndarray
        Equispaced instants, shape (m,) (units of T, or seconds).
    y : numpy.ndarray
        Samples, shape (m,).

    Returns
    -------
    freq, amp : numpy.ndarray
        Frequencies in cycles per unit of `tau` and the amplitudes 2 |FFT(y)| / m (a sine of
        amplitude A on a bin shows A), shape (m // 2 + 1,) each.
    """
    tau = np.asarray(tau, dtype=float)
    y = np.asarray(y, dtype=float)
    dt = float(tau[1] - tau[0])
    amp = np.abs(np.fft.rfft(y - y.mean())) * 2.0 / y.size
    return np.fft.rfftfreq(y.size, dt), amp


@dataclass
class Crossing:
    """First crossing of Delta RMS = threshold along a scan."""

    found: bool
    grid_value: float  #: first scanned point with Delta RMS >= threshold (the paper's rule)
    root: float  #: the crossing located by root finding (NaN if not requested or not found)
    bracket: tuple[float, float]
    message: str


def first_crossing(
    xs: np.ndarray,
    values: np.ndarray,
    threshold: float,
    refine: Callable[[float], float] | None = None,
    xtol: float = 1e-6,
) -> Crossing:
    """Bracket the first crossing of `values` >= threshold on a scan; optionally refine it.

    With `refine` (a function x -> Delta RMS) the root of refine(x) - threshold is found with
    Brent's method inside the bracket; without it the root is interpolated linearly.  Points
    that are not finite never count as a crossing.

    Parameters
    ----------
    xs : numpy.ndarray
        The scanned values (drive frequencies), increasing, shape (m,).
    values : numpy.ndarray
        Delta RMS at them, dimensionless, shape (m,).
    threshold : float
        The Delta RMS threshold, in (0, 1).
    refine : callable or None
        x -> Delta RMS, evaluated inside the bracket.
    xtol : float
        Brent's absolute tolerance in x.

    Returns
    -------
    Crossing
        The first scanned point at or above the threshold (the paper's rule), the refined or
        interpolated root (NaN when the first point is already above), the bracket and how it
        was found; ``found = False`` when no point reaches the threshold.

    Raises
    ------
    RotbeamInputError
        If `threshold` is not in (0, 1).
    """
    threshold = check_threshold(threshold)
    xs = np.asarray(xs, dtype=float)
    values = np.asarray(values, dtype=float)
    ok = np.isfinite(values)
    hits = np.nonzero(ok & (values >= threshold))[0]
    if hits.size == 0:
        return Crossing(False, np.nan, np.nan, (np.nan, np.nan), "no point reaches the threshold")
    j = int(hits[0])
    if j == 0:
        return Crossing(
            True, float(xs[0]), np.nan, (np.nan, float(xs[0])), "first scanned point is above"
        )
    a, b = float(xs[j - 1]), float(xs[j])
    va, vb = float(values[j - 1]), float(values[j])
    if refine is None:
        root = a + (threshold - va) * (b - a) / (vb - va)
        msg = "linear interpolation"
    else:
        from scipy.optimize import brentq  # here: a figure job that plots spectra never needs it

        root = brentq(lambda x: refine(x) - threshold, a, b, xtol=xtol)
        msg = "brentq"
    return Crossing(True, b, float(root), (a, b), msg)


def critical_from_scan(f_ds: np.ndarray, delta: np.ndarray, threshold: float) -> dict:
    """f_d* on one scanned line: the first scanned point with Delta RMS >= threshold (the paper's
    rule) and the root of the monotone cubic (PCHIP) interpolant of the scan inside its bracket.

    The root is found on the interpolant, not by new simulations, so that a new threshold costs
    no simulation.  Failed points (NaN) are dropped and counted.

    Parameters
    ----------
    f_ds : numpy.ndarray
        Scanned drive frequencies [Hz], shape (m,), any order.
    delta : numpy.ndarray
        Delta RMS at them, dimensionless, shape (m,); NaN for a failed point.
    threshold : float
        The Delta RMS threshold, in (0, 1).

    Returns
    -------
    dict
        ``threshold``, ``points_used``, ``points_failed``, ``f_d_grid`` and ``f_d_root`` [Hz]
        (NaN when not found), ``found`` and ``message``.

    Raises
    ------
    RotbeamInputError
        If `threshold` is not in (0, 1).
    """
    from scipy.interpolate import PchipInterpolator
    from scipy.optimize import brentq

    threshold = check_threshold(threshold)
    f_ds = np.asarray(f_ds, dtype=float)
    delta = np.asarray(delta, dtype=float)
    ok = np.isfinite(delta)
    f, d = f_ds[ok], delta[ok]
    order = np.argsort(f)
    f, d = f[order], d[order]
    out = {"threshold": threshold, "points_used": int(ok.sum()), "points_failed": int((~ok).sum()),
           "f_d_grid": np.nan, "f_d_root": np.nan, "found": False}  # fmt: skip
    c = first_crossing(f, d, threshold)
    if not c.found:
        out["message"] = c.message
        return out
    out.update(found=True, f_d_grid=c.grid_value)
    if np.isnan(c.bracket[0]):
        out["message"] = c.message
        return out
    interp = PchipInterpolator(f, d)
    a, b = c.bracket
    out["f_d_root"] = float(brentq(lambda x: float(interp(x)) - threshold, a, b, xtol=1e-10))
    out["message"] = "bracketed on the scan, root of its PCHIP interpolant"
    return out
