"""What a scene costs through the Python API and through the command line, side by side, with
the machine's other cores busy: the API holds BLAS to one thread around its work
(`rotbeam.config.threads`), as the command line does before numpy loads.

    python3 -m rotbeam.bench.api_threads [--repeats R] [--omega0 W] [--fd F] [--out table.csv]

Each run is a fresh process without the thread variables set (as a notebook starts): "cli" is
`rotbeam simulate`, "api" is `rotbeam.simulate` after numpy loaded its BLAS with its own threads,
and "api, unlimited" the same function without the limit (`__wrapped__`: the cost before the
limit).  Busy processes keep every other core at work meanwhile; the three alternate.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd

#: the thread variables a caller may have set; the runs start without them
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS",
                    "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")  # fmt: skip

#: a child that runs the scene through the API, with or without the limit, as one JSON line
API = """
import json, sys, time
import numpy as np  # BLAS loads here with its own thread count, as in a notebook
import rotbeam
from rotbeam.runs.scene import simulate
omega0, f_d, limited = json.loads(sys.argv[1])
scene = rotbeam.Scene(drive=rotbeam.Drive(omega0=omega0, f_d=f_d))
run = simulate if limited else simulate.__wrapped__
t0 = time.perf_counter()
res = run(scene)
print(json.dumps({"wall": time.perf_counter() - t0, "seconds": res.seconds,
                  "rms_dynamic": res.rms_dynamic}))
"""

#: a child that keeps one core busy with BLAS work until it is stopped
BUSY = """
import numpy as np
a = np.random.default_rng(0).random((400, 400))
while True:
    a = np.tanh(a @ a / 400.0)
"""


def clean_env() -> dict[str, str]:
    """The environment without the thread variables (a caller who set none)."""
    return {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}


def run_cli(omega0: float, f_d: float) -> dict:
    """`rotbeam simulate --json` in a fresh process: its own `seconds` and the process' wall time.

    Parameters
    ----------
    omega0, f_d : float
        The scene's Omega_0 [rad/s] and f_d [Hz].

    Returns
    -------
    dict
        ``wall`` [s] of the whole process, ``seconds`` [s] the command reports,
        ``rms_dynamic``.
    """
    cmd = [sys.executable, "-m", "rotbeam", "simulate", "--omega0", str(omega0), "--fd",
           str(f_d), "--json", "--quiet"]  # fmt: skip
    t0 = time.perf_counter()
    p = subprocess.run(cmd, env=clean_env(), capture_output=True, text=True, check=True)
    out = json.loads(p.stdout)
    return {"wall": time.perf_counter() - t0, "seconds": out["seconds"],
            "rms_dynamic": out["rms_dynamic"]}  # fmt: skip


def run_api(omega0: float, f_d: float, limited: bool) -> dict:
    """`rotbeam.simulate` in a fresh Python that loaded numpy first, with or without the limit.

    Parameters
    ----------
    omega0, f_d : float
        The scene's Omega_0 [rad/s] and f_d [Hz].
    limited : bool
        Whether the call holds BLAS to one thread (False: `simulate.__wrapped__`).

    Returns
    -------
    dict
        ``wall`` [s] of the call, ``seconds`` [s] the result reports, ``rms_dynamic``.
    """
    p = subprocess.run([sys.executable, "-c", API, json.dumps([omega0, f_d, limited])],
                       env=clean_env(), capture_output=True, text=True, check=True)  # fmt: skip
    return json.loads(p.stdout.strip().splitlines()[-1])


def side_by_side(omega0: float, f_d: float, repeats: int) -> pd.DataFrame:
    """The three ways, alternating, `repeats` times each, with the other cores busy.

    Parameters
    ----------
    omega0, f_d : float
        The scene's Omega_0 [rad/s] and f_d [Hz].
    repeats : int
        Runs of each way.

    Returns
    -------
    pandas.DataFrame
        One row a run: ``way``, ``repeat``, ``seconds`` (the reported cost), ``wall``,
        ``rms_dynamic``.
    """
    busy = [subprocess.Popen([sys.executable, "-c", BUSY], env=clean_env())
            for _ in range(max(1, (os.cpu_count() or 2) - 1))]  # fmt: skip
    rows = []
    try:
        for r in range(repeats):
            for way in ("cli", "api", "api, unlimited"):
                if way == "cli":
                    out = run_cli(omega0, f_d)
                else:
                    out = run_api(omega0, f_d, way == "api")
                rows.append({"way": way, "repeat": r, **out})
                print(f"{way:15s} {out['seconds']:7.2f} s", file=sys.stderr, flush=True)
    finally:
        for p in busy:
            p.kill()
            p.wait()
    return pd.DataFrame(rows)


def main(argv: list[str] | None = None) -> int:
    """Run the comparison and print (and optionally write) its table.

    Parameters
    ----------
    argv : list of str or None
        Command-line arguments (None: sys.argv[1:]).

    Returns
    -------
    int
        0.
    """
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--omega0", type=float, default=5.0)
    p.add_argument("--fd", type=float, default=7.0)
    p.add_argument("--out")
    args = p.parse_args(argv)
    table = side_by_side(args.omega0, args.fd, args.repeats)
    summary = table.groupby("way")["seconds"].agg(["min", "median", "max"])
    print(summary.to_string(float_format=lambda v: f"{v:.3g}"))
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        table.to_csv(args.out, index=False)
    return 0


if __name__ == "__main__":
    sys.exit(main())
