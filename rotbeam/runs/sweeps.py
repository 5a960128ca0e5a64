"""Sweeps of scenes: a line of drive frequencies at one Omega_0, with continuation and with a
row for every point, failed ones included (their reason in `message`; docs/numerics.md,
"Sweeps")."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from ..config.errors import RotbeamInputError
from ..model.modes import resonance_frequency_hz
from ..model.params import Beam, Drive, Effects, drive_groups
from ..solve.numerics import Numerics
from .scene import Scene, simulate

if TYPE_CHECKING:
    import pandas

#: the columns of a sweep's table, in order
COLUMNS = [
    "omega0", "f_d", "amplitude", "fd_over_fn", "C_max", "E_max", "E_n", "f_n_hz", "f0_hz",
    "rms_dynamic", "rms_quasistatic", "delta_rms", "converged", "status", "message",
    "periods", "N", "extrapolated", "seconds", "floquet_max", "stable", "response",
]  # fmt: skip


def boundary_scan_frequencies(
    beam: Beam, omega0: float, lo: float, hi: float, points: int, amplitude: float = 1.0
) -> np.ndarray:
    """Drive frequencies for locating f_d* on one C_max line, around the linear resonance.

    Parameters
    ----------
    beam : Beam
        The beam (SI units).
    omega0 : float
        Mean angular velocity Omega_0 [rad/s].
    lo, hi : float
        The range in units of f_0, 0 < lo < hi.
    points : int
        Number of frequencies, >= 2.
    amplitude : float
        Drive amplitude a [rad/s].

    Returns
    -------
    numpy.ndarray
        f_0 * linspace(lo, hi, points) [Hz], shape (points,), f_0 the linear resonance.

    Raises
    ------
    RotbeamInputError
        For a bad range or too few points.
    """
    if not (0 < lo < hi):
        raise RotbeamInputError(f"scan range must satisfy 0 < lo < hi, got lo={lo}, hi={hi}")
    if points < 2:
        raise RotbeamInputError(f"scan points must be >= 2, got {points}")
    return resonance_frequency_hz(beam, abs(omega0) + amplitude) * np.linspace(lo, hi, points)


def scan_line(
    beam: Beam,
    omega0: float,
    f_ds: Sequence[float],
    amplitude: float = 1.0,
    effects: Effects | None = None,
    numerics: Numerics | None = None,
    log: Callable[[str], None] | None = None,
) -> pandas.DataFrame:
    """Dynamic and quasi-static RMS at each drive frequency of one line (continuation in f_d).

    Each point is `simulate` of its scene, its collocation seeded by the previous point's
    converged orbit.  A point that fails gives a row all the same (NaN values, status -2, the
    exception in `message`); an input error stops the line.

    Parameters
    ----------
    beam : Beam
        The beam (SI units).
    omega0 : float
        Mean angular velocity Omega_0 [rad/s].
    f_ds : sequence of float
        Drive frequencies [Hz], in the order run.
    amplitude : float
        Drive amplitude a [rad/s].
    effects : Effects or None
        Effects of the model; None: the defaults.
    numerics : Numerics or None
        Numerical settings; None: the defaults.
    log : callable or None
        log(line) after every point.

    Returns
    -------
    pandas.DataFrame
        One row per frequency with the columns `COLUMNS` (RMS of y_m / L, Delta RMS, status,
        message, |mu|max, seconds, ...).

    Raises
    ------
    RotbeamInputError
        For input the scene rejects.
    """
    import pandas as pd

    effects = effects or Effects()
    numerics = numerics or Numerics()
    f0 = resonance_frequency_hz(beam, abs(omega0) + amplitude)
    rows = []
    guess = None
    t_line = time.perf_counter()
    for k, f_d in enumerate(f_ds):
        drive = Drive(omega0=omega0, amplitude=amplitude, f_d=float(f_d))
        row = {"omega0": omega0, "f_d": float(f_d), "amplitude": amplitude, "f0_hz": f0,
               "f_n_hz": beam.f_n, "N": numerics.N}  # fmt: skip
        row.update(drive_groups(beam, drive))
        t0 = time.perf_counter()
        try:
            res = simulate(Scene(beam, drive, effects, numerics), guess=guess)
            s = res.summary()
            keys = ("rms_dynamic", "rms_quasistatic", "delta_rms", "converged", "status",
                    "message", "periods")  # fmt: skip
            row.update({key: s[key] for key in keys})
            row["extrapolated"] = bool(s.get("extrapolated", False))
            row.update({key: s[key] for key in ("floquet_max", "stable")})
            row["response"] = "periodic" if res.converged else "unclassified"
            if res.dynamic.periodic is not None and res.dynamic.periodic.converged:
                guess = res.dynamic.periodic.theta.T
        except RotbeamInputError:
            raise
        except Exception as exc:  # one failed point is a row with its reason, not a lost line
            row.update({"rms_dynamic": math.nan, "rms_quasistatic": math.nan,
                        "delta_rms": math.nan, "converged": False, "status": -2,
                        "message": f"{type(exc).__name__}: {exc}", "periods": 0,
                        "extrapolated": False, "floquet_max": math.nan, "stable": None,
                        "response": "unclassified"})  # fmt: skip
            guess = None
        row["seconds"] = time.perf_counter() - t0
        rows.append(row)
        if log is not None:
            log(
                f"[{k + 1}/{len(f_ds)}] Omega_0={omega0:g} f_d={f_d:.4g} Hz "
                f"RMS_dyn={row['rms_dynamic']:.4g} dRMS={row['delta_rms']:.4g} "
                f"{'ok' if row['converged'] else 'FAILED: ' + row['message']} "
                f"({row['seconds']:.2f} s, line {time.perf_counter() - t_line:.1f} s)"
            )
    return pd.DataFrame(rows, columns=COLUMNS)


def numerics_from_config(cfg: dict | None) -> Numerics:
    """The `Numerics` of a config's `numerics` section: the defaults with its values.

    Parameters
    ----------
    cfg : dict or None
        Field names of `Numerics` and their values; None: the defaults.

    Returns
    -------
    Numerics
        The checked settings (an unknown field raises TypeError, a bad value as `Numerics`
        does).
    """
    return replace(Numerics(), **(cfg or {}))
