r"""Quasi-static condition of the canonical second-order system (App. E of the paper).

For u'' + 2 zeta u' + u = (F0/k) cos(c0 tau) the steady amplitudes are
A_dyn = (F0/k) / sqrt((1 - c0^2)^2 + (2 zeta c0)^2) and A_QS = F0/k, so Eq. (Delta_RMS) gives

    Delta RMS = (A_dyn - A_QS) / A_dyn = 1 - sqrt((1 - c0^2)^2 + (2 zeta c0)^2)    (c0 < 1 side).

Setting it to a threshold t gives the biquadratic (Eq. c_0, printed for t = 0.1 as "+0.19")

    c0^4 + (4 zeta^2 - 2) c0^2 + (1 - (1 - t)^2) = 0,

i.e. with X = c0^2, B = 1 - 2 zeta^2 and C = t (2 - t) = 1 - (1 - t)^2:
X = B -+ sqrt(B^2 - C).  The smaller root is the first crossing.  At zeta = 0, B = 1 and
sqrt(1 - C) = 1 - t, so X = t exactly: c0(zeta -> 0) = sqrt(t), with no small-t approximation.
The paper's table (0.02 -> 0.1414, ..., 0.10 -> 0.3162) is therefore the exact zeta = 0 root.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..config.checks import check_threshold
from ..config.errors import RotbeamInputError
from .params import BETA1, Beam


def _check_zeta(zeta: float) -> float:
    if isinstance(zeta, bool) or not isinstance(zeta, (int, float, np.floating)):
        raise RotbeamInputError(f"damping ratio zeta must be a number >= 0, got {zeta!r}")
    z = float(zeta)
    if not (math.isfinite(z) and z >= 0.0):
        raise RotbeamInputError(f"damping ratio zeta must be finite and >= 0, got {zeta!r}")
    return z


def delta_rms_canonical(c0: float | np.ndarray, zeta: float) -> float | np.ndarray:
    """Signed App. E expression 1 - sqrt((1 - c0^2)^2 + (2 zeta c0)^2) (>= 0 below resonance).

    Eq. (Delta_RMS) takes |.|, which differs only where A_dyn < A_QS (far above resonance).
    """
    z = _check_zeta(zeta)
    c = np.asarray(c0, dtype=float)
    out = 1.0 - np.sqrt((1.0 - c * c) ** 2 + (2.0 * z * c) ** 2)
    return float(out) if np.ndim(out) == 0 else out


def biquadratic_residual(c0: float, zeta: float, threshold: float) -> float:
    """c0^4 + (4 zeta^2 - 2) c0^2 + (1 - (1 - threshold)^2), zero at a critical c0."""
    c2 = c0 * c0
    return c2 * c2 + (4.0 * zeta * zeta - 2.0) * c2 + (1.0 - (1.0 - threshold) ** 2)


def c0_root(zeta: float, threshold: float = 0.10) -> float:
    """Smallest positive root c0 of the biquadratic: the first frequency ratio f/f_n at which
    Delta RMS reaches `threshold`.  Raises if damping is so high that it never does."""
    z = _check_zeta(zeta)
    t = check_threshold(threshold)
    B = 1.0 - 2.0 * z * z
    C = t * (2.0 - t)
    disc = B * B - C
    if B <= 0.0 or disc < 0.0:
        peak = 2.0 * z * math.sqrt(1.0 - z * z) if z < 1.0 / math.sqrt(2.0) else 1.0
        raise RotbeamInputError(
            f"no c0 reaches Delta RMS = {t} at zeta = {z}: the response never exceeds the "
            f"quasi-static one by that much (max of 1 - sqrt(...) is {1.0 - peak:.4g}); "
            f"a root needs (1 - 2 zeta^2)^2 >= threshold (2 - threshold)"
        )
    # smaller root X = B - sqrt(disc), written without cancellation
    X = C / (B + math.sqrt(disc))
    return math.sqrt(X)


def c0_limit(threshold: float = 0.10) -> float:
    """Exact zeta -> 0 root of the biquadratic: c0 = sqrt(threshold) (see module docstring)."""
    return math.sqrt(check_threshold(threshold))


#: App. E, Table (c_0): printed c0 for zeta -> 0.
PRINTED_C0_TABLE: dict[float, float] = {
    0.02: 0.1414,
    0.04: 0.2000,
    0.06: 0.2449,
    0.08: 0.2828,
    0.10: 0.3162,
}


def c0_table(zeta: float = 0.0) -> list[dict[str, float]]:
    """Printed c0 against the exact zeta = 0 root and the root at the given zeta."""
    rows = []
    for t, printed in PRINTED_C0_TABLE.items():
        exact = c0_limit(t)
        rows.append(
            {
                "threshold": t,
                "c0_printed": printed,
                "c0_exact_zeta0": exact,
                "c0_at_zeta": c0_root(zeta, t),
                "printed_minus_exact": printed - exact,
            }
        )
    return rows


def systems_table(
    beam: Beam | None = None,
    mass_spring: dict[str, float] | None = None,
    pendulum: dict[str, float] | None = None,
) -> list[dict[str, Any]]:
    """Table (systems) of App. E: zeta, k and the printed "f_n" of three systems.

    The cantilever row is evaluated for `beam` (default: reference beam).  The mass-spring row
    needs {"k_s", "m", "gamma"} and the pendulum row {"m", "g", "L", "gamma"}; without them
    their values are NaN (the reference beam does not define them).  The table's "f_n" column is
    an angular frequency [rad/s] (no 1/(2 pi)); `f_n_hz` divides it by 2 pi.
    """
    beam = beam if beam is not None else Beam()
    nan = float("nan")
    rows: list[dict[str, Any]] = []

    def row(system: str, formulas: tuple[str, str, str], values: tuple[float, ...] | None):
        z, k, w = values if values is not None else (nan, nan, nan)
        zf, kf, wf = formulas
        return {"system": system, "zeta_formula": zf, "k_formula": kf, "f_n_formula": wf,
                "zeta": z, "k": k, "f_n_table": w}  # fmt: skip

    ms = mass_spring or {}
    ms_values = None
    if ms:
        k_s, m, gam = float(ms["k_s"]), float(ms["m"]), float(ms["gamma"])
        ms_values = (gam / (2.0 * math.sqrt(k_s * m)), k_s, math.sqrt(k_s / m))
    rows.append(row("mass-spring", ("gamma / (2 sqrt(k_s m))", "k_s", "sqrt(k_s / m)"),
                    ms_values))  # fmt: skip

    pd = pendulum or {}
    pd_values = None
    if pd:
        m, g, L, gam = float(pd["m"]), float(pd["g"]), float(pd["L"]), float(pd["gamma"])
        pd_values = (gam / (2.0 * m * L * math.sqrt(g * L)), m * g * L, math.sqrt(g / L))
    rows.append(row("pendulum", ("gamma / (2 m L sqrt(g L))", "m g L", "sqrt(g / L)"),
                    pd_values))  # fmt: skip

    EI, rhoA, L = beam.EI, beam.rhoA, beam.L
    beam_values = (
        beam.gamma * L * L / (2.0 * BETA1**2 * math.sqrt(EI * rhoA)),
        3.0 * EI / L**3,
        BETA1**2 * math.sqrt(EI / (rhoA * L**4)),
    )
    formulas = ("gamma L^2 / (2 beta_1^2 sqrt(E I rho A))", "3 E I / L^3",
                "beta_1^2 sqrt(E I / (rho A L^4))")  # fmt: skip
    rows.append(row("cantilever beam", formulas, beam_values))
    for r in rows:
        r["f_n_unit"] = "rad/s (angular: the table omits 1/(2 pi))"
        r["f_n_hz"] = r["f_n_table"] / (2.0 * math.pi)
    return rows
