"""The figure of a designed move beside its baselines: Omega(t) above, the observable below."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from .style import ACCENT, DYN, GREY, QS, figure, save

if TYPE_CHECKING:
    from ..analysis.move_design import MoveDesign

#: colour and line style of each move
STYLES = {"designed": (DYN, "-"), "rigid": (GREY, ":"), "zv": (ACCENT, "--"), "zvd": (QS, "-.")}


def design_figure(design: MoveDesign, path: str | Path, png: str | Path | None = None) -> None:
    """Omega(t) of the designed move and of each baseline, and the observable of each below,
    with the tolerance band after the moves.

    Parameters
    ----------
    design : MoveDesign
        A design with its full-model check (and baselines, where run).
    path : str or Path
        The figure's file (.png, .pdf or .svg).
    png : str, Path or None
        A second file.
    """
    fig, (top, bottom) = figure(2, 1, width=7.0, height=5.6, sharex=True)
    runs = {"designed": design.check} | dict(design.baselines)
    tol = design.request["residual"]
    unit = {"y_m": "L", "tip": "L"}.get(design.request["observable"], "SI")
    for name, check in runs.items():
        if check is None or not check.t_s.size:
            continue
        colour, ls = STYLES[name]
        label = f"{name}: {check.duration_s * 1e3:.0f} ms, residual {check.residual:.2g}"
        top.plot(check.t_s, check.omega, color=colour, ls=ls, label=label)
        bottom.plot(check.t_s, check.values, color=colour, ls=ls, lw=1.0)
        bottom.axvline(check.duration_s, color=colour, ls=ls, lw=0.6)
    bottom.axhspan(-tol, tol, color="0.85", zorder=0)
    top.set_ylabel(r"$\Omega$ (rad/s)")
    bottom.set_ylabel(f"{design.request['observable']} ({unit})")
    bottom.set_xlabel("t (s) from the start of the move")
    top.set_title("vertical lines: where each move ends; grey band: the tolerance")
    top.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    save(fig, path, png)
