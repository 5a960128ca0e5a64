"""What the move stepper's absolute tolerance costs and what it changes: five moves of the
reference beam at `rotbeam.runs.move.ATOL_SHARE` and at shares 10 and 1000 times smaller,
against a reference at rtol = 1e-7.

    python3 -m rotbeam.bench.move_tolerance [--N 40] [--shares 1,0.1,0.001] [--out table.csv]

The moves (`MOVES`) are designs of `rotbeam design-move` on the reference beam: slews shaped by
one ZV train (ramps of 6.8 and 24.4 ms; a spacing 17 % short), a spin-up by two pulses and a
second-mode train, and the slew with half the beam's mass at its tip.  The table gives each
run's wall time and its residual's and peak's distance from the reference.  The choice and the
numbers: docs/model.md, "Drives".
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable

import pandas as pd

from ..analysis.motion import Limits, Motion, rigid_slew, rigid_speed_change
from ..analysis.move_check import check_move
from ..analysis.move_families import Family, family_motion
from ..runs import move as move_module
from ..runs.scene import build_scene
from .design import CASES, PAYLOAD

#: the reference's relative tolerance (its absolute one at the default share)
REFERENCE_RTOL = 1e-7
#: seconds run after each move (two first-mode periods of the reference beam at rest)
SETTLE = 0.3
#: move name -> (beam fields, family, unknowns, highest first frequency met [Hz])
MOVES: dict[str, tuple[dict, Family, tuple[float, ...], float]] = {
    "slew zv, ramp 6.8 ms": ({}, Family("zv", 0.00678), (0.07206, -0.06925), 7.4),
    "slew zv, ramp 24.4 ms": ({}, Family("zv", 0.0244), (0.07198, -0.0694), 7.4),
    "slew zv, spacing short": ({}, Family("zv", 0.00665), (0.0600, -0.06389), 7.4),
    "spin-up pulses+m2": ({}, Family("pulses", 0.00527, 0.0117, 1.0),
                          (0.02371, 0.8322, 0.008992, 0.1217), 9.0),
    "payload zv+m2": (PAYLOAD, Family("zv", 0.0103, 0.0181, 1.0),
                      (0.1266, -0.03214, 0.01986, -0.02288), 5.0),
}  # fmt: skip


def _motion(family: Family, params: tuple[float, ...]) -> Motion:
    """The move of one family at its unknowns under its worked design's request (`CASES`:
    the spin-up's for two pulses, else the slew's)."""
    r = CASES["spinup" if family.kind == "pulses" else "slew"][1]
    limits = Limits(r["max_speed"], r["max_accel"], None)
    if family.kind == "pulses":
        speeds = (r["omega_start"], r["omega_end"])
        rigid: Callable[[Limits], Motion] = lambda lim: rigid_speed_change(*speeds, lim)  # noqa: E731
        return family_motion(family, params, rigid, limits, speeds)[0]
    return family_motion(family, params, lambda lim: rigid_slew(r["angle"], lim), limits, None)[0]


def _run(beam: dict, motion: Motion, f_hz: float, rtol: float, share: float, N: int):
    """(seconds, residual, peak) of one move at this tolerance."""
    kept = move_module.ATOL_SHARE
    move_module.ATOL_SHARE = share
    try:
        scene = build_scene({"beam": beam, "numerics": {"N": N, "rtol": rtol}})
        t0 = time.perf_counter()
        c = check_move(scene, motion, f_hz, "y_m", SETTLE)
        return time.perf_counter() - t0, c.residual, c.peak
    finally:
        move_module.ATOL_SHARE = kept


def tolerance_table(shares: tuple[float, ...] = (1.0, 0.1, 0.001), N: int = 40) -> pd.DataFrame:
    """Each move at each share of the absolute tolerance, beside the reference.

    Parameters
    ----------
    shares : tuple of float
        Values of ATOL_SHARE to run (at the default rtol, 1e-5).
    N : int
        Grid intervals.

    Returns
    -------
    pandas.DataFrame
        One row per move and share: move, share, seconds, residual, peak, err_residual and
        err_peak (absolute, against the reference [L]), slower (seconds over the first share's).
    """
    rows = []
    for name, (beam, family, params, f_hz) in MOVES.items():
        motion = _motion(family, params)
        _, ref_res, ref_peak = _run(beam, motion, f_hz, REFERENCE_RTOL, shares[0], N)
        first = None
        for share in shares:
            s, res, peak = _run(beam, motion, f_hz, 1e-5, share, N)
            first = s if first is None else first
            rows.append({"move": name, "share": share, "seconds": s, "residual": res,
                         "peak": peak, "err_residual": abs(res - ref_res),
                         "err_peak": abs(peak - ref_peak), "slower": s / first})  # fmt: skip
    return pd.DataFrame(rows)


def main(argv: list[str] | None = None) -> int:
    """Run the table, print it, write it to --out if given.

    Parameters
    ----------
    argv : list of str or None
        The arguments (default sys.argv[1:]).

    Returns
    -------
    int
        0.
    """
    p = argparse.ArgumentParser(prog="python3 -m rotbeam.bench.move_tolerance")
    p.add_argument("--N", type=int, default=40, help="grid intervals (default 40)")
    p.add_argument("--shares", default="1,0.1,0.001", help="ATOL_SHARE values, comma-separated")
    p.add_argument("--out", help="CSV file for the table")
    args = p.parse_args(argv)
    table = tolerance_table(tuple(float(s) for s in args.shares.split(",")), args.N)
    print(table.to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    if args.out:
        table.to_csv(args.out, index=False)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
