"""The paper's printed numbers against this reproduction: one row per claim, with a status.

    reproduced    ours lies within the paper's stated uncertainty or printed rounding (or on the
                  claimed side of a threshold, for at_least / at_most / below claims)
    explained     ours does not, but a named hypothesis run through this model gives a value
                  within that same tolerance (explained_value; the others tried are listed)
    unexplained   neither; every hypothesis tried and what it gave is in `explanation`

Printed values come from one data file (rotbeam/paper/paper_claims.yaml); "ours" values are
read from the workflow's outputs by `ours_values`; hypotheses come from the studies as a long
table (claim, hypothesis, value, note).  Pure functions on DataFrames and dicts.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..model.criterion import power_spectrum
from .collapse import collapse_fraction
from .hypotheses import plateau
from .printed import KINDS

COLUMNS = ["id", "source", "paper", "ours", "unit", "status", "explained_value", "explanation"]
HYPOTHESIS_COLUMNS = ["claim", "hypothesis", "value", "note"]


def agrees(value: float, paper: float, tolerance: float, kind: str) -> bool:
    """Whether `value` reproduces the printed `paper` value under `kind` (NaN never does)."""
    if value is None or not math.isfinite(value):
        return False
    if kind == "at_least":
        return value >= paper
    if kind == "at_most":
        return value <= paper
    if kind == "below":
        return value < paper
    # a hair of round-off on the band edge: 0.3162 printed, 0.31623 computed
    return abs(value - paper) <= tolerance * (1 + 1e-9) + 1e-12 * abs(paper)


def _fmt(v: float) -> str:
    return "nan" if v is None or not math.isfinite(v) else format(v, ".4g")


def _band(paper: float, tolerance: float, kind: str) -> str:
    if kind in ("at_least", "at_most", "below"):
        op = {"at_least": ">=", "at_most": "<=", "below": "<"}[kind]
        return f"{op} {_fmt(paper)}"
    return f"{_fmt(paper)} +- {_fmt(tolerance)} ({kind})"


def judge_row(claim: pd.Series, ours: float, note: str, tried: pd.DataFrame) -> dict:
    """Status, explained_value and explanation of one claim."""
    p, tol, kind = float(claim["paper"]), float(claim["tolerance"]), str(claim["kind"])
    band = _band(p, tol, kind)
    tries = [
        (str(h["hypothesis"]), float(h["value"]), "" if pd.isna(h.get("note")) else str(h["note"]))
        for _, h in tried.iterrows()
    ]
    # a hypothesis marked counts = False (one that fails a sibling claim it must explain too)
    # is listed but explains nothing
    counts = tried["counts"].tolist() if "counts" in tried else [True] * len(tries)
    hits = [t for t, ok in zip(tries, counts, strict=True) if ok and agrees(t[1], p, tol, kind)]
    listing = "; ".join(f"{h} gave {_fmt(v)}" + (f" ({n})" if n else "") for h, v, n in tries)
    base = f"ours {_fmt(ours)}" + (f" ({note})" if note else "")
    if agrees(ours, p, tol, kind):
        status, value = "reproduced", math.nan
        text = f"{base} within {KINDS[kind]}: {band}"
        if tries:
            text += f". Also tried: {listing}"
    elif hits:
        status = "explained"
        # the hypothesis closest to the printed value explains it
        h, value, n = min(hits, key=lambda t: abs(t[1] - p))
        others = [t for t in tries if t[0] != h]
        text = f"{base} outside {band}; {h} gives {_fmt(value)}" + (f" ({n})" if n else "")
        if others:
            text += ". Also tried: " + "; ".join(
                f"{o[0]} gave {_fmt(o[1])}" + (f" ({o[2]})" if o[2] else "") for o in others
            )
    else:
        status, value = "unexplained", math.nan
        text = f"{base} outside {band}; " + (f"tried: {listing}" if tries else "no hypothesis run")
    return {
        "id": claim["id"], "source": claim["source"], "paper": p, "ours": ours,
        "unit": claim["unit"], "status": status, "explained_value": value, "explanation": text,
    }  # fmt: skip


def judge(
    claims: pd.DataFrame, ours: dict[str, tuple[float, str]], hypotheses: pd.DataFrame
) -> pd.DataFrame:
    """The claims table: one row per claim in file order, COLUMNS."""
    hyp = hypotheses if len(hypotheses) else pd.DataFrame(columns=HYPOTHESIS_COLUMNS)
    rows = []
    for _, c in claims.iterrows():
        value, note = ours.get(c["id"], (math.nan, "not computed by this workflow"))
        rows.append(judge_row(c, value, note, hyp[hyp["claim"] == c["id"]]))
    return pd.DataFrame(rows, columns=COLUMNS)


def c_hypotheses_long(table: pd.DataFrame, claims: pd.DataFrame | None = None) -> pd.DataFrame:
    """The c study's (hypothesis, threshold, c) rows as claims c_<threshold>.

    One mechanism must give the printed c at every threshold at once (App. D prints four values
    of one pipeline): with the claims given, a hypothesis that misses any threshold it was run
    at explains none of them (`counts` False, and its note says so), so that no claim is
    explained by one reading and its neighbour by another."""
    rows = [
        {"claim": f"c_{float(r['threshold']):.2f}", "hypothesis": str(r["hypothesis"]),
         "value": float(r["c"]), "note": "", "counts": True}
        for _, r in table.iterrows()
    ]  # fmt: skip
    out = pd.DataFrame(rows, columns=[*HYPOTHESIS_COLUMNS, "counts"])
    if claims is None or out.empty:
        return out
    printed = claims.set_index("id")
    for _, group in out.groupby("hypothesis"):
        misses = [
            c for c, v in zip(group["claim"], group["value"], strict=True)
            if c in printed.index and not agrees(
                v, float(printed.loc[c, "paper"]), float(printed.loc[c, "tolerance"]),
                str(printed.loc[c, "kind"]))
        ]  # fmt: skip
        if misses:
            out.loc[group.index, "counts"] = False
            out.loc[group.index, "note"] = "misses " + ", ".join(misses)
    return out


# --- ours: read from the workflow's outputs ---------------------------------------------------


@dataclass
class Outputs:
    """The workflow outputs the claims read (DataFrames as written, dicts from JSON)."""

    table1: pd.DataFrame
    c_per_threshold: pd.DataFrame
    boundary_ref: pd.DataFrame
    fig6_fit: dict
    fig7_fit: dict
    fig7_boundary: pd.DataFrame
    fig3_line: pd.DataFrame
    fig3_series: pd.DataFrame
    fig5_series: list[pd.DataFrame]
    ref_lines: pd.DataFrame
    c0_table: pd.DataFrame
    convergence: pd.DataFrame
    main_threshold: float = 0.10
    amplitude: float = 1.0
    convergence_tolerance: float = 0.01
    stretch: pd.DataFrame | None = None  #: rotbeam.paper.stretch_study's table
    extra: dict = field(default_factory=dict)


def _t1(o: Outputs, q: str) -> float:
    row = o.table1[o.table1["quantity"] == q]
    return float(row["value"].iloc[0]) if len(row) else math.nan


def _main(b: pd.DataFrame, th: float) -> pd.DataFrame:
    return b[np.isclose(b["threshold"], th)].sort_values("C_max")


def _slope_top(b: pd.DataFrame, column: str) -> float:
    """log-log slope of `column` against C_max over the two largest C_max."""
    ok = b[np.isfinite(b[column]) & (b[column] > 0)].sort_values("C_max").tail(2)
    if len(ok) < 2:
        return math.nan
    x, y = np.log(ok["C_max"].to_numpy(float)), np.log(ok[column].to_numpy(float))
    return float((y[1] - y[0]) / (x[1] - x[0]))


def peak_frequency(line: pd.DataFrame) -> float:
    """f_d of the largest RMS(y_m), refined by a parabola through the sampled peak."""
    ln = line[np.isfinite(line["rms_dynamic"])].sort_values("f_d")
    f, r = ln["f_d"].to_numpy(float), ln["rms_dynamic"].to_numpy(float)
    k = int(np.argmax(r))
    if 0 < k < len(f) - 1:
        a, b, c = np.polyfit(f[k - 1 : k + 2], r[k - 1 : k + 2], 2)
        if a < 0:
            return float(-b / (2 * a))
    return float(f[k])


def spectrum_peak_hz(series: pd.DataFrame) -> float:
    """Frequency [Hz] of the largest |FFT(y_m)| of a kept dynamic series (0 Hz left out)."""
    tau, t = series["tau"].to_numpy(float), series["t_s"].to_numpy(float)
    T = (t[1] - t[0]) / (tau[1] - tau[0])
    f, amp = power_spectrum(tau, series["y_m_dynamic"].to_numpy(float))
    k = 1 + int(np.argmax(amp[1:]))
    return float(f[k] / T)


def converged_n(conv: pd.DataFrame, tolerance: float) -> float:
    """Smallest N whose RMS is within `tolerance` of the finest N at every (Omega_0, f_d)."""
    n_max = conv["N"].max()
    ok_n = []
    for n in sorted(conv["N"].unique()):
        if n == n_max:
            break
        good = True
        for _, sub in conv.groupby(["omega0", "f_d"]):
            ref = sub.loc[sub["N"] == n_max, "rms_dynamic"]
            at = sub.loc[sub["N"] == n, "rms_dynamic"]
            err = abs(float(at.iloc[0]) / float(ref.iloc[0]) - 1) if len(ref) and len(at) else 1.0
            if not err <= tolerance:
                good = False
                break
        ok_n.append((n, good))
    # the smallest N from which every finer N (below the finest) also passes
    best = math.nan
    for n, good in reversed(ok_n):
        if not good:
            break
        best = float(n)
    return best


def _fig5(o: Outputs, at: dict) -> tuple[float, str]:
    c_max, e_max = float(at["C_max"]), float(at["E_max"])
    for s in o.fig5_series:
        if math.isclose(float(s["C_max"].iloc[0]), c_max, rel_tol=0.05) and math.isclose(
            float(s["E_max"].iloc[0]), e_max, rel_tol=0.05
        ):
            return float(s["delta_rms"].iloc[0]), f"f_d = {float(s['f_d'].iloc[0]):.3g} Hz"
    return math.nan, f"no series at (C_max, E_max) = ({c_max:g}, {e_max:g}) in this config"


def window_max(b: pd.DataFrame, at: dict) -> tuple[float, str]:
    """Largest E*/E_n of boundary rows with h/L = at['h_over_L'] and C_max in at['C_max']."""
    (c_lo, c_hi), hl = at["C_max"], float(at["h_over_L"])
    sel = b[np.isclose(b["h_over_L"], hl) & (b["C_max"] >= c_lo) & (b["C_max"] <= c_hi)]
    v = (sel["E_star_root"] / sel["E_n"]).to_numpy(float)
    v = v[np.isfinite(v)]
    return (float(v.max()) if v.size else math.nan), f"{v.size} boundary points in the window"


def plateau_coefficient(table1: pd.DataFrame) -> float:
    """App. D's pi lambda_1 A L^3 sqrt(rho) / (beta_1^2 I sqrt(3 E)) f_n from Table 1 (SI)."""
    from ..model.params import BETA1

    q = table1.set_index("quantity")["value"]
    L, h, b = (float(q[k]) * 1e-3 for k in ("L", "h", "b"))
    E, rho, f_n = float(q["E"]) * 1e6, float(q["rho"]), float(q["f_n"])
    A, I = b * h, b * h**3 / 12.0  # noqa: E741 - the paper's symbol
    return math.pi * (h / L) * A * L**3 * math.sqrt(rho) / (BETA1**2 * I * math.sqrt(3 * E)) * f_n


def _at(claims: pd.DataFrame) -> dict[str, dict]:
    if "at" not in claims:
        return {}
    return {r["id"]: r["at"] for _, r in claims.iterrows() if isinstance(r["at"], dict)}


def ours_values(o: Outputs, claims: pd.DataFrame) -> dict[str, tuple[float, str]]:
    """(value, note) per claim id, every value read from the workflow's outputs; where a claim
    is evaluated (drive, window, band) comes from its `at` in the claims file."""
    G, a, th = _t1(o, "G"), o.amplitude, o.main_threshold
    at = _at(claims)
    ref = _main(o.boundary_ref, th)
    c_ref = float(o.fig6_fit["c"])
    out: dict[str, tuple[float, str]] = {
        "f_n_hz": (_t1(o, "f_n"), "Eq. (natural_freq), exact beta_1, Table 1"),
        "zeta": (_t1(o, "zeta"), "Table (systems), cantilever row, gamma = 0.039"),
        "sim_C_min": (float(o.ref_lines["C_max"].min()), "smallest C_max of our reference lines"),
        "sim_E_max": (float(o.ref_lines["E_max"].max()), "largest E_max of our reference lines"),
        "resonance_omega5_hz": (peak_frequency(o.fig3_line), "peak of the simulated scan"),
        "fig3_spectrum_peak_hz": (spectrum_peak_hz(o.fig3_series), "|FFT(y_m)| of the series"),
        "f0_exponent": (_slope_top(ref, "f0_hz"), "exact linear f_0"),
        "E_star_exponent": (_slope_top(ref, "E_star_root"), ""),
        "c_fig7": (float(o.fig7_fit.get("c", math.nan)),
                   f"curve_fit over beams with zeta <= {o.fig7_fit.get('zeta_max_used', 'all')}"),
        "N_converged": (converged_n(o.convergence, o.convergence_tolerance),
                        f"within {o.convergence_tolerance:g} of N = {o.convergence['N'].max()}"),
    }  # fmt: skip
    out["figD9_plateau_coefficient"] = (plateau_coefficient(o.table1), "Table 1 and our f_n")
    for cid, w in at.items():
        if cid.startswith("exp_C"):
            out[cid] = (
                G * (float(w["omega0"]) + a) ** 2,
                f"G (Omega_0 + a)^2 at Omega_0 = {w['omega0']:g}, G from R assumed",
            )
        elif cid.startswith("exp_E"):
            out[cid] = (G * a * 2 * math.pi * float(w["f_d"]), f"G a 2 pi f_d at {w['f_d']:g} Hz")
        elif cid.startswith("fig5_"):
            out[cid] = _fig5(o, w)
        elif cid == "figD9_range":
            out[cid] = window_max(o.fig7_boundary, w)
        elif cid == "fig7_collapse":
            out[cid] = (collapse_fraction(o.fig7_boundary, c_ref, th, float(w["within"])),
                        f"c = {c_ref:.4g} of the reference beam (Fig. 6 fit)")  # fmt: skip
        elif cid == "E_star_plateau":
            out[cid] = (plateau(ref, "E_star_root", float(w["C_max_up_to"])),
                        "E* = G a 2 pi f_d*, root of the scan")  # fmt: skip
        elif cid == "f0_tilde_low_cmax":
            r = ref.assign(f0_tilde=ref["f0_hz"] / ref["f_n_hz"])
            out[cid] = (plateau(r, "f0_tilde", float(w["C_max_up_to"])), "exact linear f_0 / f_n")
    for _, r in o.c_per_threshold.iterrows():
        out[f"c_{float(r['threshold']):.2f}"] = (float(r["ref_c_root"]), "curve_fit, root of scan")
    for _, r in o.c0_table.iterrows():
        out[f"c0_{float(r['threshold']):.2f}"] = (float(r["c0_zeta0"]), "zeta -> 0")
    if "c0_small_zeta" in at:
        th0 = float(at["c0_small_zeta"]["threshold"])
        row = o.c0_table[np.isclose(o.c0_table["threshold"], th0)]
        if len(row):
            out["c0_small_zeta"] = (float(row["c0_zeta0"].iloc[0]), "zeta -> 0")
    if o.stretch is not None:
        for cid in ("inextensible_fd_star", "inextensible_c_max"):
            if cid in at:
                out[cid] = stretch_claim(o.stretch, cid, float(at[cid]["within"]))
    out.update(o.extra)
    return out


def stretch_claim(table: pd.DataFrame, cid: str, within: float) -> tuple[float, str]:
    """(value, note) of the inextensible_* claims from the stretch study's table: the largest
    |f_d* change| or the C_max where it passes `within`; the note gives every line's clamp
    strain and the studied lines' changes of f_d*, RMS and Delta RMS."""
    from .stretch_study import inextensible_limit

    parts = []
    for _, r in table.sort_values("C_max").iterrows():
        text = f"C_max {r['C_max']:g}: strain {100 * r['clamp_strain']:.3g} %"
        if bool(r["studied"]):
            text += (
                f", f_d* {100 * r['f_d_star_change']:+.3g} %, "
                f"RMS {100 * r['rms_change']:+.3g} %, Delta RMS {r['delta_change']:+.2g}"
            )
        parts.append(text)
    note = "; ".join(parts)
    if cid == "inextensible_c_max":
        return inextensible_limit(table, within), note
    studied = table[table["studied"].astype(bool)]
    worst = float(np.abs(studied["f_d_star_change"]).max()) if len(studied) else math.nan
    return worst, note


def builtin_hypotheses(
    o: Outputs, claims: pd.DataFrame, ours: dict[str, tuple[float, str]]
) -> pd.DataFrame:
    """Hypotheses that need no study of their own (readings of a printed range or digit)."""
    G, a, at = _t1(o, "G"), o.amplitude, _at(claims)
    paper = claims.set_index("id")["paper"]
    rows = [{"claim": "sim_C_min", "hypothesis": "the range starts at Omega_0 = 0 (C = G a^2)",
             "value": G * a * a, "note": "no line of ours runs at Omega_0 = 0"}]  # fmt: skip
    for cid in ("exp_C_min", "exp_C_max"):
        if cid in at:
            w = float(at[cid]["omega0"])
            need = float(paper[cid]) / (w + a) ** 2
            rows.append(
                {
                    "claim": cid,
                    "hypothesis": "C = G Omega_0^2 (a left out)",
                    "value": G * w * w,
                    "note": f"the printed end needs G = {need:.4g} s^2, ours {G:.4g}",
                }
            )
    c0 = ours.get("c0_small_zeta", (math.nan, ""))[0]
    if math.isfinite(c0):
        rows.append({"claim": "c0_small_zeta", "hypothesis": "sqrt(0.1) truncated, not rounded",
                     "value": math.floor(c0 * 100) / 100, "note": ""})  # fmt: skip
    return pd.DataFrame(rows, columns=HYPOTHESIS_COLUMNS)


def claims_markdown(table: pd.DataFrame) -> str:
    """The claims table as Markdown, with a count of each status on top."""
    from ..report.io import markdown_table

    counts = table["status"].value_counts()
    head = ", ".join(f"{counts.get(s, 0)} {s}" for s in ("reproduced", "explained", "unexplained"))
    return (
        "# Paper against reproduction\n\n"
        f"{len(table)} claims: {head}.  Printed values: rotbeam/paper/paper_claims.yaml; "
        "ours: this workflow's outputs; explanation: the band, and every hypothesis tried.\n\n"
        + markdown_table(table)
    )
