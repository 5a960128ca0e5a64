"""The motion design's families (`rotbeam.analysis.move_families`) against independent
answers: a linear oscillator time-stepped by scipy's solve_ivp (the closed forms that start the
search leave it still), the square of a ZV train (ZVD), the rigid pulse's closed-form length,
and every limit, the end speed and the angle checked on each family's samples by finite
differences and a trapezoid rule.  No beam is run: each test takes well under a second."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotbeam.analysis.motion import Limits, Motion, pulse, rigid_slew, rigid_speed_change
from rotbeam.analysis.move_families import (
    Family,
    convolve,
    family_motion,
    impulses,
    pulses_start,
    two_pulses,
)
from rotbeam.analysis.shapers import residual_factor, train

LIMITS = Limits(20.0, 100.0, None)


def _ringing(motion: Motion, f_hz: float) -> float:
    """The amplitude a linear undamped oscillator q'' + w^2 q = -u(t), u the move's
    acceleration, is left with after the move, from rest, by solve_ivp."""
    w = 2 * math.pi * f_hz
    knots = motion.knots()
    y = np.zeros(2)
    for a, b in zip(knots[:-1], knots[1:], strict=True):  # the acceleration is smooth between
        if b - a <= 0:
            continue
        sol = solve_ivp(lambda t, q: [q[1], -(w**2) * q[0] - float(motion.acceleration(t))],
                        (a, b), y, rtol=1e-11, atol=1e-14)  # fmt: skip
        y = sol.y[:, -1]
    return float(math.hypot(y[0], y[1] / w))


def test_the_oscillator_is_still_after_a_pulse_of_whole_periods_only():
    """The limit case the pulses family rests on: a constant acceleration for k periods leaves
    the oscillator still; for k + 1/2 periods it rings at 2 a / w^2."""
    f = 8.0
    still = pulse(100.0 * 2 / f, Limits(100.0, 100.0, None))  # two periods at 100 rad/s^2
    ring = pulse(100.0 * 2.5 / f, Limits(100.0, 100.0, None))
    w = 2 * math.pi * f
    assert _ringing(still, f) < 1e-8 * 2 * 100 / w**2
    assert _ringing(ring, f) == pytest.approx(2 * 100 / w**2, rel=1e-6)


@pytest.mark.parametrize("change, f_hz, ramp", [(0.2, 7.9, 0.0), (0.2, 7.9, 0.005),
                                                (0.2, 6.0, 0.004), (0.1, 6.5, 0.003)])  # fmt: skip
def test_the_two_pulses_start_leaves_a_linear_oscillator_still(change, f_hz, ramp):
    """pulses_start's coast and share: the rigid pulse rings, the two pulses do not (T > the
    period: one period's difference; T <= the period: ZV's halves)."""
    gap, share = pulses_start(change, 1 / f_hz, ramp)
    lim = Limits(20.0, 100.0, 100.0 / ramp if ramp else None)
    dv = 100.0 * change
    moved = two_pulses(0.0, dv, gap, share, lim)
    rigid = rigid_speed_change(0.0, dv, lim)
    assert _ringing(rigid, f_hz) > 0.05 * 2 * 100 / (2 * math.pi * f_hz) ** 2
    assert _ringing(moved, f_hz) < 1e-6 * _ringing(rigid, f_hz)
    assert float(moved.speed(moved.duration)) == pytest.approx(dv, abs=1e-12)
    # as long as the rigid pulse, its ramps and the coast
    assert moved.duration == pytest.approx(change + 2 * ramp + gap, abs=1e-12)


def test_two_zv_trains_at_one_spacing_are_zvd_and_at_two_cancel_both_frequencies():
    K = 0.95
    zvd = train("zvd", 0.07, K)
    both = convolve(train("zv", 0.07, K), train("zv", 0.07, K))
    assert both.times == pytest.approx(zvd.times, abs=1e-15)
    assert both.amplitudes == pytest.approx(zvd.amplitudes, abs=1e-15)
    two = convolve(train("zv", 0.5 / 7.0, 1.0), train("zv", 0.5 / 7.5, 1.0))
    assert sum(two.amplitudes) == pytest.approx(1.0, abs=1e-15) and len(two.times) == 4
    for f in (7.0, 7.5):
        assert residual_factor(two, f, 0.0) < 1e-12
    assert residual_factor(two, 7.25, 0.0) < residual_factor(train("zv", 0.5 / 7.0, 1.0), 7.25, 0)


FAMILIES = [Family("zv", 0.005), Family("zvd", 0.02), Family("zv2", 0.005, spread=0.02),
            Family("zv", 0.005, 0.012, 0.98), Family("pulses", 0.005),
            Family("pulses", 0.005, 0.012, 0.98)]  # fmt: skip
PARAMS = {"zv": (0.07, -0.05), "zvd": (0.065, -0.08), "zv2": (0.072, -0.05, 0.066, -0.03),
          "pulses": (0.024, 0.83)}  # fmt: skip


@pytest.mark.parametrize("family", FAMILIES, ids=lambda f: f"{f.name}-{f.ramp}")
def test_every_family_keeps_every_limit_at_every_sample_and_ends_where_asked(family):
    """From the samples (as a move file holds them): speed, acceleration by finite differences,
    the angle (slew) by the trapezoid rule, the end speed (change of speed)."""
    params = PARAMS[family.kind] + ((0.012, -0.02) if family.second_s else ())
    slew = family.kind != "pulses"
    limits = Limits(10.0, 100.0, None) if slew else LIMITS

    def rigid(lim: Limits) -> Motion:
        return rigid_slew(1.0, lim) if slew else rigid_speed_change(0.0, 20.0, lim)

    motion, kappa = family_motion(family, params, rigid, limits, None if slew else (0.0, 20.0))
    tr = impulses(family, params)
    assert 1.0 <= kappa <= (1.0 / max(tr.amplitudes) if tr else 1.0) + 1e-12
    t = np.linspace(0.0, motion.duration, 200001)
    omega = motion.speed(t)
    accel = np.diff(omega) / np.diff(t)
    assert np.max(np.abs(omega)) <= limits.max_speed * (1 + 1e-9)
    assert np.max(np.abs(accel)) <= limits.max_accel * (1 + 1e-6)
    # the ramps: the jerk within the family's own (limit / ramp), times kappa
    jerk = np.diff(accel) / np.diff(t[1:])
    assert np.max(np.abs(jerk)) <= kappa * limits.max_accel / family.ramp * (1 + 1e-3)
    if slew:
        angle = float(np.sum(0.5 * (omega[1:] + omega[:-1]) * np.diff(t)))
        assert angle == pytest.approx(1.0, abs=1e-8)
        assert omega[-1] == pytest.approx(0.0, abs=1e-9)
    else:
        assert omega[-1] == pytest.approx(20.0, abs=1e-9)
    # at kappa a little larger a limit breaks (the bisection's answer is the largest)
    if tr is not None and kappa < 1.0 / max(tr.amplitudes) - 1e-6:
        a = limits.max_accel
        own = Limits(limits.max_speed, a, a / family.ramp).scaled(kappa * (1 + 1e-4))
        base = rigid(own) if slew else two_pulses(0.0, 20.0, params[0], params[1], own)
        from rotbeam.analysis.shapers import shape

        assert not shape(base, tr).within(limits)
