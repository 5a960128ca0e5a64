"""Sweeps of scenes: a line of drive frequencies at one Omega_0, with continuation and with a
row for every point, failed ones included (their reason in `message`), within one time budget
for the whole line (docs/numerics.md, "Sweeps")."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..config.errors import RotbeamInputError
from ..config.threads import one_blas_thread
from ..model.modes import resonance_frequency_hz
from ..model.params import Beam, Drive, Effects, drive_groups
from ..solve.numerics import Numerics
from ..solve.periodic import Neighbour
from ..solve.timebudget import TimeBudget
from .scene import Scene, SceneResult, simulate

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


@dataclass
class Sweep:
    """A line of drive frequencies run by `sweep`: a row per point run, and where the time
    budget cut it."""

    records: list[dict]  #: one dict per point run, keyed by `COLUMNS`
    points: int  #: the points asked for
    seconds: float  #: wall time of the whole line [s]
    cut_at: int | None = None  #: 0-based index of the first point not run (budget), else None
    message: str = ""  #: why the line stops short ('' when every point ran)

    @property
    def rows(self) -> pandas.DataFrame:
        """The points as a table, a row per point run, the columns `COLUMNS` (pandas loads
        here, not before: a job that writes the records skips it)."""
        return _frame(self.records)

    @property
    def complete(self) -> bool:
        """Whether every point ran."""
        return self.cut_at is None


@one_blas_thread
def sweep(
    scene: Scene,
    f_ds: Sequence[float],
    progress: Callable[[int, dict], None] | None = None,
    time_budget: TimeBudget | None = None,
) -> Sweep:
    """Dynamic and quasi-static RMS at each drive frequency of one line (continuation in f_d).

    Every point is `simulate` of the scene at its drive frequency, its collocation started from
    the previous point's orbit (`rotbeam.solve.periodic.continued`); where that orbit is
    not continued, or is unstable or not certified, the point is solved as a scene alone (its
    collocation, then time stepping from its quasi-static state), so that its row is
    `simulate`'s.  A
    point that fails gives a row all the same (NaN values, status -2, the exception in
    `message`); an input error stops the line.  `numerics.max_seconds` is the budget of the
    whole line: each point may spend what is left of it divided by the points left (a point
    without a steady state gets its share, not the line's), and the line stops between points
    once it is spent.

    Parameters
    ----------
    scene : Scene
        The beam, drive, effects and numerics; the drive's f_d is replaced by each of `f_ds`.
    f_ds : sequence of float
        Drive frequencies [Hz], in the order run.
    progress : callable or None
        progress(k, row) after point k (0-based) with its row.
    time_budget : TimeBudget or None
        The wall-time budget of the whole line; None: numerics.max_seconds from the call.

    Returns
    -------
    Sweep
        The rows of the points run and, when the budget stopped the line, where and why.

    Raises
    ------
    RotbeamInputError
        For a drive that does not repeat (a move), or input the scenes reject.
    """
    if not scene.drive.periodic:
        raise RotbeamInputError(
            "drive.move: a sweep needs a periodic drive (a sine, harmonics or a profile); a "
            "single move has no drive frequency to sweep"
        )
    budget = time_budget or TimeBudget(scene.numerics.max_seconds)
    f0 = resonance_frequency_hz(scene.beam, scene.drive.omega_max)
    rows: list[dict] = []
    seed: Neighbour | None = None
    cut = None
    for k, f_d in enumerate(f_ds):
        if budget.spent():
            cut = k
            break
        point = replace(scene, drive=replace(scene.drive, f_d=float(f_d)))
        row, seed = _run_point(point, f0, seed, budget.part(1.0 / (len(f_ds) - k)))
        rows.append(row)
        if progress is not None:
            progress(k, row)
    seconds = budget.elapsed()
    if cut is None:
        return Sweep(rows, len(f_ds), seconds)
    where = f"the line at point {cut + 1} of {len(f_ds)} (f_d = {float(f_ds[cut]):.6g} Hz)"
    message = f"{budget.cut(where)}: {cut} points ran"
    return Sweep(rows, len(f_ds), seconds, cut, message)


def _run_point(
    scene: Scene, f0: float, seed: Neighbour | None, time_budget: TimeBudget
) -> tuple[dict, Neighbour | None]:
    """One point's row, and the neighbour the next point starts from (None after a failure)."""
    beam, drive = scene.beam, scene.drive
    row = {"omega0": drive.mean_speed, "f_d": drive.f_d, "amplitude": drive.swing,
           "f0_hz": f0, "f_n_hz": beam.f_n, "N": scene.numerics.N}  # fmt: skip
    row.update(drive_groups(beam, drive))
    t0 = time.perf_counter()
    try:
        res = simulate(scene, guess=seed, time_budget=time_budget)
    except RotbeamInputError:
        raise
    except Exception as exc:  # one failed point is a row with its reason, not a lost line
        row.update({"rms_dynamic": math.nan, "rms_quasistatic": math.nan, "delta_rms": math.nan,
                    "converged": False, "status": -2, "message": f"{type(exc).__name__}: {exc}",
                    "periods": 0, "extrapolated": False, "floquet_max": math.nan,
                    "stable": None, "response": "unclassified"})  # fmt: skip
        row["seconds"] = time.perf_counter() - t0
        return row, None
    s = res.summary()
    keys = ("rms_dynamic", "rms_quasistatic", "delta_rms", "converged", "status", "message",
            "periods", "floquet_max", "stable")  # fmt: skip
    row.update({key: s[key] for key in keys})
    row["extrapolated"] = bool(s.get("extrapolated", False))
    row["response"] = "periodic" if res.converged else "unclassified"
    row["seconds"] = time.perf_counter() - t0
    return row, _neighbour(res, seed)


def _neighbour(res: SceneResult, before: Neighbour | None) -> Neighbour | None:
    """Where the next point starts: this point's converged orbit; where collocation found
    none, the orbit before it (None without either)."""
    orbit = res.dynamic.periodic
    if orbit is not None and orbit.converged:
        return Neighbour(orbit.theta, res.scene.dimensionless.omega)
    return before


def _frame(rows: list[dict]) -> pandas.DataFrame:
    """The rows as a table with the columns `COLUMNS`."""
    import pandas as pd

    return pd.DataFrame(rows, columns=COLUMNS)


@one_blas_thread
def scan_line(
    beam: Beam,
    omega0: float,
    f_ds: Sequence[float],
    amplitude: float = 1.0,
    effects: Effects | None = None,
    numerics: Numerics | None = None,
    log: Callable[[str], None] | None = None,
) -> pandas.DataFrame:
    """Dynamic and quasi-static RMS at each drive frequency of one line of the sine drive, as a
    table (`line_sweep`'s rows).

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
        Numerical settings; None: the defaults.  max_seconds is the budget of the whole line.
    log : callable or None
        log(line) after every point, and once more when the budget cut the line.

    Returns
    -------
    pandas.DataFrame
        One row per frequency run with the columns `COLUMNS` (RMS of y_m / L, Delta RMS,
        status, message, |mu|max, seconds, ...).

    Raises
    ------
    RotbeamInputError
        For input the scene rejects.
    """
    return line_sweep(beam, omega0, f_ds, amplitude, effects, numerics, log).rows


@one_blas_thread
def line_sweep(
    beam: Beam,
    omega0: float,
    f_ds: Sequence[float],
    amplitude: float = 1.0,
    effects: Effects | None = None,
    numerics: Numerics | None = None,
    log: Callable[[str], None] | None = None,
) -> Sweep:
    """Dynamic and quasi-static RMS at each drive frequency of one line of the sine drive
    (`sweep`, the same code as `rotbeam sweep`), with a log line per point.

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
        Numerical settings; None: the defaults.  max_seconds is the budget of the whole line.
    log : callable or None
        log(line) after every point, and once more when the budget cut the line.

    Returns
    -------
    Sweep
        A record per frequency run, keyed by `COLUMNS` (RMS of y_m / L, Delta RMS, status,
        message, |mu|max, seconds, ...), and where the budget cut the line.

    Raises
    ------
    RotbeamInputError
        For input the scene rejects.
    """
    drive = Drive(omega0=omega0, amplitude=amplitude, f_d=float(f_ds[0]) if len(f_ds) else 1.0)
    scene = Scene(beam, drive, effects or Effects(), numerics or Numerics())
    t_line = time.perf_counter()

    def point(k: int, row: dict) -> None:
        if log is not None:
            log(
                f"[{k + 1}/{len(f_ds)}] Omega_0={omega0:g} f_d={row['f_d']:.4g} Hz "
                f"RMS_dyn={row['rms_dynamic']:.4g} dRMS={row['delta_rms']:.4g} "
                f"{'ok' if row['converged'] else 'FAILED: ' + row['message']} "
                f"({row['seconds']:.2f} s, line {time.perf_counter() - t_line:.1f} s)"
            )

    line = sweep(scene, f_ds, point)
    if line.message and log is not None:
        log(line.message)
    return line


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
