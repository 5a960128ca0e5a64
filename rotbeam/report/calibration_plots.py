"""Plots of the calibration commands: a ring-down with its fit, a resonance curve with the
fitted model and the scene's (Table 1) model."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from ..analysis.identify import Identification
from ..analysis.measurements import ResonanceCurve, Ringdown
from ..analysis.ringdown import RingdownFit
from .style import DYN, GREY, QS, figure, save

if TYPE_CHECKING:
    from ..runs.scene import Scene
    from ..solve.numerics import Numerics


def plot_ringdown(data: Ringdown, fit: RingdownFit, path: str | Path) -> None:
    """Draw a ring-down: the record, the fitted damped oscillation and its envelope; residuals
    below (`rotbeam damping --plot`).

    Parameters
    ----------
    data : Ringdown
        The record: t [s], y (any unit).
    fit : RingdownFit
        Its fit (`fit_ringdown`).
    path : str or Path
        The figure's file (.png, .pdf or .svg), written atomically.
    """
    t0 = float(data.t[0])
    fig, (a, b) = figure(2, 1, width=7.0, height=4.8, sharex=True,
                         gridspec_kw={"height_ratios": [3, 1]})  # fmt: skip
    tt = np.linspace(data.t[0], data.t[-1], max(2000, 20 * data.t.size))
    env = fit.amplitude * np.exp(-(tt - t0) / fit.t_decay)
    a.plot(data.t, data.y, ".", ms=2.5, color=GREY, label="measured")
    a.plot(tt, fit.curve(tt, t0), color=DYN, lw=1.0, label="fit")
    a.plot(tt, fit.offset + env, "--", color=QS, lw=1.0, label=r"$A\,e^{-t/t_{decay}}$")
    a.plot(tt, fit.offset - env, "--", color=QS, lw=1.0)
    a.set_ylabel("y")
    a.set_title(
        f"f = {fit.f_hz:.4g} ± {fit.f_hz_stderr:.2g} Hz, t_decay = {fit.t_decay:.4g} ± "
        f"{fit.t_decay_stderr:.2g} s\n"
        rf"$\gamma$ = 2$\rho$A / t_decay = {fit.gamma:.4g} ± {fit.gamma_stderr:.2g} N s/m$^2$ "
        f"(ρA = {fit.rhoA:.4g} kg/m), SNR {fit.snr:.3g}",
        loc="left",
        fontsize=9,
    )
    a.legend(fontsize=8)
    b.plot(data.t, data.y - fit.curve(data.t, t0), ".", ms=2, color=GREY)
    b.axhline(0.0, color="k", lw=0.6)
    b.set_xlabel("t [s]")
    b.set_ylabel("residual")
    save(fig, path)


def plot_identification(curve: ResonanceCurve, fit: Identification, fitted: pd.DataFrame,
                        reference: pd.DataFrame, reference_label: str,
                        path: str | Path) -> None:  # fmt: skip
    """Draw a resonance curve: data (with rms_std bars if given), the fitted model's curve and
    the scene beam's curve, with the fitted values and their 95 % intervals.

    Parameters
    ----------
    curve : ResonanceCurve
        The measurement: f_d [Hz], RMS(y_m) and optionally its std.
    fit : Identification
        The fit (`identify`).
    fitted : pandas.DataFrame
        The fitted beam's simulated curve: columns f_d [Hz], rms_dynamic, N.
    reference : pandas.DataFrame
        The scene beam's simulated curve: columns f_d [Hz], rms_dynamic.
    reference_label : str
        The legend's name for the scene beam's curve.
    path : str or Path
        The figure's file (.png, .pdf or .svg), written atomically.
    """
    fig, a = figure(width=7.0, height=4.6)
    if curve.rms_std is not None:
        a.errorbar(curve.f_d, curve.rms, yerr=curve.rms_std, fmt="o", color="k", ms=4,
                   capsize=2, label="measured")  # fmt: skip
    else:
        a.plot(curve.f_d, curve.rms, "o", color="k", ms=4, label="measured")
    text = ", ".join(
        f"{n} = {fit.values[n]:.4g} [{fit.low[n]:.4g}, {fit.high[n]:.4g}]" for n in fit.names
    )
    a.plot(fitted["f_d"], fitted["rms_dynamic"], "-", color=DYN, label=f"fit: {text}")
    a.plot(reference["f_d"], reference["rms_dynamic"], "--", color=GREY, label=reference_label)
    a.set_xlabel("$f_d$ [Hz]")
    a.set_ylabel("RMS($y_m$) / L")
    N = int(fitted["N"].iloc[0])
    a.set_title(
        f"least squares on the full model (N = {N}): {fit.evaluations} evaluations, "
        f"{fit.runs} steady states, {fit.seconds:.3g} s; 95 % intervals",
        loc="left",
        fontsize=9,
    )
    a.legend(fontsize=8)
    save(fig, path)


def plot_identification_run(curve: ResonanceCurve, fit: Identification, scene: Scene,
                            omega0: float, amplitude: float, numerics: Numerics,
                            path: str | Path) -> None:  # fmt: skip
    """`plot_identification` with the fitted beam's and the scene beam's curves simulated on 41
    drive frequencies spanning the data (5 % beyond each end): 82 more runs of the full model.

    Parameters
    ----------
    curve : ResonanceCurve
        The measurement: f_d [Hz], RMS(y_m) and optionally its std.
    fit : Identification
        The fit (`identify`); its beam is simulated.
    scene : Scene
        The scene whose beam is drawn beside the fit, and whose effects both runs use.
    omega0 : float
        Mean angular velocity of the measurement, Omega_0 [rad/s].
    amplitude : float
        Velocity amplitude a of the drive [rad/s].
    numerics : Numerics
        Numerics of the runs (the fit's).
    path : str or Path
        The figure's file (.png, .pdf or .svg), written atomically.
    """
    import numpy as np

    from ..model.params import Beam
    from ..runs.sweeps import scan_line

    lo, hi = float(curve.f_d[0]), float(curve.f_d[-1])
    grid = np.linspace(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo), 41)
    fitted = scan_line(fit.beam, omega0, grid, amplitude, scene.effects, numerics)
    ref = scan_line(scene.beam, omega0, grid, amplitude, scene.effects, numerics)
    label = "Table 1 beam" if scene.beam == Beam() else "scene beam"
    label += f" (E = {scene.beam.E:.4g} Pa, gamma = {scene.beam.gamma:.4g})"
    plot_identification(curve, fit, fitted, ref, label, path)
