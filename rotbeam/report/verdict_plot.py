"""The verdict's figure: y_m over the steady window, dynamic against quasi-static, with the
verdict of `rotbeam.analysis.verdict.judge` and the cost of the run (`rotbeam simulate --plot`).
"""

from __future__ import annotations

import math
from pathlib import Path

from ..analysis.verdict import Verdict
from ..config.checks import check_plot_suffix
from ..runs.move import MoveResult
from ..runs.scene import SceneResult
from .style import DYN, QS, figure, save


def plot_verdict(result: SceneResult, verdict: Verdict, path: str | Path) -> None:
    """Draw y_m over the steady window, dynamic against quasi-static, with the verdict and the
    cost (`rotbeam simulate --plot`).

    Parameters
    ----------
    result : SceneResult
        The simulated scene.
    verdict : Verdict
        Its verdict (`judge`).
    path : str or Path
        The figure's file: .png, .pdf or .svg (PLOT_SUFFIXES), written atomically.

    Raises
    ------
    RotbeamInputError
        If `path` does not end in one of PLOT_SUFFIXES (checked before drawing).
    """
    path = check_plot_suffix(path)
    series = result.time_series()
    t = series["t_s"] - series["t_s"][0]
    scene = result.scene
    drive, num = scene.drive, scene.numerics
    fig, ax = figure(width=7.0, height=3.8)
    ax.plot(t, series["y_m_dynamic"], color=DYN,
            label=f"dynamical, RMS {result.rms_dynamic:.4g}")  # fmt: skip
    ax.plot(t, series["y_m_quasistatic"], "--", color=QS,
            label=f"quasi-static, RMS {result.rms_quasistatic:.4g}")  # fmt: skip
    ax.set_xlabel("t [s] (steady state)")
    ax.set_ylabel("$y_m / L$ (midspan)")
    where = f"$f_d / f_0$ = {drive.f_d / verdict.f0_hz:.3g}, $f_0$ = {verdict.f0_hz:.3g} Hz"
    if math.isfinite(verdict.fd_star_estimate_hz):
        where += f"; linear estimate $f_d^*$ = {verdict.fd_star_estimate_hz:.3g} Hz"
    else:
        where += "; no Euler load, no $f_d^*$"
    what = rf"$\Omega_0$ = {drive.omega0:g} rad/s, a = {drive.amplitude:g} rad/s"
    if drive.kind != "sine":
        what = f"{drive.kind} drive, largest speed {drive.omega_max:.4g} rad/s"
    ax.set_title(
        what + rf", $f_d$ = {drive.f_d:g} Hz" + f"\n{where}\n" + verdict.text.split(" (")[0],
        loc="left",
    )
    cost = f"computed in {result.seconds:.3g} s (N = {num.N}, {num.method}"
    extrapolated = bool(result.extrapolation and result.extrapolation.get("extrapolated"))
    cost += ", Richardson-extrapolated RMS)" if extrapolated else ")"
    ax.legend(title=cost, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    save(fig, path)


def plot_move(result: MoveResult, verdict: Verdict, path: str | Path) -> None:
    """Draw a single move: the disk's speed, and y_m dynamic against quasi-static through the
    move and the settling window after it, with the verdict and the cost.

    Parameters
    ----------
    result : MoveResult
        The simulated move.
    verdict : Verdict
        Its verdict (`judge_move`).
    path : str or Path
        The figure's file: .png, .pdf or .svg, written atomically.
    """
    path = check_plot_suffix(path)
    fig, (top, ax) = figure(2, 1, width=7.0, height=5.4, sharex=True,
                            gridspec_kw={"height_ratios": (1, 2)})  # fmt: skip
    t = result.t_s
    top.plot(t, result.omega, color="k")
    top.set_ylabel(r"$\Omega$ [rad/s]")
    top.axvline(result.move_s, color="0.6", lw=0.8)
    ax.plot(t, result.y_dynamic, color=DYN, label=f"dynamical, peak {result.peak_ym:.3g}")
    ax.plot(t, result.y_quasistatic, "--", color=QS,
            label=f"quasi-static, peak {result.peak_ym_quasistatic:.3g}")  # fmt: skip
    ax.axvline(result.move_s, color="0.6", lw=0.8)
    ax.set_xlabel("t [s] from the start of the move (grey line: its end)")
    ax.set_ylabel("$y_m / L$ (midspan)")
    top.set_title(verdict.text.split(";")[0], loc="left")
    num = result.scene.numerics
    cost = f"computed in {result.seconds:.3g} s (N = {num.N}, {num.method})"
    ax.legend(title=cost, loc="upper center", bbox_to_anchor=(0.5, -0.25), ncol=2)
    save(fig, path)
