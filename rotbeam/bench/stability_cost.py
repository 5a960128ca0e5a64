"""What the stability analysis costs: each benchmark scene solved with the workflow's numerics
(N = 40 Richardson-extrapolated with N = 20, so two orbits and two Floquet passes a point), with
the CPU seconds of the whole point and of its Floquet passes (the monodromy, its multipliers and
the certificate's defect), best of `repeats`, in one process.

    python3 -m rotbeam.bench.stability_cost [repeats]
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace

import pandas as pd

from ..model.params import Beam, Drive, Effects
from ..runs.scene import Scene, simulate
from ..solve import floquet
from ..solve.numerics import Numerics
from .plan import SCENES

#: the workflow's numerics (config/config.yaml `numerics`)
WORKFLOW_NUMERICS = replace(Numerics(), N=40, extrapolate=True, rtol=1e-5)


@contextmanager
def timed_floquet() -> Iterator[list[float]]:
    """Collect the CPU seconds of every `floquet.orbit_floquet` call made inside the block.

    Yields
    ------
    list of float
        CPU seconds of each call, filled as the block runs.
    """
    spent: list[float] = []
    original = floquet.orbit_floquet

    def timed(*args, **kwargs):
        t0 = time.process_time()
        try:
            return original(*args, **kwargs)
        finally:
            spent.append(time.process_time() - t0)

    floquet.orbit_floquet = timed
    try:
        yield spent
    finally:
        floquet.orbit_floquet = original


def stability_costs(
    numerics: Numerics = WORKFLOW_NUMERICS,
    scenes: tuple[tuple[str, float, float], ...] = SCENES,
    repeats: int = 3,
) -> pd.DataFrame:
    """One row per scene: the point's CPU seconds, its Floquet passes' and their share.

    Parameters
    ----------
    numerics : Numerics
        Numerics of every point (default: the workflow's).
    scenes : sequence of (str, float, float)
        (label, Omega_0 [rad/s], f_d [Hz]) on the Table 1 beam (default: the benchmark's).
    repeats : int
        Runs per scene; the fastest counts.

    Returns
    -------
    pandas.DataFrame
        scene, omega0, f_d, cpu_point and cpu_floquet [s], floquet_passes, share (of the
        point's CPU time), floquet_max and rms.
    """
    rows = []
    for label, omega0, f_d in scenes:
        scene = Scene(Beam(), Drive(omega0=omega0, f_d=f_d), Effects(), numerics)
        best = None
        for _ in range(repeats):
            with timed_floquet() as spent:
                t0 = time.process_time()
                res = simulate(scene)
                cpu = time.process_time() - t0
            if best is None or cpu < best[0]:
                best = (cpu, sum(spent), len(spent), res)
        cpu, fl, calls, res = best
        mu = res.dynamic.floquet.max_abs
        rows.append({"scene": label, "omega0": omega0, "f_d": f_d, "cpu_point": cpu,
                     "cpu_floquet": fl, "floquet_passes": calls, "share": fl / cpu,
                     "floquet_max": mu, "rms": res.rms_dynamic})  # fmt: skip
    return pd.DataFrame(rows)


if __name__ == "__main__":  # pragma: no cover - a measurement, not a test
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    pd.set_option("display.width", 200)
    print(stability_costs(repeats=repeats).to_string(index=False))
