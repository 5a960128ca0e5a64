"""Sweeps of scenes: a line of drive frequencies at one Omega_0, with continuation and with a
row for every point, failed ones included (their reason in `message`)."""

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

COLUMNS = [
    "omega0", "f_d", "amplitude", "fd_over_fn", "C_max", "E_max", "E_n", "f_n_hz", "f0_hz",
    "rms_dynamic", "rms_quasistatic", "delta_rms", "converged", "status", "message",
    "periods", "N", "extrapolated", "seconds", "floquet_max", "stable", "response",
]  # fmt: skip


def boundary_scan_frequencies(
    beam: Beam, omega0: float, lo: float, hi: float, points: int, amplitude: float = 1.0
) -> np.ndarray:
    """Drive frequencies f_0 * linspace(lo, hi, points) for locating f_d* on one C_max line."""
    if not (0 < lo < hi):
        raise RotbeamInputError(f"scan range must satisfy 0 < lo < hi, got lo={lo}, hi={hi}")
    if points < 2:
        raise RotbeamInputError(f"scan points must be >= 2, got {points}")
    return resonance_frequency_hz(beam, omega0, amplitude) * np.linspace(lo, hi, points)


def scan_line(
    beam: Beam,
    omega0: float,
    f_ds: Sequence[float],
    amplitude: float = 1.0,
    effects: Effects | None = None,
    numerics: Numerics | None = None,
    log: Callable[[str], None] | None = None,
) -> pandas.DataFrame:
    """Dynamic and quasi-static RMS at each drive frequency of one line (continuation in f_d)."""
    import pandas as pd

    effects = effects or Effects()
    numerics = numerics or Numerics()
    f0 = resonance_frequency_hz(beam, omega0, amplitude)
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
    return replace(Numerics(), **(cfg or {}))
