"""What a period of the response classification costs at a = 3 rad/s, 7 Hz (Omega_0 = 5 rad/s,
Table 1 beam, default effects): where a Radau section period goes (steps, calls of the model
and their time); one transient period (the state) and one section period (state and tangent,
16 samples) from the same state on the attractor, by Radau with the Jacobian formed at every
call, scipy's DOP853 on the numpy model and the compiled DOP853, alternating in one process,
best of `repeats`; and numba's first compile and cached load in fresh processes.

    python3 -m rotbeam.bench.classification_cost [repeats] [N ...] [--out table.csv]
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd

from ..model.base import DiscreteModel
from ..model.params import Drive
from ..runs.response import RTOL, SAMPLES, _atol
from ..runs.scene import Scene
from ..solve import stepping
from ..solve.ivp import IvpInterval
from ..solve.lyapunov import tangent_system
from ..solve.steady import initial_state
from ..solve.system import FirstOrderSystem

SCENE = Scene(drive=Drive(omega0=5.0, amplitude=3.0, f_d=7.0))
#: periods stepped (compiled) from the quasi-static state before the measured one
SETTLE = 10
#: stepper name -> how it is built from (model, rtol, atol)
STEPPERS: dict[str, Callable[[DiscreteModel, float, np.ndarray], stepping.PeriodStepper]] = {
    "Radau": lambda m, r, a: stepping.ImplicitStepper(m, r, a),
    "DOP853 (numpy)": lambda m, r, a: stepping.ExplicitStepper(
        m, stepping.EXPLICIT_TOL * r, stepping.EXPLICIT_TOL * a
    ),
    "DOP853 (compiled)": lambda m, r, a: stepping.CompiledStepper(
        m, stepping.EXPLICIT_TOL * r, stepping.EXPLICIT_TOL * a
    ),
}


def settled_state(model: DiscreteModel, atol: np.ndarray) -> np.ndarray:
    """The state after SETTLE periods of the compiled stepper from the quasi-static state.

    Parameters
    ----------
    model : DiscreteModel
        The model.
    atol : numpy.ndarray
        The classification's absolute tolerances, shape (2 n,).

    Returns
    -------
    numpy.ndarray
        The state at tau = SETTLE P.
    """
    z = initial_state(model, "quasistatic")[0]
    P = model.dl.period
    step = STEPPERS["DOP853 (compiled)"](model, RTOL, atol)
    for k in range(SETTLE):
        z, _ = step.state(k * P, (k + 1) * P, z)
    return z


def one_period(stepper: stepping.PeriodStepper, z: np.ndarray, P: float, tangent: bool) -> float:
    """Wall seconds of one period from tau = SETTLE P: the state alone, or the state and a
    tangent vector with SAMPLES samples (what `largest_lyapunov` asks of a section period).

    Parameters
    ----------
    stepper : PeriodStepper
        A fresh stepper.
    z : numpy.ndarray
        The state at SETTLE P.
    P : float
        The drive period.
    tangent : bool
        Whether the tangent rides along.

    Returns
    -------
    float
        Seconds (time.perf_counter).
    """
    ta = SETTLE * P
    v = np.random.default_rng(12345).standard_normal(z.size)
    y = np.concatenate([z, v / np.linalg.norm(v)])
    t_eval = np.append(ta + np.arange(SAMPLES) * P / SAMPLES, ta + P)
    t0 = time.perf_counter()
    if tangent:
        stepper.tangent(ta, ta + P, y, t_eval)
    else:
        stepper.state(ta, ta + P, z)
    return time.perf_counter() - t0


def period_costs(grids: tuple[int, ...] = (6, 8), repeats: int = 3) -> pd.DataFrame:
    """One row per grid, phase and stepper: the best of `repeats` periods, all steppers
    alternating (their order reversed every other repeat).

    Parameters
    ----------
    grids : tuple of int
        Grid intervals N.
    repeats : int
        Periods timed per stepper and phase.

    Returns
    -------
    pandas.DataFrame
        N, phase ("transient" or "section"), stepper, seconds (best), runs (all, s), steps
        (accepted, of the last run) and speedup (Radau's best over this one's).
    """
    rows = []
    for N in grids:
        model = SCENE.model(N)
        qs = initial_state(model, "quasistatic")[0]
        atol = _atol(qs[: model.n], RTOL, model.dl.omega)
        z = settled_state(model, atol)
        for phase in ("transient", "section"):
            times = {name: [] for name in STEPPERS}
            steps = {}
            for r in range(repeats):
                for name in list(STEPPERS)[:: 1 if r % 2 == 0 else -1]:
                    st = STEPPERS[name](model, RTOL, atol)
                    times[name].append(one_period(st, z, model.dl.period, phase == "section"))
                    steps[name] = st.steps
            base = min(times["Radau"])
            for name, ts in times.items():
                rows.append({"N": N, "phase": phase, "stepper": name, "seconds": min(ts),
                             "runs": ", ".join(f"{t:.3g}" for t in ts), "steps": steps[name],
                             "speedup": base / min(ts)})  # fmt: skip
    return pd.DataFrame(rows)


def radau_profile(N: int) -> dict[str, float]:
    """Where a Radau section period goes: its steps, and the calls of the model's right-hand
    side and Jacobian (one of each in every right-hand side of the tangent system) with their
    time.

    Parameters
    ----------
    N : int
        Grid intervals.

    Returns
    -------
    dict
        N, seconds, steps, rhs_calls, jac_calls, rhs_us and jac_us (per call), share (of the
        period spent in the two).
    """
    model = SCENE.model(N)
    qs = initial_state(model, "quasistatic")[0]
    atol = _atol(qs[: model.n], RTOL, model.dl.omega)
    z = settled_state(model, atol)
    system = FirstOrderSystem(model)
    spent = {"rhs": [0, 0.0], "jac": [0, 0.0]}

    def counted(name: str, f: Callable) -> Callable:
        def call(t, y):
            t0 = time.perf_counter()
            out = f(t, y)
            spent[name][0] += 1
            spent[name][1] += time.perf_counter() - t0
            return out

        return call

    aug, aug_jac = tangent_system(counted("rhs", system.rhs), counted("jac", system.jac), z.size)
    tangent_atol = np.concatenate([atol, np.full(z.size, stepping.TANGENT_ATOL)])
    step = IvpInterval(aug, "Radau", RTOL, tangent_atol, aug_jac)
    seconds = one_period(_Tangent(step), z, model.dl.period, True)
    (nr, tr), (nj, tj) = spent["rhs"], spent["jac"]
    return {"N": N, "seconds": seconds, "steps": step.last.steps, "rhs_calls": nr, "jac_calls": nj,
            "rhs_us": 1e6 * tr / nr, "jac_us": 1e6 * tj / nj,
            "share": (tr + tj) / seconds}  # fmt: skip


class _Tangent(stepping.PeriodStepper):
    """An `IvpInterval` of the tangent system as a stepper (`one_period`)."""

    name = "Radau"

    def __init__(self, step: IvpInterval) -> None:
        self.step = step

    def state(self, ta, tb, z):
        """Not used."""
        raise NotImplementedError

    def tangent(self, ta, tb, y, t_eval):
        """(z, v) at tb and the samples (`PeriodStepper.tangent`)."""
        return self.step(ta, tb, y, t_eval)


_FIRST_CALL = (
    "import time\nt0 = time.perf_counter()\nimport numpy as np\n"
    "from rotbeam.model import elastica_kernel as elastica_rk\nt1 = time.perf_counter()\n"
    "y = np.zeros(4); s = np.empty((1, 4)); c = np.zeros(3, dtype=np.int64)\n"
    "m = (np.eye(2), np.eye(2), np.ones((3, 2)), np.ones((2, 3)), np.zeros(9),\n"
    "     np.zeros((1, 3)), np.zeros(0), np.zeros((4, 0)), np.zeros((0, 0)), np.zeros((2, 0)))\n"
    "elastica_rk.advance(y, np.array([0.0, 1e-3]), 0.0, 1e-6, np.full(4, 1e-9), False, m, s, c)\n"
    "print(t1 - t0, time.perf_counter() - t1)\n"
)


def compile_costs() -> dict[str, float]:
    """numba's import, first compile (into an empty cache) and cached load, each in a fresh
    Python.

    Returns
    -------
    dict
        import, compile and cached_load [s].
    """
    root = str(Path(__file__).resolve().parents[2])  # this rotbeam, not an installed one
    path = os.pathsep.join([root, *filter(None, [os.environ.get("PYTHONPATH")])])
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONPATH=path)
        out = []
        for _ in range(2):  # the first compiles into the empty cache, the second loads it
            p = subprocess.run([sys.executable, "-c", _FIRST_CALL], env=env, capture_output=True,
                               text=True, check=True)  # fmt: skip
            out.append([float(x) for x in p.stdout.split()])
    return {"import": out[1][0], "compile": out[0][1], "cached_load": out[1][1]}


def main(argv: list[str]) -> None:
    """Print the table (and write it as CSV with --out PATH).

    Parameters
    ----------
    argv : list of str
        [repeats] [N ...] [--out PATH].
    """
    out = None
    if "--out" in argv:
        i = argv.index("--out")
        out, argv = argv[i + 1], argv[:i] + argv[i + 2 :]
    repeats = int(argv[0]) if argv else 3
    grids = tuple(int(a) for a in argv[1:]) or (6, 8)
    pd.set_option("display.width", 200)
    profile = pd.DataFrame([radau_profile(N) for N in grids])
    print(profile.to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    df = period_costs(grids, repeats)
    print(df.to_string(index=False, float_format=lambda x: f"{x:.3g}"))
    costs = compile_costs()
    print("numba: " + ", ".join(f"{k} {v:.2f} s" for k, v in costs.items()))
    if out:
        df.to_csv(out, index=False)


if __name__ == "__main__":  # pragma: no cover - a measurement, not a test
    main(sys.argv[1:])
