"""The nonlinear resonance: branches of periodic orbits (stable solid, unstable dashed, folds,
period doublings and tori marked) beside the sweeps that follow the beam, one column per
amplitude; and the response at one scene from rest (section and the Lyapunov exponent's
convergence)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from .style import ACCENT, DYN, GREY, QS, figure, save

#: the marker and colour of each loss of stability a branch shows, and its legend entry
MARKS = {
    "fold": ("o", "k", "fold (mu through +1)"),
    "period doubling": ("s", "#9467bd", "period doubling (mu through -1)"),
    "torus": ("D", "#8c564b", "torus (complex pair through |mu| = 1)"),
}


def _segments(arm: pd.DataFrame):
    """Runs of consecutive points with the same stability (each run joined to the next point)."""
    stable = arm["stable"].to_numpy(bool)
    start = 0
    for k in range(1, len(arm) + 1):
        if k == len(arm) or stable[k] != stable[start]:
            yield arm.iloc[start : min(k + 1, len(arm))], bool(stable[start])
            start = k


def _kinds(cell) -> list[str]:
    """The bifurcations a row of `branches.csv` names ("fold", "period doubling+torus", empty)."""
    return cell.split("+") if isinstance(cell, str) and cell else []


def _crossings(arm: pd.DataFrame):
    """(f_d, rms, kind) of the folds (a real multiplier through +1), period doublings (through
    -1) and tori (a complex pair through |mu| = 1) the continuation detected, at the point after
    each."""
    for _, r in arm.iterrows():
        kinds = _kinds(r["bifurcation"])
        for kind in MARKS:
            if kind in kinds:
                yield r["f_d"], r["rms_ym"], kind


def _panel(ax, rows: pd.DataFrame, folds: pd.DataFrame, a: float) -> None:
    br = rows[rows["kind"] == "branch"]
    for name, color in (("from_below", DYN), ("from_above", ACCENT)):
        arm = br[br["arm"] == name].sort_values("index")
        for seg, stable in _segments(arm):
            ax.plot(seg["f_d"], seg["rms_ym"], color=color, ls="-" if stable else "--", lw=1.2)
        for f, y, kind in _crossings(arm):
            m, c, _ = MARKS[kind]
            ax.plot(f, y, m, mfc="none", mec=c, ms=6)
    for name, m, color in (("up", "^", QS), ("down", "v", GREY)):
        sw = rows[(rows["kind"] == "sweep") & (rows["arm"] == name)]
        steady = sw["status"].to_numpy() == 0
        ax.plot(sw["f_d"][steady], sw["rms_ym"][steady], m, color=color, ms=4, ls="none")
        # not steady within the budget, or settled on an unstable orbit: hollow, RMS of the last
        # period only
        ax.plot(sw["f_d"][~steady], sw["rms_ym"][~steady], m, mfc="none", mec="r", ms=5,
                ls="none")  # fmt: skip
    for _, fr in folds[folds["amplitude"] == a].iterrows():
        if math.isfinite(fr["f_loss"]):
            ax.axvline(fr["f_loss"], color=GREY, ls=":", lw=0.8)
    ax.set_title(f"a = {a:g} rad/s", loc="left")
    ax.set_xlabel("$f_d$ [Hz]")
    ax.set_ylabel("RMS $y_m / L$")


def _zoom(ax, rows: pd.DataFrame, folds: pd.DataFrame, a: float, margin: float = 0.12) -> None:
    """Limit the panel to `margin` Hz around the amplitude's losses of stability (the y range
    from what is drawn there)."""
    f = folds.loc[folds["amplitude"] == a, "f_loss"].to_numpy(float)
    f = f[np.isfinite(f)]
    if f.size == 0:
        return
    lo, hi = f.min() - margin, f.max() + margin
    y = rows.loc[rows["f_d"].between(lo, hi), "rms_ym"].to_numpy(float)
    ax.set_xlim(lo, hi)
    if y.size:
        pad = 0.08 * max(np.ptp(y), 1e-3)
        ax.set_ylim(y.min() - pad, y.max() + pad)
    ax.set_title(f"a = {a:g} rad/s, near the losses of stability", loc="left")


def legend_entries(rows: pd.DataFrame) -> list[tuple[str, dict]]:
    """The legend of `branches_figure`: an entry for each kind of mark the rows draw, none for
    one they do not (a sweep whose points all reached a steady state lists no "not steady").

    Parameters
    ----------
    rows : pandas.DataFrame
        Branch and sweep points, as `branches_figure` takes them.

    Returns
    -------
    list of (str, dict)
        Each entry's label and the `plot` keywords of its handle, in the legend's order.
    """
    br, sw = rows[rows["kind"] == "branch"], rows[rows["kind"] == "sweep"]
    kinds = {k for cell in br["bifurcation"] for k in _kinds(cell)}
    entries = [
        ("branch from below (stable)", {"color": DYN}, (br["arm"] == "from_below").any()),
        ("branch from above (stable)", {"color": ACCENT}, (br["arm"] == "from_above").any()),
        ("unstable", {"color": "k", "ls": "--"}, (~br["stable"].astype(bool)).any()),
    ]
    entries += [(label, {"marker": m, "mfc": "none", "mec": c, "ls": "none"}, kind in kinds)
                for kind, (m, c, label) in MARKS.items()]  # fmt: skip
    entries += [
        ("sweep up", {"marker": "^", "color": QS, "ls": "none"}, (sw["arm"] == "up").any()),
        ("sweep down", {"marker": "v", "color": GREY, "ls": "none"}, (sw["arm"] == "down").any()),
        ("sweep point not steady", {"marker": "^", "mfc": "none", "mec": "r", "ls": "none"},
         (sw["status"] != 0).any()),
    ]  # fmt: skip
    return [(label, style) for label, style, drawn in entries if drawn]


def branches_figure(
    rows: pd.DataFrame, folds: pd.DataFrame, omega0: float, pdf: str | Path, png: str | Path
) -> None:
    """Draw the branches of periodic orbits beside the sweeps: one column per amplitude, both
    arms of the branch and both sweeps over the whole range (top) and around the arms' losses of
    stability (bottom).

    Parameters
    ----------
    rows : pandas.DataFrame
        Branch and sweep points (`rotbeam.runs.nonlinear`): columns kind, arm, amplitude
        [rad/s], f_d [Hz], rms_ym (RMS(y_m) / L), stable, bifurcation, status, index.
    folds : pandas.DataFrame
        Losses of stability per amplitude: columns amplitude [rad/s], f_loss [Hz].
    omega0 : float
        Mean angular velocity Omega_0 [rad/s], for the title.
    pdf, png : str or Path
        The figure's files, written atomically.
    """
    amps = sorted(rows["amplitude"].unique())
    ncols = len(amps)
    # at least 7.2 in wide, and a two-column legend below three panels: the legend fits
    fig, axes = figure(2, ncols, width=max(3.6 * ncols, 7.2), height=6.6, squeeze=False)
    for k, a in enumerate(amps):
        sub = rows[rows["amplitude"] == a]
        _panel(axes[0, k], sub, folds, a)
        _panel(axes[1, k], sub, folds, a)
        _zoom(axes[1, k], sub, folds, a)
    entries = legend_entries(rows)
    h = [axes[0, 0].plot([], [], **style)[0] for _, style in entries]
    fig.legend(h, [label for label, _ in entries], loc="outside lower center",
               ncols=4 if ncols >= 3 else 2)  # fmt: skip
    fig.suptitle(rf"Periodic orbits and sweeps at $\Omega_0$ = {omega0:g} rad/s")
    save(fig, Path(pdf), Path(png))


def response_figure(
    section: np.ndarray,
    running: np.ndarray,
    f_d: float,
    title: str,
    png: str | Path,
    late: float | None = None,
) -> None:
    """Stroboscopic section beside the running Lyapunov exponent (per second) against periods,
    with the rate over the second half (`late`, what the class rests on) where given.

    Parameters
    ----------
    section : numpy.ndarray
        Poincare section, one row (y_m / L, dy_m/dt / L [1/s]) per drive period.
    running : numpy.ndarray
        Running estimate of the largest Lyapunov exponent [1/s], one per period.
    f_d : float
        Drive frequency [Hz], for the axis label.
    title : str
        The figure's title.
    png : str or Path
        The figure's file, written atomically.
    late : float or None
        The exponent over the second half [1/s]; None: not drawn.
    """
    fig, (a1, a2) = figure(1, 2, width=9.0, height=3.6)
    a1.plot(section[:, 0], section[:, 1], ".", color=DYN, ms=3)
    a1.set_xlabel("$y_m / L$ at $t = k / f_d$")
    a1.set_ylabel(r"$\dot y_m / L$ [1/s]")
    a1.set_title(f"Poincare section ({section.shape[0]} periods)", loc="left")
    a2.plot(np.arange(1, running.size + 1), running, color=DYN, label="running mean (Benettin)")
    if late is not None and math.isfinite(late) and running.size >= 4:
        k = running.size
        a2.plot([k // 2 + 1, k], [late, late], color=ACCENT, ls="--",
                label="rate over the second half")  # fmt: skip
        a2.legend(loc="upper right")
    a2.axhline(0.0, color=GREY, lw=0.8)
    a2.set_xlabel(f"periods of the section (1 / {f_d:g} Hz)")
    a2.set_ylabel(r"running $\lambda_{max}$ [1/s]")
    fig.suptitle(title)
    save(fig, Path(png))
