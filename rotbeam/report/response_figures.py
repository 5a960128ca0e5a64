"""The response when there is no stable periodic state: Poincare section and spectrum."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..runs.response import ResponseResult
from ..runs.scene import Scene
from .style import DYN, GREY, figure, save


def plot_response(r: ResponseResult, scene: Scene, path: str | Path) -> None:
    """Stroboscopic section (y_m, dy_m/dt at t = k / f_d) beside the spectrum of y_m, for a
    scene without a stable periodic state (`rotbeam simulate --plot`).

    Parameters
    ----------
    r : ResponseResult
        The classified response (section, spectrum, class, Lyapunov exponent).
    scene : Scene
        The scene, for the drive frequency and the title.
    path : str or Path
        The figure's file (.png, .pdf or .svg), written atomically.
    """
    drive = scene.drive
    fig, (a1, a2) = figure(1, 2, width=9.0, height=3.8)
    a1.plot(r.section[:, 0], r.section[:, 1], ".", color=DYN, ms=3)
    a1.set_xlabel("$y_m / L$ at $t = k / f_d$")
    a1.set_ylabel(r"$\dot y_m / L$ [1/s]")
    a1.set_title(f"Poincare section ({r.section.shape[0]} periods)", loc="left")
    a2.semilogy(r.spectrum_hz, np.maximum(r.spectrum, 1e-300), color=DYN)
    a2.axvline(drive.f_d, color=GREY, ls=":", label=f"$f_d$ = {drive.f_d:g} Hz")
    a2.set_xlim(0, 4 * drive.f_d)
    a2.set_xlabel("f [Hz]")
    a2.set_ylabel("|FFT($y_m$)|")
    a2.legend()
    fig.suptitle(
        rf"$\Omega_0$ = {drive.omega0:g} rad/s, a = {drive.amplitude:g} rad/s, "
        rf"$f_d$ = {drive.f_d:g} Hz: {r.response}, "
        rf"$\lambda_{{max}}$ = {r.lyapunov_max:.3g} $\pm$ {r.lyapunov_spread:.2g} 1/s (N = {r.N})"
    )
    save(fig, Path(path))
