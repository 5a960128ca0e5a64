"""Runs of an atlas of the phase plane: every (Omega_0, f_d) of a grid, one sweep line per
Omega_0 (`rotbeam.runs.sweeps.sweep`, continuation in f_d), the lines in parallel processes
within one time budget for the whole grid (docs/numerics.md, "The atlas")."""

from __future__ import annotations

import math
import multiprocessing
import os
import queue
import time
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..config.errors import RotbeamInputError
from ..model.modes import resonance_frequency_hz
from ..model.params import drive_groups
from ..solve.timebudget import TimeBudget
from .scene import Scene
from .sweeps import COLUMNS, Sweep, sweep

#: the columns of an atlas's table: a sweep's, the line's index (0-based, in Omega_0 order) and
#: whether the point ran (False: the time budget ended before it; its values are NaN)
ATLAS_COLUMNS = [*COLUMNS, "line", "ran"]

#: `status` of a grid point that the time budget did not reach (a sweep's failed point: -2)
NOT_RUN = -3

#: the progress callback: progress(line, k, row) after point k of line `line` (both 0-based)
Progress = Callable[[int, int, dict], None]


@dataclass
class AtlasRun:
    """The rows of an atlas's grid, every point's row (run or marked not run), and where the
    time budget cut it."""

    records: list[dict]  #: one dict per grid point, keyed by `ATLAS_COLUMNS`, line by line
    omega0s: np.ndarray  #: the lines' Omega_0 [rad/s], shape (I,)
    f_ds: np.ndarray  #: the drive frequencies of every line [Hz], shape (J,)
    seconds: float  #: wall time of the whole atlas [s]
    cut_lines: list[int]  #: 0-based lines with a point the budget cut short or did not reach
    message: str = ""  #: where the budget cut the atlas ('' when every point ran)
    workers: int = 1  #: processes that ran the lines

    @property
    def complete(self) -> bool:
        """Whether every point of the grid ran."""
        return not self.cut_lines


def check_axis(values: Sequence[float], name: str, unit: str, positive: bool) -> np.ndarray:
    """One axis of the grid as an array: at least 2 finite values, strictly increasing.

    Parameters
    ----------
    values : sequence of float
        The axis' values.
    name : str
        Its name in messages ("omega0s", "f_ds").
    unit : str
        Its unit, for the messages.
    positive : bool
        Whether every value must be > 0 (drive frequencies).

    Returns
    -------
    numpy.ndarray
        The values as floats, shape (n,).

    Raises
    ------
    RotbeamInputError
        For fewer than 2 values, a value that is not finite (or not > 0 where `positive`), or
        values not strictly increasing.
    """
    try:
        a = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise RotbeamInputError(
            f"{name} = {values!r}: allowed: a list of numbers [{unit}]"
        ) from None
    shown = np.array2string(a, threshold=6, precision=6) if a.ndim else repr(values)
    if a.ndim != 1 or a.size < 2:
        raise RotbeamInputError(f"{name} = {shown}: allowed: at least 2 values [{unit}]")
    if not np.all(np.isfinite(a)):
        raise RotbeamInputError(f"{name} = {shown}: allowed: finite values [{unit}]")
    if positive and not np.all(a > 0):
        raise RotbeamInputError(f"{name} = {shown}: allowed: values > 0 [{unit}]")
    if not np.all(np.diff(a) > 0):
        raise RotbeamInputError(f"{name} = {shown}: allowed: strictly increasing values [{unit}]")
    return a


def grid_axes(omega0: Sequence[float], f_d: Sequence[float],
              name: str = "atlas") -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """The grid of a config's atlas section: [first, last, count] of each axis, linearly spaced.

    Parameters
    ----------
    omega0 : sequence
        [first, last, I]: Omega_0 of the first and last line [rad/s] and the lines, I >= 2.
    f_d : sequence
        [first, last, J]: the lowest and highest drive frequency [Hz], > 0, and J >= 2.
    name : str
        The section's key, for the messages.

    Returns
    -------
    omega0s : numpy.ndarray
        Shape (I,) [rad/s].
    f_ds : numpy.ndarray
        Shape (J,) [Hz].

    Raises
    ------
    RotbeamInputError
        For an axis that is not [first, last, count] with first < last and count an integer
        >= 2, or frequencies not > 0.
    """
    axes = []
    for key, spec, unit, positive in (("omega0", omega0, "rad/s", False),
                                      ("f_d", f_d, "Hz", True)):  # fmt: skip
        allowed = f"allowed: [first, last, count], first < last [{unit}], count an integer >= 2"
        try:
            lo, hi, n = (float(v) for v in spec)
        except (TypeError, ValueError):
            raise RotbeamInputError(f"{name}.{key} = {spec!r}; {allowed}") from None
        if not (n == int(n) and n >= 2 and math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise RotbeamInputError(f"{name}.{key} = {spec!r}; {allowed}")
        if positive and lo <= 0:
            raise RotbeamInputError(f"{name}.{key} = {spec!r}; allowed: frequencies > 0 [{unit}]")
        axes.append(np.linspace(lo, hi, int(n)))
    return axes[0], axes[1]


def line_scene(scene: Scene, omega0: float) -> Scene:
    """The scene of one line: `scene` with the drive's Omega_0 set to `omega0`.

    Parameters
    ----------
    scene : Scene
        The beam, drive, effects and numerics of the atlas; its drive must read Omega_0 (a sine
        or a sum of harmonics).
    omega0 : float
        Mean angular velocity of the line [rad/s].

    Returns
    -------
    Scene
        The line's scene (its f_d is the drive's, replaced point by point by the sweep).

    Raises
    ------
    RotbeamInputError
        For a drive with its own speeds (a sampled profile, a move).
    """
    if not scene.drive.periodic or "omega0" not in scene.drive.as_kind.fields:
        raise RotbeamInputError(
            f"drive: a {scene.drive.kind} has its own speeds; allowed for an atlas: a sine or a "
            "sum of harmonics about the Omega_0 of each line"
        )
    return replace(scene, drive=replace(scene.drive, omega0=float(omega0)))


def run_line(
    scene: Scene,
    omega0: float,
    f_ds: Sequence[float],
    time_budget: TimeBudget | None = None,
    progress: Callable[[int, dict], None] | None = None,
) -> Sweep:
    """One line of the atlas: `sweep` of the scene at Omega_0 = `omega0` over `f_ds`.

    Parameters
    ----------
    scene : Scene
        The atlas's scene (`line_scene`).
    omega0 : float
        The line's Omega_0 [rad/s].
    f_ds : sequence of float
        Drive frequencies [Hz], in the order run.
    time_budget : TimeBudget or None
        The line's budget; None: numerics.max_seconds from the call.
    progress : callable or None
        progress(k, row) after point k.

    Returns
    -------
    Sweep
        The line's rows and where its budget cut it.
    """
    return sweep(line_scene(scene, omega0), f_ds, progress, time_budget)


def line_records(scene: Scene, omega0: float, f_ds: Sequence[float], line: Sweep | None,
                 index: int, why: str) -> list[dict]:  # fmt: skip
    """Every point's row of one line: the sweep's rows, then a marked row (`ran` False, NaN
    values, status `NOT_RUN`, `why` in message) for each point it did not reach.

    Parameters
    ----------
    scene : Scene
        The atlas's scene.
    omega0 : float
        The line's Omega_0 [rad/s].
    f_ds : sequence of float
        The line's drive frequencies [Hz].
    line : Sweep or None
        What the line ran; None: it never started.
    index : int
        The line's 0-based index in the atlas.
    why : str
        Why the points not run were not run.

    Returns
    -------
    list of dict
        len(f_ds) rows keyed by `ATLAS_COLUMNS`.
    """
    ran = list(line.records) if line is not None else []
    out = [{**r, "line": index, "ran": True} for r in ran]
    s = line_scene(scene, omega0)
    f0 = resonance_frequency_hz(s.beam, s.drive.omega_max)
    for f_d in f_ds[len(ran) :]:
        drive = replace(s.drive, f_d=float(f_d))
        row = {key: math.nan for key in ATLAS_COLUMNS}
        row.update(drive_groups(s.beam, drive))
        row.update({"omega0": drive.mean_speed, "f_d": drive.f_d, "amplitude": drive.swing,
                    "f0_hz": f0, "f_n_hz": s.beam.f_n, "N": s.numerics.N, "converged": False,
                    "status": NOT_RUN, "message": f"not run: {why}", "periods": 0,
                    "extrapolated": False, "stable": None, "response": "not run",
                    "seconds": 0.0, "line": index, "ran": False})  # fmt: skip
        out.append({key: row[key] for key in ATLAS_COLUMNS})
    return out


def cut_by_budget(row: dict) -> bool:
    """Whether the time budget cut a grid point: not run, or run without a steady state because
    the budget ended its solvers (its message says so).

    Parameters
    ----------
    row : dict
        A grid point's row (`ATLAS_COLUMNS`).

    Returns
    -------
    bool
    """
    if not row["ran"]:
        return True
    return not row["converged"] and "time budget" in str(row["message"])


def where_cut(records: Sequence[dict]) -> tuple[list[int], list[str]]:
    """The lines the time budget cut, and for each a note: its Omega_0, the points that reached
    an answer, those cut short and those not run.

    Parameters
    ----------
    records : sequence of dict
        An atlas's rows (`ATLAS_COLUMNS`), in any order.

    Returns
    -------
    lines : list of int
        0-based indices of the lines with a point the budget cut, increasing.
    notes : list of str
        One per such line, e.g. "line 3 (Omega_0 = 68.3 rad/s): 1 of 30 points answered, 29 cut
        short, 0 not run".
    """
    by_line: dict[int, list[dict]] = {}
    for r in records:
        by_line.setdefault(int(r["line"]), []).append(r)
    lines, notes = [], []
    for i in sorted(by_line):
        rows = by_line[i]
        cut = [r for r in rows if cut_by_budget(r)]
        if not cut:
            continue
        not_run = sum(not r["ran"] for r in cut)
        lines.append(i)
        notes.append(
            f"line {i + 1} (Omega_0 = {float(rows[0]['omega0']):.6g} rad/s): "
            f"{len(rows) - len(cut)} of {len(rows)} points answered, {len(cut) - not_run} cut "
            f"short, {not_run} not run"
        )
    return lines, notes


#: cut lines a message names one by one; the rest are counted (the rows say which)
LISTED_LINES = 5


def cut_notes(records: Sequence[dict], notes: list[str]) -> str:
    """The points cut in all, then the notes of the first LISTED_LINES cut lines and how many
    more there are: a message that stays readable when a budget cuts many lines.

    Parameters
    ----------
    records : sequence of dict
        An atlas's rows (`ATLAS_COLUMNS`).
    notes : list of str
        `where_cut`'s notes, one per cut line.

    Returns
    -------
    str
        E.g. "237 points cut short, 0 not run; line 1 (...): ...; ...; and 52 more lines".
    """
    cut = [r for r in records if cut_by_budget(r)]
    not_run = sum(not r["ran"] for r in cut)
    short = len(cut) - not_run
    out = f"{short} point{'s' if short != 1 else ''} cut short, {not_run} not run; " + "; ".join(
        notes[:LISTED_LINES]
    )
    more = len(notes) - LISTED_LINES
    return out + (f"; and {more} more line{'s' if more > 1 else ''}" if more > 0 else "")


def default_workers(lines: int) -> int:
    """Processes for `lines` lines: the cores this process may run on, at most one per line.

    Parameters
    ----------
    lines : int
        The atlas's lines.

    Returns
    -------
    int
        >= 1.
    """
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - platforms without affinity
        cores = os.cpu_count() or 1
    return max(1, min(cores, lines))


def run_atlas(
    scene: Scene,
    omega0s: Sequence[float],
    f_ds: Sequence[float],
    workers: int | None = None,
    progress: Progress | None = None,
) -> AtlasRun:
    """Every (Omega_0, f_d) of the grid omega0s x f_ds: one sweep line per Omega_0, the lines
    spread over `workers` processes; `numerics.max_seconds` bounds the whole atlas.

    A line may spend what is left of the atlas's budget times `workers` over the lines left
    (itself included; all that is left for the last `workers` lines), and the sweep shares that
    among its points, so that a line with a point without a steady state (time stepping to the
    end of its share) takes its share, not the atlas's; a line that starts after the budget is
    spent does not run.  Every grid point has a
    row: a point not reached is marked (`ran` False, status `NOT_RUN`, the cut in `message`).

    Parameters
    ----------
    scene : Scene
        Beam, drive (a sine or harmonics; its Omega_0 and f_d are replaced), effects, numerics.
    omega0s : sequence of float
        Omega_0 of the lines [rad/s], >= 2 values, increasing.
    f_ds : sequence of float
        Drive frequencies of every line [Hz], >= 2 values > 0, increasing.
    workers : int or None
        Processes; 1 runs the lines here, one after the other; None: `default_workers`.
    progress : callable or None
        progress(line, k, row) after each point run (from the processes, as they report).

    Returns
    -------
    AtlasRun
        The rows of every grid point and where the budget cut the atlas.

    Raises
    ------
    RotbeamInputError
        For a bad axis, a drive without Omega_0, a `workers` < 1, or input the scenes reject.
    """
    omega0s = check_axis(omega0s, "omega0s", "rad/s", positive=False)
    f_ds = check_axis(f_ds, "f_ds", "Hz", positive=True)
    line_scene(scene, omega0s[0])  # a drive without Omega_0 stops here, not in a process
    if workers is None:
        workers = default_workers(len(omega0s))
    if not isinstance(workers, (int, np.integer)) or workers < 1:
        raise RotbeamInputError(f"workers = {workers!r}: allowed: an integer >= 1")
    total = scene.numerics.max_seconds
    deadline = time.time() + total
    tasks = [(i, scene, float(w), f_ds, deadline, total, len(omega0s), int(workers))
             for i, w in enumerate(omega0s)]  # fmt: skip
    t0 = time.perf_counter()
    if workers == 1:
        done = [_line_task(t, progress) for t in tasks]
    else:
        done = _in_processes(tasks, int(workers), progress)
    records: list[dict] = []
    for (i, w), (line, why) in zip(enumerate(omega0s), done, strict=True):
        records += line_records(scene, w, f_ds, line, i, why)
    seconds = time.perf_counter() - t0
    cut_lines, notes = where_cut(records)
    message = ""
    if cut_lines:
        message = (
            f"the time budget of {total:.3g} s (numerics.max_seconds) cut the atlas, "
            f"{seconds:.3g} s: {len(omega0s) - len(cut_lines)} of {len(omega0s)} lines whole, "
            f"{cut_notes(records, notes)}"
        )
    return AtlasRun(records, omega0s, f_ds, seconds, cut_lines, message, int(workers))


def _line_task(task: tuple, progress: Progress | None = None) -> tuple[Sweep | None, str]:
    """Run one line within what is left of the atlas's budget: (its sweep, why its points not
    run were not run); (None, why) when the budget was spent before it started."""
    index, scene, omega0, f_ds, deadline, total, lines, workers = task
    left = deadline - time.time()
    if left <= 0:
        return None, f"the atlas's time budget of {total:.3g} s was spent before this line began"
    # the line's share: the lines from this one on run `workers` at a time, so each may take
    # what is left times workers / lines left (a line with a hard point takes its share, not
    # the atlas's; the last `workers` lines may take all that is left)
    left *= min(1.0, workers / (lines - index))
    report = _QUEUE.put if _QUEUE is not None else None

    def point(k: int, row: dict) -> None:
        if progress is not None:
            progress(index, k, row)
        if report is not None:
            report((index, k, row))

    line = run_line(scene, omega0, f_ds, TimeBudget(left, whole=total), point)
    return line, line.message


#: the queue a worker process reports its points on (None outside the atlas's processes)
_QUEUE: Any = None


def _start_worker(q: Any) -> None:
    """Each worker's start: keep the queue it reports on."""
    global _QUEUE
    _QUEUE = q


def _in_processes(tasks: list[tuple], workers: int, progress: Progress | None) -> list:
    """The lines' results, in the order of `tasks`, run in `workers` fresh processes (spawned:
    nothing of this process's threads or BLAS state is inherited; each sweep holds BLAS to one
    thread), with the points reported to `progress` as they come."""
    ctx = multiprocessing.get_context("spawn")
    q = ctx.Queue()
    out: list = [None] * len(tasks)

    def drain() -> None:
        while True:
            try:
                line, k, row = q.get_nowait()
            except queue.Empty:
                return
            if progress is not None:
                progress(line, k, row)

    with ProcessPoolExecutor(workers, mp_context=ctx, initializer=_start_worker,
                             initargs=(q,)) as pool:  # fmt: skip
        futures = {pool.submit(_line_task, t): t[0] for t in tasks}
        pending = set(futures)
        try:
            while pending:
                finished, pending = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
                drain()
                for f in finished:
                    out[futures[f]] = f.result()
        except BaseException:
            for f in pending:
                f.cancel()
            raise
    drain()
    return out
