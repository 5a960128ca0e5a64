"""Work-precision benchmark: what each digit of accuracy costs, measured side by side in one run.

For a fixed set of scenes on the reference beam, every *curve* (an integrator with a steady-state
strategy, at N = 40) is run over a ladder of tolerances; each run records its wall time and the
error of RMS(y_m) and of Delta RMS against references computed in the same run:

* the **same-N reference** (N = 40, tight tolerance): the error of a run against it is what the
  time integration and the steady-state strategy cost (the spatial error is common to all curves);
* the **converged reference**: Richardson extrapolation (order 2, measured in tests/test_dynamics)
  of tight solutions at N = 40 and 80; the error of the grid study (N = 10 ... 80) and of the
  surrogate is against it.  The same extrapolation from N = 20 and 40 says how many digits the
  reference has (`reference_digits`).

Errors of RMS are relative.  Delta RMS is itself a relative number that is compared with a
threshold (0.1 in the paper), so its error is |Delta - Delta_ref| / max(|Delta_ref|, 0.1).

The baseline is the plain port of the paper: scipy Radau with its finite-difference Jacobian, from
the straight beam at rest, integrated over the time in which every transient decays below the
target error (`baseline_run`); its ladder varies rtol.  The
speed-up of a curve on a scene is the ratio of the cheapest baseline run and the cheapest run of
the curve whose RMS error is below `target` (0.1 %); both measured in the same process.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass, field, replace
from typing import Any

import numpy as np
import pandas as pd

from ..config.errors import RotbeamInputError
from ..model.params import Beam, Dimensionless, Drive, Effects
from ..simulate.scene import Scene, simulate
from ..solve.numerics import Numerics

#: (label, Omega_0 [rad/s], f_d [Hz]) on the reference beam (issue #5)
SCENES: tuple[tuple[str, float, float], ...] = (
    ("O5_f2", 5.0, 2.0),
    ("O5_f7", 5.0, 7.0),
    ("O5_f15", 5.0, 15.0),
    ("O100_f5", 100.0, 5.0),
    ("O100_f30", 100.0, 30.0),
)

TOLERANCES: tuple[float, ...] = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
DELTA_SCALE = 0.1  #: Delta RMS errors are relative to max(|Delta_ref|, this)


@dataclass(frozen=True)
class Curve:
    """One line of the work-precision figure: fixed numerics, tolerance knobs set to `tol`."""

    name: str
    label: str
    numerics: dict[str, Any]
    knobs: tuple[str, ...]  #: Numerics fields set to the tolerance of the ladder

    def numerics_at(self, N: int, tol: float) -> Numerics:
        return Numerics(N=N, **self.numerics, **{k: tol for k in self.knobs})


CURVES: dict[str, Curve] = {
    c.name: c
    for c in (
        Curve(
            "baseline",
            "Radau, FD Jacobian, from rest (baseline)",
            {"method": "Radau", "jacobian": "fd", "start": "rest"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "radau_rest",
            "Radau, exact Jacobian, from rest",
            {"method": "Radau", "start": "rest"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "radau_qs",
            "Radau, from the quasi-static state",
            {"method": "Radau", "start": "quasistatic"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "trbdf2_qs",
            "TR-BDF2 (ode23tb), from the quasi-static state",
            {"method": "TRBDF2", "start": "quasistatic"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "bdf_qs",
            "BDF, from the quasi-static state",
            {"method": "BDF", "start": "quasistatic"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "lsoda_qs",
            "LSODA, from the quasi-static state",
            {"method": "LSODA", "start": "quasistatic"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "collocation",
            "periodic collocation only (no time stepping)",
            {"start": "periodic", "integrate": False},
            ("tail_tol",),
        ),
        Curve(
            "default",
            "periodic collocation + Radau verification (default)",
            {"start": "periodic"},
            ("rtol", "ss_tol", "tail_tol"),
        ),
    )  # fmt: skip
}


@dataclass
class BenchPlan:
    """What to run.  `quick()` is the small plan the tests and the quick config use."""

    scenes: tuple[tuple[str, float, float], ...] = SCENES
    curves: tuple[str, ...] = tuple(CURVES)
    tolerances: tuple[float, ...] = TOLERANCES
    N: int = 40  #: grid of the method comparison
    grid: tuple[int, ...] = (10, 20, 40, 80)  #: grid study with the default curve
    grid_tol: float = 1e-3  #: tolerance of the grid study (the default's)
    ref_N: tuple[int, int, int] = (20, 40, 80)
    ref_tol: float = 1e-7
    max_seconds: float = 60.0  #: per run; a curve's ladder stops at its first failure
    target: float = 1e-3  #: RMS error at which speed-ups are compared
    accept: float = 5e-3  #: error that a default must keep (README: 0.5 %)
    surrogate: bool = True
    beam: Beam = field(default_factory=Beam)

    def __post_init__(self) -> None:
        unknown = set(self.curves) - set(CURVES)
        if unknown:
            raise RotbeamInputError(
                f"bench curves {sorted(unknown)} unknown; allowed: {', '.join(CURVES)}"
            )
        for t in self.tolerances:
            if not (1e-12 <= t <= 0.1):
                raise RotbeamInputError(f"bench tolerance must be in [1e-12, 0.1], got {t!r}")
        if not (math.isfinite(self.max_seconds) and self.max_seconds > 0):
            raise RotbeamInputError(
                f"bench max_seconds must be a finite number > 0, got {self.max_seconds!r}"
            )
        if self.N not in self.ref_N or len(self.ref_N) != 3 or min(self.ref_N) < 3:
            raise RotbeamInputError(
                f"bench N = {self.N} must be one of ref_N = {self.ref_N} (three grids >= 3)"
            )

    @classmethod
    def quick(cls) -> BenchPlan:
        return cls(
            scenes=(SCENES[0], SCENES[3]),
            curves=("baseline", "radau_qs", "trbdf2_qs", "collocation", "default"),
            tolerances=(1e-3, 1e-5),
            grid=(10, 20),
            ref_N=(10, 20, 40),
            ref_tol=1e-7,
            max_seconds=60.0,
        )


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
    tolerance scipy's default 1e-6, relative tolerance `rtol` (the ladder)."""
    from scipy.integrate import solve_ivp

    from ..model.criterion import delta_rms, rms
    from ..model.elastica import DiscreteElastica
    from ..simulate.scene import quasistatic_midspan
    from ..solve.steady import OutOfTime, first_order_rhs

    t0 = time.perf_counter()
    dl = Dimensionless.from_physical(plan.beam, Drive(omega0, 1.0, f_d), Effects())
    model = DiscreteElastica(N, dl.hub_ratio, dl.eta, dl.effects)
    n, P, m, p = model.n, dl.period, 64, 2
    K = math.ceil(2.0 * math.log(1.0 / plan.target) / dl.eta / P)
    taus = (K + np.arange(p * m) / m) * P
    _, y_qs = quasistatic_midspan(dl, N, taus[:m])
    atol = 1e-6  # scipy's default, as MATLAB's ode23tb: the plain port keeps it
    deadline = t0 + plan.max_seconds

    rhs = first_order_rhs(model, dl, deadline)

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
            r = rms(np.atleast_1d(model.grid.midspan(sol.y[:n])))
            r_qs = rms(np.tile(y_qs, p))
            row.update(rms=r, delta_rms=delta_rms(r, r_qs), converged=True, status=0)
    row["seconds"] = time.perf_counter() - t0
    return row


def reference(plan: BenchPlan, omega0: float, f_d: float) -> dict[str, Any]:
    """Tight solutions at the three reference grids and their Richardson limits."""
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
        f1, f2 = out[f"{key}_N{n1}"], out[f"{key}_N{n2}"]
        q = (n2 / n1) ** 2
        return (q * f2 - f1) / (q - 1.0)

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
    """All runs of the plan; returns (runs, references), one row per run / per scene."""
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
    """The one-mode surrogate: time and error against the converged reference."""
    from ..model.surrogate import steady_rms

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


def cheapest(runs: pd.DataFrame, curve: str, target: float, study: str = "method") -> pd.Series:
    """Per scene: seconds of the cheapest run of `curve` with RMS error <= target (NaN: none)."""
    sel = runs[(runs.curve == curve) & (runs.study == study) & (runs.err_rms <= target)]
    return sel.groupby("scene", sort=False)["seconds"].min()


def speedups(runs: pd.DataFrame, target: float) -> pd.DataFrame:
    """Per scene and curve: cheapest seconds at the target error and ratio to the baseline."""
    scenes = list(dict.fromkeys(runs.scene))
    base = cheapest(runs, "baseline", target).reindex(scenes)
    out = []
    for curve in dict.fromkeys(runs[runs.study == "method"].curve):
        t = cheapest(runs, curve, target).reindex(scenes)
        for s in scenes:
            out.append({"scene": s, "curve": curve, "seconds_at_target": t[s],
                        "baseline_seconds": base[s], "speedup": base[s] / t[s]})  # fmt: skip
    return pd.DataFrame(out)


def choose_default(runs: pd.DataFrame, accept: float) -> dict[str, Any]:
    """Cheapest grid setting (N, Richardson or not) whose RMS and Delta RMS errors against the
    converged reference stay within `accept` on every scene."""
    grid = runs[runs.study == "grid"]
    ok = []
    for (curve, N), g in grid.groupby(["curve", "N"]):
        worst = float(np.nanmax(g[["err_rms", "err_delta"]].to_numpy())) if len(g) else math.inf
        good = bool(g.converged.all()) and worst <= accept
        ok.append({"setting": curve, "N": int(N), "worst_error": worst,
                   "total_seconds": float(g.seconds.sum()), "within": good})  # fmt: skip
    table = pd.DataFrame(ok).sort_values(["setting", "N"])
    within = table[table.within].sort_values("total_seconds")
    chosen = None
    if len(within):
        best = within.iloc[0]
        chosen = {"setting": best.setting, "N": int(best.N)}
    return {"accept": accept, "chosen": chosen, "table": table.to_dict("records")}


def summary_markdown(
    runs: pd.DataFrame, refs: pd.DataFrame, plan: BenchPlan, header: Iterable[str] = ()
) -> str:
    from ..report.io import markdown_table

    sp = speedups(runs, plan.target)
    wide = sp.pivot(index="curve", columns="scene", values="speedup")
    wide = wide.reindex([c for c in CURVES if c in wide.index]).reset_index()
    choice = choose_default(runs, plan.accept)
    lines = [
        "# Work-precision benchmark",
        "",
        *header,
        "",
        f"## Speed-up over the baseline at RMS(y_m) error <= {plan.target:g} (N = {plan.N})",
        "",
        "Ratio of the cheapest baseline run and the cheapest run of each curve that reach the",
        "error, measured in the same process (NaN: the curve never reached it in the ladder).",
        "",
        markdown_table(wide, ".3g"),
        "## References",
        "",
        markdown_table(refs[["scene", "omega0", "f_d", "rms", "delta_rms",
                             f"rms_N{plan.N}", "reference_rel_change", "seconds"]], ".6g"),
        f"## Grid study (default curve, tolerance {plan.grid_tol:g}; error vs converged)",
        "",
        markdown_table(pd.DataFrame(choice["table"]), ".3g"),
        f"Cheapest setting within {plan.accept:g} on every scene: {choice['chosen']}",
        "",
        "## Every run",
        "",
        markdown_table(runs[["scene", "study", "curve", "N", "tol", "seconds", "rms",
                             "err_rms", "err_delta", "periods", "nfev", "njev", "M",
                             "converged"]], ".3g"),
    ]  # fmt: skip
    return "\n".join(lines) + "\n"


def plot(runs: pd.DataFrame, refs: pd.DataFrame, plan: BenchPlan, pdf: str, png: str) -> None:
    """Error against wall time, log-log: one panel per scene (N = plan.N), one for the grid."""
    from ..report import style as plotting

    scenes = list(dict.fromkeys(runs.scene))
    ncols = 3
    nrows = math.ceil((len(scenes) + 1) / ncols)
    fig, axes = plotting.figure(nrows, ncols, width=11.0, height=3.4 * nrows, squeeze=False)
    axes = axes.ravel()
    colours = dict(zip(CURVES, ["0.2", "#8c564b", "#d95f02", "#9467bd", "#17becf", "#bcbd22",
                                "#2ca02c", plotting.DYN], strict=True))  # fmt: skip
    markers = dict(zip(CURVES, "ovs^DPxo", strict=True))
    floor = 1e-12
    for ax, scene in zip(axes, scenes, strict=False):
        sel = runs[(runs.scene == scene) & (runs.study == "method")]
        ref = refs[refs.scene == scene].iloc[0]
        for name in [c for c in CURVES if c in set(sel.curve)]:
            c = sel[(sel.curve == name) & sel.converged]
            ax.loglog(c.seconds, np.maximum(c.err_rms, floor), marker=markers[name],
                      color=colours[name], label=CURVES[name].label)  # fmt: skip
        sur = runs[(runs.scene == scene) & (runs.study == "surrogate")]
        if len(sur):
            ax.loglog(sur.seconds, sur.err_rms, "*", ms=11, color="k",
                      label="surrogate (error vs converged)")  # fmt: skip
        spatial = abs(ref[f"rms_N{plan.N}"] - ref["rms"]) / abs(ref["rms"])
        ax.axhline(spatial, ls="--", lw=1, color=plotting.GREY,
                   label=f"N = {plan.N} vs converged (spatial error)")  # fmt: skip
        ax.axhline(plan.target, ls=":", lw=1, color="r", label=f"target {plan.target:g}")
        omega0, f_d = ref["omega0"], ref["f_d"]
        ax.set_title(f"$\\Omega_0$ = {omega0:g} rad/s, $f_d$ = {f_d:g} Hz")
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("relative error of RMS($y_m$)")
    ax = axes[len(scenes)]
    grid = runs[runs.study == "grid"]
    for i, scene in enumerate(scenes):
        for curve, style in (("default", "o-"), ("default_richardson", "s--")):
            g = grid[(grid.scene == scene) & (grid.curve == curve) & grid.converged]
            g = g.sort_values("N")
            lab = scene if curve == "default" else f"{scene}, Richardson N, N/2"
            ax.loglog(g.seconds, np.maximum(g.err_rms, floor), style, color=f"C{i}", label=lab)
            if i == 0:
                for _, r in g.iterrows():
                    ax.annotate(f"N={r.N}", (r.seconds, max(r.err_rms, floor)), fontsize=7,
                                xytext=(3, 3), textcoords="offset points")  # fmt: skip
    ax.axhline(plan.accept, ls=":", lw=1, color="r", label=f"accept {plan.accept:g}")
    from matplotlib.ticker import LogLocator, NullFormatter

    for a in axes:
        a.xaxis.set_minor_formatter(NullFormatter())
        a.yaxis.set_minor_formatter(NullFormatter())
        a.xaxis.set_major_locator(LogLocator(base=10, numticks=12))
    ax.set_title("grid study (default), error vs converged")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("relative error of RMS($y_m$)")
    ax.legend(fontsize=6, ncol=2)
    handles, labels = axes[0].get_legend_handles_labels()
    for ax in axes[len(scenes) + 1 :]:
        ax.axis("off")
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=7, bbox_to_anchor=(0.5, 0.0))
    fig.text(0.99, 0.005, f"errors below {floor:g} (agreement to round-off) are drawn at {floor:g}",
             ha="right", va="bottom", fontsize=7, color=plotting.GREY)  # fmt: skip
    fig.get_layout_engine().set(rect=(0, 0.12 + 0.1 * (nrows == 1), 1, 0.88 - 0.1 * (nrows == 1)))
    plotting.save(fig, pdf, png)


def plan_to_dict(plan: BenchPlan) -> dict[str, Any]:
    d = asdict(plan)
    d["beam"] = asdict(plan.beam)
    return d


OUTPUT_STEMS = ("work_precision",)


def plan_from_dict(spec: dict[str, Any] | None) -> BenchPlan:
    """BenchPlan from a config mapping (keys = BenchPlan fields; `quick: true` starts small)."""
    spec = dict(spec or {})
    base = BenchPlan.quick() if spec.pop("quick", False) else BenchPlan()
    allowed = {f for f in asdict(base) if f != "beam"}
    unknown = set(spec) - allowed
    if unknown:
        raise RotbeamInputError(
            f"benchmark: unknown key(s) {sorted(unknown)}; allowed: {', '.join(sorted(allowed))}"
        )
    shapes = {"scenes": "a list of [label, Omega_0 rad/s, f_d Hz]", "curves": "a list of names",
              "tolerances": "a list of numbers in [1e-12, 0.1]", "grid": "a list of integers",
              "ref_N": "three integers >= 3"}  # fmt: skip
    for key, what in shapes.items():
        if key not in spec:
            continue
        try:
            if key == "scenes":
                spec[key] = tuple((str(s[0]), float(s[1]), float(s[2])) for s in spec[key])
            elif key in ("grid", "ref_N"):
                spec[key] = tuple(int(v) for v in spec[key])
            elif key == "tolerances":
                spec[key] = tuple(float(v) for v in spec[key])
            else:
                spec[key] = tuple(str(v) for v in spec[key])
        except (TypeError, ValueError, IndexError):
            raise RotbeamInputError(f"benchmark.{key} = {spec[key]!r}: must be {what}") from None
    return replace(base, **spec)


def write_outputs(runs: pd.DataFrame, refs: pd.DataFrame, plan: BenchPlan, stem: str) -> None:
    """`stem`.csv (every run), .md (speed-ups, references, grid study, runs), .pdf, .png, and
    `stem`_references.csv; all written atomically."""
    import platform

    from ..report.io import write_csv, write_text

    header = [
        f"Machine: {platform.machine()}, {platform.processor() or '?'}, python "
        f"{platform.python_version()}; wall times from time.perf_counter in one process.",
        f"Scenes (reference beam, a = 1 rad/s): {', '.join(s[0] for s in plan.scenes)}; "
        f"per-run budget {plan.max_seconds:g} s.",
    ]
    write_csv(runs, f"{stem}.csv")
    write_csv(refs, f"{stem}_references.csv")
    write_text(summary_markdown(runs, refs, plan, header), f"{stem}.md")
    plot(runs, refs, plan, f"{stem}.pdf", f"{stem}.png")
