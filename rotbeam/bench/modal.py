"""What the modal reduced model gains and loses, side by side with the full model: its error in
RMS(y_m) and in Delta RMS and its wall time at n modes, at the benchmark's five scenes.

    python3 -m rotbeam.bench.modal [--modes 1,2,3,5] [--N 40] [--repeats 3] [--out table.csv]

The full model (the discrete elastica, default numerics at grid N) is the reference; each scene
runs on it and on the modal model of every n (`numerics.model: modal`) with the same grid and
numerics, alternating, `repeats` times, and the table keeps the fastest run of each.  The
smallest n within 1 % of the full model's RMS and Delta RMS closes each scene's rows.  The
model and the numbers: docs/model.md, "The modal reduced model".
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from dataclasses import replace

import pandas as pd

from ..model.params import Drive, Effects
from ..runs.scene import Scene, simulate
from ..solve.numerics import Numerics
from .plan import SCENES, BenchPlan

#: the largest error the smallest sufficient n is held to, in RMS and Delta RMS (relative)
WITHIN = 0.01


def _timed(scene: Scene) -> tuple[float, float, float, bool]:
    """(seconds, RMS, Delta RMS, converged) of one simulation."""
    t0 = time.perf_counter()
    res = simulate(scene)
    return time.perf_counter() - t0, res.rms_dynamic, res.delta_rms, bool(res.converged)


def modal_table(
    modes: tuple[int, ...] = (1, 2, 3, 5), N: int = 40, repeats: int = 3
) -> pd.DataFrame:
    """The full model and its modal models at the benchmark scenes, timed side by side.

    Parameters
    ----------
    modes : tuple of int
        The numbers of modes n to run, each in [1, N - 1].
    N : int
        Grid intervals of the full model (and of the modal models' basis).
    repeats : int
        Runs of each model per scene (alternating); the fastest counts.

    Returns
    -------
    pandas.DataFrame
        One row per scene and model: scene, model ("full" or "modal n"), modes, seconds, rms,
        delta_rms, err_rms (relative), err_delta (relative to |Delta RMS| of the full model),
        speedup (the full model's seconds over this one's), converged and, on the modal rows,
        within (both errors below WITHIN).
    """
    beam = BenchPlan().beam
    rows = []
    for label, omega0, f_d in SCENES:
        base = Scene(beam, Drive(omega0, 1.0, f_d), Effects(), Numerics(N=N))
        variants = {"full": base}
        for n in modes:
            variants[f"modal {n}"] = replace(base, numerics=Numerics(N=N, model="modal", modes=n))
        runs = {name: [] for name in variants}
        for _ in range(repeats):
            for name, scene in variants.items():
                runs[name].append(_timed(scene))
        best = {name: min(r, key=lambda x: x[0]) for name, r in runs.items()}
        t_full, rms_full, delta_full, _ = best["full"]
        for name, (seconds, rms, delta, ok) in best.items():
            n = 0 if name == "full" else int(name.split()[1])
            err_rms = abs(rms / rms_full - 1.0)
            err_delta = abs(delta / delta_full - 1.0) if delta_full else math.nan
            rows.append({"scene": label, "omega0": omega0, "f_d": f_d, "model": name,
                         "modes": n, "seconds": seconds, "rms": rms, "delta_rms": delta,
                         "err_rms": err_rms, "err_delta": err_delta,
                         "speedup": t_full / seconds, "converged": ok,
                         "within": 0 < n and max(err_rms, err_delta) <= WITHIN})  # fmt: skip
    return pd.DataFrame(rows)


def smallest_modes(table: pd.DataFrame) -> dict[str, int | None]:
    """The smallest n of each scene whose errors in RMS and Delta RMS are both within WITHIN.

    Parameters
    ----------
    table : pandas.DataFrame
        `modal_table`'s rows.

    Returns
    -------
    dict
        scene -> n, or None where no n run is within.
    """
    out: dict[str, int | None] = {}
    for scene, rows in table.groupby("scene", sort=False):
        ok = rows[rows["within"]]
        out[str(scene)] = int(ok["modes"].min()) if len(ok) else None
    return out


def main(argv: list[str] | None = None) -> int:
    """Run the table, print it and the smallest sufficient n, write it to --out if given.

    Parameters
    ----------
    argv : list of str or None
        The arguments (default sys.argv[1:]).

    Returns
    -------
    int
        0.
    """
    p = argparse.ArgumentParser(prog="python3 -m rotbeam.bench.modal")
    p.add_argument("--modes", default="1,2,3,5", help="numbers of modes, comma-separated")
    p.add_argument("--N", type=int, default=40, help="grid intervals (default 40)")
    p.add_argument("--repeats", type=int, default=3, help="runs of each model (default 3)")
    p.add_argument("--out", help="CSV file for the table")
    args = p.parse_args(argv)
    modes = tuple(int(m) for m in args.modes.split(","))
    table = modal_table(modes, args.N, args.repeats)
    cols = ["scene", "model", "seconds", "speedup", "err_rms", "err_delta", "converged"]
    print(table[cols].to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    for scene, n in smallest_modes(table).items():
        print(f"{scene}: smallest n within {WITHIN:.0%} of RMS and Delta RMS: {n}", file=sys.stdout)
    if args.out:
        table.to_csv(args.out, index=False)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
