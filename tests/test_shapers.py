"""Input shapers and rigid-body moves against closed forms: ZV and ZVD leave the linear damped
oscillator still at their mode (ZVD also to first order in the frequency), a shaped move keeps
its angle and lasts the train longer, and the rigid-body time-optimal moves take the textbook
times (Singer and Seering 1990; docs/design.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotbeam.analysis.motion import Limits, rigid_slew, rigid_speed_change
from rotbeam.analysis.shapers import for_mode, residual_factor, shape
from rotbeam.config.errors import RotbeamInputError

F, ZETA = 6.52, 0.0203


def _oscillator_residual(motion, f, zeta, t_end):
    """Free vibration amplitude of q'' + 2 zeta w q' + w^2 q = -Omega'(t) after the move,
    by direct time stepping (an answer independent of the shapers' algebra)."""
    from scipy.integrate import solve_ivp

    w = 2 * math.pi * f

    def rhs(t, y):
        return [y[1], -2 * zeta * w * y[1] - w * w * y[0] - float(motion.acceleration(t))]

    sol = solve_ivp(rhs, (0, t_end), [0.0, 0.0], rtol=1e-10, atol=1e-12, max_step=2e-4)
    q, v = sol.y[:, -1]
    return math.hypot(q, (v + zeta * w * q) / (w * math.sqrt(1 - zeta**2)))


@pytest.mark.parametrize("kind", ["zv", "zvd"])
def test_the_shaper_leaves_its_mode_still(kind):
    train = for_mode(kind, F, ZETA)
    assert sum(train.amplitudes) == pytest.approx(1.0, abs=1e-15)
    assert residual_factor(train, F, ZETA) < 1e-12
    rigid = rigid_slew(0.5, Limits(10, 100, 20000))
    shaped = shape(rigid, train)
    bare = _oscillator_residual(rigid, F, ZETA, shaped.duration)
    assert _oscillator_residual(shaped, F, ZETA, shaped.duration) < 1e-6 * bare


def test_zvd_is_flat_in_the_frequency_and_zv_is_not():
    """The residual share at f (1 + eps): O(eps) for ZV, O(eps^2) for ZVD."""
    zv, zvd = for_mode("zv", F, ZETA), for_mode("zvd", F, ZETA)
    for eps in (0.01, 0.02):
        assert residual_factor(zv, F * (1 + eps), ZETA) == pytest.approx(math.pi * eps / 2,
                                                                        rel=0.1)  # fmt: skip
    ratio = residual_factor(zvd, F * 1.02, ZETA) / residual_factor(zvd, F * 1.01, ZETA)
    assert ratio == pytest.approx(4.0, rel=0.05)


def test_a_shaped_move_keeps_its_angle_and_lasts_the_train_longer():
    K = math.exp(-ZETA * math.pi / math.sqrt(1 - ZETA**2))
    zv = for_mode("zv", F, ZETA)
    assert zv.amplitudes == pytest.approx((1 / (1 + K), K / (1 + K)))
    td = 1 / (F * math.sqrt(1 - ZETA**2))
    assert zv.length == pytest.approx(td / 2)
    assert for_mode("zvd", F, ZETA).length == pytest.approx(td)
    rigid = rigid_slew(1.0, Limits(10, 100))
    for train in (zv, for_mode("zvd", F, ZETA)):
        m = shape(rigid, train)
        assert m.duration == pytest.approx(rigid.duration + train.length)
        assert m.angle(m.duration) == pytest.approx(1.0, rel=1e-12)
        assert m.speed(m.duration) == pytest.approx(0.0, abs=1e-12)


def test_rigid_moves_take_the_textbook_times():
    # bang-bang: the speed limit not reached, T = 2 sqrt(angle / a)
    m = rigid_slew(0.25, Limits(10, 100))
    assert m.duration == pytest.approx(2 * math.sqrt(0.25 / 100))
    # bang-coast-bang: T = angle / v + v / a
    m = rigid_slew(3.0, Limits(10, 100))
    assert m.duration == pytest.approx(3.0 / 10 + 10 / 100)
    assert m.peaks()[:2] == pytest.approx((10, 100))
    # S-curve with a coast: T = angle / v + v / a + a / j
    m = rigid_slew(3.0, Limits(10, 100, 5000))
    assert m.duration == pytest.approx(3.0 / 10 + 10 / 100 + 100 / 5000)
    assert m.peaks() == pytest.approx((10, 100, 5000))
    # a speed change by one S-curve pulse: dv / a + a / j
    m = rigid_speed_change(2.0, 20.0, Limits(25, 100, 5000))
    assert m.duration == pytest.approx(18 / 100 + 100 / 5000)
    assert m.speed(m.duration) == pytest.approx(20.0)
    t = np.linspace(0, m.duration, 101)
    assert np.all(np.diff(m.speed(t)) >= 0)


@pytest.mark.parametrize("bad", [0.0, -1.0, math.inf, math.nan])
def test_limits_must_be_positive(bad):
    for kwargs in ({"max_speed": bad, "max_accel": 1}, {"max_speed": 1, "max_accel": bad},
                   {"max_speed": 1, "max_accel": 1, "max_jerk": bad}):  # fmt: skip
        with pytest.raises(RotbeamInputError, match=r"allowed a finite number > 0"):
            Limits(**kwargs)
