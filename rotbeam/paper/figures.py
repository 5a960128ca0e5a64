"""The paper's figures, drawn from the workflow's tables (one function per figure)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd
from matplotlib import transforms
from matplotlib.ticker import NullFormatter

from ..model.criterion import power_spectrum
from ..model.params import Beam, Drive
from ..report.style import (
    ACCENT,
    DYN,
    GREY,
    QS,
    apply_style,
    figure,
    legend_in_headroom,
    ordered_colors,
    panel_label,
    plt,
    save,
)


def fig1_drive(omega0: float, amplitude: float, f_d: float, pdf: str, png: str) -> None:
    """Fig. 1b,c: the drive, Omega(t) and dOmega/dt, over two drive periods.

    Parameters
    ----------
    omega0 : float
        Mean rotation rate Omega_0 [rad/s].
    amplitude : float
        Drive amplitude a [rad/s].
    f_d : float
        Drive frequency [Hz].
    pdf, png : str
        Paths the figure is written to.
    """
    d = Drive(omega0, amplitude, f_d)
    t = np.linspace(0.0, 2.0 / f_d, 400)
    fig, (a, b) = figure(2, 1, height=4.2, sharex=True)
    a.plot(t, [d.omega(x) for x in t], color=DYN)
    a.axhline(omega0, color=GREY, ls="--", lw=0.8)
    a.set_ylabel(r"$\Omega$ [rad/s]")
    b.plot(t, [d.omega_dot(x) for x in t], color=QS)
    b.set_ylabel(r"$\dot\Omega$ [rad/s$^2$]")
    b.set_xlabel("t [s]")
    panel_label(a, "(b)")
    panel_label(b, "(c)")
    a.set_title(rf"$\Omega_0$ = {omega0:g} rad/s, a = {amplitude:g} rad/s, $f_d$ = {f_d:g} Hz")
    save(fig, pdf, png)


def fig2_shapes(shapes: pd.DataFrame, pdf: str, png: str) -> None:
    """Fig. 2c stand-in: centerlines over one period, lab and rotating frame, midspan marked.

    Parameters
    ----------
    shapes : pandas.DataFrame
        Centerlines per frame (frame, phase, s, x_lab, y_lab, x_rot, y_rot; lengths in units of
        L).
    pdf, png : str
        Paths the figure is written to.
    """
    fig, (a, b) = figure(1, 2, width=8.0, height=4.0)
    frames = sorted(shapes["frame"].unique())
    cmap = matplotlib.colormaps["viridis"]
    for k in frames:
        f = shapes[shapes["frame"] == k]
        col = cmap(k / max(1, len(frames) - 1))
        mid = f.iloc[(f["s"] - 0.5).abs().argmin()]
        a.plot(f["x_lab"], f["y_lab"], color=col, lw=2)
        a.plot(mid["x_lab"], mid["y_lab"], "o", color="m", ms=5)
        b.plot(f["x_rot"], f["y_rot"], color=col, lw=1.5, label=f"t/P = {f['phase'].iloc[0]:.2f}")
        b.plot(mid["x_rot"], mid["y_rot"], "o", color="m", ms=4)
    a.plot(0, 0, "k+", ms=10)
    a.set_aspect("equal")
    a.set_xlabel("X / L (lab frame)")
    a.set_ylabel("Y / L")
    a.set_title("lab frame, axis at +")
    b.set_xlabel("(R_o + x) / L (rotating frame)")
    b.set_ylabel("y / L")
    b.set_title("rotating frame, midspan in magenta")
    b.legend(ncol=2)
    save(fig, pdf, png)


def fig3_resonance(
    line: pd.DataFrame, series: pd.DataFrame, pdf: str, png: str, measured=None
) -> None:
    """Fig. 3: resonance curve RMS(y_m) against f_d, y_m(tau) at one f_d, its power spectrum.

    Parameters
    ----------
    line : pandas.DataFrame
        The sweep line (f_d, rms_dynamic, rms_quasistatic, converged, omega0); failed points
        are marked.
    series : pandas.DataFrame
        The kept time series at one f_d (tau, t_s, f_d, y_m_dynamic, y_m_quasistatic).
    pdf, png : str
        Paths the figure is written to.
    measured : ResonanceCurve or None
        A measured resonance curve (`rotbeam.analysis.measurements`), drawn over panel (a).
    """
    fig, axes = figure(1, 3, width=11.0, height=3.6)
    a, b, c = axes
    ok = line["converged"].astype(bool)
    a.plot(line["f_d"], line["rms_dynamic"], "o-", color=DYN, mfc="none", label="dynamical")
    a.plot(line["f_d"], line["rms_quasistatic"], "*--", color=QS, label="quasi-static")
    if (~ok).any():
        a.plot(line.loc[~ok, "f_d"], line.loc[~ok, "rms_dynamic"], "x", color="r", label="failed")
    if measured is not None:
        _draw_measured(a, measured.f_d, measured)
    a.set_xlabel("$f_d$ [Hz]")
    a.set_ylabel("RMS($y_m$) / L")
    a.set_title(rf"$\Omega_0$ = {line['omega0'].iloc[0]:g} rad/s")
    a.legend()
    b.plot(series["tau"] - series["tau"].iloc[0], series["y_m_dynamic"], color=DYN, label="dyn.")
    b.plot(series["tau"] - series["tau"].iloc[0], series["y_m_quasistatic"], "--", color=QS,
           label="QS")  # fmt: skip
    b.set_xlabel(r"$\tau$ (steady state)")
    b.set_ylabel("$y_m$ / L")
    b.set_title(rf"$f_d$ = {series['f_d'].iloc[0]:g} Hz")
    legend_in_headroom(b, 0.2, ncol=2)  # the curves fill the panel's height
    T = float(series["t_s"].iloc[1] - series["t_s"].iloc[0]) / float(
        series["tau"].iloc[1] - series["tau"].iloc[0]
    )
    f, amp = power_spectrum(series["tau"].to_numpy(), series["y_m_dynamic"].to_numpy())
    c.plot(f / T, amp, color=DYN)
    c.set_xlim(0, 5 * series["f_d"].iloc[0])
    c.set_xlabel("$f_r$ [Hz]")
    c.set_ylabel("|FFT($y_m$)| / L")
    for ax, lab in zip(axes, "abc", strict=True):
        panel_label(ax, f"({lab})")
    save(fig, pdf, png)


def _draw_measured(ax, x, curve) -> None:
    """A measured resonance curve (with its rms_std bars if given) on an RMS axis."""
    name = Path(curve.source).name if curve.source else "measured"
    ax.errorbar(x, curve.rms, yerr=curve.rms_std, fmt="s", color="k", ms=4, mfc="none",
                capsize=2, label=f"measured ({name})")  # fmt: skip


PEAK_MS = 6.0  #: size of Fig. 4's peak marker [points]
#: Fig. 4's bands above the data for the legends, RMS and Delta RMS panels (over the data's span)
FIG4_HEADROOM = (0.5, 0.25)


def fig4_compare(
    lines: Sequence[pd.DataFrame],
    crit: pd.DataFrame,
    threshold: float,
    pdf: str,
    png: str,
    measured: dict | None = None,
) -> None:
    """Fig. 4: RMS dynamic and quasi-static and Delta RMS against f_d/f_n at two Omega_0.

    f_d*, f_0 and the peak of the scan are marked, and the first scanned point at or above the
    threshold; the band below f_d* is where the quasi-static model suffices.  The legends stand
    in bands above the data (`legend_in_headroom`), the peak's marker just above the peak,
    pointing at it.

    Parameters
    ----------
    lines : sequence of pandas.DataFrame
        The two sweep lines, one per Omega_0 (f_d, rms_dynamic, rms_quasistatic, delta_rms,
        omega0, f_n_hz, f0_hz).
    crit : pandas.DataFrame
        Their boundary rows (omega0, f_d_root, f_d_grid).
    threshold : float
        The Delta RMS threshold.
    pdf, png : str
        Paths the figure is written to.
    measured : dict or None
        {Omega_0 [rad/s]: a measured ResonanceCurve}, drawn over that column's RMS panel.
    """
    measured = measured or {}
    fig, axes = figure(2, len(lines), width=4.2 * len(lines), height=6.0, squeeze=False)
    for j, line in enumerate(lines):
        w0 = float(line["omega0"].iloc[0])
        fn = float(line["f_n_hz"].iloc[0])
        x = line["f_d"] / fn
        a, b = axes[0, j], axes[1, j]
        a.plot(x, line["rms_dynamic"], "o-", color=DYN, mfc="none", label="dynamical")
        a.plot(x, line["rms_quasistatic"], "*--", color=QS, label="quasi-static")
        a.set_ylabel("RMS($y_m$) / L")
        a.set_title(rf"$\Omega_0$ = {w0:g} rad/s")
        b.semilogy(x, line["delta_rms"], "o-", color=DYN, mfc="none")
        b.axhline(threshold, color="k", lw=0.8, label=f"threshold {threshold:g}")
        b.set_ylabel(r"$\Delta$RMS")
        b.set_xlabel("$f_d / f_n$")
        row = crit[np.isclose(crit["omega0"], w0)]
        f0 = float(line["f0_hz"].iloc[0]) / fn
        peak = float(x.iloc[int(np.nanargmax(line["rms_dynamic"].to_numpy()))])
        # the marks end below the legends' bands; (a)'s legend names them for both panels
        for ax, room, named in zip((a, b), FIG4_HEADROOM, (True, False), strict=True):
            kw = dict(ymax=1.0 / (1.0 + room))
            ax.axvline(f0, color=GREY, ls="--", lw=1, **kw,
                       label=r"$f_0/f_n$ (linear)" if named else None)  # fmt: skip
            if not row.empty and np.isfinite(row["f_d_root"].iloc[0]):
                fs = float(row["f_d_root"].iloc[0]) / fn
                ax.axvline(fs, color=ACCENT, ls=":", lw=1.5, **kw,
                           label=r"$f_d^\star/f_n$" if named else None)  # fmt: skip
                ax.axvspan(0, fs, color=ACCENT, alpha=0.12, **kw,
                           label="quasi-static suffices" if named else None)  # fmt: skip
        # above the peak, clear of the peak's own marker (5 points across, and its edge)
        above = transforms.offset_copy(a.transData, fig=fig, y=PEAK_MS / 2 + 5, units="points")
        a.plot([peak], [np.nanmax(line["rms_dynamic"])], "v", color="k", ms=PEAK_MS,
               transform=above, label="peak of scan")  # fmt: skip
        for w, curve in measured.items():
            if np.isclose(float(w), w0):
                _draw_measured(a, curve.f_d / fn, curve)
        if not row.empty and np.isfinite(row["f_d_grid"].iloc[0]):
            g = float(row["f_d_grid"].iloc[0])
            gd = line.loc[np.isclose(line["f_d"], g), "delta_rms"]
            b.plot([g / fn], gd.to_numpy()[:1], "^", color="k", mfc="none", ms=9,
                   label=r"first point $\geq$ threshold")  # fmt: skip
        for ax, room in zip((a, b), FIG4_HEADROOM, strict=True):  # the curves fill the panels
            legend_in_headroom(ax, room, fontsize=7, ncol=2)
        panel_label(a, "(" + "ab"[j] + ")")
        panel_label(b, "(" + "cd"[j] + ")")
    save(fig, pdf, png)


def fig5_phase(
    boundary: pd.DataFrame, threshold: float, series: Sequence[pd.DataFrame], pdf: str, png: str
) -> None:
    """Fig. 5: E*(C_max) with the quasi-static region shaded, and time series on either side.

    Parameters
    ----------
    boundary : pandas.DataFrame
        The reference beam's boundary table (threshold, C_max, E_star_root, E_star_grid).
    threshold : float
        The Delta RMS threshold drawn.
    series : sequence of pandas.DataFrame
        Two kept time series (tau, y_m_dynamic, y_m_quasistatic, C_max, E_max, delta_rms),
        marked in panel (a) and drawn in (b) and (c).
    pdf, png : str
        Paths the figure is written to.
    """
    apply_style()
    fig = plt.figure(figsize=(10, 4.0))
    gs = fig.add_gridspec(2, 2, width_ratios=[1.2, 1])
    a = fig.add_subplot(gs[:, 0])
    sub = boundary[np.isclose(boundary["threshold"], threshold)].sort_values("C_max")
    c, e, eg = sub["C_max"], sub["E_star_root"], sub["E_star_grid"]
    a.loglog(c, e, "^-", color="k", label=r"$\mathcal{E}^\star$ (root)")
    a.loglog(c, eg, "^", color=GREY, mfc="none", label="first grid point (paper's rule)")
    a.fill_between(c, 1e-3, e, color=ACCENT, alpha=0.15, label="quasi-static")
    a.set_ylim(min(0.5 * np.nanmin(e), 0.1), 3 * np.nanmax(e))
    for k, s in enumerate(series):
        a.plot(s["C_max"].iloc[0], s["E_max"].iloc[0], "s", color=DYN,
               label="time series (b), (c)" if k == 0 else None)  # fmt: skip
    a.set_xlabel(r"$\mathcal{C}_{max}$")
    a.set_ylabel(r"$\mathcal{E}^\star$")
    a.legend(loc="lower right")
    panel_label(a, "(a)")
    for k, s in enumerate(series):
        ax = fig.add_subplot(gs[k, 1])
        tau = s["tau"] - s["tau"].iloc[0]
        ax.plot(tau, s["y_m_dynamic"], color=DYN, label="dynamical")
        ax.plot(tau, s["y_m_quasistatic"], "--", color=QS, label="quasi-static")
        ax.set_title(
            rf"$\mathcal{{C}}_{{max}}$={s['C_max'].iloc[0]:.3g}, "
            rf"$\mathcal{{E}}_{{max}}$={s['E_max'].iloc[0]:.3g}: "
            rf"$\Delta$RMS={s['delta_rms'].iloc[0]:.3f}",
            fontsize=9,
        )
        ax.set_ylabel("$y_m$ / L")
        panel_label(ax, "(" + "bc"[k] + ")")
        if k == len(series) - 1:
            ax.set_xlabel(r"$\tau$")
            legend_in_headroom(ax, 0.3, fontsize=7, ncol=2)  # the curves fill the panel's height
    fig.set_layout_engine("constrained")
    save(fig, pdf, png)


def fig6_critical(
    boundary: pd.DataFrame, threshold: float, c: float, c_err: float, pdf: str, png: str
) -> None:
    """Fig. 6: f_0/f_n, f_d*/f_n and c f_0/f_n against C_max.

    Parameters
    ----------
    boundary : pandas.DataFrame
        The reference beam's boundary table (threshold, C_max, f_n_hz, f0_hz, f_d_root).
    threshold : float
        The Delta RMS threshold drawn.
    c : float
        The fitted c (dimensionless).
    c_err : float
        Its standard error.
    pdf, png : str
        Paths the figure is written to.
    """
    sub = boundary[np.isclose(boundary["threshold"], threshold)].sort_values("C_max")
    fn = sub["f_n_hz"]
    fig, a = figure(height=4.0)
    a.loglog(sub["C_max"], sub["f0_hz"] / fn, "o", color=DYN, mfc="none", label=r"$f_0/f_n$")
    a.loglog(sub["C_max"], sub["f_d_root"] / fn, "^", color="k", label=r"$f_d^\star/f_n$")
    a.loglog(sub["C_max"], c * sub["f0_hz"] / fn, "s", color=QS, mfc="none",
             label=rf"$c f_0/f_n$, c = {c:.3f} $\pm$ {c_err:.3f}")  # fmt: skip
    a.set_xlabel(r"$\mathcal{C}_{max}$")
    a.set_ylabel("frequency / $f_n$")
    a.legend()
    save(fig, pdf, png)


def figB8_convergence(lines: pd.DataFrame, pdf: str, png: str) -> None:
    """Fig. B.8: RMS(y_m) against N for each (Omega_0, f_d), and its error against the finest N.

    Parameters
    ----------
    lines : pandas.DataFrame
        The grid-convergence lines (N, omega0, f_d, rms_dynamic).
    pdf, png : str
        Paths the figure is written to.
    """
    fig, (a, b) = figure(1, 2, width=9.0, height=3.8)
    Nmax = lines["N"].max()
    for (w0, fd), sub in lines.groupby(["omega0", "f_d"]):
        sub = sub.sort_values("N")
        ref = float(sub.loc[sub["N"] == Nmax, "rms_dynamic"].iloc[0])
        lab = rf"$\Omega_0$ = {w0:g} rad/s, $f_d$ = {fd:g} Hz"
        a.plot(sub["N"], sub["rms_dynamic"], "o-", label=lab)
        err = (sub["rms_dynamic"] / ref - 1).abs()
        b.loglog(sub["N"][sub["N"] < Nmax], err[sub["N"] < Nmax], "o-", label=lab)
    n = np.array(sorted(lines["N"].unique()))[:-1].astype(float)
    if n.size:
        b.loglog(n, 0.5 * (n / n[0]) ** -2, "k:", label=r"$N^{-2}$")
    a.set_xlabel("N (grid intervals)")
    a.set_ylabel("RMS($y_m$) / L")
    b.set_xlabel("N (grid intervals)")
    b.set_ylabel(f"|RMS / RMS(N={Nmax}) - 1|")
    if n.size:  # the grids' N as plain ticks (log minor labels overlap)
        b.set_xticks(n, [f"{v:g}" for v in n])
        b.xaxis.set_minor_formatter(NullFormatter())
    a.legend(fontsize=6)
    b.legend(fontsize=6, loc="lower left")  # below the lines: they fall from the top left
    save(fig, pdf, png)


def _scaled_x(row) -> float:
    """S_1 G a^2 C_max / E_n^2, the abscissa on which Eq. (scaled_analytical_sol) is universal."""
    from ..model.surrogate import southwell_coefficient

    S1 = southwell_coefficient(row["hub_ratio"])
    return S1 * row["G"] * row["C_max"] / row["E_n"] ** 2


def figD9_thresholds(boundary: pd.DataFrame, cfit: pd.DataFrame, pdf: str, png: str) -> None:
    """Fig. D.9: the scaled boundary E*/E_n against C_max for each threshold, with its c.

    Parameters
    ----------
    boundary : pandas.DataFrame
        The reference beam's boundary table, every threshold (threshold, C_max, E_star_root,
        E_n).
    cfit : pandas.DataFrame
        c per threshold (threshold and ref_c_root, or c_root).
    pdf, png : str
        Paths the figure is written to.
    """
    fig, a = figure(height=4.2)
    markers = ">", "<", "^", "v", "o", "s", "D"
    for k, (th, sub) in enumerate(boundary.groupby("threshold")):
        sub = sub.sort_values("C_max")
        row = cfit[np.isclose(cfit["threshold"], th)]
        col = "ref_c_root" if "ref_c_root" in cfit else "c_root"
        c = float(row[col].iloc[0]) if not row.empty else math.nan
        a.loglog(sub["C_max"], sub["E_star_root"] / sub["E_n"], markers[k % 7] + "-",
                 label=rf"$\Delta$RMS$_{{th}}$={th:g}: c={c:.3f}")  # fmt: skip
    a.set_xlabel(r"$\mathcal{C}_{max}$")
    a.set_ylabel(r"$\mathcal{E}^\star/\mathcal{E}_n$")
    a.legend()
    save(fig, pdf, png)


ZETA_UNDERDAMPED = 0.2  #: beams above this damping ratio are drawn dotted in Fig. 7


def fig7_collapse(boundary: pd.DataFrame, c: float, pdf: str, png: str) -> None:
    """Fig. 7: (a) E* against C_max per beam; (b) E*/E_n against x with c sqrt(1 + x).

    x = S_1 G a^2 C_max / E_n^2 (Eq. scaled_analytical_sol).  The colour says h/L (one distinct
    colour per value), the marker E, its size L; beams with zeta above `ZETA_UNDERDAMPED` (not
    in the fit of c) are drawn dotted.  Panel (a)'s legend stands beside the panel, clear of its
    curves and of its label.

    Parameters
    ----------
    boundary : pandas.DataFrame
        The grid's boundary rows (E, L, h_over_L, C_max, E_star_root, E_n, hub_ratio, G,
        optionally zeta).
    c : float
        The constant c of the curve (dimensionless).
    pdf, png : str
        Paths the figure is written to.
    """
    fig, (a, b) = figure(1, 2, width=11.0, height=4.2)
    markers = dict(zip(sorted(boundary["E"].unique()), "osD^v<>ph", strict=False))
    hls = sorted(boundary["h_over_L"].unique())
    colors = dict(zip(hls, ordered_colors(len(hls)), strict=True))
    Ls = sorted(boundary["L"].unique())
    b2 = boundary.copy()
    b2["x"] = [_scaled_x(r) for _, r in b2.iterrows()]
    overdamped = "zeta" in b2 and bool((b2["zeta"] > ZETA_UNDERDAMPED).any())
    for (E, L, hl), sub in b2.groupby(["E", "L", "h_over_L"]):
        sub = sub.sort_values("C_max")
        # overdamped or nearly: App. E's c is not expected to hold
        dotted = "zeta" in sub and float(sub["zeta"].iloc[0]) > ZETA_UNDERDAMPED
        ms = 4 + 3 * Ls.index(L)
        kw = dict(marker=markers[E], color=colors[hl], ms=ms, mfc="none", ls=":" if dotted else "-",
                  lw=0.9 if dotted else 0.6)  # fmt: skip
        a.loglog(sub["C_max"], sub["E_star_root"], **kw)
        b.loglog(sub["x"], sub["E_star_root"] / sub["E_n"], **kw)
    x = np.logspace(np.log10(max(b2["x"].min(), 1e-6)) - 0.3, np.log10(b2["x"].max()) + 0.3, 200)
    b.loglog(x, c * np.sqrt(1 + x), "k-", label=rf"$c\sqrt{{1+x}}$, c = {c:.3f}")
    dotted_label = rf"dotted: $\zeta$ > {ZETA_UNDERDAMPED:g} (not fitted)"
    if overdamped:
        b.plot([], [], ":", color="k", lw=0.9, label=dotted_label)
    for E, m in markers.items():
        a.plot([], [], m, color="k", mfc="none", ls="none", label=f"E = {E:.0e} Pa")
    for hl in hls:
        a.plot([], [], "-", color=colors[hl], label=f"h/L = {hl:g}")
    if overdamped:
        a.plot([], [], ":", color="k", lw=0.9, label=dotted_label)
    a.set_xlabel(r"$\mathcal{C}_{max}$")
    a.set_ylabel(r"$\mathcal{E}^\star$")
    a.legend(fontsize=6, title="marker size: L", title_fontsize=6, loc="upper left",
             bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)  # fmt: skip
    b.set_xlabel(r"$x = S_1 G a^2 \mathcal{C}_{max} / \mathcal{E}_n^2$")
    b.set_ylabel(r"$\mathcal{E}^\star/\mathcal{E}_n$")
    b.legend()
    panel_label(a, "(a)")
    panel_label(b, "(b)")
    save(fig, pdf, png)


def figE10_c0(zeta_max: float, points: int, beam: Beam, pdf: str, png: str) -> None:
    """Fig. E.10: c_0 against zeta for threshold 0.10, the reference beam's zeta marked.

    Parameters
    ----------
    zeta_max : float
        The largest zeta drawn (dimensionless).
    points : int
        Points from zeta = 0 to zeta_max.
    beam : Beam
        The reference beam, whose zeta is marked.
    pdf, png : str
        Paths the figure is written to.
    """
    from ..model.secondorder import c0_root

    z = np.linspace(0.0, zeta_max, points)
    c0 = [c0_root(x, 0.10) for x in z]
    fig, a = figure(height=3.8)
    a.plot(z, c0, color=DYN)
    a.axvline(beam.zeta, color=QS, ls="--", label=rf"reference beam $\zeta$ = {beam.zeta:.4f}")
    a.axhline(math.sqrt(0.1), color=GREY, ls=":", label=r"$\zeta \to 0$: $c_0 = \sqrt{0.1}$")
    a.set_xlabel(r"$\zeta$")
    a.set_ylabel("$c_0$")
    a.legend()
    save(fig, pdf, png)
