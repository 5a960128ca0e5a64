"""Points a second of a sweep (`rotbeam sweep`; `rotbeam.runs.sweeps.scan_line`, the code it
runs) on lines of the reference beam at N = 40 and the default numerics, for this source tree
and, side by side, for others (e.g. a worktree of an earlier commit), each line run in a fresh
process, the trees in alternating order, the fastest of `--repeats` runs kept.

    python3 -m rotbeam.bench.sweep_rate [--compare DIR ...] [--line NAME ...] [--points K]
                                        [--repeats R] [--max-seconds S] [--out table.csv]

Points a second are per CPU second of the sweep's process (one BLAS thread), so that another
job on the machine slows the figure less than it slows the wall clock; both are in the table.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd

#: the lines: name -> (Omega_0 [rad/s], first and last drive frequency [Hz])
LINES: dict[str, tuple[float, float, float]] = {
    "5 rad/s, 1-20 Hz": (5.0, 1.0, 20.0),
    "100 rad/s, 5-40 Hz": (100.0, 5.0, 40.0),
    "100 rad/s, 5-30 Hz (calm)": (100.0, 5.0, 30.0),
}

#: what a child process runs: the tree's scan_line on one line, timed, as one JSON line
CHILD = """
import json, os, sys, time
import numpy as np
from dataclasses import replace
from rotbeam.model.params import Beam
from rotbeam.runs.sweeps import scan_line
from rotbeam.solve.numerics import Numerics
omega0, lo, hi, points, budget = json.loads(sys.argv[1])
numerics = Numerics() if budget is None else replace(Numerics(), max_seconds=budget)
f_ds = np.linspace(lo, hi, points)
t0, c0 = time.perf_counter(), time.process_time()
df = scan_line(Beam(), omega0, f_ds, numerics=numerics)
wall, cpu = time.perf_counter() - t0, time.process_time() - c0
slow = df.nlargest(1, "seconds")
print(json.dumps({"cpu": cpu, "wall": wall, "points": len(df),
                  "converged": int(df.converged.sum()), "slowest_f_d": float(slow.f_d.iloc[0]),
                  "slowest_s": float(slow.seconds.iloc[0])}))
"""


def run_line(root: Path, line: tuple[float, float, float], points: int, budget: float | None):
    """One line with the source tree at `root`, in a fresh Python with one BLAS thread.

    Parameters
    ----------
    root : Path
        The folder that holds the tree's `rotbeam` package.
    line : tuple of float
        (Omega_0 [rad/s], first and last drive frequency [Hz]).
    points : int
        Drive frequencies, equally spaced.
    budget : float or None
        numerics.max_seconds [s]; None: the tree's default.

    Returns
    -------
    dict
        cpu and wall [s] of the sweep, points run, converged points, and the slowest point's
        f_d [Hz] and seconds.

    Raises
    ------
    RuntimeError
        When the child process fails (its stderr's last lines in the message).
    """
    env = dict(os.environ, PYTHONPATH=str(root), OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1",
               MKL_NUM_THREADS="1")  # fmt: skip
    args = json.dumps([*line, points, budget])
    p = subprocess.run([sys.executable, "-c", CHILD, args], env=env, cwd=root,
                       capture_output=True, text=True)  # fmt: skip
    if p.returncode != 0:
        raise RuntimeError(f"{root}: {' | '.join(p.stderr.strip().splitlines()[-3:])}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def rate_table(
    roots: dict[str, Path],
    lines: dict[str, tuple[float, float, float]] = LINES,
    points: int = 40,
    repeats: int = 2,
    budget: float | None = None,
) -> pd.DataFrame:
    """Each line with each tree, the trees alternating, the fastest run (CPU) kept.

    Parameters
    ----------
    roots : dict
        Label -> the folder holding that tree's `rotbeam` package.
    lines : dict
        Name -> (Omega_0 [rad/s], first and last f_d [Hz]).
    points : int
        Drive frequencies of each line.
    repeats : int
        Runs of each line with each tree.
    budget : float or None
        numerics.max_seconds [s] for every run (None: each tree's default).

    Returns
    -------
    pandas.DataFrame
        line, code, points, converged, cpu_s (the fastest), cpu_all (every run's), wall_s,
        points_per_s (points over CPU seconds), slowest (the slowest point's f_d and seconds).
    """
    runs: dict[tuple[str, str], list[dict]] = {}
    labels = list(roots)
    for name, line in lines.items():
        for r in range(repeats):
            for label in labels if r % 2 == 0 else labels[::-1]:
                out = run_line(roots[label], line, points, budget)
                runs.setdefault((name, label), []).append(out)
                print(f"  {name}, {label}: {out['points']} points, CPU {out['cpu']:.2f} s, "
                      f"wall {out['wall']:.2f} s", file=sys.stderr, flush=True)  # fmt: skip
    rows = []
    for (name, label), outs in runs.items():
        best = min(outs, key=lambda o: o["cpu"])
        rows.append(
            {
                "line": name,
                "code": label,
                "points": best["points"],
                "converged": best["converged"],
                "cpu_s": best["cpu"],
                "cpu_all": ", ".join(f"{o['cpu']:.2f}" for o in outs),
                "wall_s": best["wall"],
                "points_per_s": best["points"] / best["cpu"],
                "slowest": f"{best['slowest_f_d']:.4g} Hz, {best['slowest_s']:.3g} s",
            }
        )
    return pd.DataFrame(rows)  # fmt: skip


def main(argv: list[str] | None = None) -> None:
    """The command line: run the lines, print the table, write it with --out.

    Parameters
    ----------
    argv : list of str or None
        The arguments; None: the process's.
    """
    p = argparse.ArgumentParser(prog="python3 -m rotbeam.bench.sweep_rate",
                                description=__doc__.split("\n\n")[0])  # fmt: skip
    p.add_argument("--compare", nargs="*", default=[], metavar="DIR",
                   help="other source trees (folders holding a rotbeam package)")  # fmt: skip
    p.add_argument("--line", nargs="*", choices=list(LINES), help="lines to run (default: all)")
    p.add_argument("--points", type=int, default=40, help="drive frequencies a line (40)")
    p.add_argument("--repeats", type=int, default=2, help="runs of each line and tree (2)")
    p.add_argument(
        "--max-seconds",
        type=float,
        default=None,
        help="numerics.max_seconds of every run (default: each tree's own)",
    )
    p.add_argument("--out", help="write the table to this CSV file")
    args = p.parse_args(argv)
    here = Path(__file__).resolve().parents[2]
    roots = {"this tree": here} | {str(Path(d)): Path(d).resolve() for d in args.compare}
    lines = {k: LINES[k] for k in args.line} if args.line else LINES
    df = rate_table(roots, lines, args.points, args.repeats, args.max_seconds)
    with pd.option_context("display.width", 200, "display.max_colwidth", 60):
        print(df.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    if args.out:
        from ..report.io import write_csv

        write_csv(df, args.out)


if __name__ == "__main__":  # pragma: no cover - a measurement, not a test
    main()
