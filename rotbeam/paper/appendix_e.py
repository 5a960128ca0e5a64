"""Table (systems) of App. E of the paper: the damping ratio, stiffness and the printed "f_n"
column of a mass-spring, a pendulum and the cantilever beam."""

from __future__ import annotations

import math
from typing import Any

from ..model.params import BETA1, Beam


def systems_table(
    beam: Beam | None = None,
    mass_spring: dict[str, float] | None = None,
    pendulum: dict[str, float] | None = None,
) -> list[dict[str, Any]]:
    """Table (systems) of App. E: zeta, k and the printed "f_n" of three systems.

    The cantilever row is evaluated for `beam`; the mass-spring and pendulum rows only when their
    values are given (the reference beam does not define them), NaN otherwise.  The table's "f_n"
    column is an angular frequency [rad/s] (no 1/(2 pi)); ``f_n_hz`` divides it by 2 pi.

    Parameters
    ----------
    beam : Beam or None
        The cantilever (SI); None: the reference beam.
    mass_spring : dict or None
        ``k_s`` [N/m], ``m`` [kg] and ``gamma`` [N s/m].
    pendulum : dict or None
        ``m`` [kg], ``g`` [m/s^2], ``L`` [m] and ``gamma`` [N m s].

    Returns
    -------
    list of dict
        One row per system (mass-spring, pendulum, cantilever beam): ``system``; the formulas
        ``zeta_formula``, ``k_formula`` and ``f_n_formula``; ``zeta`` (dimensionless); ``k``
        (N/m for the mass-spring and the beam, N m for the pendulum); ``f_n_table`` [rad/s];
        ``f_n_unit`` (that unit in words) and ``f_n_hz`` [Hz].
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
