"""What axial stretching (effect `extension`, off in the paper) does on the Fig. 5 lines.

`stretch_study` tables every line's clamp strain and, on the lines it studies, f_d*, RMS(y_m)
and Delta RMS with stretching off and on; `inextensible_limit` gives the C_max above which the
paper's inextensible model stops holding.  The study and its two claims: docs/reproduction.md.
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

#: the columns of the study's table
COLUMNS = ["C_max", "omega0", "clamp_strain", "studied", "f_d_star_off", "f_d_star_on",
           "f_d_star_change", "rms_off", "rms_on", "rms_change", "delta_off", "delta_on",
           "delta_change", "seconds"]  # fmt: skip


def clamp_strain(beam: Beam, omega0: float, amplitude: float) -> float:
    """The axial strain N/(EA) at the clamp of the straight beam, in closed form.

    It is taken at the rotation the model freezes the stretch at (`Dimensionless.lam_stretch`):
    exact in the strain (`rotbeam.model.grid.centrifugal_strain`), rho Omega^2 L^2 (R_o/L + 1/2)
    / E to first order.

    Parameters
    ----------
    beam : Beam
        The beam (SI).
    omega0 : float
        Mean rotation rate Omega_0 [rad/s].
    amplitude : float
        Drive amplitude a [rad/s].

    Returns
    -------
    float
        The strain (dimensionless).
    """
    on = Effects(extension=True)
    dl = Dimensionless.from_physical(beam, Drive(omega0=omega0, f_d=1.0, amplitude=amplitude), on)
    return float(centrifugal_strain(0.0, dl.hub_ratio, dl.kappa, dl.lam_stretch, dl.tip_mass))


def stretch_line(beam: Beam, c_max: float, amplitude: float, threshold: float, effects: Effects,
                 numerics: Numerics, rtol: float = 1e-3) -> dict[str, float]:  # fmt: skip
    """One studied line: f_d* with stretching off and on, and the response at the first.

    f_d* comes from root finding (`rotbeam.analysis.verdict.critical`); RMS(y_m) and Delta RMS
    off and on are taken at the inextensible f_d*.

    Parameters
    ----------
    beam : Beam
        The beam (SI).
    c_max : float
        The line's C_max (dimensionless); Omega_0 = sqrt(C_max / G) - a.
    amplitude : float
        Drive amplitude a [rad/s].
    threshold : float
        The Delta RMS threshold.
    effects : Effects
        The other effects; ``extension`` is switched off and on.
    numerics : Numerics
        The solver settings.
    rtol : float
        Relative tolerance of the root finding.

    Returns
    -------
    dict
        f_d_star_off and f_d_star_on [Hz], rms_off and rms_on (units of L), delta_off and
        delta_on, f_d_star_change and rms_change (relative), delta_change (difference) and
        seconds (wall time).
    """
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
    """The study's table: every line's clamp strain, and stretching off and on where studied.

    Parameters
    ----------
    beam : Beam
        The beam (SI).
    c_max : list of float
        The lines' C_max (config ``boundary.c_max``).
    studied : list of float
        The C_max studied with stretching off and on (config ``reproduction.stretch.c_max``);
        they need not be among `c_max`: they are added.
    amplitude : float
        Drive amplitude a [rad/s].
    threshold : float
        The Delta RMS threshold.
    effects : Effects
        The other effects.
    numerics : Numerics
        The solver settings.
    rtol : float
        Relative tolerance of the root finding.

    Returns
    -------
    pandas.DataFrame
        One row per C_max, ascending, columns `COLUMNS`; the `stretch_line` columns are NaN
        on the lines not studied.
    """
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
    """The C_max above which stretching moves f_d* by more than a given fraction.

    |f_d* change| is interpolated log-log between the studied lines (it grows like the strain,
    ~C_max).

    Parameters
    ----------
    table : pandas.DataFrame
        The study's table (`stretch_study`).
    within : float
        The relative change of f_d* (dimensionless) that marks the limit; 0.01 in the claims.

    Returns
    -------
    float
        That C_max (dimensionless): inf when no studied line reaches it, the smallest studied
        C_max when the first already does, NaN with no studied line.
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
