"""The work-precision benchmark's runs: what each digit of accuracy costs, measured side by side.

Every curve of the plan (an integrator with a steady-state strategy) runs over a ladder of
tolerances on each scene; each run records its wall time and the errors of RMS(y_m) and of Delta
RMS against references computed in the same run (`reference`), beside the baseline, the plain
port of the paper (`baseline_run`).  What to run is `rotbeam.bench.plan`; the speed-ups, the
default, the summary and the figure are `rotbeam.bench.report`.  The references, the error
measures and the results: docs/numerics.md, "What accuracy costs, and how to trade it".
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from ..model.criterion import delta_rms, rms
from ..model.elastica import DiscreteElastica
from ..model.params import Dimensionless, Drive, Effects
from ..model.surrogate import steady_rms
from ..runs.scene import Scene, quasistatic_midspan, simulate
from ..solve.extrapolation import richardson
from ..solve.numerics import Numerics
from ..solve.system import FirstOrderSystem, OutOfTime
from .plan import CURVES, DELTA_SCALE, BenchPlan


def _scene(plan: BenchPlan, omega0: float, f_d: float, numerics: Numerics) -> Scene:
    return Scene(plan.beam, Drive(omega0, 1.0, f_d), Effects(), numerics)


def _run(scene: Scene) -> dict[str, Any]:
    t0 = time.perf_counter()
    try:
        res = simulate(scene)
    except Exception as exc:  # a failing method is a result of the benchmark, not its end
        return {"seconds": time.perf_counter() - t0, "rms": math.nan, "delta_rms": math.nan,
                "converged": False, "status": -2, "periods": 0, "nfev": 0, "njev": 0, "M": 0,
                "message": f"{type(exc).__name__}: {exc}"}  # fmt: skip
    dyn = res.dynamic
    return {
        "seconds": time.perf_counter() - t0,
        "rms": res.rms_dynamic,
        "delta_rms": res.delta_rms,
        "converged": bool(res.converged),
        "status": dyn.status,
        "periods": dyn.periods,
        "nfev": dyn.nfev,
        "njev": dyn.njev,
        "M": dyn.periodic.M if dyn.periodic is not None else 0,
        "message": dyn.message,
    }


def baseline_run(plan: BenchPlan, omega0: float, f_d: float, N: int, rtol: float) -> dict:
    """The plain port of the paper: scipy Radau with its finite-difference Jacobian, from the
    straight beam at rest, over the a-priori transient time tau_tr = 2 ln(1 / target) / eta
    (every mode decays as exp(-eta tau / 2)), then two periods sampled for the RMS; absolute
    tolerance scipy's default 1e-6, relative tolerance `rtol` (the ladder).

    Parameters
    ----------
    plan : BenchPlan
        The plan: beam, target error, budget per run.
    omega0 : float
        Mean angular velocity Omega_0 [rad/s] (velocity amplitude 1 rad/s).
    f_d : float
        Drive frequency [Hz].
    N : int
        Grid intervals.
    rtol : float
        Relative tolerance of Radau, dimensionless.

    Returns
    -------
    dict
        One run's row: seconds, rms, delta_rms, converged, status, periods, nfev, njev, M,
        message (rms and delta_rms NaN where the run failed or ran out of time).
    """
    t0 = time.perf_counter()
    dl = Dimensionless.from_physical(plan.beam, Drive(omega0, 1.0, f_d), Effects())
    model = DiscreteElastica(dl, N)
    n, P, m, p = model.n, dl.period, 64, 2
    K = math.ceil(2.0 * math.log(1.0 / plan.target) / dl.eta / P)
    taus = (K + np.arange(p * m) / m) * P
    _, y_qs = quasistatic_midspan(model, taus[:m])
    atol = 1e-6  # scipy's default, as MATLAB's ode23tb: the plain port keeps it
    deadline = t0 + plan.max_seconds

    rhs = FirstOrderSystem(model, deadline).rhs

    row = {"rms": math.nan, "delta_rms": math.nan, "converged": False, "status": 1,
           "periods": K + p, "nfev": 0, "njev": 0, "M": 0}  # fmt: skip
    try:
        sol = solve_ivp(rhs, (0.0, (K + p) * P), np.zeros(2 * n), method="Radau", rtol=rtol,
                        atol=atol, t_eval=taus)  # fmt: skip
    except OutOfTime:
        row["message"] = f"out of time ({plan.max_seconds:g} s)"
    else:
        row.update(nfev=sol.nfev, njev=sol.njev, message=f"{K} + {p} periods: {sol.message}")
        if sol.success and np.all(np.isfinite(sol.y)):
            r = rms(np.atleast_1d(model.grid.midspan(sol.y[:n].T)))  # scipy: states in columns
            r_qs = rms(np.tile(y_qs, p))
            row.update(rms=r, delta_rms=delta_rms(r, r_qs), converged=True, status=0)
    row["seconds"] = time.perf_counter() - t0
    return row


def reference(plan: BenchPlan, omega0: float, f_d: float) -> dict[str, Any]:
    """Tight solutions at the three reference grids and their Richardson limits.

    Parameters
    ----------
    plan : BenchPlan
        The plan: beam, reference grids `ref_N`, reference tolerance `ref_tol`.
    omega0 : float
        Mean angular velocity Omega_0 [rad/s] (velocity amplitude 1 rad/s).
    f_d : float
        Drive frequency [Hz].

    Returns
    -------
    dict
        rms_N<N> and delta_N<N> at each grid; rms and delta_rms, the limit of the two finest;
        reference_rel_change against the limit of the two coarsest and reference_digits; seconds.

    Raises
    ------
    RuntimeError
        If a reference run finds no steady state.
    """
    tight = dict(rtol=plan.ref_tol, ss_tol=10 * plan.ref_tol, tail_tol=plan.ref_tol)
    out: dict[str, Any] = {"seconds": 0.0}
    for N in plan.ref_N:
        r = _run(_scene(plan, omega0, f_d, Numerics(N=N, max_seconds=1800.0, **tight)))
        if not (r["converged"] and math.isfinite(r["rms"])):
            raise RuntimeError(f"reference at N={N} failed: {r['message']}")
        out[f"rms_N{N}"], out[f"delta_N{N}"] = r["rms"], r["delta_rms"]
        out["seconds"] += r["seconds"]
    a, b, c = plan.ref_N

    def rich(key: str, n1: int, n2: int) -> float:  # order 2 in 1/N
        return richardson(out[f"{key}_N{n2}"], out[f"{key}_N{n1}"], n2 / n1)

    out["rms"], out["delta_rms"] = rich("rms", b, c), rich("delta", b, c)
    coarse = rich("rms", a, b)
    out["reference_rel_change"] = abs(coarse - out["rms"]) / abs(out["rms"])
    out["reference_digits"] = -math.log10(max(out["reference_rel_change"], 1e-16))
    return out


def _errors(row: dict[str, Any], rms_ref: float, delta_ref: float) -> tuple[float, float]:
    if not (row["converged"] and math.isfinite(row["rms"])):
        return math.nan, math.nan
    e_rms = abs(row["rms"] - rms_ref) / abs(rms_ref)
    e_delta = abs(row["delta_rms"] - delta_ref) / max(abs(delta_ref), DELTA_SCALE)
    return e_rms, e_delta


def run_benchmark(
    plan: BenchPlan, progress: Callable[[str], None] | None = None
) -> tuple[pd.DataFrame, pd.DataFrame]:
    """All runs of the plan, after one untimed warm-up run of each kind.

    Parameters
    ----------
    plan : BenchPlan
        What to run.
    progress : callable or None
        Called with one line per run (e.g. printed to stderr); None: silent.

    Returns
    -------
    runs : pandas.DataFrame
        One row per run: scene, study, curve, N, tol, seconds, rms, errors against the same-N
        and the converged reference, and the solver's counts.
    references : pandas.DataFrame
        One row per scene (`reference`).

    Raises
    ------
    RuntimeError
        If a reference run finds no steady state.
    """
    say = progress or (lambda _msg: None)
    # warm-up: imports, caches and first-call costs stay out of the first timed run
    _run(_scene(plan, 5.0, 2.0, Numerics(N=10)))
    baseline_run(plan, 5.0, 2.0, 10, 1e-2)
    rows: list[dict[str, Any]] = []
    refs: list[dict[str, Any]] = []
    for label, omega0, f_d in plan.scenes:
        say(f"{label}: reference (N = {plan.ref_N}, tol {plan.ref_tol:g})")
        ref = reference(plan, omega0, f_d)
        refs.append({"scene": label, "omega0": omega0, "f_d": f_d, **ref})
        same = (ref[f"rms_N{plan.N}"], ref[f"delta_N{plan.N}"])
        base = {"scene": label, "omega0": omega0, "f_d": f_d}
        for name in plan.curves:
            curve = CURVES[name]
            for tol in plan.tolerances:
                if name == "baseline":
                    r = baseline_run(plan, omega0, f_d, plan.N, tol)
                else:
                    num = replace(curve.numerics_at(plan.N, tol), max_seconds=plan.max_seconds)
                    r = _run(_scene(plan, omega0, f_d, num))
                e, ed = _errors(r, *same)
                et, edt = _errors(r, ref["rms"], ref["delta_rms"])
                rows.append({**base, "study": "method", "curve": name, "N": plan.N, "tol": tol,
                             **r, "err_rms": e, "err_delta": ed,
                             "err_rms_converged": et, "err_delta_converged": edt})  # fmt: skip
                say(f"{label}: {name} tol {tol:g}: {r['seconds']:.3g} s, error {e:.2g}")
                if not r["converged"]:
                    break  # tighter tolerances only cost more
        grid = [(N, False) for N in plan.grid] + [(N, True) for N in plan.grid if 10 <= N <= plan.N]
        for N, extrapolate in grid:
            num = CURVES["default"].numerics_at(N, plan.grid_tol)
            num = replace(num, max_seconds=plan.max_seconds, extrapolate=extrapolate)
            r = _run(_scene(plan, omega0, f_d, num))
            et, edt = _errors(r, ref["rms"], ref["delta_rms"])
            name = "default_richardson" if extrapolate else "default"
            rows.append({**base, "study": "grid", "curve": name, "N": N,
                         "tol": plan.grid_tol, **r, "err_rms": et, "err_delta": edt,
                         "err_rms_converged": et, "err_delta_converged": edt})  # fmt: skip
            say(f"{label}: grid {name} N = {N}: {r['seconds']:.3g} s, error {et:.2g}")
        if plan.surrogate:
            rows.append({**base, **surrogate_row(plan, omega0, f_d, ref)})
    return pd.DataFrame(rows), pd.DataFrame(refs)


def surrogate_row(plan: BenchPlan, omega0: float, f_d: float, ref: dict) -> dict[str, Any]:
    """The one-mode surrogate: time and error against the converged reference.

    Parameters
    ----------
    plan : BenchPlan
        The plan (its beam).
    omega0 : float
        Mean angular velocity Omega_0 [rad/s] (velocity amplitude 1 rad/s).
    f_d : float
        Drive frequency [Hz].
    ref : dict
        The scene's reference (`reference`).

    Returns
    -------
    dict
        The surrogate's row of the runs table (study and curve "surrogate").
    """
    t0 = time.perf_counter()
    dl = Dimensionless.from_physical(plan.beam, Drive(omega0, 1.0, f_d), Effects())
    s = steady_rms(dl)
    r = {"seconds": time.perf_counter() - t0, "rms": s["rms_dynamic"],
         "delta_rms": s["delta_rms"], "converged": True, "status": 0, "periods": 0,
         "nfev": 0, "njev": 0, "M": 0,
         "message": "one-mode Galerkin, harmonic balance"}  # fmt: skip
    et, edt = _errors(r, ref["rms"], ref["delta_rms"])
    return {"study": "surrogate", "curve": "surrogate", "N": 0, "tol": math.nan, **r,
            "err_rms": et, "err_delta": edt, "err_rms_converged": et,
            "err_delta_converged": edt}  # fmt: skip
