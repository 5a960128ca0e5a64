"""The quasi-static/dynamic boundary from sweep lines: f_d*, E*, and the fitted c of f_d* = c f_0.

Downstream of the simulations: a new threshold is a new table, not a new simulation.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

import numpy as np
import pandas as pd

from ..config.checks import check_threshold
from ..model.criterion import critical_from_scan
from ..model.params import Beam
from ..model.secondorder import c0_limit


def lines_of(df: pd.DataFrame) -> list[pd.DataFrame]:
    """The sweep lines in one file: a line per `c_max_target` (a grid beam's file holds all its
    lines), or the whole frame when it has no such column (one line per file).

    Parameters
    ----------
    df : pandas.DataFrame
        One sweep file's rows (one row per drive frequency).

    Returns
    -------
    list of pandas.DataFrame
        One frame per line, in increasing `c_max_target`.
    """
    if "c_max_target" not in df or df.empty:
        return [df]
    return [line for _, line in df.groupby("c_max_target", sort=True)]


def boundary_table(
    lines: Iterable[pd.DataFrame], thresholds: Iterable[float], beam: dict, beam_id: str = "ref"
) -> pd.DataFrame:
    """One row per (line, threshold): f_d* by the grid rule and by the root, and E*.

    Every line gives its rows, an empty one included (NaN, found False), so that a fit over the
    table counts it as dropped.  `points_failed` counts points without a finite Delta RMS
    (solver failures, status -2) or from runs that report no converged steady state;
    `points_unconverged` counts the latter.  Unconverged points are left out of f_d*: their RMS
    is what the solver saw when its budget ran out, not the steady state.

    Parameters
    ----------
    lines : iterable of pandas.DataFrame
        Sweep lines (`lines_of`): columns f_d [Hz], delta_rms, amplitude [rad/s], omega0
        [rad/s], C_max, f0_hz [Hz], optionally converged.
    thresholds : iterable of float
        Delta RMS thresholds, dimensionless, each in (0, 1).
    beam : dict
        The beam's fields (`Beam(**beam)`), SI units.
    beam_id : str
        The beam's label in the table.

    Returns
    -------
    pandas.DataFrame
        One row per (line, threshold): f_d_grid and f_d_root [Hz], E_star_grid and E_star_root
        (dimensionless), found, the points used and failed, and a message.

    Raises
    ------
    RotbeamInputError
        If a threshold is not a number in (0, 1).
    """
    b = Beam(**beam)
    rows = []
    for df in lines:
        if df.empty:
            for th in thresholds:
                rows.append({
                    "beam": beam_id, "E": b.E, "L": b.L, "h_over_L": float(f"{b.h / b.L:.6g}"),
                    "zeta": b.zeta, "omega0": math.nan, "C_max": math.nan,
                    "threshold": check_threshold(float(th)), "f_n_hz": b.f_n, "f0_hz": math.nan,
                    "f_d_grid": math.nan, "f_d_root": math.nan, "E_star_grid": math.nan,
                    "E_star_root": math.nan, "E_n": math.nan, "G": b.G,
                    "hub_ratio": b.hub_ratio, "found": False, "points_used": 0,
                    "points_failed": 0, "points_unconverged": 0,
                    "message": "empty line: no scanned points",
                })  # fmt: skip
            continue
        first = df.iloc[0]
        unconverged = 0
        delta = df["delta_rms"].to_numpy(float).copy()
        if "converged" in df:
            conv = df["converged"].astype(str).str.lower().isin(["true", "1", "1.0"]).to_numpy()
            # a run that ended without a steady state (status 1, 2), not a solver failure (-2)
            ran = df["status"].to_numpy() != -2 if "status" in df else np.isfinite(delta)
            unconverged = int((~conv & ran).sum())
            delta[~conv] = np.nan
        a = float(first["amplitude"])
        for th in thresholds:
            th = check_threshold(float(th))
            cr = critical_from_scan(df["f_d"].to_numpy(), delta, th)
            e = b.G * a * 2.0 * math.pi
            rows.append({
                "beam": beam_id, "E": b.E, "L": b.L, "h_over_L": float(f"{b.h / b.L:.6g}"),
                "zeta": b.zeta,
                "omega0": float(first["omega0"]), "C_max": float(first["C_max"]),
                "threshold": th, "f_n_hz": b.f_n, "f0_hz": float(first["f0_hz"]),
                "f_d_grid": cr["f_d_grid"], "f_d_root": cr["f_d_root"],
                "E_star_grid": e * cr["f_d_grid"], "E_star_root": e * cr["f_d_root"],
                "E_n": e * b.f_n, "G": b.G, "hub_ratio": b.hub_ratio,
                "found": cr["found"], "points_used": cr["points_used"],
                "points_failed": cr["points_failed"], "points_unconverged": unconverged,
                "message": cr["message"],
            })  # fmt: skip
    return pd.DataFrame(rows)


def fit_c(table: pd.DataFrame, column: str = "f_d_root") -> dict:
    """Nonlinear least squares (scipy curve_fit) of f_d* = c f_0 over the lines of a table.

    Parameters
    ----------
    table : pandas.DataFrame
        A boundary table (`boundary_table`), usually of one threshold.
    column : str
        The f_d* column to fit: "f_d_root" or "f_d_grid".

    Returns
    -------
    dict
        ``c`` and ``c_stderr`` (dimensionless; NaN with fewer than 2 lines), ``points_used``,
        ``points_dropped``, ``dropped`` (beam, C_max and reason per dropped line), ``column`` and
        ``message``.
    """
    ok = table["found"].astype(bool) & np.isfinite(table[column]) & np.isfinite(table["f0_hz"])
    f0 = table.loc[ok, "f0_hz"].to_numpy(float)
    fd = table.loc[ok, column].to_numpy(float)
    dropped = [
        {
            "beam": str(r.get("beam", "")),
            "C_max": float(r["C_max"]),
            "reason": str(r.get("message", "")) if not r["found"] else f"{column} not finite",
        }
        for _, r in table[~ok].iterrows()
    ]
    out = {"points_used": int(ok.sum()), "points_dropped": int((~ok).sum()), "column": column,
           "dropped": dropped}  # fmt: skip
    if f0.size < 2:
        out.update(c=math.nan, c_stderr=math.nan, message="fewer than 2 lines with a crossing")
        return out
    from scipy.optimize import curve_fit  # imported here: most boundary jobs fit nothing

    popt, pcov = curve_fit(lambda x, c: c * x, f0, fd, p0=[0.35])
    out.update(c=float(popt[0]), c_stderr=float(np.sqrt(pcov[0, 0])), message="curve_fit")
    return out


def c_per_threshold(
    table: pd.DataFrame, paper: Mapping[float, float] | None = None
) -> pd.DataFrame:
    """Fitted c per threshold (root and grid rule) beside App. E's c_0 and the printed c.

    Parameters
    ----------
    table : pandas.DataFrame
        A boundary table (`boundary_table`) over one or more thresholds.
    paper : mapping or None
        Threshold -> the paper's printed c (from rotbeam/paper/paper_claims.yaml); None: none.

    Returns
    -------
    pandas.DataFrame
        One row per threshold: c_root, c_grid and their standard errors, the lines used and
        dropped, c0_second_order (App. E's zeta -> 0 root) and c_paper (NaN where not printed).
    """
    paper = paper or {}
    rows = []
    for th, sub in table.groupby("threshold"):
        root = fit_c(sub, "f_d_root")
        grid = fit_c(sub, "f_d_grid")
        rows.append({
            "threshold": th, "c_root": root["c"], "c_root_stderr": root["c_stderr"],
            "c_grid": grid["c"], "c_grid_stderr": grid["c_stderr"],
            "lines_used": root["points_used"], "lines_dropped": root["points_dropped"],
            "grid_lines_used": grid["points_used"], "grid_lines_dropped": grid["points_dropped"],
            "c0_second_order": c0_limit(th), "c_paper": paper.get(round(th, 4), math.nan),
        })  # fmt: skip
    return pd.DataFrame(rows)
