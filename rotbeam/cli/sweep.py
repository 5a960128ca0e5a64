"""`rotbeam sweep`: a line of drive frequencies at one speed, each point continued from its
neighbour's orbit: a resonance curve, dynamic beside quasi-static."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from ..config.errors import RotbeamInputError
from . import options, show
from .progress import bar

HELP = ("a line of drive frequencies from --fd-min to --fd-max at one speed (continuation from "
        "point to point): RMS of both models, Delta RMS and |mu|max at each")  # fmt: skip

#: the table's columns: (row key, heading, format)
TABLE = (
    ("f_d", "f_d [Hz]", ".6g"),
    ("rms_dynamic", "rms_dynamic", ".6g"),
    ("rms_quasistatic", "rms_quasistatic", ".6g"),
    ("delta_rms", "delta_rms", ".6g"),
    ("floquet_max", "floquet_max", ".6f"),
    ("response", "response", "s"),
)


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam sweep`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    options.add_scene_flags(p, drive_frequency=False, auto_effects=False)
    for name in ("fd_min", "fd_max", "points"):
        options.add_field(p, "sweep", name)
    p.add_argument("--out", help="write the rows to this CSV file")


def line_request(args: argparse.Namespace) -> list[float]:
    """The drive frequencies of the line: --points equally spaced from --fd-min to --fd-max.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags.

    Returns
    -------
    list of float
        The frequencies [Hz], in the order run.

    Raises
    ------
    RotbeamInputError
        If a bound is missing, not > 0, or --fd-max is not above --fd-min, or --points < 2.
    """
    lo = options.option(args, "sweep", "fd_min")
    hi = options.option(args, "sweep", "fd_max")
    points = options.option(args, "sweep", "points")
    for value, flag in ((lo, "--fd-min"), (hi, "--fd-max")):
        if value is None:
            raise RotbeamInputError(f"{flag} is missing: give the line's drive frequencies from "
                                    f"--fd-min to --fd-max (Hz, > 0)")  # fmt: skip
    if not hi > lo:
        raise RotbeamInputError(
            f"argument --fd-max: sweep.fd_max = {hi!r} must be > --fd-min ({lo!r})"
        )
    return [lo + (hi - lo) * k / (points - 1) for k in range(points)]


def run(args: argparse.Namespace) -> int:
    """Parse, sweep, print: a row per drive frequency (a table, or JSON with --json), the rows
    as CSV with --out, and why the line stopped short when its time budget
    (numerics.max_seconds, for the whole line) ran out.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (`add_arguments`).

    Returns
    -------
    int
        Exit status: 0 where every point ran and reached a steady state, 1 where not.

    Raises
    ------
    RotbeamInputError
        If a flag or the scene file is not allowed, omega0 or a bound of the line is missing,
        the drive is a single move, or --out does not end in .csv.
    """
    if args.out and Path(args.out).suffix != ".csv":
        raise RotbeamInputError(f"--out must end in .csv, got {args.out!r}")
    f_ds = line_request(args)
    scene, tol, _ = options.scene_request(args, needs=("omega0",))
    if tol is not None:
        raise RotbeamInputError(
            "effects: auto runs an effect budget at one drive frequency; allowed for a sweep: a "
            "list of effects (--effects centrifugal,euler or the scene file's effects section)"
        )

    from ..runs.sweeps import sweep

    with bar(args, "sweep", "point", len(f_ds)) as b:

        def point(k: int, row: dict) -> None:
            b.update(1)
            b.set_postfix_str(f"f_d {row['f_d']:.4g} Hz, RMS {row['rms_dynamic']:.3g}")

        line = sweep(scene, f_ds, point)
    table = line.rows  # made once: the file and the printed or JSON rows read the same table
    if args.out:
        from ..report.io import write_csv

        write_csv(table, args.out)
    rows = table.to_dict(orient="records")
    ok = line.complete and all(r["converged"] for r in rows)
    if args.json:
        show.as_json({"omega0": scene.drive.mean_speed, "f0_hz": _first(rows, "f0_hz"),
                      "points": line.points, "ran": len(rows), "complete": line.complete,
                      "message": line.message, "seconds": line.seconds,
                      "rows": rows})  # fmt: skip
        return 0 if ok else 1
    _print(rows, line)
    return 0 if ok else 1


def _first(rows: list[dict], key: str) -> float:
    return rows[0][key] if rows else math.nan


def _print(rows: list[dict], line) -> None:
    """The table, the failed points' reasons and the line's cost."""
    show.table(rows, TABLE)
    for row in rows:
        if not row["converged"]:
            show.line(f"f_d {row['f_d']:.6g}", row["message"])
    show.line("f0_hz", f"{_first(rows, 'f0_hz'):.6g}")
    rate = len(rows) / line.seconds if line.seconds > 0 else math.inf
    show.line("points", f"{len(rows)} of {line.points} in {line.seconds:.3g} s "
              f"({rate:.3g} per second)")  # fmt: skip
    if line.message:
        show.line("budget", line.message)
