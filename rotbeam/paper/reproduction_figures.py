"""Figures of the reproduction studies (rule reproduction): Fig. 7 per damping/geometry
hypothesis and Fig. D.9 as the paper describes it, with the bound on E*/E_n."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..report.style import ACCENT, GREY, figure, panel_label, save
from .collapse import collapse_by_beam, scaled_abscissa


def _scaled(boundary: pd.DataFrame, threshold: float) -> pd.DataFrame:
    b = boundary[np.isclose(boundary["threshold"], threshold)].copy()
    b["x"] = [scaled_abscissa(r) for _, r in b.iterrows()]
    b["E_scaled"] = b["E_star_root"] / b["E_n"]
    return b


def fig7_variants(
    variants: dict[str, pd.DataFrame], c: float, threshold: float, tolerance: float,
    pdf: str, png: str,
) -> None:  # fmt: skip
    """Fig. 7b for each (damping, geometry) hypothesis of the grid, one panel each.

    E*/E_n against x = S_1 G a^2 C_max / E_n^2, with c sqrt(1 + x) and its +- tolerance band;
    beams that do not collapse are drawn dashed, with open markers.

    Parameters
    ----------
    variants : dict
        {tag: the boundary table of its grid} (`rotbeam.paper.hypotheses.fig7_variant_study`).
    c : float
        The constant c (dimensionless).
    threshold : float
        The Delta RMS threshold whose rows are drawn.
    tolerance : float
        Largest relative deviation of a collapsing beam, drawn as a band.
    pdf, png : str
        Paths the figure is written to.
    """
    tags = sorted(variants)
    ncol = min(3, len(tags))
    nrow = math.ceil(len(tags) / ncol)
    fig, axes = figure(nrow, ncol, width=3.6 * ncol, height=3.2 * nrow, squeeze=False)
    for k, tag in enumerate(tags):
        ax = axes[k // ncol, k % ncol]
        b = _scaled(variants[tag], threshold)
        per = collapse_by_beam(variants[tag], c, threshold, tolerance)
        good = set(per.loc[per["collapses"], "beam"])
        for bid, sub in b.groupby("beam"):
            sub = sub.sort_values("C_max")
            z = float(sub["zeta"].iloc[0])
            ax.loglog(sub["x"], sub["E_scaled"], "o-" if bid in good else "o--", ms=4, lw=0.8,
                      mfc=None if bid in good else "none",
                      label=f"{_short(bid, tag)}, zeta={z:.3g}")  # fmt: skip
        finite = b["x"][np.isfinite(b["x"]) & (b["x"] > 0)]
        lo, hi = (finite.min(), finite.max()) if len(finite) else (1e-2, 1e3)
        x = np.logspace(np.log10(lo) - 0.3, np.log10(hi) + 0.3, 100)
        y = c * np.sqrt(1 + x)
        ax.loglog(x, y, "k-", lw=1)
        ax.fill_between(x, y * (1 - tolerance), y * (1 + tolerance), color=ACCENT, alpha=0.15)
        frac = per["collapses"].mean() if len(per) else math.nan
        ax.set_title(f"{tag}: {int(per['collapses'].sum())}/{len(per)} collapse ({frac:.2f})",
                     fontsize=9)  # fmt: skip
        ax.set_xlabel(r"$x = S_1 G a^2 \mathcal{C}_{max}/\mathcal{E}_n^2$")
        ax.set_ylabel(r"$\mathcal{E}^\star/\mathcal{E}_n$")
        ax.legend(fontsize=5, loc="upper left")  # the data run along the diagonal, from x ~ 1
    for k in range(len(tags), nrow * ncol):
        axes[k // ncol, k % ncol].set_axis_off()
    save(fig, pdf, png)


def _short(beam_id: str, tag: str) -> str:
    """ "E100000_L0.0001_hL0.05" from the study's "r7_E100000_L0.0001_hL0.05_eta-R"."""
    return beam_id.removeprefix("r7_").removesuffix(f"_{tag}")


def figD9_window(
    grid: pd.DataFrame, bound: pd.DataFrame, window: dict, c_max_bound: float, pdf: str, png: str
) -> None:
    """Fig. D.9 as the paper describes it, and the bound on E*/E_n.

    (a) E*/E_n against C_max of the grid beams of one h/L for every threshold; (b) the window
    the paper magnifies; (c) the largest E*/E_n Eq. (scaled_analytical_sol) allows at
    c_max_bound, over delta = L/R.

    Parameters
    ----------
    grid : pandas.DataFrame
        Boundary rows of the grid beams of one h/L (threshold, beam, C_max, E_star_root, E_n).
    bound : pandas.DataFrame
        `rotbeam.paper.hypotheses.figD9_bound`.
    window : dict
        ``C_max`` and ``E_scaled`` (lowest, highest each) and ``h_over_L``.
    c_max_bound : float
        The C_max of the bound (dimensionless).
    pdf, png : str
        Paths the figure is written to.
    """
    fig, (a, b, cax) = figure(1, 3, width=12.0, height=3.8)
    markers = ">", "<", "^", "v", "o", "s", "D"
    for k, (th, sub) in enumerate(grid.groupby("threshold")):
        for j, (_, line) in enumerate(sub.groupby("beam")):
            line = line.sort_values("C_max")
            y = line["E_star_root"] / line["E_n"]
            lab = rf"$\Delta$RMS$_{{th}}$={th:g}" if j == 0 else None
            for ax in (a, b):
                ax.loglog(line["C_max"], y, markers[k % 7] + "-", color=f"C{k}", ms=4, lw=0.6,
                          label=lab)  # fmt: skip
    (c_lo, c_hi), (e_lo, e_hi) = window["C_max"], window["E_scaled"]
    a.add_patch(_rect(c_lo, c_hi, e_lo, e_hi))
    a.set_xlabel(r"$\mathcal{C}_{max}$")
    a.set_ylabel(r"$\mathcal{E}^\star/\mathcal{E}_n$")
    a.legend(fontsize=6, title=f"h/L = {window['h_over_L']:g}", title_fontsize=6)
    b.set_xlim(c_lo, c_hi)
    b.set_ylim(e_lo, e_hi)
    b.set_title("as printed: no data in this window", fontsize=9)
    b.set_xlabel(r"$\mathcal{C}_{max}$")
    b.set_ylabel(r"$\mathcal{E}^\star/\mathcal{E}_n$")
    col = [k for k in bound.columns if k.startswith("E_scaled_at")][0]
    cax.semilogx(bound["delta"], bound[col], color="k",
                 label=r"largest $\mathcal{E}^\star/\mathcal{E}_n$ allowed")  # fmt: skip
    cax.semilogx(bound["delta"], bound["S1_delta"], color=GREY, ls="--", label=r"$S_1\delta$")
    cax.axhline(
        e_lo,
        color=ACCENT,
        ls=":",
        label=rf"window floor $\mathcal{{E}}^\star/\mathcal{{E}}_n$ = {e_lo:g}",
    )
    cax.set_yscale("log")
    cax.set_ylim(top=3 * e_lo)  # room above the window's floor for the panel label
    cax.set_ylabel(r"$\mathcal{E}^\star/\mathcal{E}_n$, $S_1\delta$")
    cax.set_xlabel(r"$\delta = L/R$")
    cax.set_title(rf"Eq. (scaled_analytical_sol) at $\mathcal{{C}}_{{max}}$ = {c_max_bound:g}",
                  fontsize=9)  # fmt: skip
    cax.legend(fontsize=6)
    for ax, lab in zip((a, b, cax), "abc", strict=True):
        panel_label(ax, f"({lab})")
    save(fig, pdf, png)


def _rect(x0, x1, y0, y1):
    from matplotlib.patches import Rectangle

    return Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ec=ACCENT, lw=1, ls="--")
