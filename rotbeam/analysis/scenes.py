"""Many scenes, one table: each simulated (a steady state, or a single move) and judged.

The workflow's `user_scenes` (config/config.yaml -> results/scenes/) runs through here: a
periodic drive by `rotbeam.runs.scene.simulate` and `judge`, a move by
`rotbeam.runs.move.simulate_move` and `judge_move`; the observables asked for
(`user_scenes_observe`, `rotbeam.runs.observables`) add their columns.
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import pandas as pd

from ..config.errors import RotbeamInputError
from ..runs.move import simulate_move
from ..runs.observables import OBSERVABLES, observable_names
from ..runs.scene import Scene, build_scene, model_name, simulate
from .verdict import judge, judge_move

#: the table's columns, a scene a row
COLUMNS = ["scene", "drive", "tip_mass_kg", "N", "model", "rms_dynamic", "rms_quasistatic",
           "delta_rms", "quasistatic_ok", "f0_hz", "peak_ym", "peak_ym_quasistatic", "residual_ym",
           "settling_time_s", "converged", "seconds", "verdict"]  # fmt: skip

#: an observable's numbers in the table: the key of its `observables` entry and whether the
#: column carries the observable's unit (Delta RMS is dimensionless)
OBSERVED = (("rms_dynamic", True), ("rms_quasistatic", True), ("delta_rms", False),
            ("peak_dynamic", True), ("peak_quasistatic", True), ("residual", True))  # fmt: skip


def unit_tag(unit: str) -> str:
    """A unit as a column name's suffix: "N m" -> "N_m", "m/s^2" -> "m_s2", "L" -> "L".

    Parameters
    ----------
    unit : str
        An observable's unit (`rotbeam.runs.observables.Observable.unit`).

    Returns
    -------
    str
        Letters, digits and underscores only.
    """
    return unit.replace(" ", "_").replace("/", "_").replace("^", "")


def observable_columns(names: tuple[str, ...]) -> list[str]:
    """The table's columns for the observables `names`: name_key_unit for each number of
    OBSERVED (name_delta_rms without a unit), in the order of `names`.

    Parameters
    ----------
    names : tuple of str
        Observables' names, checked (`rotbeam.runs.observables.observable_names`).

    Returns
    -------
    list of str
        E.g. ``root_moment_rms_dynamic_N_m``, ``root_moment_delta_rms``,
        ``tip_acceleration_peak_dynamic_m_s2``.
    """
    out = []
    for name in names:
        tag = unit_tag(OBSERVABLES[name].unit)
        out += [f"{name}_{key}_{tag}" if unit else f"{name}_{key}" for key, unit in OBSERVED]
    return out


def observe_names(observe: Any, where: str = "user_scenes_observe") -> tuple[str, ...]:
    """The observables a table carries, checked: none for None or an empty list.

    Parameters
    ----------
    observe : list of str, str or None
        Observables' names (`rotbeam.runs.observables.OBSERVABLES`), or one comma-separated
        string.
    where : str
        What the list is called in messages (the config key).

    Returns
    -------
    tuple of str
        The names, in the order given, each once.

    Raises
    ------
    RotbeamInputError
        One line naming the config key, the bad value and the allowed names.
    """
    if observe is None or (isinstance(observe, list | tuple) and not observe):
        return ()
    if not isinstance(observe, str | list | tuple):
        allowed = ", ".join(OBSERVABLES)
        raise RotbeamInputError(f"{where} = {observe!r} must be a list of: {allowed}")
    try:
        return observable_names(observe)
    except RotbeamInputError as exc:
        raise RotbeamInputError(f"{where}: {exc}") from None


def observable_row(table: dict[str, dict[str, Any]]) -> dict[str, float]:
    """One scene's observable columns from its `observables` table (`SceneResult.observables`
    or `MoveResult.observables`); ``residual`` is NaN for a periodic drive, which has no
    after-the-move window.

    Parameters
    ----------
    table : dict
        name -> {``unit``, ``rms_dynamic``, ``rms_quasistatic``, ``delta_rms``,
        ``peak_dynamic``, ``peak_quasistatic`` and, for a move, ``residual``}.

    Returns
    -------
    dict
        Column (`observable_columns`) -> value, in the observable's unit.
    """
    values = [table[name].get(key, math.nan) for name in table for key, _ in OBSERVED]
    return dict(zip(observable_columns(tuple(table)), values, strict=True))


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
    specs: dict[str, dict[str, Any]],
    threshold: float = 0.10,
    base: str | Path = ".",
    observe: Any = None,
) -> pd.DataFrame:
    """Simulate and judge every scene of `specs`, one after the other, with the observables
    asked for.

    Parameters
    ----------
    specs : dict
        Scene name -> a scene spec (the sections of a scene file).
    threshold : float
        Delta RMS below which quasi-static is good enough, dimensionless, in (0, 1).
    base : str or Path
        The folder relative drive files start from.
    observe : list of str, str or None
        Observables (`rotbeam.runs.observables.OBSERVABLES`) whose numbers join the table; None
        or empty: none (config `user_scenes_observe`).

    Returns
    -------
    pandas.DataFrame
        One row per scene (COLUMNS): RMS values, peaks and residual in units of L, Delta RMS
        dimensionless, f0_hz [Hz], settling_time_s and seconds [s]; the peaks, residual and
        settling time only for moves (NaN otherwise).  Then, per observable, the columns of
        `observable_columns`: its RMS and peaks, dynamic and quasi-static, in its unit (named
        in the column), its Delta RMS and, for moves, its residual (NaN otherwise).

    Raises
    ------
    RotbeamInputError
        For a scene spec `rotbeam.runs.scene.build_scene` refuses, an unknown observable or a
        bad threshold.
    """
    names = observe_names(observe)
    rows = []
    for name, scene in build_scenes(specs, base).items():  # all checked before any runs
        t0 = time.perf_counter()
        row: dict[str, Any] = {"scene": name, "drive": scene.drive.kind, "N": scene.numerics.N,
                               "model": model_name(scene.numerics),
                               "tip_mass_kg": scene.beam.tip_mass}  # fmt: skip
        if not scene.drive.periodic:
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
        if names:
            row.update(observable_row(res.observables(names)))
        row.update(quasistatic_ok=verdict.quasistatic_ok, f0_hz=verdict.f0_hz, verdict=verdict.text,
                   seconds=time.perf_counter() - t0)  # fmt: skip
        rows.append(row)
    table = pd.DataFrame(rows, columns=COLUMNS + observable_columns(names))
    return table.fillna({k: math.nan for k in ("peak_ym", "residual_ym")})
