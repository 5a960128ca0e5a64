"""The figure of many judged scenes: Delta RMS of each beside the threshold."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from .style import DYN, QS, figure, save


def scenes_figure(table: pd.DataFrame, threshold: float, pdf: str | Path, png: str | Path) -> None:
    """One bar per scene: its Delta RMS, coloured by the verdict, and the threshold.

    Parameters
    ----------
    table : pandas.DataFrame
        `rotbeam.analysis.scenes.judge_scenes`'s table.
    threshold : float
        The verdict's threshold.
    pdf, png : str or Path
        The figure's two files.
    """
    fig, ax = figure(width=7.0, height=0.6 + 0.55 * max(len(table), 1))
    y = np.arange(len(table))
    ok = table["quasistatic_ok"].astype("boolean").fillna(False).to_numpy(bool)
    delta = table["delta_rms"].to_numpy(float)
    ax.barh(y, delta, color=np.where(ok, QS, DYN), height=0.6)
    ax.axvline(threshold, color="k", lw=1.0, ls="--")
    ax.set_yticks(y, [f"{s} ({d})" for s, d in zip(table["scene"], table["drive"], strict=True)])
    ax.invert_yaxis()
    ax.set_xlim(0.0, 1.1 * max(float(np.nanmax(delta)) if delta.size else 0.0, threshold))
    ax.set_xlabel(r"$\Delta$RMS (dimensionless); dashed: the threshold")
    from matplotlib.patches import Patch

    handles = [Patch(color=QS, label="quasi-static is good enough"),
               Patch(color=DYN, label="inertia matters")]  # fmt: skip
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.5 / len(table) - 0.25),
              ncol=2)  # fmt: skip
    save(fig, pdf, png)
