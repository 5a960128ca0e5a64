"""The verdict's figure: y_m over the steady window, dynamic against quasi-static, with the
verdict of `rotbeam.analysis.verdict.judge` and the cost of the run (`rotbeam simulate --plot`).
"""

from __future__ import annotations

from pathlib import Path

from ..analysis.verdict import Verdict
from ..config.checks import check_plot_suffix
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
    where += f"; linear estimate $f_d^*$ = {verdict.fd_star_estimate_hz:.3g} Hz"
    ax.set_title(
        rf"$\Omega_0$ = {drive.omega0:g} rad/s, a = {drive.amplitude:g} rad/s, "
        rf"$f_d$ = {drive.f_d:g} Hz" + f"\n{where}\n" + verdict.text.split(" (")[0],
        loc="left",
    )
    cost = f"computed in {result.seconds:.3g} s (N = {num.N}, {num.method}"
    extrapolated = bool(result.extrapolation and result.extrapolation.get("extrapolated"))
    cost += ", Richardson-extrapolated RMS)" if extrapolated else ")"
    ax.legend(title=cost, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    save(fig, path)
