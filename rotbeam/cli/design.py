"""`rotbeam design-move`: the fastest move within limits that leaves the beam still, beside
the rigid-body time-optimal move and its ZV and ZVD shapings."""

from __future__ import annotations

import argparse
import math

from ..config.errors import RotbeamInputError
from . import options, show
from .progress import bar

HELP = ("the shortest slew through an angle (or change of speed) within speed, acceleration and "
        "jerk limits whose residual vibration is at most a tolerance, beside the rigid-body "
        "time-optimal move shaped by ZV and ZVD")  # fmt: skip

#: the API's names in error messages -> the flags that set them
FLAGS = {"angle": "--angle", "omega_start": "--omega-start", "omega_end": "--omega-end",
         "max_speed": "--max-speed", "max_accel": "--max-accel", "max_jerk": "--max-jerk",
         "residual": "--residual", "observable": "--observable", "robust": "--robust"}  # fmt: skip


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam design-move`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    num = options.finite
    p.add_argument("--angle", type=num, help="rest-to-rest slew through this angle [rad], > 0")
    p.add_argument("--omega-start", type=num, help="a change of speed from this steady speed "
                   "[rad/s] (with --omega-end, instead of --angle)")  # fmt: skip
    p.add_argument("--omega-end", type=num, help="... to this steady speed [rad/s]")
    p.add_argument("--max-speed", type=num, required=True, help="largest |Omega| [rad/s]")
    p.add_argument("--max-accel", type=num, required=True, help="largest |dOmega/dt| [rad/s^2]")
    p.add_argument("--max-jerk", type=num, help="largest |d^2 Omega/dt^2| [rad/s^3] (default: "
                   "none; the rigid baseline's acceleration steps)")  # fmt: skip
    p.add_argument("--residual", type=num, default=0.005, help="largest |observable| allowed "
                   "after the move, in its unit (y_m: L; default 0.005)")  # fmt: skip
    p.add_argument("--observable", default="y_m", help="y_m (default), tip, root_moment, "
                   "root_stress or tip_acceleration")  # fmt: skip
    p.add_argument("--robust", metavar="BOX", help="hold at every corner of this box of beam "
                   "inputs, e.g. \"E=+-5%%,gamma=+-25%%,tip_mass=+-10%%\" (share of the value, "
                   "or +-X in SI units)")  # fmt: skip
    p.add_argument("--out", help="write the designed move to this CSV file (columns t, omega: "
                   "`rotbeam simulate --move` reads it)")  # fmt: skip
    p.add_argument("--plot", help="draw Omega(t) of each move and its observable below to this "
                   ".png, .pdf or .svg file")  # fmt: skip
    p.add_argument(
        "--no-baselines",
        action="store_true",
        help="skip the rigid, ZV and ZVD baselines (their full-model runs)",
    )
    p.add_argument("--scene", help="YAML scene file (sections beam, effects, numerics; its "
                   "drive is the designed move's)")  # fmt: skip
    for section in ("beam", "numerics"):
        options.add_section(p, section)
    p.add_argument("--effects", help="comma list of effects switched on, e.g. "
                   "centrifugal,euler,damping")  # fmt: skip
    p.add_argument("--json", action="store_true", help="print one JSON object")


def run(args: argparse.Namespace) -> int:
    """Parse, design, print: the designed move and each baseline (duration, residual, peak),
    how much shorter the design is than each baseline that meets the tolerance, and the cost.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (`add_arguments`).

    Returns
    -------
    int
        Exit status: 0 where a move meets the tolerance, 1 where none does (or the time budget
        cut the search first; the message says what it found so far).

    Raises
    ------
    RotbeamInputError
        For a bad flag, scene file, limit, tolerance, observable or box (one line).
    """
    options.check_plot_path(args.plot)
    if args.out and not args.out.endswith(".csv"):
        raise RotbeamInputError(f"argument --out: {args.out!r}; allowed: a .csv file")
    scene, tol, _ = options.scene_request(args, needs=())
    if tol is not None:
        raise RotbeamInputError("argument --effects: auto is not read here; allowed: a list")

    from ..analysis.move_design import design_move

    try:
        with bar(args, "design-move", "run") as b:

            def progress(text: str) -> None:
                b.update(1)
                b.set_postfix_str(text)

            design = design_move(
                scene, angle=args.angle, omega_start=args.omega_start, omega_end=args.omega_end,
                max_speed=args.max_speed, max_accel=args.max_accel, max_jerk=args.max_jerk,
                residual=args.residual, observable=args.observable, robust=args.robust,
                baselines=not args.no_baselines, progress=progress,
            )  # fmt: skip
    except RotbeamInputError as exc:
        raise RotbeamInputError(_flagged(str(exc))) from None
    if args.out and design.t.size:
        design.write_csv(args.out)
    if args.plot and design.check is not None:
        from ..report.design_figures import design_figure

        design_figure(design, args.plot)
    out = design.summary()
    if args.json:
        show.as_json(out)
        return 0 if design.found else 1
    _table(out)
    return 0 if design.found else 1


def _flagged(message: str) -> str:
    """The message naming the flag of the API name it starts with."""
    for name, flag in FLAGS.items():
        if message.startswith(name) and not message[len(name) : len(name) + 1].isalnum():
            if message[len(name) : len(name) + 1] != "_":
                return f"argument {flag}: {message}"
    return message


def _table(out: dict) -> None:
    """The moves' table and the design's numbers."""
    tol = out["tolerance"]
    print(f"{'move':10s} {'duration_s':>11s} {'residual':>10s} {'peak':>10s}  vs tolerance {tol:g}")
    rows = {"designed": out} | out["baselines"]
    for name, row in rows.items():
        meets = row["residual"] <= tol if math.isfinite(row["residual"]) else False
        note = "meets" if meets else "misses"
        if name != "designed" and row.get("shorter_by") is not None:
            note += f"; designed {100 * row['shorter_by']:.1f} % shorter"
        print(f"{name:10s} {row['duration_s']:11.4f} {row['residual']:10.3g} {row['peak']:10.3g}"
              f"  {note}")  # fmt: skip
    show.line("found", f"{out['found']} ({out['message']})")
    show.line("angle_rad", f"{out['angle_rad']:.6g}")
    if out["robust_residual"] is not None:
        show.line("robust_residual", f"{out['robust_residual']:.3g} (worst over the box)")
    if out["profile_csv"]:
        show.line("profile_csv", out["profile_csv"])
    first = "coast" if out["family"].startswith("pulses") else "spacing"
    show.line("family", f"{out['family']}, {first} {1e3 * out['spacing_s']:.4g} ms, ramps "
              f"{1e3 * out['ramp_s']:.3g} ms, acceleration x{out['kappa']:.3g}")  # fmt: skip
    show.line("first mode", f"{out['f_hz']:.4g} Hz, zeta {out['zeta']:.3g} (the baselines')")
    show.line("seconds", f"{out['seconds']:.3g} search ({out['evaluations']} inner runs), "
              f"{out['baseline_seconds']:.3g} baselines")  # fmt: skip
