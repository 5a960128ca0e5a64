"""The one-mode surrogate (Sec. 6) beside the full model: the tables of the surrogate study.

`southwell_table` sets the Southwell line f_0 against the exact first in-plane frequency;
`vs_full_table` and `surrogate_boundary` set the surrogate's RMS, Delta RMS, f_d* and cost
against the full model's.  Their figures are `rotbeam.paper.surrogate_figures`; the two studies:
docs/reproduction.md.
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

    The true maximum lies between the neighbours of the grid maximum (``f_peak_lo_hz``,
    ``f_peak_hi_hz``); ``f_peak_interp_hz`` is the vertex of the parabola through the three
    points (NaN, like the bracket, when the maximum is the first or last point of the scan, or
    when the parabola opens upwards).

    Parameters
    ----------
    line : pandas.DataFrame
        A full sweep line (f_d, rms_dynamic, converged).

    Returns
    -------
    dict
        ``f_peak_hz`` (the grid maximum), ``f_peak_lo_hz``, ``f_peak_hi_hz`` and
        ``f_peak_interp_hz`` [Hz]; ``rms_peak`` (units of L); ``peak_at_edge`` (bool);
        ``points_used`` (the converged points).  NaN with no converged point.
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
    """The Southwell line against the exact first in-plane frequency, at Omega_0 + a, over C_max.

    Southwell: Eq. (centrifugal_stiffening) with the in-plane S_1; exact: the first frequency of
    the linearised discrete model on N intervals.

    Parameters
    ----------
    beam : dict
        The beam's `Beam` fields (SI).
    c_max : sequence of float
        C_max of the curve's rows (dimensionless).
    amplitude : float
        Drive amplitude a [rad/s].
    N : int
        Grid intervals of the exact frequency.
    peak_lines : mapping of str to pandas.DataFrame or None
        Full sweep lines by name, whose resonance peaks (`peak_of_line`) become extra rows.

    Returns
    -------
    table : pandas.DataFrame
        Rows of kind "curve" (one per C_max with Omega_0 >= 0) and "dynamic_peak" (one per
        line, at its own C_max): omega, f_n_hz, f0_southwell_hz, f0_exact_hz and
        rel_error_southwell; peak rows also the `peak_of_line` columns and the peak's relative
        difference to both frequencies.
    skipped : list of float
        The C_max left out because Omega_0 = sqrt(C_max / G) - a < 0.
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
    """The discrete model's error in f_1 at rest: f_1(Omega = 0) / f_n - 1.

    Parameters
    ----------
    beam : dict
        The beam's `Beam` fields (SI).
    N : int
        Grid intervals.

    Returns
    -------
    float
        The relative error (dimensionless) against the continuum f_n.
    """
    b = Beam(**beam)
    return float(modes(b, 0.0, 1, N, softening=True)[0]) / b.f_n - 1.0


# --- surrogate vs full model -----------------------------------------------------------------


def surrogate_points(
    beam: dict, line: pd.DataFrame, effects: Effects, repeats: int = 3
) -> tuple[pd.DataFrame, float]:
    """Surrogate steady state at every drive frequency of a full sweep line, beside the full one.

    Parameters
    ----------
    beam : dict
        The beam's `Beam` fields (SI).
    line : pandas.DataFrame
        A full sweep line (omega0, amplitude, C_max, f_d, rms_dynamic, rms_quasistatic,
        delta_rms, converged, seconds).
    effects : Effects
        The effects of the surrogate.
    repeats : int
        Passes over the points; the fastest is timed.

    Returns
    -------
    points : pandas.DataFrame
        One row per f_d: the full model's RMS, Delta RMS, convergence and seconds, the
        surrogate's RMS and Delta RMS, and their relative RMS differences.
    seconds : float
        Wall time [s] of `steady_rms` over these points, best of `repeats` passes.
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
    """Surrogate RMS and Delta RMS on a fine f_d grid spanning a sweep line, for plotting.

    Parameters
    ----------
    beam : dict
        The beam's `Beam` fields (SI).
    line : pandas.DataFrame
        A full sweep line (omega0, amplitude, f_d).
    effects : Effects
        The effects of the surrogate.
    points : int
        Drive frequencies, evenly spaced from the line's lowest f_d to its highest.

    Returns
    -------
    pandas.DataFrame
        Columns f_d [Hz], rms_dynamic, rms_quasistatic (units of L) and delta_rms.
    """
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
    """The full model's f_d* (the PCHIP root of its scan) on every line of the comparison.

    Parameters
    ----------
    fig4_lines : mapping of str to pandas.DataFrame
        The Fig. 4 sweep lines by name; their f_d* is found as rule fig4 finds it.
    boundary_lines : mapping of str to pandas.DataFrame
        Boundary sweep lines by name; their f_d* is read from `boundary`, matched on Omega_0.
    boundary : pandas.DataFrame
        The reference beam's boundary table (threshold, omega0, f_d_root).
    threshold : float
        The Delta RMS threshold.
    beam : dict
        The beam's `Beam` fields (SI).

    Returns
    -------
    dict
        {line name: f_d* [Hz]}, NaN where the line has none.
    """
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
    """Per line: f_d* of the surrogate and of the full model, E* of both and of the formula.

    The surrogate's f_d* is its own root (`critical_frequency`);
    ``f_d_star_surrogate_grid_hz`` is the surrogate's f_d* found as the full model's is, on the
    same scan points with the same PCHIP rule, which separates the model difference from the
    scan's interpolation error.  E* of Eq. (analytical_sol) uses the fitted c, with S_1 and with
    the exact frequencies.

    Parameters
    ----------
    beam : dict
        The beam's `Beam` fields (SI).
    lines : mapping of str to pandas.DataFrame
        Full sweep lines by name.
    full_critical : mapping of str to float
        The full model's f_d* [Hz] of each line (`full_critical`).
    threshold : float
        The Delta RMS threshold.
    effects : Effects
        The effects of the surrogate.
    n_scan : int
        Scan points of the surrogate's own root finding.
    N : int
        Grid intervals of the exact frequencies.
    c_fit : float
        The fitted c of Eq. (analytical_sol) (dimensionless).
    tolerance : float
        Largest relative difference of f_d* for "within_tolerance".

    Returns
    -------
    table : pandas.DataFrame
        One row per line, by C_max: f_d* of both and their relative difference, E* of both
        models and of Eq. (analytical_sol), c of both, the cost per point.
    points : pandas.DataFrame
        The `surrogate_points` of every line, with a column ``line``.
    speed : dict
        The cost per point of both models and the speed-up.

    Raises
    ------
    RotbeamInputError
        When the lines hold no point.
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
    """Where the surrogate's f_d* is within a tolerance of the full model's, in words.

    Parameters
    ----------
    table : pandas.DataFrame
        The line table of `vs_full_table`.
    tolerance : float
        Largest relative difference |f_d*_surrogate / f_d*_full - 1|.

    Returns
    -------
    str
        The C_max of the lines within and above it, measured on the lines.
    """
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
    """The surrogate's boundary E*(C_max) on a log grid, beside Eq. (analytical_sol).

    Parameters
    ----------
    beam : dict
        The beam's `Beam` fields (SI).
    c_lo, c_hi : float
        The grid's ends (dimensionless); C_max below G a^2 (Omega_0 < 0) is left out.
    points : int
        Grid points.
    threshold : float
        The Delta RMS threshold.
    amplitude : float
        Drive amplitude a [rad/s].
    effects : Effects
        The effects of the surrogate.
    n_scan : int
        Scan points of the surrogate's root finding.
    N : int
        Grid intervals of the exact f_0.
    c_fit : float
        The fitted c of Eq. (analytical_sol).

    Returns
    -------
    pandas.DataFrame
        Columns C_max, f_d_star_surrogate_hz (NaN where the surrogate has no root),
        E_star_surrogate, E_star_analytical_S1 and E_star_analytical_exact.
    """
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
