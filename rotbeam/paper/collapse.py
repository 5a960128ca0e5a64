"""How well a grid of beams collapses on Eq. (scaled_analytical_sol), E*/E_n = c sqrt(1 + x).

x = S_1 G a^2 C_max / E_n^2; why it depends on the beam only through S_1 delta, and what that
bounds: docs/reproduction.md.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..model.params import BETA1
from ..model.surrogate import southwell_coefficient


def scaled_abscissa(row: pd.Series) -> float:
    """The abscissa x = S_1 G a^2 C_max / E_n^2 of one boundary row.

    Parameters
    ----------
    row : pandas.Series
        A boundary row: hub_ratio, G [s^2], C_max and E_n (a is folded into E_n = G a 2 pi f_n).

    Returns
    -------
    float
        x (dimensionless).
    """
    S1 = southwell_coefficient(float(row["hub_ratio"]))
    return S1 * float(row["G"]) * float(row["C_max"]) / float(row["E_n"]) ** 2


def southwell_delta(delta: float) -> float:
    """S_1(r_o) delta, the only way x depends on the beam.

    Parameters
    ----------
    delta : float
        L/R (dimensionless, in (0, 1)); the clamp sits r_o = 1/delta - 1 lengths from the axis.

    Returns
    -------
    float
        S_1(r_o) delta (dimensionless).
    """
    return southwell_coefficient(1.0 / delta - 1.0) * delta


def scaled_bound(c: float, delta: float, c_max: float) -> float:
    """E*/E_n from Eq. (scaled_analytical_sol) at one C_max for a beam of L/R = delta.

    Parameters
    ----------
    c : float
        The constant c (dimensionless).
    delta : float
        L/R (dimensionless, in (0, 1)).
    c_max : float
        C_max (dimensionless).

    Returns
    -------
    float
        c sqrt(1 + S_1 delta C_max / beta_1^4) (dimensionless).
    """
    return c * math.sqrt(1.0 + southwell_delta(delta) * c_max / BETA1**4)


def collapse_by_beam(
    boundary: pd.DataFrame, c: float, threshold: float, tolerance: float = 0.10
) -> pd.DataFrame:
    """Per beam: how far its boundary lies from c sqrt(1 + x), and whether it collapses.

    A beam collapses when every line has a crossing and lies within `tolerance` of the curve.

    Parameters
    ----------
    boundary : pandas.DataFrame
        Boundary rows of a grid (beam, threshold, found, E_star_root, E_n, hub_ratio, G, C_max,
        E, L, h_over_L, zeta).
    c : float
        The constant c (dimensionless).
    threshold : float
        The Delta RMS threshold whose rows are read.
    tolerance : float
        Largest relative deviation |E*/E_n / (c sqrt(1 + x)) - 1| of a collapsing beam.

    Returns
    -------
    pandas.DataFrame
        One row per beam: beam, E, L, h_over_L, zeta, lines, lines_with_crossing,
        worst_deviation (NaN with no crossing) and collapses.
    """
    sub = boundary[np.isclose(boundary["threshold"], threshold)].copy()
    rows = []
    for beam, b in sub.groupby("beam", sort=True):
        ok = b["found"].astype(bool) & np.isfinite(b["E_star_root"])
        dev = []
        for _, r in b[ok].iterrows():
            pred = c * math.sqrt(1.0 + scaled_abscissa(r))
            dev.append(abs(float(r["E_star_root"]) / float(r["E_n"]) / pred - 1.0))
        worst = max(dev) if dev else math.nan
        rows.append({
            "beam": beam, "E": float(b["E"].iloc[0]), "L": float(b["L"].iloc[0]),
            "h_over_L": float(b["h_over_L"].iloc[0]), "zeta": float(b["zeta"].iloc[0]),
            "lines": len(b), "lines_with_crossing": int(ok.sum()), "worst_deviation": worst,
            "collapses": bool(ok.all() and dev and worst <= tolerance),
        })  # fmt: skip
    return pd.DataFrame(rows)


def collapse_fraction(
    boundary: pd.DataFrame, c: float, threshold: float, tolerance: float = 0.10
) -> float:
    """The fraction of a grid's beams that collapse (`collapse_by_beam`).

    Parameters
    ----------
    boundary : pandas.DataFrame
        Boundary rows of a grid.
    c : float
        The constant c (dimensionless).
    threshold : float
        The Delta RMS threshold whose rows are read.
    tolerance : float
        Largest relative deviation of a collapsing beam.

    Returns
    -------
    float
        The fraction, in [0, 1]; NaN with no beam.
    """
    t = collapse_by_beam(boundary, c, threshold, tolerance)
    return float(t["collapses"].mean()) if len(t) else math.nan
