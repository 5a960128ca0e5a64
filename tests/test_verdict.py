"""The engineer's answer for one scene (rotbeam.verdict, `rotbeam simulate --threshold --plot`):
the full model's verdict against an independent route (App. E's linear second-order estimate of
the boundary), the flip at the threshold, no verdict without a steady state.  The CLI's
`--threshold` and `--plot` are tested in test_cli.py."""

import math

import pytest

from rotbeam.integrate import Numerics
from rotbeam.params import Beam, Drive, Effects
from rotbeam.scene import Scene, simulate
from rotbeam.verdict import judge

NUM = Numerics(N=20)


def scene(omega0: float, f_d: float, beam: Beam | None = None) -> Scene:
    return Scene(beam or Beam(), Drive(omega0, 1.0, f_d), Effects(), NUM)


@pytest.mark.parametrize("omega0", [5.0, 50.0])
def test_verdict_agrees_with_the_linear_estimate_away_from_the_boundary(omega0):
    """App. E's oscillator (f_d* = c_0 f_0) and the full nonlinear beam are independent routes to
    the boundary; they differ by a few per cent near it (README), so at half and at twice the
    estimate the two must agree on the side."""
    probe = judge(simulate(scene(omega0, 1.0)))
    estimate = probe.fd_star_estimate_hz
    assert math.isfinite(estimate) and estimate == pytest.approx(probe.c0 * probe.f0_hz)
    below = judge(simulate(scene(omega0, 0.5 * estimate)))
    above = judge(simulate(scene(omega0, 2.0 * estimate)))
    assert below.quasistatic_ok is True and below.delta_rms < 0.10
    assert above.quasistatic_ok is False and above.delta_rms >= 0.10
    assert "good enough" in below.text and "inertia matters" in above.text


def test_verdict_flips_at_the_threshold():
    res = simulate(scene(5.0, 3.0))
    d = res.delta_rms
    assert judge(res, threshold=d * 1.01).quasistatic_ok is True
    assert judge(res, threshold=d * 0.99).quasistatic_ok is False
    # a larger threshold admits more: its linear boundary lies at a higher frequency
    assert judge(res, 0.2).fd_star_estimate_hz > judge(res, 0.05).fd_star_estimate_hz


def test_no_verdict_without_a_steady_state():
    res = simulate(scene(5.0, 2.0, Beam(gamma=0.0)))  # undamped: no steady state exists
    assert not res.converged
    v = judge(res)
    assert v.quasistatic_ok is None and v.text.startswith("no verdict")


def test_overdamped_beam_has_no_linear_estimate_but_a_verdict():
    """L = 0.1 mm, E = 1 GPa (Fig. 7 grid, zeta = 35.5): the oscillator never exceeds its static
    response by the threshold, so c_0 does not exist; the full model still answers."""
    ref = Beam()
    h = 0.01 * 1e-4
    tiny = Beam(L=1e-4, h=h, b=ref.b / ref.h * h, E=1e9)
    v = judge(simulate(scene(5.0, 2.0, tiny)))
    assert math.isnan(v.c0) and math.isnan(v.fd_star_estimate_hz)
    assert "no linear estimate" in v.text
    assert v.quasistatic_ok is True  # 2 Hz against f_n = 14.9 kHz
