"""The worked designs of `rotbeam design-move` on the reference beam: a slew through 1 rad at
10 rad/s and 100 rad/s^2 with a residual of 0.005 L, a spin-up from 0 to 20 rad/s, and the
slew with half the beam's mass at its tip, each also robust over E +-5 % and gamma +-25 %.

    python3 -m rotbeam.bench.design [--N 40]
        [--cases slew,robust,spinup,robust_spinup,payload,robust_payload] [--out table.csv]

One row per case and move (designed, rigid, ZV, ZVD; a robust case's design alone): duration,
residual and peak on the full model, whether it meets the tolerance and how much shorter the
design is; per case the search's seconds and, for a robust case, its price in duration over
its nominal design.  The goals and the method: docs/design.md.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from typing import Any

import pandas as pd

from ..analysis.move_design import MoveDesign, design_move
from ..runs.scene import build_scene

#: the reference beam's payload of half its mass (docs/model.md, "A payload at the tip")
PAYLOAD = {"tip_mass": 4.68e-4, "tip_inertia": 1e-8}
BOX = "E=+-5%,gamma=+-25%"
#: case -> (beam fields, request); a robust case's baselines are its nominal case's
CASES: dict[str, tuple[dict[str, float], dict[str, Any]]] = {
    "slew": ({}, {"angle": 1.0, "max_speed": 10.0, "max_accel": 100.0}),
    "robust": ({}, {"angle": 1.0, "max_speed": 10.0, "max_accel": 100.0,
                    "robust": BOX, "baselines": False}),
    "spinup": ({}, {"omega_start": 0.0, "omega_end": 20.0, "max_speed": 20.0,
                    "max_accel": 100.0}),
    "robust_spinup": ({}, {"omega_start": 0.0, "omega_end": 20.0, "max_speed": 20.0,
                           "max_accel": 100.0, "robust": BOX, "baselines": False}),
    "payload": (PAYLOAD, {"angle": 1.0, "max_speed": 10.0, "max_accel": 100.0}),
    "robust_payload": (PAYLOAD, {"angle": 1.0, "max_speed": 10.0, "max_accel": 100.0,
                                 "robust": BOX, "baselines": False}),
}  # fmt: skip
#: robust case -> its nominal case (the robust design's price is its duration over that one's)
NOMINAL = {"robust": "slew", "robust_spinup": "spinup", "robust_payload": "payload"}
TOLERANCE = 0.005


def run_case(name: str, N: int = 40) -> tuple[MoveDesign, float]:
    """One worked design and its wall time.

    Parameters
    ----------
    name : str
        A key of CASES.
    N : int
        Grid intervals of the full model.

    Returns
    -------
    design : MoveDesign
    seconds : float
        Wall time of the whole case (search and baselines).
    """
    beam, request = CASES[name]
    scene = build_scene({"beam": beam, "numerics": {"N": N}})
    t0 = time.perf_counter()
    design = design_move(scene, residual=TOLERANCE, **request)
    return design, time.perf_counter() - t0


def design_table(cases: tuple[str, ...] = tuple(CASES), N: int = 40) -> pd.DataFrame:
    """The worked designs' table.

    Parameters
    ----------
    cases : tuple of str
        Keys of CASES.
    N : int
        Grid intervals.

    Returns
    -------
    pandas.DataFrame
        One row per case and move: case, move, duration_s, residual, peak, meets, shorter_by,
        and per case found, search_s (the search with its full-model checks), case_s (with the
        baselines), evaluations (inner runs), family, robust_residual and robust_price_s (the
        robust design's duration over its nominal case's, `NOMINAL`, where both ran).
    """
    rows, nominal = [], {}
    for name in cases:
        design, seconds = run_case(name, N)
        s = design.summary()
        print(f"{name}: {design.message} ({seconds:.1f} s)", file=sys.stderr, flush=True)
        nominal[name] = design.duration_s
        for row in design.rows():
            rows.append({"case": name, **row, "found": design.found, "search_s": s["seconds"],
                         "case_s": seconds, "evaluations": s["evaluations"],
                         "family": s["family"], "robust_residual": s["robust_residual"],
                         "message": s["message"]})  # fmt: skip
    table = pd.DataFrame(rows)
    price = {c: nominal[c] - nominal[n] for c, n in NOMINAL.items()
             if c in nominal and n in nominal}  # fmt: skip
    table["robust_price_s"] = [price.get(c, math.nan) for c in table["case"]]
    return table


def main(argv: list[str] | None = None) -> int:
    """Run the worked designs, print the table, write it to --out and the slew's figure to
    --plot if given.

    Parameters
    ----------
    argv : list of str or None
        The arguments (default sys.argv[1:]).

    Returns
    -------
    int
        0.
    """
    p = argparse.ArgumentParser(prog="python3 -m rotbeam.bench.design")
    p.add_argument("--N", type=int, default=40, help="grid intervals (default 40)")
    p.add_argument("--cases", default=",".join(CASES), help="comma-separated: " + ", ".join(CASES))
    p.add_argument("--out", help="CSV file for the table")
    args = p.parse_args(argv)
    table = design_table(tuple(args.cases.split(",")), args.N)
    cols = ["case", "move", "duration_s", "residual", "peak", "meets", "shorter_by", "search_s",
            "robust_residual", "robust_price_s"]  # fmt: skip
    print(table[cols].to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    for case, rows in table.groupby("case", sort=False):
        print(f"{case}: {rows['message'].iloc[0]}")
    if args.out:
        table.to_csv(args.out, index=False)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
