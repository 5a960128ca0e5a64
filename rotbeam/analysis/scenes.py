"""Many scenes, one table: each simulated (a steady state, or a single move) and judged.

The workflow's `user_scenes` (config/config.yaml -> results/scenes/) runs through here: a
periodic drive by `rotbeam.runs.scene.simulate` and `judge`, a move by
`rotbeam.runs.move.simulate_move` and `judge_move`.
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import pandas as pd

from ..config.errors import RotbeamInputError
from ..runs.move import simulate_move
from ..runs.scene import Scene, build_scene, simulate
from .verdict import judge, judge_move

#: the table's columns, a scene a row
COLUMNS = ["scene", "drive", "tip_mass_kg", "N", "rms_dynamic", "rms_quasistatic", "delta_rms",
           "quasistatic_ok", "f0_hz", "peak_ym", "peak_ym_quasistatic", "residual_ym",
           "settling_time_s", "converged", "seconds", "verdict"]  # fmt: skip


def build_scenes(
    specs: dict[str, dict[str, Any]], base: str | Path = ".", where: str = "user_scenes"
) -> dict[str, Scene]:
    """Every scene of `specs` built and checked (`rotbeam.runs.scene.build_scene`).

    Parameters
    ----------
    specs : dict
        Scene name -> a scene spec (the sections of a scene file).
    base : str or Path
        The folder relative drive files start from.
    where : str
        What the specs are called in messages (the config key).

    Returns
    -------
    dict
        Scene name -> Scene, in the order given.

    Raises
    ------
    RotbeamInputError
        At the first spec refused, named as where.name.section.key.
    """
    if not isinstance(specs, dict):
        raise RotbeamInputError(f"{where} = {specs!r} must be a mapping of name -> scene spec")
    out = {}
    for name, spec in specs.items():
        try:
            out[name] = build_scene(spec, base)
        except RotbeamInputError as exc:
            raise RotbeamInputError(f"{where}.{name}.{exc}") from None
    return out


def judge_scenes(
    specs: dict[str, dict[str, Any]], threshold: float = 0.10, base: str | Path = "."
) -> pd.DataFrame:
    """Simulate and judge every scene of `specs`, one after the other.

    Parameters
    ----------
    specs : dict
        Scene name -> a scene spec (the sections of a scene file).
    threshold : float
        Delta RMS below which quasi-static is good enough, dimensionless, in (0, 1).
    base : str or Path
        The folder relative drive files start from.

    Returns
    -------
    pandas.DataFrame
        One row per scene (COLUMNS): RMS values, peaks and residual in units of L, Delta RMS
        dimensionless, f0_hz [Hz], settling_time_s and seconds [s]; the peaks, residual and
        settling time only for moves (NaN otherwise).

    Raises
    ------
    RotbeamInputError
        For a scene spec `rotbeam.runs.scene.build_scene` refuses, or a bad threshold.
    """
    rows = []
    for name, scene in build_scenes(specs, base).items():  # all checked before any runs
        t0 = time.perf_counter()
        row: dict[str, Any] = {"scene": name, "drive": scene.drive.kind, "N": scene.numerics.N,
                               "tip_mass_kg": scene.beam.tip_mass}  # fmt: skip
        if scene.drive.move is not None:
            res = simulate_move(scene)
            verdict = judge_move(res, threshold)
            row.update({k: getattr(res, k) for k in ("rms_dynamic", "rms_quasistatic", "delta_rms",
                        "peak_ym", "peak_ym_quasistatic", "residual_ym", "settling_time_s",
                        "converged")})  # fmt: skip
        else:
            res = simulate(scene)
            verdict = judge(res, threshold)
            row.update({k: getattr(res, k) for k in ("rms_dynamic", "rms_quasistatic",
                        "delta_rms", "converged")})  # fmt: skip
        row.update(quasistatic_ok=verdict.quasistatic_ok, f0_hz=verdict.f0_hz, verdict=verdict.text,
                   seconds=time.perf_counter() - t0)  # fmt: skip
        rows.append(row)
    table = pd.DataFrame(rows, columns=COLUMNS)
    return table.fillna({k: math.nan for k in ("peak_ym", "residual_ym")})
