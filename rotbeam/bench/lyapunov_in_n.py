"""The largest Lyapunov exponent of the a = 3 rad/s, 7 Hz scene (Omega_0 = 5 rad/s, Table 1 beam,
default effects) as the grid N grows: the response classification (`response_of`, the stepper
`period_stepper` picks) on grids N, each from the quasi-static state, its class, exponent,
spread, section distance, periods and wall time.

    python3 -m rotbeam.bench.lyapunov_in_n [--N 6 8 10 ...] [--transient P] [--section P]
                                           [--out table.csv]
"""

from __future__ import annotations

import argparse
import time

import pandas as pd

from ..model.params import Drive
from ..runs.response import response_of
from ..runs.scene import Scene

SCENE = Scene(drive=Drive(omega0=5.0, amplitude=3.0, f_d=7.0))


def exponent_row(N: int, transient: int, section: int) -> dict:
    """One grid's classification of SCENE.

    Parameters
    ----------
    N : int
        Grid intervals.
    transient, section : int
        Periods of transient and of the classified section.

    Returns
    -------
    dict
        N, response, lyapunov_max and lyapunov_spread [1/s], d(1), periods, seconds, stepper.
    """
    t0 = time.perf_counter()
    r = response_of(SCENE.model(N), SCENE.beam.T, transient, section, max_seconds=1e9)
    return {
        "N": N,
        "response": r.response,
        "lyapunov_max": r.lyapunov_max,
        "lyapunov_spread": r.lyapunov_spread,
        "d1": r.distances[0] if r.distances else float("nan"),
        "periods": r.periods,
        "seconds": time.perf_counter() - t0,
        "message": r.message,
    }


def main(argv: list[str] | None = None) -> pd.DataFrame:
    """Run the grids and print the table.

    Parameters
    ----------
    argv : list of str or None
        Command-line arguments (None: sys.argv).

    Returns
    -------
    pandas.DataFrame
        One row a grid (`exponent_row`).
    """
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--N", type=int, nargs="*", default=[6, 8, 10, 12, 16])
    p.add_argument("--transient", type=int, default=40, help="transient periods (40)")
    p.add_argument("--section", type=int, default=100, help="classified periods (100)")
    p.add_argument("--out", help="write the table to this CSV file")
    args = p.parse_args(argv)
    rows = []
    for N in args.N:
        rows.append(exponent_row(N, args.transient, args.section))
        r = rows[-1]
        print(f"N={N}: {r['response']}, lambda {r['lyapunov_max']:.4g} +- "
              f"{r['lyapunov_spread']:.2g} 1/s, d(1) {r['d1']:.2g}, {r['seconds']:.1f} s",
              flush=True)  # fmt: skip
    table = pd.DataFrame(rows)
    if args.out:
        table.to_csv(args.out, index=False)
    return table


if __name__ == "__main__":
    main()
