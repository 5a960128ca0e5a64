"""The verdict's figure: y_m over the steady window, dynamic against quasi-static, with the
verdict of `rotbeam.analysis.verdict.judge` and the cost of the run (`rotbeam simulate --plot`).
"""

from __future__ import annotations

import math
from pathlib import Path

from matplotlib.figure import Figure

from ..analysis.verdict import Verdict
from ..config.checks import check_plot_suffix
from ..model.modes import resonance_frequency_hz
from ..model.params import Drive
from ..runs.move import MoveResult
from ..runs.scene import SceneResult
from .style import DYN, QS, figure, save

#: points the verdict's figure draws per period of the first in-plane mode at the drive's
#: largest speed (a slow drive's window samples the vibration a few times a cycle)
MODE_PERIOD_POINTS = 32


def plot_samples(result: SceneResult) -> int:
    """Instants per drive period the verdict's figure draws.

    Parameters
    ----------
    result : SceneResult
        The simulated scene.

    Returns
    -------
    int
        MODE_PERIOD_POINTS per period of the first in-plane mode at the drive's largest speed
        (`rotbeam.model.modes.resonance_frequency_hz`), rounded up to a multiple of the
        window's samples (the curves pass through every computed sample).
    """
    scene = result.scene
    m = max(result.dynamic.samples_per_period, 1)
    f1 = resonance_frequency_hz(scene.beam, scene.drive.omega_max)
    return m * max(1, math.ceil(MODE_PERIOD_POINTS * f1 / scene.drive.f_d / m))


def largest_speed_text(drive: Drive) -> str:
    """The title's largest speed of a drive that is not the sine.

    Its kind's words (`DriveKind.largest_speed`): a sampled profile's own largest |Omega|
    sample, and its trigonometric interpolant's beside it where the two differ at the title's
    four digits (the Gibbs overshoot at a trapezoid's corners: 6.018 rad/s for a 6 rad/s
    trapezoid of 32 harmonics).

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    str
        "largest speed W rad/s", with "(W' after the K-harmonic interpolant)" where it differs.
    """
    return drive.as_kind.largest_speed()


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
    save(verdict_figure(result, verdict), path)


def verdict_figure(result: SceneResult, verdict: Verdict) -> Figure:
    """The figure of `plot_verdict`: y_m over the steady window at `plot_samples` instants a
    drive period (`SceneResult.dense_series`), the verdict in the title, the cost in the legend.

    Parameters
    ----------
    result : SceneResult
        The simulated scene.
    verdict : Verdict
        Its verdict (`judge`).

    Returns
    -------
    matplotlib.figure.Figure
        The figure, not yet saved.
    """
    series = result.dense_series(plot_samples(result))
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
    what = drive.as_kind.title()
    ax.set_title(
        what + rf", $f_d$ = {drive.f_d:g} Hz" + f"\n{where}\n" + verdict.text.split(" (")[0],
        loc="left",
    )
    cost = f"computed in {result.seconds:.3g} s (N = {num.N}, {num.method}"
    extrapolated = bool(result.extrapolation and result.extrapolation.get("extrapolated"))
    cost += ", Richardson-extrapolated RMS)" if extrapolated else ")"
    ax.legend(title=cost, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    return fig


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
