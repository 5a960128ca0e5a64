"""The atlas's figure: Delta RMS over the (f_d, Omega_0) plane with the f_d* boundary, beside
the same grid in the paper's Fig. 5 axes (C_max, E_max)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import LogNorm

from ..analysis.atlas import Atlas
from .style import apply_style, save

#: the colour map of Delta RMS; grid points without a value (failed, not run) are grey
CMAP = "viridis"
MISSING = "0.8"
#: the smallest Delta RMS the colour scale shows (the log scale needs a floor)
FLOOR = 1e-4


def cell_edges(centres: np.ndarray, log: bool = False) -> np.ndarray:
    """The edges of the cells around increasing centres: midpoints between neighbours, the ends
    as far out as the first and last half-steps (on a log scale: geometric midpoints).

    Parameters
    ----------
    centres : numpy.ndarray
        Increasing values, shape (n,), n >= 2 (> 0 with `log`).
    log : bool
        Whether the axis is logarithmic.

    Returns
    -------
    numpy.ndarray
        Shape (n + 1,).
    """
    x = np.log(centres) if log else np.asarray(centres, float)
    mid = 0.5 * (x[1:] + x[:-1])
    edges = np.concatenate([[x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]])
    return np.exp(edges) if log else edges


def plot_atlas(atlas: Atlas, path: str | Path) -> None:
    """Draw the atlas: (a) Delta RMS over f_d [Hz] and Omega_0 [rad/s] with the f_d* boundary
    of each line; (b) the same over the paper's Fig. 5 axes, C_max (centrifugal number at the
    largest speed, x) and E_max (Euler number at the largest acceleration, y), with E* of each
    line.
    One colour bar (log scale, the threshold marked); the legend sits below the panels.

    Parameters
    ----------
    atlas : Atlas
        The atlas (`rotbeam.analysis.atlas.atlas`).
    path : str or Path
        The image file (PNG, PDF, SVG: by its suffix).
    """
    apply_style()
    delta = atlas.grid("delta_rms")
    conv = atlas.grid("converged") == 1
    delta = np.where(conv, delta, np.nan)
    finite = delta[np.isfinite(delta) & (delta > 0)]
    vmax = max(float(finite.max()) if finite.size else 1.0, 2 * atlas.threshold)
    vmin = max(min(float(finite.min()) if finite.size else FLOOR, atlas.threshold / 2), FLOOR)
    norm = LogNorm(vmin=vmin, vmax=vmax)
    cmap = plt.get_cmap(CMAP).with_extremes(bad=MISSING)
    shown = np.ma.masked_invalid(np.clip(delta, vmin, None))

    fig, (a, b) = plt.subplots(1, 2, figsize=(11.0, 4.8))
    omega0s, f_ds = atlas.omega0s, atlas.f_ds
    mesh = a.pcolormesh(cell_edges(f_ds), cell_edges(omega0s), shown, cmap=cmap, norm=norm)
    bnd = atlas.boundary.sort_values("omega0")
    label = rf"$f_d^\star$: $\Delta$RMS = {atlas.threshold:g} on each line"
    a.plot(bnd["f_d_root"], bnd["omega0"], "-", color="w", lw=3.0)
    a.plot(bnd["f_d_root"], bnd["omega0"], ".-", color="k", lw=1.4, label=label)
    a.set_xlabel(r"drive frequency $f_d$ [Hz]")
    a.set_ylabel(r"mean speed $\Omega_0$ [rad/s]")
    a.set_title("(a) physical axes", loc="left")
    a.grid(False)

    c_max = _per_line(atlas, "C_max")
    e_max = atlas.grid("E_max")[0]
    if np.all(np.diff(c_max) > 0) and np.all(np.diff(e_max) > 0) and c_max[0] > 0:
        b.pcolormesh(cell_edges(c_max, log=True), cell_edges(e_max, log=True), shown.T,
                     cmap=cmap, norm=norm)  # fmt: skip
    else:  # C_max not increasing with Omega_0 (Omega_0 < 0): the points as they fall
        cc, ee = np.meshgrid(c_max, e_max, indexing="ij")
        b.scatter(cc.ravel(), ee.ravel(), c=shown.ravel(), cmap=cmap, norm=norm, marker="s")
    b.set_xscale("log")
    b.set_yscale("log")
    b.plot(bnd["C_max"], bnd["E_star_root"], "-", color="w", lw=3.0)
    b.plot(bnd["C_max"], bnd["E_star_root"], ".-", color="k", lw=1.4)
    b.set_xlabel(r"$\mathcal{C}_{max}$ (centrifugal number at the largest speed)")
    b.set_ylabel(r"$\mathcal{E}_{max}$ (Euler number at the largest acceleration)")
    b.set_title(r"(b) the paper's Fig. 5 axes ($\mathcal{E}^\star$ on each line)", loc="left")
    b.grid(False)

    bar = fig.colorbar(mesh, ax=[a, b], location="right", shrink=0.95)
    bar.set_label(r"$\Delta$RMS = |RMS$_{dyn}$ - RMS$_{QS}$| / RMS$_{dyn}$ of $y_m$")
    bar.ax.axhline(atlas.threshold, color="k", lw=1.5)
    handles = a.get_legend_handles_labels()[0]
    if np.isnan(delta).any():
        handles.append(plt.Rectangle((0, 0), 1, 1, color=MISSING,
                                     label="no steady state, failed or not run"))  # fmt: skip
    fig.legend(handles=handles, loc="outside lower center", ncol=len(handles))
    fig.suptitle(
        f"Atlas of {len(omega0s)} x {len(f_ds)} scenes: quasi-static good enough left of the "
        f"boundary ($\\Delta$RMS < {atlas.threshold:g})",
        fontsize=10,
    )
    save(fig, path)


def _per_line(atlas: Atlas, column: str) -> np.ndarray:
    """One value per line (the first of its row), in increasing Omega_0."""
    first = atlas.rows.groupby("omega0", sort=True)[column].first()
    return first.reindex(atlas.omega0s).to_numpy(float)
