"""One style for every figure, and atomic PDF + PNG output."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .io import atomic_write  # noqa: E402

STYLE = {
    "figure.dpi": 100,
    "savefig.dpi": 200,
    "font.size": 10,
    "axes.labelsize": 10,
    "axes.titlesize": 10,
    "legend.fontsize": 8,
    "legend.frameon": False,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "lines.linewidth": 1.4,
    "lines.markersize": 5,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "figure.constrained_layout.use": True,
}
DYN = "#1f4e9c"  #: dynamical model
QS = "#d95f02"  #: quasi-static model
ACCENT = "#2ca02c"
GREY = "0.4"


def apply_style() -> None:
    """Set matplotlib's rcParams to rotbeam's one style (STYLE)."""
    plt.rcParams.update(STYLE)


def figure(
    nrows: int = 1, ncols: int = 1, width: float = 6.4, height: float = 4.0, **kw: Any
) -> tuple[plt.Figure, Any]:
    """A figure and its axes in rotbeam's style (`plt.subplots` after `apply_style`).

    Parameters
    ----------
    nrows, ncols : int
        Rows and columns of panels.
    width, height : float
        Size of the figure [inch].
    **kw
        Passed to `plt.subplots` (sharex, squeeze, gridspec_kw, ...).

    Returns
    -------
    tuple
        (figure, axes) as `plt.subplots` returns them.
    """
    apply_style()
    return plt.subplots(nrows, ncols, figsize=(width, height), **kw)


def save(fig: plt.Figure, pdf: str | Path, png: str | Path | None = None) -> None:
    """Write the figure as PDF (and PNG) atomically (`io.atomic_write`), then close it.  The
    format comes from the final name's suffix (the temporary name ends in `.part`).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    pdf : str or Path
        The first file (any suffix matplotlib writes, despite the name).
    png : str, Path or None
        A second file; None: none.
    """
    for path in (pdf, png):
        if path is None:
            continue
        path = Path(path)
        fmt = path.suffix.lstrip(".")
        atomic_write(path, lambda tmp, fmt=fmt: fig.savefig(tmp, format=fmt))
        # the first file fixed the constrained layout: the second reuses it instead of solving it
        # again (the layout costs about as much as drawing the figure)
        fig.set_layout_engine("none")
    plt.close(fig)


def legend_in_headroom(ax: plt.Axes, headroom: float, **kwargs) -> None:
    """A legend in a band added above the data, for a panel whose curves fill its height: the
    y-axis is extended upward by `headroom` times its span (on a log axis, its span in decades)
    and the legend stands in the upper right of that band, over no point or curve.  The data
    keep the lower 1 / (1 + headroom) of the panel: lines across it (axvline) end there with
    ``ymax=1 / (1 + headroom)``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel (a linear or log y-axis), drawn and with its limits set.
    headroom : float
        The band's height over the data's span (e.g. 0.4 for a four-line legend).
    **kwargs
        Passed to `matplotlib.axes.Axes.legend` (fontsize, ncol, ...).
    """
    lo, hi = ax.get_ylim()
    if ax.get_yscale() == "log":
        ax.set_ylim(lo, hi * (hi / lo) ** headroom)
    else:
        ax.set_ylim(lo, hi + headroom * (hi - lo))
    ax.legend(loc="upper right", **kwargs)


#: the part of the plasma colormap whose colours stand out on white (contrast ratio >= 3; beyond
#: 0.6 plasma turns to light orange and yellow)
ORDERED_SPAN = (0.0, 0.6)


def ordered_colors(n: int) -> list[tuple[float, float, float, float]]:
    """`n` distinct colours in order (dark blue, purple, coral) for the values of an ordered
    parameter, each dark enough to read on white.

    Parameters
    ----------
    n : int
        How many colours (at least 1).

    Returns
    -------
    list of tuple
        `n` RGBA colours from plasma over `ORDERED_SPAN`, evenly spaced.
    """
    lo, hi = ORDERED_SPAN
    cmap = matplotlib.colormaps["plasma"]
    return [cmap(lo + (hi - lo) * k / max(1, n - 1)) for k in range(n)]


def panel_label(ax: plt.Axes, text: str) -> None:
    """Write a panel's label, e.g. "(a)", in bold at the top left corner of its axes.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel.
    text : str
        The label.
    """
    ax.text(0.01, 0.99, text, transform=ax.transAxes, ha="left", va="top", fontweight="bold")
