"""Rigid-body motions of the disk: exact piecewise-polynomial Omega(t) from jerk and
acceleration steps, the time-optimal moves under speed, acceleration and jerk limits, and
their samples for a move file.

A `Motion` is Omega(t) = omega_start + sum of ramps (jerk steps) and steps (acceleration steps),
so that its acceleration, speed and angle are exact at every instant and shaping it with a
train of impulses (`rotbeam.analysis.shapers`) is a sum of shifted copies.  The rigid-body
time-optimal moves and why they are so: docs/design.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..config.errors import RotbeamInputError

#: relative slack of the limit checks (rounding of the closed forms)
LIMIT_SLACK = 1e-9


@dataclass(frozen=True)
class Limits:
    """What a move may do: its largest |Omega|, |dOmega/dt| and |d^2 Omega/dt^2|.

    Parameters
    ----------
    max_speed : float
        rad/s, > 0.
    max_accel : float
        rad/s^2, > 0.
    max_jerk : float or None
        rad/s^3, > 0; None: no jerk limit (the acceleration may step).

    Raises
    ------
    RotbeamInputError
        For a limit that is not a finite number > 0.
    """

    max_speed: float
    max_accel: float
    max_jerk: float | None = None

    def __post_init__(self) -> None:
        for name, flag in (("max_speed", "rad/s"), ("max_accel", "rad/s^2"),
                           ("max_jerk", "rad/s^3")):  # fmt: skip
            value = getattr(self, name)
            if value is None and name == "max_jerk":
                continue
            if not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
                raise RotbeamInputError(f"{name} = {value!r}: allowed a finite number > 0 ({flag})")

    def scaled(self, kappa: float) -> Limits:
        """The acceleration and jerk limits times kappa (the speed limit kept).

        Parameters
        ----------
        kappa : float
            > 0.

        Returns
        -------
        Limits
        """
        jerk = None if self.max_jerk is None else self.max_jerk * kappa
        return Limits(self.max_speed, self.max_accel * kappa, jerk)


@dataclass(frozen=True)
class Motion:
    """Omega(t) = omega_start + sum_k j_k (t - s_k)_+^2 / 2 + sum_k a_k (t - r_k)_+, t <= duration.

    Jerk steps j_k at s_k and acceleration steps a_k at r_k; the acceleration is piecewise
    linear, the speed piecewise quadratic and the angle piecewise cubic, all exact.

    Parameters
    ----------
    omega_start : float
        Omega at t = 0 [rad/s].
    jerk_at, jerk : tuple of float
        Instants [s] and sizes [rad/s^3] of the jerk steps.
    accel_at, accel : tuple of float
        Instants [s] and sizes [rad/s^2] of the acceleration steps.
    duration : float
        The move's length [s]; the acceleration is zero after it.
    """

    omega_start: float
    jerk_at: tuple[float, ...]
    jerk: tuple[float, ...]
    accel_at: tuple[float, ...]
    accel: tuple[float, ...]
    duration: float

    def _terms(self, t: np.ndarray, power: int) -> np.ndarray:
        """sum_k j_k (t - s_k)_+^(power+1) / (power+1)! + sum_k a_k (t - r_k)_+^power / power!."""
        t = np.asarray(t, dtype=float)[..., None]
        out = np.zeros(t.shape[:-1])
        if self.jerk:
            x = np.maximum(t - np.asarray(self.jerk_at), 0.0)
            out = out + (x ** (power + 1) / math.factorial(power + 1)) @ np.asarray(self.jerk)
        if self.accel:
            x = t - np.asarray(self.accel_at)
            xp = np.where(x >= 0.0, np.maximum(x, 0.0) ** power, 0.0)
            out = out + (xp / math.factorial(power)) @ np.asarray(self.accel)
        return out

    def acceleration(self, t: np.ndarray) -> np.ndarray:
        """dOmega/dt [rad/s^2] at instants t [s] (right-continuous at a step).

        Parameters
        ----------
        t : array_like

        Returns
        -------
        numpy.ndarray
        """
        return self._terms(t, 0)

    def speed(self, t: np.ndarray) -> np.ndarray:
        """Omega [rad/s] at instants t [s].

        Parameters
        ----------
        t : array_like

        Returns
        -------
        numpy.ndarray
        """
        return self.omega_start + self._terms(t, 1)

    def angle(self, t: np.ndarray) -> np.ndarray:
        """The angle turned since t = 0 [rad] at instants t [s].

        Parameters
        ----------
        t : array_like

        Returns
        -------
        numpy.ndarray
        """
        return self.omega_start * np.asarray(t, dtype=float) + self._terms(t, 2)

    def jerk_values(self, t: np.ndarray) -> np.ndarray:
        """d^2 Omega/dt^2 [rad/s^3] at instants t [s], between the acceleration's steps.

        Parameters
        ----------
        t : array_like

        Returns
        -------
        numpy.ndarray
        """
        t = np.asarray(t, dtype=float)[..., None]
        if not self.jerk:
            return np.zeros(t.shape[:-1])
        return (t >= np.asarray(self.jerk_at)).astype(float) @ np.asarray(self.jerk)

    def knots(self) -> np.ndarray:
        """Every instant where the acceleration or the jerk changes, 0 and the end, sorted."""
        return np.unique(np.concatenate([[0.0, self.duration], self.jerk_at, self.accel_at]))

    def shifted(self, delay: float, weight: float) -> Motion:
        """weight times this motion's acceleration, delay later (its start speed not kept).

        Parameters
        ----------
        delay : float
            Seconds.
        weight : float
            The factor.

        Returns
        -------
        Motion
            Starting at 0 rad/s; add it to another with `plus`.
        """
        return Motion(0.0, tuple(s + delay for s in self.jerk_at),
                      tuple(weight * j for j in self.jerk),
                      tuple(r + delay for r in self.accel_at),
                      tuple(weight * a for a in self.accel), self.duration + delay)  # fmt: skip

    def plus(self, other: Motion) -> Motion:
        """The sum of two motions' accelerations, from this one's start speed.

        Parameters
        ----------
        other : Motion

        Returns
        -------
        Motion
        """
        return Motion(self.omega_start, self.jerk_at + other.jerk_at, self.jerk + other.jerk,
                      self.accel_at + other.accel_at, self.accel + other.accel,
                      max(self.duration, other.duration))  # fmt: skip

    def samples(self, per_second: float, least: int = 64) -> tuple[np.ndarray, np.ndarray]:
        """Omega on an even grid of the move and at every knot: a move file's rows.

        Parameters
        ----------
        per_second : float
            Samples per second of the even grid.
        least : int
            At least this many even samples.

        Returns
        -------
        t, omega : numpy.ndarray
            Instants [s] from 0 to the duration, increasing, and Omega there [rad/s].
        """
        n = max(least, math.ceil(self.duration * per_second)) + 1
        grid = np.linspace(0.0, self.duration, n)
        t = np.unique(np.concatenate([grid, self.knots()]))
        # knots closer than a hundredth of a step to a grid point would make a tiny interval
        keep = np.concatenate([[True], np.diff(t) > 1e-2 * self.duration / n])
        t = t[keep]
        t[-1] = self.duration
        return t, self.speed(t)

    def peaks(self, samples: int = 4001) -> tuple[float, float, float]:
        """The largest |Omega|, |dOmega/dt| and |d^2 Omega/dt^2| over the move.

        At every knot (each side of a step) and on an even grid: the acceleration is
        piecewise linear, so its extremes lie at knots; the speed's at knots or between, where
        the grid finds them.

        Parameters
        ----------
        samples : int
            Even-grid samples.

        Returns
        -------
        tuple of float
            rad/s, rad/s^2, rad/s^3.
        """
        k = self.knots()
        eps = 1e-12 * max(self.duration, 1.0)
        t = np.concatenate([np.linspace(0.0, self.duration, samples), k, np.maximum(k - eps, 0)])
        t = t[t <= self.duration]
        mid = 0.5 * (k[1:] + k[:-1])
        return (float(np.max(np.abs(self.speed(t)))),
                float(np.max(np.abs(self.acceleration(t)))),
                float(np.max(np.abs(self.jerk_values(mid)))) if mid.size else 0.0)  # fmt: skip

    def within(self, limits: Limits) -> bool:
        """Whether every limit holds over the move (to LIMIT_SLACK).

        Parameters
        ----------
        limits : Limits

        Returns
        -------
        bool
        """
        speed, accel, jerk = self.peaks()
        ok = speed <= limits.max_speed * (1 + LIMIT_SLACK)
        ok = ok and accel <= limits.max_accel * (1 + LIMIT_SLACK)
        if limits.max_jerk is not None:
            ok = ok and not self.accel and jerk <= limits.max_jerk * (1 + LIMIT_SLACK)
        return bool(ok)


def pulse(delta: float, limits: Limits, start: float = 0.0) -> Motion:
    """The fastest change of speed by `delta` from rest acceleration to rest acceleration.

    A rectangle of the largest acceleration, or with a jerk limit its trapezoid (a triangle when
    the change is too small to reach the largest acceleration).

    Parameters
    ----------
    delta : float
        The change of speed [rad/s], either sign.
    limits : Limits
        The acceleration and jerk limits (the speed limit is not read).
    start : float
        When it starts [s].

    Returns
    -------
    Motion
        From 0 rad/s (add the start speed with `Motion.plus` onto a motion that has it); its
        duration is start plus the pulse's.
    """
    sign, dv = math.copysign(1.0, delta), abs(delta)
    a, j = limits.max_accel, limits.max_jerk
    if dv == 0.0:
        return Motion(0.0, (), (), (), (), start)
    if j is None:
        w = dv / a
        return Motion(0.0, (), (), (start, start + w), (sign * a, -sign * a), start + w)
    peak = min(a, math.sqrt(dv * j))
    r = peak / j
    w = dv / peak - r
    at = (start, start + r, start + r + w, start + 2 * r + w)
    return Motion(0.0, at, (sign * j, -sign * j, -sign * j, sign * j), (), (), at[-1])


def pulse_duration(delta: float, limits: Limits) -> float:
    """How long `pulse` takes to change the speed by `delta` [s].

    Parameters
    ----------
    delta : float
        rad/s.
    limits : Limits

    Returns
    -------
    float
    """
    return pulse(delta, limits).duration


def rigid_slew(angle: float, limits: Limits) -> Motion:
    """The rigid-body time-optimal rest-to-rest move through `angle`: bang-coast-bang.

    Speed up at the largest acceleration (with a jerk limit, its trapezoid: the S-curve), coast
    at the largest speed if the angle leaves room, slow down symmetrically.  Without a duration
    limit every angle is reachable: a larger one coasts longer.

    Parameters
    ----------
    angle : float
        rad, > 0.
    limits : Limits

    Returns
    -------
    Motion
        From rest to rest.
    """
    from scipy.optimize import brentq

    def covered(v: float) -> float:  # angle of speeding up to v and back down, no coast
        return v * pulse_duration(v, limits)

    v = limits.max_speed
    if covered(v) > angle:
        v = brentq(lambda x: covered(x) - angle, 0.0, v, xtol=1e-14 * v, rtol=1e-14)
    up = pulse(v, limits)
    coast = (angle - covered(v)) / v
    down = pulse(-v, limits, up.duration + max(coast, 0.0))
    return up.plus(down)


def rigid_speed_change(omega_start: float, omega_end: float, limits: Limits) -> Motion:
    """The rigid-body time-optimal change from one steady speed to another: one pulse.

    Parameters
    ----------
    omega_start, omega_end : float
        rad/s.
    limits : Limits

    Returns
    -------
    Motion
    """
    p = pulse(omega_end - omega_start, limits)
    return Motion(omega_start, p.jerk_at, p.jerk, p.accel_at, p.accel, p.duration)
