"""Measurement files: a ring-down (columns t, y) and a resonance curve (f_d, rms[, rms_std]).

CSV with a header row; lines starting with '#' are comments (where the data came from).  Every
problem is one `RotbeamInputError` line naming the file, the column or row, and what is allowed:
a missing column, a cell that is not a finite number, too few rows, an abscissa (t or f_d) that
is not strictly increasing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ..config.errors import RotbeamInputError


def read_columns(
    path: str | Path, required: tuple[str, ...], optional: tuple[str, ...] = ()
) -> dict[str, np.ndarray]:
    """The named columns of a CSV file as float arrays, every cell checked finite.

    Parameters
    ----------
    path : str or Path
        The CSV file (a header row; lines starting with '#' are comments).
    required : tuple of str
        Columns the file must have.
    optional : tuple of str
        Columns read when present.

    Returns
    -------
    dict
        Column name -> float array, for the required columns and the optional ones present.

    Raises
    ------
    RotbeamInputError
        If the file does not exist or is not a readable CSV, lacks a required column, or has a
        cell that is not a finite number.
    """
    path = Path(path)
    name = str(path)
    if not path.is_file():
        raise RotbeamInputError(f"measurement file {name!r} does not exist")
    try:
        df = pd.read_csv(path, comment="#", skipinitialspace=True)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise RotbeamInputError(f"{name!r} is not a readable CSV file: {first}") from None
    df.columns = [str(c).strip() for c in df.columns]
    missing = [c for c in required if c not in df.columns]
    if missing:
        raise RotbeamInputError(
            f"{name!r} lacks column(s) {', '.join(missing)}; needs {', '.join(required)}"
            + (f" (optional: {', '.join(optional)})" if optional else "")
            + f", has {', '.join(df.columns) or 'none'}"
        )
    out = {}
    for col in required + tuple(c for c in optional if c in df.columns):
        out[col] = _numeric(df[col], col, name)
    return out


def _numeric(values: pd.Series, col: str, name: str) -> np.ndarray:
    num = pd.to_numeric(values, errors="coerce").to_numpy(dtype=float)
    bad = np.flatnonzero(~np.isfinite(num))
    if bad.size:
        k = int(bad[0])
        raise RotbeamInputError(
            f"{name!r}, column {col}, data row {k + 1}: {values.iloc[k]!r} is not a finite "
            f"number ({bad.size} such cell(s))"
        )
    return num


def check_increasing(x: np.ndarray, col: str, name: str) -> None:
    """Check that an abscissa is strictly increasing (sorted, no repeats).

    Parameters
    ----------
    x : numpy.ndarray
        The column's values.
    col : str
        The column's name, for the message.
    name : str
        The file's name, for the message.

    Raises
    ------
    RotbeamInputError
        At the first row where `x` repeats or decreases.
    """
    dx = np.diff(x)
    bad = np.flatnonzero(dx <= 0)
    if bad.size:
        k = int(bad[0])
        what = "repeats" if dx[k] == 0 else "decreases"
        raise RotbeamInputError(
            f"{name!r}, column {col}: {col} {what} at data row {k + 2} ({x[k]:g} then "
            f"{x[k + 1]:g}); allowed: strictly increasing {col} (sort the file, merge repeats)"
        )


@dataclass(frozen=True)
class Ringdown:
    """A free decay: times t [s] and a deflection y (any unit)."""

    t: np.ndarray
    y: np.ndarray
    source: str = ""


#: Fewest samples a ring-down fit accepts (5 parameters and a residual variance, and enough
#: to see several cycles).
MIN_RINGDOWN_POINTS = 20


def load_ringdown(path: str | Path) -> Ringdown:
    """A ring-down file (columns t, y), checked: numbers, >= MIN_RINGDOWN_POINTS rows, t sorted
    and uniformly enough sampled for an FFT start (steps within a factor 2 of the median).

    Parameters
    ----------
    path : str or Path
        CSV file with columns t [s] and y (any unit).

    Returns
    -------
    Ringdown
        The record, with the file's name as its source.

    Raises
    ------
    RotbeamInputError
        If the file breaks any of the checks above, or y is constant.
    """
    cols = read_columns(path, ("t", "y"))
    name = str(path)
    t, y = cols["t"], cols["y"]
    if t.size < MIN_RINGDOWN_POINTS:
        raise RotbeamInputError(
            f"{name!r} has {t.size} data rows; a ring-down fit needs >= {MIN_RINGDOWN_POINTS}"
        )
    check_increasing(t, "t", name)
    dt = np.diff(t)
    med = float(np.median(dt))
    if dt.max() > 2.0 * med or dt.min() < 0.5 * med:
        raise RotbeamInputError(
            f"{name!r}, column t: steps range from {dt.min():.3g} s to {dt.max():.3g} s; allowed: "
            f"uniform sampling within a factor 2 of the median step {med:.3g} s"
        )
    if np.ptp(y) == 0.0:
        raise RotbeamInputError(f"{name!r}, column y: constant ({y[0]:g}); nothing rings down")
    return Ringdown(t, y, name)


@dataclass(frozen=True)
class ResonanceCurve:
    """A measured resonance curve: drive frequencies f_d [Hz], RMS(y_m) and its std if given."""

    f_d: np.ndarray
    rms: np.ndarray
    rms_std: np.ndarray | None = None
    source: str = ""


def load_resonance(path: str | Path, n_params: int = 0) -> ResonanceCurve:
    """A resonance-curve file (columns f_d, rms, optional rms_std), checked: numbers, f_d > 0
    strictly increasing, rms >= 0, rms_std > 0, more rows than `n_params` (the fit needs one
    more to estimate the residual variance).

    Parameters
    ----------
    path : str or Path
        CSV file with columns f_d [Hz], rms (RMS(y_m), dimensionless) and optionally rms_std.
    n_params : int
        Number of parameters to be fitted to the curve (0: no fit planned; at least 2 rows).

    Returns
    -------
    ResonanceCurve
        The curve, with the file's name as its source.

    Raises
    ------
    RotbeamInputError
        If the file breaks any of the checks above.
    """
    cols = read_columns(path, ("f_d", "rms"), ("rms_std",))
    name = str(path)
    f, r = cols["f_d"], cols["rms"]
    if f.size <= max(n_params, 1):
        raise RotbeamInputError(
            f"{name!r} has {f.size} data rows; fitting {n_params} parameter(s) needs at least "
            f"{max(n_params, 1) + 1}"
        )
    if f.min() <= 0:
        raise RotbeamInputError(f"{name!r}, column f_d: {f.min():g}; allowed: f_d > 0 Hz")
    check_increasing(f, "f_d", name)
    if r.min() < 0:
        raise RotbeamInputError(f"{name!r}, column rms: {r.min():g}; allowed: rms >= 0")
    std = cols.get("rms_std")
    if std is not None and not std.min() > 0:
        raise RotbeamInputError(f"{name!r}, column rms_std: {std.min():g}; allowed: rms_std > 0")
    return ResonanceCurve(f, r, std, name)


def finite_or_nan(x: float) -> float:
    """`x` as a float where it is finite, NaN where it is infinite or NaN."""
    return float(x) if math.isfinite(x) else math.nan
