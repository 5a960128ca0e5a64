"""The engineer's answer for one scene (rotbeam.verdict, `rotbeam simulate --threshold --plot`):
the full model's verdict against an independent route (App. E's linear second-order estimate of
the boundary), the flip at the threshold, no verdict without a steady state; f_d* by root finding
against the root of a dense scan.  The CLI (`--threshold`, `--plot`, `rotbeam critical`) is
tested in test_cli.py."""

import math

import numpy as np
import pytest

from rotbeam.analysis.verdict import _lag_ratio, critical, judge
from rotbeam.model.criterion import critical_from_scan
from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.model.secondorder import delta_rms_canonical
from rotbeam.runs.scene import Scene, simulate
from rotbeam.runs.sweeps import scan_line
from rotbeam.solve.numerics import Numerics

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


def test_overdamped_beam_gets_the_lag_branch_estimate_and_a_verdict():
    """L = 0.1 mm, E = 1 GPa (Fig. 7 grid, zeta = 35.5): the oscillator never exceeds its static
    response by the threshold, so c_0 does not exist; the estimate comes from where it lags."""
    ref = Beam()
    h = 0.01 * 1e-4
    tiny = Beam(L=1e-4, h=h, b=ref.b / ref.h * h, E=1e9)
    v = judge(simulate(scene(5.0, 2.0, tiny)))
    assert math.isnan(v.c0)
    lag = _lag_ratio(tiny.derived()["zeta"], 0.10) * v.f0_hz
    assert v.fd_star_estimate_hz == pytest.approx(lag, rel=1e-12) and "lags" in v.text
    assert v.quasistatic_ok is True  # 2 Hz against f_n = 14.9 kHz and f_d* near 97 Hz


# --- f_d* by root finding (rotbeam critical) ------------------------------------------------------


@pytest.mark.parametrize("omega0", [5.0, 50.0])
def test_critical_equals_the_root_of_a_dense_scan(omega0):
    """Root finding on the full model against the workflow's route: a 21-point scan and the root
    of its PCHIP interpolant (criterion.critical_from_scan)."""
    crit = critical(Scene(Beam(), Drive(omega0=omega0), numerics=NUM), rtol=1e-5)
    assert crit.found and len(crit.visited) <= 12, crit
    df = scan_line(Beam(), omega0, crit.f0_hz * np.linspace(0.2, 0.45, 21), numerics=NUM)
    scan = critical_from_scan(df["f_d"], df["delta_rms"], 0.10)
    assert scan["found"]
    assert crit.f_d_star == pytest.approx(scan["f_d_root"], rel=1e-3)
    # the linear estimate started it close: App. E within 2 % of the full model
    assert crit.estimate_hz == pytest.approx(crit.f_d_star, rel=0.02)


def test_lag_ratio_solves_the_overdamped_branch():
    """Where App. E's oscillator lags: 1 - sqrt((1 - c^2)^2 + (2 zeta c)^2) = -threshold."""
    for zeta in (0.5, 0.8, 2.0, 35.5):
        for th in (0.05, 0.1, 0.3):
            assert delta_rms_canonical(_lag_ratio(zeta, th), zeta) == pytest.approx(-th, abs=1e-12)


def test_overdamped_critical():
    """The tiny Fig. 7 beam (zeta 35.5) has no App. E root; its boundary is where the dynamic
    response lags the static one by the threshold, and the full model brackets it there."""
    ref = Beam()
    h = 0.01 * 1e-4
    tiny = Beam(L=1e-4, h=h, b=ref.b / ref.h * h, E=1e9)
    crit = critical(Scene(tiny, Drive(omega0=5.0), numerics=NUM))
    assert crit.found
    assert crit.estimate_hz == pytest.approx(_lag_ratio(tiny.derived()["zeta"], 0.1) * crit.f0_hz)
    assert crit.f_d_star == pytest.approx(crit.estimate_hz, rel=0.05)
    below = judge(simulate(scene(5.0, 0.8 * crit.f_d_star, tiny)))
    above = judge(simulate(scene(5.0, 1.25 * crit.f_d_star, tiny)))
    assert below.quasistatic_ok is True and above.quasistatic_ok is False


def test_critical_without_a_steady_state_says_so():
    crit = critical(Scene(Beam(gamma=0.0), Drive(omega0=5.0), numerics=NUM))
    assert not crit.found and math.isnan(crit.f_d_star)
    assert crit.message.startswith("no steady state")
