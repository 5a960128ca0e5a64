"""Input shapers: trains of impulses that, convolved with a command, leave a linear damped
oscillator still after it (Singer and Seering 1990; derivation: docs/design.md).

ZV: two impulses half a damped period apart; ZVD: three, also zero in the derivative of the
residual with respect to the frequency.  `shape` convolves a `Motion`'s acceleration with a
train, so that the shaped move is as long as the move plus the train.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..config.errors import RotbeamInputError
from .motion import Motion

#: the shapers by name and their impulses' count
KINDS = {"zv": 2, "zvd": 3}


@dataclass(frozen=True)
class Shaper:
    """A train of impulses: amplitudes (summing to 1) at instants from 0.

    Parameters
    ----------
    kind : str
        Its name ("zv", "zvd").
    times : tuple of float
        Instants [s], the first 0.
    amplitudes : tuple of float
        Weights, summing to 1.
    """

    kind: str
    times: tuple[float, ...]
    amplitudes: tuple[float, ...]

    @property
    def length(self) -> float:
        """How much longer a shaped move is than the move [s]."""
        return self.times[-1]


def decay_ratio(zeta: float) -> float:
    """K = exp(-zeta pi / sqrt(1 - zeta^2)): the amplitude ratio over half a damped period.

    Parameters
    ----------
    zeta : float
        Damping ratio, 0 <= zeta < 1.

    Returns
    -------
    float
    """
    if not 0.0 <= zeta < 1.0:
        raise RotbeamInputError(f"damping ratio zeta = {zeta!r}: allowed 0 <= zeta < 1")
    return math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta * zeta))


def shaper(kind: str, spacing: float, zeta: float) -> Shaper:
    """The `kind` shaper whose impulses are `spacing` apart, with zeta's amplitudes.

    At spacing = half the damped period of the mode, Td / 2 = pi / (omega sqrt(1 - zeta^2)),
    this is the textbook shaper of that mode (`for_mode`).

    Parameters
    ----------
    kind : str
        "zv" or "zvd".
    spacing : float
        Seconds between consecutive impulses, > 0.
    zeta : float
        Damping ratio of the mode.

    Returns
    -------
    Shaper

    Raises
    ------
    RotbeamInputError
        For an unknown kind, a spacing that is not > 0 or a zeta outside [0, 1).
    """
    return train(kind, spacing, decay_ratio(zeta))


def train(kind: str, spacing: float, ratio: float) -> Shaper:
    """A train of the `kind` pattern: ZV's amplitudes 1, K and ZVD's 1, 2K, K^2, normalised.

    K = `decay_ratio` (zeta) gives the textbook shaper; any K > 0 keeps the pattern (K > 1: a
    first impulse weaker than the second, for a mode whose frequency or decay changes between
    the impulses).

    Parameters
    ----------
    kind : str
        "zv" or "zvd".
    spacing : float
        Seconds between consecutive impulses, > 0.
    ratio : float
        K, > 0.

    Returns
    -------
    Shaper

    Raises
    ------
    RotbeamInputError
        For an unknown kind, a spacing or a ratio that is not > 0.
    """
    if kind not in KINDS:
        raise RotbeamInputError(f"shaper {kind!r}: allowed {', '.join(KINDS)}")
    if not math.isfinite(spacing) or spacing <= 0:
        raise RotbeamInputError(f"shaper spacing = {spacing!r}: allowed > 0 s")
    K = ratio
    if not math.isfinite(K) or K <= 0:
        raise RotbeamInputError(f"shaper amplitude ratio = {K!r}: allowed > 0")
    if kind == "zv":
        amps = (1.0 / (1.0 + K), K / (1.0 + K))
    else:
        amps = (1.0 / (1.0 + K) ** 2, 2.0 * K / (1.0 + K) ** 2, K * K / (1.0 + K) ** 2)
    return Shaper(kind, tuple(i * spacing for i in range(len(amps))), amps)


def for_mode(kind: str, f_hz: float, zeta: float) -> Shaper:
    """The textbook shaper of a mode of frequency f_hz and damping ratio zeta.

    Parameters
    ----------
    kind : str
        "zv" or "zvd".
    f_hz : float
        The mode's undamped frequency [Hz], > 0.
    zeta : float
        Its damping ratio.

    Returns
    -------
    Shaper
        Impulses half a damped period apart.
    """
    if not math.isfinite(f_hz) or f_hz <= 0:
        raise RotbeamInputError(f"mode frequency = {f_hz!r} Hz: allowed > 0")
    decay_ratio(zeta)  # checks zeta
    return shaper(kind, 0.5 / (f_hz * math.sqrt(1.0 - zeta * zeta)), zeta)


def shape(motion: Motion, train: Shaper) -> Motion:
    """The motion's acceleration convolved with the train: sum_i A_i a(t - t_i).

    The shaped move keeps the start and (the amplitudes summing to 1) the end speed and the
    angle of a rest-to-rest move, and lasts train.length longer.

    Parameters
    ----------
    motion : Motion
    train : Shaper

    Returns
    -------
    Motion
    """
    out = Motion(motion.omega_start, (), (), (), (), 0.0)
    for t, a in zip(train.times, train.amplitudes, strict=True):
        out = out.plus(motion.shifted(t, a))
    return out


def residual_factor(train: Shaper, f_hz: float, zeta: float) -> float:
    """|sum_i A_i exp((zeta omega + i omega_d) t_i)| / exp(zeta omega t_n): the linear
    oscillator's residual vibration after the shaped command as a share of the unshaped one's.

    Parameters
    ----------
    train : Shaper
    f_hz : float
        The oscillator's undamped frequency [Hz].
    zeta : float
        Its damping ratio.

    Returns
    -------
    float
        0 for the train of that very mode; 1 for a single impulse.
    """
    w = 2.0 * math.pi * f_hz
    wd = w * math.sqrt(1.0 - zeta * zeta)
    z = sum(A * complex(math.exp(zeta * w * t) * math.cos(wd * t),
                        math.exp(zeta * w * t) * math.sin(wd * t))
            for t, A in zip(train.times, train.amplitudes, strict=True))  # fmt: skip
    return abs(z) / math.exp(zeta * w * train.times[-1])
