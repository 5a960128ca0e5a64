"""The engineer's question for one scene: is the quasi-static answer good enough here?

The criterion is the paper's: the quasi-static model is adequate where
Delta RMS = |RMS_dyn - RMS_QS| / RMS_dyn stays below a threshold (0.10 in the paper's main
figures).  Beside the answer of the full model this module gives the linear estimate of where
the boundary lies along the drive frequency at this rotation speed, so that the user sees how
far from it the scene is:

    f_d* ~ c_0(zeta, threshold) f_0,

f_0 the first in-plane frequency of the linearised beam at the maximal speed Omega_0 + a (the
premise of Eq. Southwell) and c_0 the first root of the canonical damped oscillator's Delta RMS
(App. E, `secondorder.c0_root`).  On the reference beam the full model's fitted c is 2-3 %
above c_0 (README, "Results"); the estimate is a guide, the verdict comes from the simulation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from .criterion import check_threshold
from .params import RotbeamInputError
from .plotting import DYN, QS, figure, save
from .scene import SceneResult
from .secondorder import c0_root
from .sweeps import resonance_frequency_hz


@dataclass(frozen=True)
class Verdict:
    """Whether the quasi-static model is adequate for one simulated scene."""

    threshold: float
    delta_rms: float
    #: True: Delta RMS < threshold; False: inertia matters; None: no steady state, no verdict
    quasistatic_ok: bool | None
    f0_hz: float  #: first in-plane frequency at Omega_0 + a (linearised model)
    c0: float  #: App. E ratio f_d* / f_0 at the beam's zeta (NaN where no root exists)
    fd_star_estimate_hz: float  #: c0 * f0 (NaN where no root exists)
    text: str  #: one line for a reader

    def as_dict(self) -> dict[str, float | bool | str | None]:
        return {
            "threshold": self.threshold,
            "quasistatic_ok": self.quasistatic_ok,
            "f0_hz": self.f0_hz,
            "c0": self.c0,
            "fd_star_estimate_hz": self.fd_star_estimate_hz,
            "verdict": self.text,
        }


def judge(result: SceneResult, threshold: float = 0.10) -> Verdict:
    """The verdict of the full model on one scene, and the linear estimate of the boundary."""
    th = check_threshold(threshold)
    beam, drive = result.scene.beam, result.scene.drive
    f0 = resonance_frequency_hz(beam, drive.omega0, drive.amplitude)
    zeta = beam.derived()["zeta"]
    try:
        c0 = c0_root(zeta, th)
        estimate = f"linear estimate f_d* = c_0 f_0 = {c0 * f0:.3g} Hz"
    except RotbeamInputError:  # too damped: the canonical oscillator never reaches the threshold
        c0 = math.nan
        estimate = f"no linear estimate of f_d*: at zeta = {zeta:.3g} Delta RMS never reaches it"
    where = f"f_d / f_0 = {drive.f_d / f0:.3g}; {estimate}"
    d = result.delta_rms
    if not result.converged or not math.isfinite(d):
        ok = None
        text = f"no verdict: the dynamic run reached no steady state ({where})"
    elif d < th:
        ok = True
        text = f"quasi-static is good enough: Delta RMS {d:.3g} < {th:g} ({where})"
    else:
        ok = False
        text = f"inertia matters: Delta RMS {d:.3g} >= {th:g}, use the dynamic model ({where})"
    return Verdict(th, d, ok, f0, c0, c0 * f0, text)


#: File types `plot_verdict` writes.
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def plot_verdict(result: SceneResult, verdict: Verdict, path: str | Path) -> None:
    """y_m over the steady window, dynamic against quasi-static, with the verdict and the cost."""
    path = Path(path)
    if path.suffix not in PLOT_SUFFIXES:
        raise RotbeamInputError(f"--plot must end in {', '.join(PLOT_SUFFIXES)}, got {str(path)!r}")
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
    ax.set_title(
        rf"$\Omega_0$ = {drive.omega0:g} rad/s, a = {drive.amplitude:g} rad/s, "
        rf"$f_d$ = {drive.f_d:g} Hz" + f"\n{where}\n" + verdict.text.split(" (")[0],
        loc="left",
    )
    cost = f"computed in {result.seconds:.3g} s (N = {num.N}, {num.method}"
    cost += ", Richardson-extrapolated RMS)" if result.extrapolation else ")"
    ax.legend(title=cost, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    save(fig, path)
