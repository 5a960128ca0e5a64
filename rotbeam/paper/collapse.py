"""How well a grid of beams collapses on Eq. (scaled_analytical_sol), E*/E_n = c sqrt(1 + x).

x = S_1 G a^2 C_max / E_n^2.  With E_n = G a 2 pi f_n and G (2 pi f_n)^2 = beta_1^4 / delta
(time by T, G = T^2 / delta), x = S_1 delta C_max / beta_1^4: the abscissa depends on the beam
only through S_1(r_o) delta, which is why a bounded S_1 delta bounds E*/E_n at a given C_max.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..model.params import BETA1
from ..model.surrogate import southwell_coefficient


def scaled_abscissa(row: pd.Series) -> float:
    """x = S_1 G a^2 C_max / E_n^2 of one boundary row (a is folded into E_n = G a 2 pi f_n)."""
    S1 = southwell_coefficient(float(row["hub_ratio"]))
    return S1 * float(row["G"]) * float(row["C_max"]) / float(row["E_n"]) ** 2


def southwell_delta(delta: float) -> float:
    """S_1(r_o) delta for a beam whose clamp sits at r_o = 1/delta - 1 lengths from the axis."""
    return southwell_coefficient(1.0 / delta - 1.0) * delta


def scaled_bound(c: float, delta: float, c_max: float) -> float:
    """E*/E_n from Eq. (scaled_analytical_sol) at C_max for a beam of L/R = delta."""
    return c * math.sqrt(1.0 + southwell_delta(delta) * c_max / BETA1**4)


def collapse_by_beam(
    boundary: pd.DataFrame, c: float, threshold: float, tolerance: float = 0.10
) -> pd.DataFrame:
    """Per beam: the largest |E*/E_n / (c sqrt(1 + x)) - 1| over its lines and whether it
    collapses (every line has a crossing and lies within `tolerance`)."""
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
    """Fraction of beams that collapse (NaN for an empty table)."""
    t = collapse_by_beam(boundary, c, threshold, tolerance)
    return float(t["collapses"].mean()) if len(t) else math.nan
