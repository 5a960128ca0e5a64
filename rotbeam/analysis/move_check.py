"""One candidate move run through the beam: its residual vibration and peak of one observable.

The move is a `rotbeam.analysis.motion.Motion`, sampled densely into the scene's drive as a
`move` (the very samples a move file holds, so that `rotbeam simulate --move` on that file
repeats the run) and time-stepped from rest by `rotbeam.runs.move.simulate_move`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..config.errors import RotbeamInputError
from ..model.params import Drive, Samples
from ..runs.move import simulate_move
from ..runs.scene import Scene
from .motion import Motion

#: samples of a move file per second, and per first-mode period at the move's highest speed:
#: the drive's cubic spline through them reproduces the residual of the exact motion to 1e-3
#: of itself (docs/design.md, "Checks")
SAMPLES_PER_SECOND = 2000
SAMPLES_PER_PERIOD = 200


@dataclass(frozen=True)
class MoveCheck:
    """What one run of a move says.

    Attributes
    ----------
    duration_s : float
        The move's length [s].
    residual : float
        Largest |observable| after the move, in its unit (NaN if the run did not get there).
    peak : float
        Largest |observable| during the move.
    converged : bool
        The run went through the move and its settling window.
    message : str
        The run's message.
    seconds : float
        Its wall time.
    t_s : numpy.ndarray
        Sample instants from the start of the move [s].
    values : numpy.ndarray
        The observable there.
    omega : numpy.ndarray
        Omega there [rad/s].
    """

    duration_s: float
    residual: float
    peak: float
    converged: bool
    message: str
    seconds: float
    t_s: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    values: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    omega: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)

    def as_dict(self) -> dict[str, float]:
        """``duration_s``, ``residual``, ``peak``.

        Returns
        -------
        dict
        """
        return {"duration_s": self.duration_s, "residual": self.residual, "peak": self.peak}


def move_samples(motion: Motion, f_hz: float) -> tuple[np.ndarray, np.ndarray]:
    """The rows of the move's file: t [s] and Omega [rad/s], dense and at every knot.

    Parameters
    ----------
    motion : Motion
    f_hz : float
        The highest first-mode frequency the move meets [Hz].

    Returns
    -------
    t, omega : numpy.ndarray
    """
    return motion.samples(max(SAMPLES_PER_SECOND, SAMPLES_PER_PERIOD * f_hz))


def move_scene(scene: Scene, t: np.ndarray, omega: np.ndarray, settle: float | None) -> Scene:
    """The scene with its drive replaced by the sampled move.

    Parameters
    ----------
    scene : Scene
        Beam, effects and numerics (its drive is not read).
    t, omega : numpy.ndarray
        The move's samples.
    settle : float or None
        Seconds integrated after the move (None: `simulate_move`'s own rule, as
        `rotbeam simulate --move` runs it).

    Returns
    -------
    Scene
    """
    samples = Samples(tuple(t), tuple(omega), "move", "designed move")
    return replace(scene, drive=Drive(move=samples, settle=settle))


def check_move(
    scene: Scene,
    motion: Motion,
    f_hz: float,
    observable: str = "y_m",
    settle: float | None = None,
    max_seconds: float | None = None,
) -> MoveCheck:
    """Run a move through the scene's beam from rest and read its residual and peak.

    Parameters
    ----------
    scene : Scene
        Beam, effects and numerics; the drive is the move's.
    motion : Motion
        The move.
    f_hz : float
        The highest first-mode frequency the move meets [Hz] (its samples' density).
    observable : str
        A name of `rotbeam.runs.observables.OBSERVABLES`.
    settle : float or None
        Seconds integrated after the move; None: `simulate_move`'s rule.
    max_seconds : float or None
        Wall-time bound of the run (default numerics.max_seconds).

    Returns
    -------
    MoveCheck
    """
    t, omega = move_samples(motion, f_hz)
    sc = move_scene(scene, t, omega, settle)
    if max_seconds is not None:
        sc = replace(sc, numerics=replace(sc.numerics, max_seconds=max(max_seconds, 1e-3)))
    res = simulate_move(sc)
    if observable == "y_m":
        residual, peak, values = res.residual_ym, res.peak_ym, res.y_dynamic
    else:
        obs = res.observables([observable])[observable]
        residual, peak = obs["residual"], obs["peak_dynamic"]
        values = res.series(observable)
    if not res.converged:
        residual = math.nan
    return MoveCheck(motion.duration, float(residual), float(peak), res.converged, res.message,
                     res.seconds, res.t_s, values, res.omega)  # fmt: skip


def integrated_angle(t: np.ndarray, omega: np.ndarray) -> float:
    """The angle turned along a move file's samples as the drive reads them [rad].

    The integral of the drive's not-a-knot cubic spline through the samples
    (`rotbeam.model.drive.MoveLaw`), independent of the closed form the samples came from.

    Parameters
    ----------
    t, omega : numpy.ndarray
        Samples.

    Returns
    -------
    float
    """
    from scipy.interpolate import CubicSpline

    return float(CubicSpline(t, omega).integrate(t[0], t[-1]))


def write_move_csv(path: str | Path, t: np.ndarray, omega: np.ndarray) -> None:
    """Write a move file (columns t [s], omega [rad/s]) that `rotbeam simulate --move` reads.

    Every value to 17 significant digits, so that the file repeats the run exactly.

    Parameters
    ----------
    path : str or Path
    t, omega : numpy.ndarray
    """
    path = Path(path)
    if path.parent and not path.parent.exists():
        raise RotbeamInputError(f"--out {str(path)!r}: folder {str(path.parent)!r} does not exist")
    rows = "\n".join(f"{a:.17g},{b:.17g}" for a, b in zip(t, omega, strict=True))
    path.write_text("t,omega\n" + rows + "\n")


def ringing(check: MoveCheck, f_hz: tuple[float, float], decay: float) -> tuple[complex, complex]:
    """The first two modes' complex amplitudes in the observable after the move.

    A least-squares fit of the samples after the move by
    Re(C_1 exp(i w_1 t) + C_2 exp(i w_2 t)) exp(-decay t) + c, the first two modes of the beam
    turning at the final speed (viscous damping per unit length decays both at one rate), t
    from the move's end.  C_1 (and, for a family with a second-mode train, C_2) is what the
    search drives to zero: its modulus is the mode's residual, its phase says which way the
    unknowns move it.

    Parameters
    ----------
    check : MoveCheck
        A run with its samples.
    f_hz : tuple of float
        The first two frequencies at the final speed [Hz].
    decay : float
        Their decay rate zeta_1 w_1 [1/s].

    Returns
    -------
    tuple of complex
        C_1, C_2 (NaN where fewer than eight samples follow the move).
    """
    after = check.t_s > check.duration_s
    t = check.t_s[after] - check.duration_s
    if t.size < 8:
        return complex(math.nan, math.nan), complex(math.nan, math.nan)
    env = np.exp(-decay * t)
    cols = []
    for f in f_hz:
        w = 2.0 * math.pi * f
        cols += [env * np.cos(w * t), -env * np.sin(w * t)]
    basis = np.column_stack([*cols, np.ones_like(t)])
    coef = np.linalg.lstsq(basis, check.values[after], rcond=None)[0]
    return complex(coef[0], coef[1]), complex(coef[2], coef[3])
