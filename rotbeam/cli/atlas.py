"""`rotbeam atlas`: Delta RMS at every (Omega_0, f_d) of a grid, one sweep line per Omega_0,
the lines in parallel on the machine's cores; the f_d* boundary through the grid."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from ..config.errors import RotbeamInputError
from . import options, show
from .progress import bar

HELP = (
    "every (Omega_0, f_d) of an I x J grid (Omega_0 from --omega0-min to --omega0-max, f_d from "
    "--fd-min to --fd-max, each linearly spaced), one sweep line per Omega_0, the lines in "
    "parallel: RMS of both models, Delta RMS and |mu|max at each, and the f_d* boundary"
)

#: the boundary's printed columns: (key, heading, format)
TABLE = (
    ("omega0", "Omega_0 [rad/s]", ".6g"),
    ("C_max", "C_max", ".6g"),
    ("f_d_root", "f_d* [Hz]", ".6g"),
    ("E_star_root", "E*", ".6g"),
    ("points_used", "points", "d"),
)


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam atlas`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    options.add_scene_flags(p, drive_frequency=False, auto_effects=False)
    grid = p.add_argument_group("the grid (I values of Omega_0 by J of f_d, linearly spaced)")
    grid.add_argument("--omega0-min", type=options.finite, help="first line's mean speed "
                      "Omega_0 [rad/s] (required; a finite number)")  # fmt: skip
    grid.add_argument("--omega0-max", type=options.finite, help="last line's mean speed "
                      "Omega_0 [rad/s] (required; > --omega0-min)")  # fmt: skip
    options.add_field(grid, "sweep", "fd_min", help="lowest drive frequency [Hz] (required; > 0)")
    options.add_field(grid, "sweep", "fd_max",
                      help="highest drive frequency [Hz] (required; > --fd-min)")  # fmt: skip
    grid.add_argument("--points", metavar="I,J", help="I lines of Omega_0 by J drive "
                      "frequencies, each >= 2, e.g. 10,10 (required)")  # fmt: skip
    options.add_field(p, "verdict", "threshold")
    p.add_argument("--workers", type=options.integer, help="processes that run the lines "
                   "(default: one per core it may use, at most one per line)")  # fmt: skip
    p.add_argument("--out", help="write every grid point's row to this CSV file")
    p.add_argument("--plot", help="draw Delta RMS over (f_d, Omega_0) and over the "
                   "paper's Fig. 5 axes (C_max, E_max), with the f_d* boundary (.png, .pdf, "
                   ".svg)")  # fmt: skip


def points_flag(text: str | None) -> tuple[int, int]:
    """I and J of --points.

    Parameters
    ----------
    text : str or None
        The flag's value, "I,J".

    Returns
    -------
    tuple of int
        (I, J), each >= 2.

    Raises
    ------
    RotbeamInputError
        If the flag is missing or not two integers >= 2.
    """
    allowed = (
        "allowed: I,J, two integers >= 2 (I lines of Omega_0, J drive frequencies), e.g. 10,10"
    )
    if text is None:
        raise RotbeamInputError(f"--points is missing; {allowed}")
    parts = text.split(",")
    try:
        i, j = (int(q) for q in parts)
    except ValueError:
        raise RotbeamInputError(f"argument --points: {text!r}; {allowed}") from None
    if i < 2 or j < 2:
        raise RotbeamInputError(f"argument --points: {text!r}; {allowed}")
    return i, j


def grid_request(args: argparse.Namespace) -> tuple[np.ndarray, np.ndarray]:
    """The grid of the command line: I values of Omega_0 and J of f_d, linearly spaced.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags.

    Returns
    -------
    omega0s : numpy.ndarray
        [rad/s], shape (I,).
    f_ds : numpy.ndarray
        [Hz], shape (J,).

    Raises
    ------
    RotbeamInputError
        For a missing bound, --omega0 given, a bound not finite (not > 0 for f_d), a maximum
        not above its minimum, or bad --points.
    """
    if getattr(args, options.dest("drive", "omega0")) is not None:
        raise RotbeamInputError("argument --omega0: the atlas sets Omega_0 on each line; "
                                "allowed: --omega0-min and --omega0-max")  # fmt: skip
    for value, flag, what in ((args.omega0_min, "--omega0-min", "rad/s, finite"),
                              (args.omega0_max, "--omega0-max", "rad/s, finite"),
                              (args.sweep__fd_min, "--fd-min", "Hz, > 0"),
                              (args.sweep__fd_max, "--fd-max", "Hz, > 0")):  # fmt: skip
        if value is None:
            raise RotbeamInputError(
                f"{flag} is missing: give the grid's bounds --omega0-min, --omega0-max, "
                f"--fd-min, --fd-max ({flag}: {what})"
            )
    w_lo, w_hi = args.omega0_min, args.omega0_max
    if not w_hi > w_lo:
        raise RotbeamInputError(
            f"argument --omega0-max: {w_hi!r} must be > --omega0-min ({w_lo!r})"
        )
    lo = options.option(args, "sweep", "fd_min")
    hi = options.option(args, "sweep", "fd_max")
    if not hi > lo:
        raise RotbeamInputError(f"argument --fd-max: {hi!r} must be > --fd-min ({lo!r})")
    i, j = points_flag(args.points)
    return np.linspace(w_lo, w_hi, i), np.linspace(lo, hi, j)


def run(args: argparse.Namespace) -> int:
    """Parse, run the grid, print: the atlas's summary and its boundary (a table, or JSON with
    --json), every grid point's row as CSV with --out, the figure with --plot, and where the
    time budget (numerics.max_seconds, for the whole atlas) cut it.

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
        If a flag or the scene file is not allowed, a bound of the grid is missing, the drive
        has its own speeds (a profile) or --out, --plot have a wrong suffix.
    """
    if args.out and Path(args.out).suffix != ".csv":
        raise RotbeamInputError(f"--out must end in .csv, got {args.out!r}")
    options.check_plot_path(args.plot)
    if args.workers is not None and args.workers < 1:
        raise RotbeamInputError(f"argument --workers: {args.workers!r}; allowed: an integer >= 1")
    omega0s, f_ds = grid_request(args)
    threshold = options.option(args, "verdict", "threshold")
    scene, tol, _ = options.scene_request(args, needs=())
    if tol is not None:
        raise RotbeamInputError(
            "effects: auto runs an effect budget at one drive frequency; allowed for an atlas: "
            "a list of effects (--effects centrifugal,euler or the scene file's effects section)"
        )

    from ..analysis.atlas import atlas

    with bar(args, "atlas", "point", len(omega0s) * len(f_ds)) as b:

        def point(line: int, k: int, row: dict) -> None:
            b.update(1)
            b.set_postfix_str(f"Omega_0 {row['omega0']:.4g}, f_d {row['f_d']:.4g} Hz")

        result = atlas(scene, omega0s, f_ds, threshold, args.workers, point)
    if args.out:
        from ..report.io import write_csv

        write_csv(result.rows, args.out)
    if args.plot:
        from ..report.atlas_figure import plot_atlas

        plot_atlas(result, args.plot)
    summary = result.summary()
    ok = result.complete and summary["converged"] == summary["ran"]
    if args.json:
        show.as_json({"summary": summary,
                      "boundary": result.boundary.to_dict(orient="records"),
                      "rows": result.rows.to_dict(orient="records")})  # fmt: skip
        return 0 if ok else 1
    _print(result, summary)
    return 0 if ok else 1


def _print(result, summary: dict) -> None:
    """The boundary line by line, then the summary."""
    show.table(result.boundary.to_dict(orient="records"), TABLE)
    show.line("threshold", f"{summary['threshold']:g} (f_d*: Delta RMS reaches it on the line; "
              f"nan: not within the line)")  # fmt: skip
    show.line("points", f"{summary['ran']} of {summary['points']} ran, {summary['converged']} "
              f"steady, {summary['failed']} without a steady state, {summary['not_run']} not "
              f"run")  # fmt: skip
    show.line("delta_rms", f"{summary['delta_rms_min']:.3g} to {summary['delta_rms_max']:.3g}")
    show.line("floquet_max", f"{summary['floquet_max']:.6f}")
    n = summary["workers"]
    show.line("seconds", f"{summary['seconds']:.3g} ({summary['points_per_second']:.3g} points "
              f"a second, {n} process{'es' if n != 1 else ''})")  # fmt: skip
    if summary["message"]:
        show.line("budget", summary["message"])
