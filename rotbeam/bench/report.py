"""The benchmark's report: speed-ups at the target error, the default chosen from the grid
study, the Markdown summary, the work-precision figure, and the files they go to.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np
import pandas as pd

from ..report import style as plotting
from ..report.io import markdown_table, write_csv, write_text
from .plan import CURVES, BenchPlan


def cheapest(runs: pd.DataFrame, curve: str, target: float, study: str = "method") -> pd.Series:
    """Per scene: seconds of the cheapest run of `curve` with RMS error <= target (NaN: none).

    Parameters
    ----------
    runs : pandas.DataFrame
        Every run of the benchmark (`run_benchmark`).
    curve : str
        The curve's name.
    target : float
        The relative error of RMS(y_m) to reach.
    study : str
        "method", "grid" or "surrogate".

    Returns
    -------
    pandas.Series
        Wall time [s] by scene, for the scenes where the curve reached the target.
    """
    sel = runs[(runs.curve == curve) & (runs.study == study) & (runs.err_rms <= target)]
    return sel.groupby("scene", sort=False)["seconds"].min()


def speedups(runs: pd.DataFrame, target: float) -> pd.DataFrame:
    """Per scene and curve: cheapest seconds at the target error and ratio to the baseline.

    Parameters
    ----------
    runs : pandas.DataFrame
        Every run of the benchmark (`run_benchmark`).
    target : float
        The relative error of RMS(y_m) to reach.

    Returns
    -------
    pandas.DataFrame
        One row per (scene, curve): seconds_at_target and baseline_seconds [s], speedup (NaN
        where either never reached the target).
    """
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
    converged reference stay within `accept` on every scene.

    Parameters
    ----------
    runs : pandas.DataFrame
        Every run of the benchmark (`run_benchmark`); its grid study is read.
    accept : float
        The largest relative error a default may have.

    Returns
    -------
    dict
        ``accept``, ``chosen`` ({"setting", "N"}, or None where no setting keeps it) and
        ``table`` (per setting and N: worst error, total seconds, within).
    """
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
    """The benchmark's Markdown summary: speed-ups, references, grid study and every run.

    Parameters
    ----------
    runs : pandas.DataFrame
        Every run of the benchmark (`run_benchmark`).
    refs : pandas.DataFrame
        The references, one row per scene.
    plan : BenchPlan
        The plan (target, accept, N, grid tolerance).
    header : iterable of str
        Lines under the title (machine, scenes, budget).

    Returns
    -------
    str
        The Markdown document.
    """
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


#: errors below this (agreement to round-off) are drawn at it on the log axes
FLOOR = 1e-12


def plot(runs: pd.DataFrame, refs: pd.DataFrame, plan: BenchPlan, pdf: str, png: str) -> None:
    """Error against wall time, log-log: one panel per scene (N = plan.N), one for the grid.

    Parameters
    ----------
    runs : pandas.DataFrame
        Every run of the benchmark (`run_benchmark`).
    refs : pandas.DataFrame
        The references, one row per scene.
    plan : BenchPlan
        The plan (N, target, accept).
    pdf, png : str
        The figure's files, written atomically.
    """
    from matplotlib.ticker import LogLocator, NullFormatter

    scenes = list(dict.fromkeys(runs.scene))
    ncols = 3
    nrows = math.ceil((len(scenes) + 1) / ncols)
    fig, axes = plotting.figure(nrows, ncols, width=11.0, height=3.4 * nrows, squeeze=False)
    axes = axes.ravel()
    for ax, scene in zip(axes, scenes, strict=False):
        _scene_panel(ax, runs, refs[refs.scene == scene].iloc[0], scene, plan)
    _grid_panel(axes[len(scenes)], runs, scenes, plan)
    for a in axes:
        a.xaxis.set_minor_formatter(NullFormatter())
        a.yaxis.set_minor_formatter(NullFormatter())
        a.xaxis.set_major_locator(LogLocator(base=10, numticks=12))
    handles, labels = axes[0].get_legend_handles_labels()
    for ax in axes[len(scenes) + 1 :]:
        ax.axis("off")
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=7, bbox_to_anchor=(0.5, 0.0))
    fig.text(0.99, 0.005, f"errors below {FLOOR:g} (agreement to round-off) are drawn at {FLOOR:g}",
             ha="right", va="bottom", fontsize=7, color=plotting.GREY)  # fmt: skip
    fig.get_layout_engine().set(rect=(0, 0.12 + 0.1 * (nrows == 1), 1, 0.88 - 0.1 * (nrows == 1)))
    plotting.save(fig, pdf, png)


def _scene_panel(ax, runs: pd.DataFrame, ref: pd.Series, scene: str, plan: BenchPlan) -> None:
    """One scene: every curve's error against wall time, the surrogate, N's spatial error."""
    colours = dict(zip(CURVES, ["0.2", "#8c564b", "#d95f02", "#9467bd", "#17becf", "#bcbd22",
                                "#2ca02c", plotting.DYN], strict=True))  # fmt: skip
    markers = dict(zip(CURVES, "ovs^DPxo", strict=True))
    sel = runs[(runs.scene == scene) & (runs.study == "method")]
    for name in [c for c in CURVES if c in set(sel.curve)]:
        c = sel[(sel.curve == name) & sel.converged]
        ax.loglog(c.seconds, np.maximum(c.err_rms, FLOOR), marker=markers[name],
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


def _grid_panel(ax, runs: pd.DataFrame, scenes: list[str], plan: BenchPlan) -> None:
    """The grid study (default curve, with and without Richardson), error vs converged."""
    grid = runs[runs.study == "grid"]
    for i, scene in enumerate(scenes):
        for curve, style in (("default", "o-"), ("default_richardson", "s--")):
            g = grid[(grid.scene == scene) & (grid.curve == curve) & grid.converged]
            g = g.sort_values("N")
            lab = scene if curve == "default" else f"{scene}, Richardson N, N/2"
            ax.loglog(g.seconds, np.maximum(g.err_rms, FLOOR), style, color=f"C{i}", label=lab)
            if i == 0:
                for _, r in g.iterrows():
                    ax.annotate(f"N={r.N}", (r.seconds, max(r.err_rms, FLOOR)), fontsize=7,
                                xytext=(3, 3), textcoords="offset points")  # fmt: skip
    ax.axhline(plan.accept, ls=":", lw=1, color="r", label=f"accept {plan.accept:g}")
    ax.set_title("grid study (default), error vs converged")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("relative error of RMS($y_m$)")
    # beside the panel: inside it the legend would cover the points of the finest grids
    ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)


def write_outputs(runs: pd.DataFrame, refs: pd.DataFrame, plan: BenchPlan, stem: str) -> None:
    """The benchmark's files: STEM.csv (every run), STEM.md (speed-ups, references, grid study,
    runs), STEM.pdf, STEM.png and STEM_references.csv, all written atomically.

    Parameters
    ----------
    runs : pandas.DataFrame
        Every run of the benchmark (`run_benchmark`).
    refs : pandas.DataFrame
        The references, one row per scene.
    plan : BenchPlan
        The plan that was run.
    stem : str
        Path of the outputs without suffix, e.g. results/performance/work_precision.
    """
    import platform

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
