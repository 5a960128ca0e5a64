"""What axial stretching (effect `extension`, off in the paper) does on the Fig. 5 lines.

For each reference boundary line C_max (config `boundary.c_max`, Omega_0 = sqrt(C_max / G) - a)
the clamp strain N/(EA) at s = 0, in closed form (`rotbeam.model.elastica.centrifugal_strain` at
the rotation the model freezes the stretch at, `Dimensionless.lam_stretch`). On the lines the
study names (config `reproduction.stretch.c_max`): f_d* by root finding (`critical`)
with stretching off and on, and RMS(y_m) and Delta RMS at the inextensible f_d* with it off and
on. `inextensible_limit` interpolates the C_max above which stretching moves f_d* by more than a
given fraction (1 % in the claims): where the paper's inextensible model stops holding.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np
import pandas as pd

from ..analysis.verdict import critical
from ..model.grid import centrifugal_strain
from ..model.params import Beam, Dimensionless, Drive, Effects, omega0_for_cmax
from ..runs.scene import Scene, simulate
from ..solve.numerics import Numerics

COLUMNS = ["C_max", "omega0", "clamp_strain", "studied", "f_d_star_off", "f_d_star_on",
           "f_d_star_change", "rms_off", "rms_on", "rms_change", "delta_off", "delta_on",
           "delta_change", "seconds"]  # fmt: skip


def clamp_strain(beam: Beam, omega0: float, amplitude: float) -> float:
    """N/(EA) at the clamp of the straight beam at the stretch rotation of the model (exact in
    the strain; rho Omega^2 L^2 (R_o/L + 1/2) / E to first order)."""
    on = Effects(extension=True)
    dl = Dimensionless.from_physical(beam, Drive(omega0=omega0, f_d=1.0, amplitude=amplitude), on)
    return float(centrifugal_strain(0.0, dl.hub_ratio, dl.kappa, dl.lam_stretch))


def stretch_line(beam: Beam, c_max: float, amplitude: float, threshold: float, effects: Effects,
                 numerics: Numerics, rtol: float = 1e-3) -> dict[str, float]:  # fmt: skip
    """One studied line: f_d* off and on, RMS and Delta RMS off and on at the f_d* of `off`."""
    t0 = time.perf_counter()
    w0 = omega0_for_cmax(beam, c_max, amplitude)
    off, on = replace(effects, extension=False), replace(effects, extension=True)
    drive = Drive(omega0=w0, amplitude=amplitude, f_d=1.0)  # f_d: the search sets it
    crit = {k: critical(Scene(beam, drive, e, numerics), threshold, rtol)
            for k, e in (("off", off), ("on", on))}  # fmt: skip
    row: dict[str, float] = {"f_d_star_off": crit["off"].f_d_star,
                             "f_d_star_on": crit["on"].f_d_star}  # fmt: skip
    f = crit["off"].f_d_star
    for k, e in (("off", off), ("on", on)):
        if math.isfinite(f):
            res = simulate(Scene(beam, Drive(omega0=w0, f_d=f, amplitude=amplitude), e, numerics))
            row[f"rms_{k}"], row[f"delta_{k}"] = res.rms_dynamic, res.delta_rms
        else:
            row[f"rms_{k}"] = row[f"delta_{k}"] = math.nan
    row["f_d_star_change"] = row["f_d_star_on"] / row["f_d_star_off"] - 1.0
    row["rms_change"] = row["rms_on"] / row["rms_off"] - 1.0
    row["delta_change"] = row["delta_on"] - row["delta_off"]
    row["seconds"] = time.perf_counter() - t0
    return row


def stretch_study(beam: Beam, c_max: list[float], studied: list[float], amplitude: float,
                  threshold: float, effects: Effects, numerics: Numerics,
                  rtol: float = 1e-3) -> pd.DataFrame:  # fmt: skip
    """The table: every line's clamp strain; f_d*, RMS and Delta RMS off and on where studied
    (NaN elsewhere). Studied C_max need not be among the lines; they are added."""
    rows = []
    for c in sorted(set(map(float, c_max)) | set(map(float, studied))):
        w0 = omega0_for_cmax(beam, c, amplitude)
        row = {k: math.nan for k in COLUMNS}
        row.update(C_max=c, omega0=w0, clamp_strain=clamp_strain(beam, w0, amplitude),
                   studied=c in set(map(float, studied)), seconds=0.0)  # fmt: skip
        if row["studied"]:
            row.update(stretch_line(beam, c, amplitude, threshold, effects, numerics, rtol))
        rows.append(row)
    return pd.DataFrame(rows, columns=COLUMNS)


def inextensible_limit(table: pd.DataFrame, within: float = 0.01) -> float:
    """The C_max above which stretching moves f_d* by more than `within` (relative): log-log
    interpolation of |f_d* change| between studied lines (it grows like the strain, ~C_max);
    inf when no studied line reaches it, the smallest studied C_max when the first already does.
    """
    t = table[table["studied"].astype(bool)].dropna(subset=["f_d_star_change"])
    t = t.sort_values("C_max")
    c, d = t["C_max"].to_numpy(float), np.abs(t["f_d_star_change"].to_numpy(float))
    if not len(c):
        return math.nan
    above = np.nonzero(d > within)[0]
    if not len(above):
        return math.inf
    i = int(above[0])
    if i == 0:
        return float(c[0])
    x0, x1, y0, y1 = np.log(c[i - 1]), np.log(c[i]), np.log(max(d[i - 1], 1e-300)), np.log(d[i])
    return float(np.exp(x0 + (np.log(within) - y0) * (x1 - x0) / (y1 - y0)))
