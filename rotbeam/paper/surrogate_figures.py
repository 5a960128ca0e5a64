"""Figures of the one-mode surrogate (Sec. 6) beside the full model.

The tables they draw are built in `rotbeam.paper.surrogate_study`:

* `southwell_figure`: the Southwell line f_0 against the exact first in-plane frequency over
  C_max, with the resonance peaks of full sweep lines (`southwell_table`).
* `vs_full_figure`: RMS and Delta RMS of both models along f_d, the phase boundaries with
  Eq. (analytical_sol), and the relative difference of f_d* per line (`vs_full_table`,
  `surrogate_curve`, `surrogate_boundary`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

from ..model.params import Beam
from ..model.surrogate import southwell_frequency_hz
from ..report.style import (
    ACCENT,
    DYN,
    GREY,
    QS,
    apply_style,
    figure,
    legend_in_headroom,
    panel_label,
    save,
)


def southwell_figure(table: pd.DataFrame, beam: dict, N: int, pdf: str, png: str) -> None:
    """f_0/f_n against C_max (Southwell line, exact, dynamic peaks) and the Southwell error.

    Parameters
    ----------
    table : pandas.DataFrame
        The table of `rotbeam.paper.surrogate_study.southwell_table`.
    beam : dict
        The beam's `Beam` fields (SI).
    N : int
        Grid intervals of the exact frequencies (for the legend).
    pdf, png : str
        Paths the figure is written to.
    """
    bm = Beam(**beam)
    fig, (a, b) = figure(2, 1, height=5.6, sharex=True)
    cur = table[table["kind"] == "curve"].sort_values("C_max")
    fn = cur["f_n_hz"]
    if not table.empty:
        cs = np.logspace(np.log10(table["C_max"].min()), np.log10(table["C_max"].max()), 200)
        om = np.sqrt(cs / bm.G)  # Omega_0 + a
        sw = [southwell_frequency_hz(bm, float(o), softening=True) / bm.f_n for o in om]
        a.semilogx(cs, sw, "-", color=QS,
                   label=r"Southwell line $\sqrt{f_n^2 + S_1 \Omega^2/4\pi^2}$")  # fmt: skip
    a.semilogx(cur["C_max"], cur["f0_exact_hz"] / fn, "o", color=DYN, mfc="none",
               label=f"exact linearised (N = {N})")  # fmt: skip
    pk = table[table["kind"] == "dynamic_peak"]
    for k, (_, r) in enumerate(pk.iterrows()):
        y = r["f_peak_hz"] / r["f_n_hz"]
        lo = r["f_peak_lo_hz"] if np.isfinite(r["f_peak_lo_hz"]) else r["f_peak_hz"]
        hi = r["f_peak_hi_hz"] if np.isfinite(r["f_peak_hi_hz"]) else r["f_peak_hz"]
        yerr = [[(r["f_peak_hz"] - lo) / r["f_n_hz"]], [(hi - r["f_peak_hz"]) / r["f_n_hz"]]]
        a.errorbar([r["C_max"]], [y], yerr=yerr, fmt="v^<>sD"[k % 6], color="k", capsize=3,
                   label=f"peak of dynamic RMS, {r['source']} (bar: grid neighbours)")  # fmt: skip
    a.set_ylabel("$f_0 / f_n$")
    a.legend(fontsize=7)
    panel_label(a, "(a)")
    b.semilogx(cur["C_max"], 100.0 * cur["rel_error_southwell"], "o-", color=QS, mfc="none")
    b.axhline(0.0, color=GREY, lw=0.8)
    b.set_xlabel(r"$\mathcal{C}_{max}$")
    b.set_ylabel(r"$f_0^{Southwell} / f_0^{exact} - 1$ [%]")
    if not cur.empty:
        last = cur.iloc[-1]
        b.set_title(
            f"Southwell error {100 * last['rel_error_southwell']:+.2f} % at "
            rf"$\mathcal{{C}}_{{max}}$ = {last['C_max']:g}",
            fontsize=9,
        )
    panel_label(b, "(b)")
    save(fig, pdf, png)


def vs_full_figure(
    fig4_lines: Sequence[pd.DataFrame],
    curves: Sequence[pd.DataFrame],
    table: pd.DataFrame,
    boundary: pd.DataFrame,
    threshold: float,
    tolerance: float,
    c_fit: float,
    pdf: str,
    png: str,
) -> None:
    """The surrogate against the full model: responses, boundaries and f_d* per line.

    RMS and Delta RMS of both models along f_d (one column per Omega_0), the phase boundaries
    with Eq. (analytical_sol), and the relative difference of f_d* per line.

    Parameters
    ----------
    fig4_lines : sequence of pandas.DataFrame
        The full model's Fig. 4 sweep lines.
    curves : sequence of pandas.DataFrame
        The surrogate on each of them (`rotbeam.paper.surrogate_study.surrogate_curve`).
    table : pandas.DataFrame
        The line table of `rotbeam.paper.surrogate_study.vs_full_table`.
    boundary : pandas.DataFrame
        `rotbeam.paper.surrogate_study.surrogate_boundary`.
    threshold : float
        The Delta RMS threshold.
    tolerance : float
        The relative f_d* difference drawn as the band of the last panel.
    c_fit : float
        The fitted c of Eq. (analytical_sol) (for the legend).
    pdf, png : str
        Paths the figure is written to.
    """
    import matplotlib.pyplot as plt

    apply_style()
    n = max(1, len(fig4_lines))
    mosaic = [[f"rms{j}" for j in range(n) for _ in (0, 1)],
              [f"d{j}" for j in range(n) for _ in (0, 1)],
              ["pb"] * n + ["err"] * n]  # fmt: skip
    fig = plt.figure(figsize=(max(9.0, 4.5 * n), 10.0))
    ax = fig.subplot_mosaic(mosaic)
    labels = iter("abcdefghijklmnop")
    for j, (line, cur) in enumerate(zip(fig4_lines, curves, strict=True)):
        _line_panels(ax[f"rms{j}"], ax[f"d{j}"], line, cur, table, threshold, labels)
    t = table.sort_values("C_max")
    _boundary_panel(ax["pb"], t, boundary, c_fit, labels)
    _error_panel(ax["err"], t, tolerance, labels)
    save(fig, pdf, png)


def _line_panels(a, d, line: pd.DataFrame, cur: pd.DataFrame, table: pd.DataFrame,
                 threshold: float, labels) -> None:  # fmt: skip
    """RMS (a) and Delta RMS (d) of both models along f_d on one Fig. 4 line, with both f_d*."""
    w0 = float(line["omega0"].iloc[0])
    fn = float(line["f_n_hz"].iloc[0])
    a.plot(line["f_d"] / fn, line["rms_dynamic"], "o", color=DYN, mfc="none",
           label="full: dynamical")  # fmt: skip
    a.plot(line["f_d"] / fn, line["rms_quasistatic"], "*", color=QS, label="full: quasi-static")
    a.plot(cur["f_d"] / fn, cur["rms_dynamic"], "-", color=DYN, label="surrogate: dynamical")
    a.plot(cur["f_d"] / fn, cur["rms_quasistatic"], "--", color=QS,
           label="surrogate: quasi-static")  # fmt: skip
    a.set_ylabel("RMS($y_m$) / L")
    a.set_title(rf"$\Omega_0$ = {w0:g} rad/s")
    d.semilogy(line["f_d"] / fn, line["delta_rms"], "o", color=DYN, mfc="none", label="full")
    d.semilogy(cur["f_d"] / fn, cur["delta_rms"], "-", color=DYN, label="surrogate")
    d.axhline(threshold, color="k", lw=0.8)
    row = table[np.isclose(table["omega0"], w0)]
    if not row.empty:
        r = row.iloc[0]
        for f, ls, lab in ((r["f_d_star_full_hz"], ":", "full"),
                           (r["f_d_star_surrogate_hz"], "--", "surrogate")):  # fmt: skip
            if np.isfinite(f):
                for x in (a, d):
                    x.axvline(f / fn, color=ACCENT, ls=ls, lw=1.2,
                              label=rf"$f_d^\star/f_n$ {lab}" if x is d else None)  # fmt: skip
        d.set_title(rf"$f_d^\star$: {100 * r['rel_diff']:+.1f} % (surrogate vs full)",
                    fontsize=9)  # fmt: skip
    d.set_ylabel(r"$\Delta$RMS")
    d.set_xlabel("$f_d / f_n$")
    legend_in_headroom(a, 0.4, fontsize=6)  # the resonance peak reaches the top
    d.legend(fontsize=6)
    panel_label(a, f"({next(labels)})")
    panel_label(d, f"({next(labels)})")


def _boundary_panel(pb, t: pd.DataFrame, boundary: pd.DataFrame, c_fit: float, labels) -> None:
    """E*(C_max): the full model's roots, the surrogate's boundary, Eq. (analytical_sol)."""
    pb.loglog(t["C_max"], t["E_star_full"], "^", color="k", ms=7, label="full model (root)")
    pb.loglog(boundary["C_max"], boundary["E_star_surrogate"], "-", color=DYN, label="surrogate")
    pb.loglog(t["C_max"], t["E_star_surrogate"], "o", color=DYN, mfc="none")
    pb.loglog(boundary["C_max"], boundary["E_star_analytical_S1"], "--", color=QS,
              label=rf"Eq. (analytical_sol), $S_1$, c = {c_fit:.3f}")  # fmt: skip
    pb.loglog(boundary["C_max"], boundary["E_star_analytical_exact"], ":", color=ACCENT, lw=2,
              label="same, exact $f_0$")  # fmt: skip
    pb.set_xlabel(r"$\mathcal{C}_{max}$")
    pb.set_ylabel(r"$\mathcal{E}^\star$")
    pb.legend(fontsize=7)
    panel_label(pb, f"({next(labels)})")


def _error_panel(err, t: pd.DataFrame, tolerance: float, labels) -> None:
    """The relative difference of f_d* per line, surrogate against full."""
    ok = t["within_tolerance"].astype(bool)
    err.axhspan(-100 * tolerance, 100 * tolerance, color=ACCENT, alpha=0.12,
                label=rf"$\pm${100 * tolerance:g} %")  # fmt: skip
    err.semilogx(t.loc[ok, "C_max"], 100 * t.loc[ok, "rel_diff"], "o", color=DYN,
                 label="surrogate root, within")  # fmt: skip
    err.semilogx(t.loc[~ok, "C_max"], 100 * t.loc[~ok, "rel_diff"], "o", color="r",
                 label="surrogate root, outside")  # fmt: skip
    err.semilogx(t["C_max"], 100 * t["rel_diff_grid"], "x", color=GREY,
                 label="surrogate on the full scan grid")  # fmt: skip
    err.axhline(0.0, color=GREY, lw=0.8)
    err.set_xlabel(r"$\mathcal{C}_{max}$")
    err.set_ylabel(r"$f_d^{\star,sur} / f_d^{\star,full} - 1$ [%]")
    inside = ", ".join(f"{c:.3g}" for c in t.loc[ok, "C_max"])
    err.set_title(
        f"within {100 * tolerance:g} % at {int(ok.sum())} of {len(t)} lines"
        + (f":\nC_max = {inside}" if inside else ""),
        fontsize=9,
    )
    err.legend(fontsize=7)
    panel_label(err, f"({next(labels)})")
