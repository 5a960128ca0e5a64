"""The one-mode surrogate (Sec. 6) beside the full model: the tables of the surrogate study.

Two studies (their figures are `rotbeam.paper.surrogate_figures`; the workflow's scripts only
read, call and write):

* `southwell_table`: the Southwell line f_0 (Eq. centrifugal_stiffening) against the exact first
  in-plane frequency of the linearised discrete model over C_max, with the resonance peaks of full
  dynamic sweep lines as extra points (`peak_of_line`); `discretisation_floor` is the error of
  the discrete model's f_1 at rest.
* `surrogate_points`, `vs_full_table`, `surrogate_boundary`: RMS and Delta RMS of the surrogate
  at the drive frequencies of full sweep lines, the critical frequency f_d* of both per line
  (the full model's from `full_critical`), the surrogate's phase boundary with
  Eq. (analytical_sol) on the same axes, and the cost per point of both models;
  `validity_statement` says in words where the two f_d* agree.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from ..analysis.boundary import boundary_table
from ..config.errors import RotbeamInputError
from ..model.criterion import critical_from_scan
from ..model.modes import modes
from ..model.params import Beam, Dimensionless, Drive, Effects, omega0_for_cmax
from ..model.surrogate import (
    analytical_boundary,
    analytical_boundary_exact,
    critical_frequency,
    phase_boundary,
    southwell_frequency_hz,
    steady_rms,
)

# --- Southwell line vs exact frequencies -----------------------------------------------------


def peak_of_line(line: pd.DataFrame) -> dict:
    """Peak of the dynamic RMS over the converged points of one sweep line.

    The true maximum lies between the neighbours of the grid maximum (`f_peak_lo_hz`,
    `f_peak_hi_hz`); `f_peak_interp_hz` is the vertex of the parabola through the three points
    (NaN, like the bracket, when the maximum is the first or last point of the scan).
    """
    ok = line["converged"].astype(bool) & np.isfinite(line["rms_dynamic"])
    sub = line.loc[ok].sort_values("f_d")
    f = sub["f_d"].to_numpy(float)
    r = sub["rms_dynamic"].to_numpy(float)
    out = {"f_peak_hz": math.nan, "f_peak_lo_hz": math.nan, "f_peak_hi_hz": math.nan,
           "f_peak_interp_hz": math.nan, "rms_peak": math.nan, "peak_at_edge": True,
           "points_used": int(ok.sum())}  # fmt: skip
    if f.size == 0:
        return out
    j = int(np.argmax(r))
    out.update(f_peak_hz=float(f[j]), rms_peak=float(r[j]))
    if 0 < j < f.size - 1:
        x, y = f[j - 1 : j + 2], r[j - 1 : j + 2]
        a, b, _ = np.polyfit(x, y, 2)
        vertex = -b / (2.0 * a) if a < 0 else math.nan
        out.update(f_peak_lo_hz=float(x[0]), f_peak_hi_hz=float(x[2]), peak_at_edge=False,
                   f_peak_interp_hz=float(vertex))  # fmt: skip
    return out


def southwell_table(
    beam: dict,
    c_max: Sequence[float],
    amplitude: float,
    N: int,
    peak_lines: Mapping[str, pd.DataFrame] | None = None,
) -> tuple[pd.DataFrame, list[float]]:
    """Southwell vs exact first in-plane frequency at Omega = Omega_0 + a over C_max.

    Rows of kind `curve` come from `c_max` (values with Omega_0 < 0 are skipped and returned);
    rows of kind `dynamic_peak` from the peaks of full sweep lines, at their own C_max.
    """
    b = Beam(**beam)
    rows, skipped = [], []

    def freqs(omega: float) -> dict:
        fs = southwell_frequency_hz(b, omega, softening=True)
        fe = float(modes(b, omega, 1, N, softening=True)[0])
        return {"omega": omega, "f_n_hz": b.f_n, "f0_southwell_hz": fs, "f0_exact_hz": fe,
                "rel_error_southwell": fs / fe - 1.0}  # fmt: skip

    for c in c_max:
        w0 = omega0_for_cmax(b, float(c), amplitude)
        if w0 < 0:
            skipped.append(float(c))
            continue
        rows.append({"kind": "curve", "source": "config", "C_max": float(c), "omega0": w0,
                     **freqs(w0 + amplitude)})  # fmt: skip
    for name, line in (peak_lines or {}).items():
        if line.empty:
            continue
        w0 = float(line["omega0"].iloc[0])
        a = float(line["amplitude"].iloc[0])
        row = {"kind": "dynamic_peak", "source": name, "C_max": float(line["C_max"].iloc[0]),
               "omega0": w0, **freqs(abs(w0) + a), **peak_of_line(line)}  # fmt: skip
        row["rel_peak_vs_exact"] = row["f_peak_hz"] / row["f0_exact_hz"] - 1.0
        row["rel_peak_vs_southwell"] = row["f_peak_hz"] / row["f0_southwell_hz"] - 1.0
        rows.append(row)
    return pd.DataFrame(rows), skipped


def discretisation_floor(beam: dict, N: int) -> float:
    """f_1(Omega = 0) of the discrete model over the continuum f_n, minus 1 (error at N)."""
    b = Beam(**beam)
    return float(modes(b, 0.0, 1, N, softening=True)[0]) / b.f_n - 1.0


# --- surrogate vs full model -----------------------------------------------------------------


def surrogate_points(
    beam: dict, line: pd.DataFrame, effects: Effects, repeats: int = 3
) -> tuple[pd.DataFrame, float]:
    """Surrogate steady state at every drive frequency of a full sweep line, beside the full one.

    Returns the point table and the wall time [s] of `steady_rms` over these points (best of
    `repeats` passes).
    """
    b = Beam(**beam)
    w0 = float(line["omega0"].iloc[0])
    a = float(line["amplitude"].iloc[0])
    dls = [Dimensionless.from_physical(b, Drive(w0, a, float(f)), effects) for f in line["f_d"]]
    seconds = math.inf
    for _ in range(repeats):  # best of `repeats` passes: the cost, not the machine's load
        t0 = time.perf_counter()
        sur = [steady_rms(dl) for dl in dls]
        seconds = min(seconds, time.perf_counter() - t0)
    out = pd.DataFrame({
        "omega0": w0, "C_max": line["C_max"].to_numpy(float), "f_d": line["f_d"].to_numpy(float),
        "full_rms_dynamic": line["rms_dynamic"].to_numpy(float),
        "full_rms_quasistatic": line["rms_quasistatic"].to_numpy(float),
        "full_delta_rms": line["delta_rms"].to_numpy(float),
        "full_converged": line["converged"].astype(bool).to_numpy(),
        "full_seconds": line["seconds"].to_numpy(float),
        "sur_rms_dynamic": [s["rms_dynamic"] for s in sur],
        "sur_rms_quasistatic": [s["rms_quasistatic"] for s in sur],
        "sur_delta_rms": [s["delta_rms"] for s in sur],
    })  # fmt: skip
    out["rel_diff_rms_dynamic"] = out["sur_rms_dynamic"] / out["full_rms_dynamic"] - 1.0
    out["rel_diff_rms_quasistatic"] = out["sur_rms_quasistatic"] / out["full_rms_quasistatic"] - 1.0
    return out, seconds


def surrogate_curve(beam: dict, line: pd.DataFrame, effects: Effects, points: int) -> pd.DataFrame:
    """Surrogate RMS and Delta RMS on a fine f_d grid spanning a sweep line (for plotting)."""
    b = Beam(**beam)
    w0 = float(line["omega0"].iloc[0])
    a = float(line["amplitude"].iloc[0])
    fs = np.linspace(float(line["f_d"].min()), float(line["f_d"].max()), points)
    rows = [steady_rms(Dimensionless.from_physical(b, Drive(w0, a, float(f)), effects)) for f in fs]
    return pd.DataFrame({"f_d": fs, **{k: [r[k] for r in rows] for k in
                         ("rms_dynamic", "rms_quasistatic", "delta_rms")}})  # fmt: skip


def _surrogate_critical(beam: Beam, w0, threshold, a, effects, n_scan) -> tuple[float, float, str]:
    t0 = time.perf_counter()
    try:
        f = critical_frequency(beam, w0, threshold, a, effects, n_scan)
        msg = "brentq on the surrogate"
    except RotbeamInputError as exc:
        f, msg = math.nan, str(exc)
    return f, time.perf_counter() - t0, msg


def full_critical(
    fig4_lines: Mapping[str, pd.DataFrame],
    boundary_lines: Mapping[str, pd.DataFrame],
    boundary: pd.DataFrame,
    threshold: float,
    beam: dict,
) -> dict[str, float]:
    """The full model's f_d* (PCHIP root of its scan) per line: the Fig. 4 lines as rule fig4
    finds it, the boundary lines from the boundary table at `threshold` (matched on Omega_0)."""
    out = {}
    for name, line in fig4_lines.items():
        crit = boundary_table([line], [threshold], beam)
        out[name] = float(crit["f_d_root"].iloc[0]) if not crit.empty else math.nan
    ref = boundary[np.isclose(boundary["threshold"], threshold)]
    for name, line in boundary_lines.items():
        row = ref[np.isclose(ref["omega0"], float(line["omega0"].iloc[0]))]
        out[name] = float(row["f_d_root"].iloc[0]) if not row.empty else math.nan
    return out


def _line_row(
    b: Beam,
    name: str,
    line: pd.DataFrame,
    p: pd.DataFrame,
    sec: float,
    f_full: float,
    threshold: float,
    effects: Effects,
    n_scan: int,
    N: int,
    c_fit: float,
    tolerance: float,
) -> dict:
    """One line of `vs_full_table`: f_d* and E* of both models and the analytical boundary, the
    cost; `p` and `sec` are the line's surrogate points and their time (`surrogate_points`)."""
    w0 = float(line["omega0"].iloc[0])
    a = float(line["amplitude"].iloc[0])
    c_max = float(line["C_max"].iloc[0])
    f_sur, t_crit, msg = _surrogate_critical(b, w0, threshold, a, effects, n_scan)
    f_grid = critical_from_scan(p["f_d"].to_numpy(), p["sur_delta_rms"].to_numpy(), threshold)
    e = b.G * a * 2.0 * math.pi
    f0_ex = float(modes(b, abs(w0) + a, 1, N, softening=True)[0])
    f0_sw = southwell_frequency_hz(b, abs(w0) + a, effects.softening)
    rel = f_sur / f_full - 1.0
    rel_grid = f_grid["f_d_root"] / f_full - 1.0
    return {
        "line": name, "omega0": w0, "C_max": c_max, "threshold": threshold,
        "f0_exact_hz": f0_ex, "f0_southwell_hz": f0_sw,
        "f_d_star_full_hz": f_full, "f_d_star_surrogate_hz": f_sur,
        "rel_diff": rel, "within_tolerance": bool(abs(rel) <= tolerance),
        "f_d_star_surrogate_grid_hz": f_grid["f_d_root"], "rel_diff_grid": rel_grid,
        "E_star_full": e * f_full, "E_star_surrogate": e * f_sur,
        "E_star_analytical_S1": analytical_boundary(b, c_max, c_fit, amplitude=a),
        "E_star_analytical_exact": analytical_boundary_exact(b, c_max, c_fit, a, N),
        "c_full": f_full / f0_ex, "c_surrogate": f_sur / f0_sw,
        "points": len(p),
        "full_seconds_per_point": float(p["full_seconds"].mean()),
        "surrogate_seconds_per_point": sec / max(1, len(p)),
        "surrogate_seconds_critical": t_crit,
        "full_N": int(line["N"].iloc[0]) if "N" in line else -1,
        "message": msg,
    }  # fmt: skip


def _speed_summary(
    table: pd.DataFrame, points: pd.DataFrame, sur_seconds: float, n_scan: int
) -> dict:
    """Cost per point of both models (surrogate: measured here; full: the lines' `seconds`)."""
    n_points = len(points)
    full_s = points["full_seconds"].to_numpy(float)
    sur_pp = sur_seconds / n_points
    return {
        "points": n_points,
        "lines": len(table),
        "surrogate_seconds_per_point": sur_pp,
        "full_seconds_per_point_mean": float(np.nanmean(full_s)),
        "full_seconds_per_point_median": float(np.nanmedian(full_s)),
        "speedup_mean": float(np.nanmean(full_s)) / sur_pp if sur_pp > 0 else math.nan,
        "surrogate_seconds_per_f_d_star": float(table["surrogate_seconds_critical"].mean()),
        "surrogate_n_scan": n_scan,
        "full_seconds_per_line_mean": float(points.groupby("line")["full_seconds"].sum().mean()),
        "full_N": sorted({int(n) for n in table["full_N"]}),
        "note": "surrogate: time.perf_counter around steady_rms (dynamic + quasi-static harmonic "
        "balance) at the full lines' drive frequencies, best of 3 passes after a warm-up call; "
        "full: the sweep lines' `seconds` column (dynamic + quasi-static per point, with "
        "continuation).",
    }


def vs_full_table(
    beam: dict,
    lines: Mapping[str, pd.DataFrame],
    full_critical: Mapping[str, float],
    threshold: float,
    effects: Effects,
    n_scan: int,
    N: int,
    c_fit: float,
    tolerance: float,
) -> tuple[pd.DataFrame, pd.DataFrame, dict]:
    """Per-line f_d* of the surrogate and of the full model, their relative difference, E* of
    both and of Eq. (analytical_sol) (fitted c; S_1 and exact frequencies), and the cost.

    `full_critical[name]` is the full model's f_d* (root) of line `name`.  The surrogate's f_d* is
    its own root (`critical_frequency`); `f_d_star_surrogate_grid_hz` is the surrogate's f_d*
    found as the full model's is, on the same scan points with the same PCHIP rule, which
    separates the model difference from the scan's interpolation error.
    Returns the line table, the point table and a speed summary.
    """
    b = Beam(**beam)
    rows, pts, sur_seconds = [], [], 0.0
    steady_rms(Dimensionless.from_physical(b, Drive(1.0, 1.0, 1.0), effects))  # warm caches
    for name, line in lines.items():
        p, sec = surrogate_points(beam, line, effects)
        p.insert(0, "line", name)
        pts.append(p)
        sur_seconds += sec
        f_full = float(full_critical.get(name, math.nan))
        rows.append(_line_row(b, name, line, p, sec, f_full, threshold, effects, n_scan, N, c_fit,
                              tolerance))  # fmt: skip
    if not sum(len(p) for p in pts):
        raise RotbeamInputError("no sweep line to compare the surrogate with")
    table = pd.DataFrame(rows).sort_values("C_max", kind="stable").reset_index(drop=True)
    points = pd.concat(pts, ignore_index=True)
    return table, points, _speed_summary(table, points, sur_seconds, n_scan)


def validity_statement(table: pd.DataFrame, tolerance: float) -> str:
    """Where |f_d*_surrogate / f_d*_full - 1| <= tolerance, in words (measured on the lines)."""
    t = table[np.isfinite(table["rel_diff"])].sort_values("C_max")
    if t.empty:
        return "no line with f_d* of both models"
    ok = t[t["within_tolerance"]]
    bad = t[~t["within_tolerance"]]
    fmt = ", ".join
    s = f"|f_d*_sur/f_d*_full - 1| <= {100 * tolerance:g} % at C_max = "
    s += fmt(f"{c:.3g}" for c in ok["C_max"]) if not ok.empty else "none"
    if not bad.empty:
        pairs = zip(bad["C_max"], bad["rel_diff"], strict=True)
        s += "; above at C_max = " + fmt(f"{c:.3g} ({100 * r:+.1f} %)" for c, r in pairs)
    return s + f" (of {len(t)} lines, C_max {t['C_max'].min():.3g}-{t['C_max'].max():.3g})"


def surrogate_boundary(
    beam: dict,
    c_lo: float,
    c_hi: float,
    points: int,
    threshold: float,
    amplitude: float,
    effects: Effects,
    n_scan: int,
    N: int,
    c_fit: float,
) -> pd.DataFrame:
    """Surrogate E*(C_max) on a log grid with Eq. (analytical_sol) (S_1 and exact f_0)."""
    b = Beam(**beam)
    lo = max(float(c_lo), b.G * amplitude**2 * (1.0 + 1e-9))  # Omega_0 >= 0
    cs = np.logspace(math.log10(lo), math.log10(max(float(c_hi), lo)), points)
    rows = []
    for c in cs:
        try:
            pb = phase_boundary(b, [float(c)], threshold, amplitude, effects, n_scan)
            e_sur, f_sur = float(pb["e_star"][0]), float(pb["f_d_star"][0])
        except RotbeamInputError:
            e_sur = f_sur = math.nan
        rows.append({"C_max": float(c), "f_d_star_surrogate_hz": f_sur, "E_star_surrogate": e_sur})
    out = pd.DataFrame(rows)
    out["E_star_analytical_S1"] = analytical_boundary(b, cs, c_fit, amplitude=amplitude)
    out["E_star_analytical_exact"] = analytical_boundary_exact(b, cs, c_fit, amplitude, N)
    return out
