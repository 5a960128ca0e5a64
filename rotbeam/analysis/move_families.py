"""The families of candidate moves the motion design searches, and each one's unknowns.

``zv``, ``zvd``: the rigid-body time-optimal move at kappa times the acceleration limit,
convolved with a ZV (1, K) or ZVD (1, 2K, K^2) train; unknowns s, log K.  ``zv2`` (a box of
beams): two ZV trains convolved; unknowns s_1, log K_1, s_2, log K_2.  ``pulses`` (a change of
speed): two pulses at the acceleration limit and a coast; unknowns the coast and the first
pulse's share.  Any family may also be convolved with a ZV train at the second mode (``+m2``):
two more unknowns, last.  Why each family and where it wins: docs/design.md.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from .motion import Limits, Motion, pulse
from .shapers import Shaper, shape, train

#: halvings of the interval of the acceleration's factor kappa, from 1 to 1 / the train's
#: largest amplitude: kappa to 2^-24 of it, so that the move (and its residual) is continuous
#: in the unknowns to that resolution
KAPPA_BISECT = 24
#: the first pulse's share of the speed change, within (SHARE_MIN, 1 - SHARE_MIN)
SHARE_MIN = 0.02


@dataclass(frozen=True)
class Family:
    """A family of candidate moves.

    Parameters
    ----------
    kind : str
        "zv", "zvd", "zv2" or "pulses" (module docstring).
    ramp : float
        How long the acceleration takes to ramp to the limit [s] (its jerk: limit / ramp).
    second_s : float
        Where the spacing of a ZV-pattern train at the second mode, convolved with the move,
        starts [s] (half the second mode's period); 0: no such train.
    second_ratio : float
        Where that train's amplitude ratio starts.
    spread : float
        zv2: the two trains' spacings start at s (1 + spread) and s (1 - spread) where no
        search has run yet (the families' order).
    at : int
        The beam whose first-mode amplitude a zv, zvd or pulses family cancels: 0 the nominal
        one, k the k-th corner of a box (zv2 cancels it at the box's two extreme corners).
    """

    kind: str
    ramp: float
    second_s: float = 0.0
    second_ratio: float = 1.0
    spread: float = 0.0
    at: int = 0

    @property
    def name(self) -> str:
        """The kind, with "+m2" where a second-mode train is convolved."""
        return self.kind + ("+m2" if self.second_s > 0 else "")

    @property
    def without_second(self) -> Family:
        """The same family without its second-mode train."""
        return replace(self, second_s=0.0, second_ratio=1.0)


def convolve(*trains: Shaper) -> Shaper:
    """The train whose convolution with a command is the trains' convolutions in turn.

    Parameters
    ----------
    *trains : Shaper

    Returns
    -------
    Shaper
        Impulses at every sum of instants with the product of amplitudes, merged where they
        coincide, sorted.
    """
    times, amps = np.zeros(1), np.ones(1)
    for tr in trains:
        times = (times[:, None] + np.asarray(tr.times)[None, :]).ravel()
        amps = (amps[:, None] * np.asarray(tr.amplitudes)[None, :]).ravel()
    order = np.argsort(times, kind="stable")
    t_out: list[float] = []
    a_out: list[float] = []
    for t, a in zip(times[order], amps[order], strict=True):
        if t_out and abs(t - t_out[-1]) <= 1e-12 * max(1.0, abs(t)):
            a_out[-1] += float(a)
        else:
            t_out.append(float(t))
            a_out.append(float(a))
    return Shaper("+".join(tr.kind for tr in trains), tuple(t_out), tuple(a_out))


def impulses(family: Family, params: tuple[float, ...]) -> Shaper | None:
    """The train a family's move is convolved with at these unknowns (None for ``pulses``
    without a second-mode train).

    Parameters
    ----------
    family : Family
    params : tuple of float
        The family's unknowns (module docstring).

    Returns
    -------
    Shaper or None
    """
    if family.kind == "pulses":
        trains = []
    elif family.kind == "zv2":
        trains = [train("zv", params[0], math.exp(params[1])),
                  train("zv", params[2], math.exp(params[3]))]  # fmt: skip
    else:
        trains = [train(family.kind, params[0], math.exp(params[1]))]
    if family.second_s > 0:
        trains.append(train("zv", params[-2], math.exp(params[-1])))
    return convolve(*trains) if trains else None


def two_pulses(omega_start: float, omega_end: float, gap: float, share: float,
               limits: Limits) -> Motion:  # fmt: skip
    """A change of speed as two pulses at the acceleration limit, `gap` apart.

    Parameters
    ----------
    omega_start, omega_end : float
        rad/s.
    gap : float
        The coast between the pulses [s], >= 0.
    share : float
        The first pulse's share of the change, in (0, 1).
    limits : Limits
        Their acceleration and jerk (the pulses' ramps).

    Returns
    -------
    Motion
    """
    dv = omega_end - omega_start
    first = pulse(share * dv, limits)
    second = pulse((1.0 - share) * dv, limits, first.duration + max(gap, 0.0))
    return Motion(omega_start, (), (), (), (), 0.0).plus(first).plus(second)


def pulses_start(change: float, period: float, ramp: float) -> tuple[float, float]:
    """The coast and first share of two pulses that leave a linear undamped oscillator still.

    Two rectangles of the acceleration limit, lasting t_1 + t_2 = T = change in all, leave an
    oscillator of this period still when t_1 - t_2 = period and their centres lie a period
    apart (T > period), or when t_1 = t_2 and their centres lie half a period apart (T <=
    period: ZV on the rigid pulse); ramps of `ramp` convolve both with one box and shift the
    second by a ramp more (docs/design.md).

    Parameters
    ----------
    change : float
        The rigid pulse's length |omega_end - omega_start| / max_accel [s], > 0.
    period : float
        The oscillator's period [s], > 0.
    ramp : float
        The pulses' ramps [s], >= 0.

    Returns
    -------
    gap : float
        The coast between the pulses [s] (at least 0).
    share : float
        The first pulse's share of the change.
    """
    T = change
    if T > period:
        share, gap = 0.5 * (T + period) / T, period - 0.5 * T
    else:
        share, gap = 0.5, 0.5 * period - 0.5 * T
    return max(gap - ramp, 0.0), share


def family_motion(
    family: Family,
    params: tuple[float, ...],
    rigid: Callable[[Limits], Motion],
    limits: Limits,
    speeds: tuple[float, float] | None,
) -> tuple[Motion, float]:
    """The move of one family at its unknowns, within the limits.

    The rigid move (or the two pulses) at kappa times the acceleration and jerk, convolved with
    the family's train: the largest kappa between 1 and 1 / the train's largest amplitude whose
    move keeps every limit, by bisection (the limits hold at kappa = 1: a convex combination of
    shifted copies of a move within them).

    Parameters
    ----------
    family : Family
    params : tuple of float
        Its unknowns.
    rigid : callable
        rigid(limits) -> the rigid-body time-optimal move of the request under those limits.
    limits : Limits
        The request's limits.
    speeds : tuple of float or None
        (omega_start, omega_end) of a change of speed (needed by ``pulses``).

    Returns
    -------
    motion : Motion
    kappa : float
    """
    a = limits.max_accel
    own = Limits(limits.max_speed, a, a / family.ramp)
    tr = impulses(family, params)
    if family.kind == "pulses":
        if speeds is None:
            raise ValueError("the pulses family is a change of speed's")

        def base(lim: Limits) -> Motion:
            return two_pulses(speeds[0], speeds[1], params[0], params[1], lim)
    else:
        base = rigid
    if tr is None:
        return base(own), 1.0
    lo, hi = 1.0, 1.0 / max(tr.amplitudes)
    best = shape(base(own), tr)
    top = shape(base(own.scaled(hi)), tr)
    if top.within(limits):
        return top, hi
    for _ in range(KAPPA_BISECT):  # the largest kappa within the limits, to KAPPA_BISECT halvings
        mid = 0.5 * (lo + hi)
        m = shape(base(own.scaled(mid)), tr)
        if m.within(limits):
            lo, best = mid, m
        else:
            hi = mid
    return best, lo
