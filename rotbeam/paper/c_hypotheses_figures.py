"""The c-hypotheses study for a reader: Markdown (table and verdict) and the figure of c against
the Delta RMS threshold beside the paper's printed values."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..report.io import markdown_table
from ..report.style import figure, plt, save
from .c_hypotheses import PAPER_C, PAPER_C_ERR


def wide_table(table: pd.DataFrame) -> pd.DataFrame:
    """The study's table, one row per hypothesis, for reading.

    Parameters
    ----------
    table : pandas.DataFrame
        The long table of `rotbeam.paper.c_hypotheses.study_table`.

    Returns
    -------
    pandas.DataFrame
        Per hypothesis: c at each threshold (columns "c(<threshold>)"), the largest
        |c - c_paper| over the thresholds and, when the table has an "ours" row, "gap closed":
        (c - c_ours) / (c_paper - c_ours), the mean over thresholds (0: ours, 1: the paper).
    """
    wide = table.pivot_table(index="hypothesis", columns="threshold", values="c", sort=False)
    wide.columns = [f"c({t:g})" for t in wide.columns]
    paper = table.groupby("threshold", sort=False)["c_paper"].first()
    diff = table.assign(d=(table["c"] - table["c_paper"]).abs())
    wide["max |c - c_paper|"] = diff.groupby("hypothesis", sort=False)["d"].max()
    if "ours" in set(table["hypothesis"]):
        ours = table[table["hypothesis"] == "ours"].set_index("threshold")["c"]
        gap = paper - ours
        closed = table.assign(f=(table["c"] - table["threshold"].map(ours))
                              / table["threshold"].map(gap))  # fmt: skip
        wide["gap closed"] = closed.groupby("hypothesis", sort=False)["f"].mean()
    return wide.reset_index()


def verdict(table: pd.DataFrame, tol: float = PAPER_C_ERR) -> str:
    """The study's verdict in words: the hypotheses that meet the paper, and the closest one.

    Parameters
    ----------
    table : pandas.DataFrame
        The long table of `rotbeam.paper.c_hypotheses.study_table`.
    tol : float
        Largest |c - c_paper| (dimensionless) at every threshold; default the printed +-.

    Returns
    -------
    str
        One or two sentences: the hypotheses within `tol` at every threshold (or that none
        is), and the one with the smallest largest miss.
    """
    d = table.assign(d=(table["c"] - table["c_paper"]).abs())
    worst = d.groupby("hypothesis", sort=False)["d"].max()
    hits = [h for h, v in worst.items() if v <= tol + 1e-12]
    best = worst.idxmin() if worst.notna().any() else None
    head = (
        f"Within +-{tol:g} of the paper at every threshold: {', '.join(hits)}."
        if hits
        else f"No hypothesis gives every threshold within +-{tol:g} of the paper."
    )
    if best is not None:
        head += f" Closest: {best} (largest |c - c_paper| = {worst[best]:.4f})."
    return head


def c_hypotheses_markdown(table: pd.DataFrame, setup: str) -> str:
    """The study's Markdown: setup, verdict, the wide table and the hypotheses in words.

    Parameters
    ----------
    table : pandas.DataFrame
        The long table of `rotbeam.paper.c_hypotheses.study_table`.
    setup : str
        The setup in one line (`Study.describe`).

    Returns
    -------
    str
        The Markdown document.
    """
    names = table.drop_duplicates("hypothesis")[["hypothesis", "description"]]
    paper = ", ".join(f"{PAPER_C[t]:.3f}" for t in sorted(PAPER_C))
    return (
        "# c of f_d* = c f_0 under candidate mechanisms for the paper's values\n\n"
        f"Setup: {setup}. Paper (App. D): {paper} (+-{PAPER_C_ERR:g}).\n"
        "c_err is the standard error of the fit over the C_max lines (NaN with one line).\n\n"
        f"{verdict(table)}\n\n"
        + markdown_table(wide_table(table), ".4f")
        + "\n## The hypotheses\n\n"
        + markdown_table(names)
    )


def c_hypotheses_figure(table: pd.DataFrame, pdf: str, png: str) -> None:
    """The figure of c against the Delta RMS threshold per hypothesis, beside the paper's c.

    Hypotheses under a grid rule are drawn dashed; the paper's values carry their printed +-.

    Parameters
    ----------
    table : pandas.DataFrame
        The long table of `rotbeam.paper.c_hypotheses.study_table`.
    pdf, png : str
        Paths the figure is written to.
    """
    fig, ax = figure(width=9.0, height=4.6)
    names = list(dict.fromkeys(table["hypothesis"]))
    colors = plt.get_cmap("tab20")(np.linspace(0, 1, max(len(names), 2)))
    markers = "osD^v<>phX*"
    for k, name in enumerate(names):
        sub = table[table["hypothesis"] == name].sort_values("threshold")
        style = "--" if "+grid_" in name else "-"
        ax.plot(sub["threshold"], sub["c"], style, marker=markers[k % len(markers)],
                color=colors[k], mfc="none", label=name)  # fmt: skip
    th = np.array(sorted(PAPER_C))
    ax.errorbar(th, [PAPER_C[t] for t in th], yerr=PAPER_C_ERR, fmt="s", color="k", ms=7,
                capsize=4, label="paper (App. D), $\\pm$0.001", zorder=5)  # fmt: skip
    ax.set_xlabel(r"$\Delta$RMS threshold")
    ax.set_ylabel(r"$c = f_d^\star / f_0$")
    finite = table["c"][np.isfinite(table["c"])]
    if not finite.empty:
        lo = min(float(finite.min()), min(PAPER_C.values()))
        hi = max(float(finite.max()), max(PAPER_C.values()))
        pad = 0.05 * (hi - lo) if math.isfinite(hi - lo) and hi > lo else 0.01
        ax.set_ylim(lo - pad, hi + pad)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    save(fig, pdf, png)
