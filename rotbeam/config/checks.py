"""Number checks shared by every room: each returns the checked value or raises
`RotbeamInputError` with one line naming the key, the value and what is allowed."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .errors import RotbeamInputError


def check_finite(name: str, value: object) -> float:
    """A finite real number (bools are not numbers here).

    Parameters
    ----------
    name : str
        The key, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The value as a float.

    Raises
    ------
    RotbeamInputError
        If the value is not a real number (or is a bool), or is not finite.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise RotbeamInputError(f"{name} must be a number, got {value!r} ({type(value).__name__})")
    value = float(value)
    if not math.isfinite(value):
        raise RotbeamInputError(f"{name} must be finite, got {value!r}")
    return value


def check_positive(name: str, value: object) -> float:
    """A finite real number > 0.

    Parameters
    ----------
    name : str
        The key, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The value as a float.

    Raises
    ------
    RotbeamInputError
        If the value is not a finite real number, or is <= 0.
    """
    value = check_finite(name, value)
    if value <= 0:
        raise RotbeamInputError(f"{name} must be > 0, got {value!r}")
    return value


def check_nonnegative(name: str, value: object) -> float:
    """A finite real number >= 0.

    Parameters
    ----------
    name : str
        The key, for the message.
    value : object
        The value to check.

    Returns
    -------
    float
        The value as a float.

    Raises
    ------
    RotbeamInputError
        If the value is not a finite real number, or is < 0.
    """
    value = check_finite(name, value)
    if value < 0:
        raise RotbeamInputError(f"{name} must be >= 0, got {value!r}")
    return value


def check_threshold(threshold: object, name: str = "threshold") -> float:
    """A Delta RMS threshold: a number in (0, 1).

    Parameters
    ----------
    threshold : object
        The value to check (dimensionless).
    name : str
        The key, for the message.

    Returns
    -------
    float
        The threshold as a float.

    Raises
    ------
    RotbeamInputError
        If the value is not a number (or is a bool), or is not in (0, 1).
    """
    if isinstance(threshold, bool) or not isinstance(threshold, (int, float, np.floating)):
        raise RotbeamInputError(f"{name} must be a number in (0, 1), got {threshold!r}")
    t = float(threshold)
    if not (0.0 < t < 1.0):
        raise RotbeamInputError(f"{name} must be in (0, 1), got {threshold!r}")
    return t


#: what the figures of rotbeam are written as
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def check_plot_suffix(path: str | Path) -> Path:
    """A figure path whose suffix is one of PLOT_SUFFIXES (checked before any work).

    Parameters
    ----------
    path : str or Path
        Where a figure goes.

    Returns
    -------
    Path
        The path as a Path.

    Raises
    ------
    RotbeamInputError
        If the suffix is not one of PLOT_SUFFIXES.
    """
    path = Path(path)
    if path.suffix not in PLOT_SUFFIXES:
        raise RotbeamInputError(f"--plot must end in {', '.join(PLOT_SUFFIXES)}, got {str(path)!r}")
    return path
