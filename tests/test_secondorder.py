"""App. E: the canonical second-order system's quasi-static condition and Table (systems).

References used here are independent of `rotbeam.secondorder`'s closed forms: numpy's polynomial
root finder on the printed biquadratic, a brute-force scan of Delta RMS, a time integration of the
forced oscillator, and hand-evaluated Table 1 numbers.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.params import Beam
from rotbeam.model.secondorder import (
    biquadratic_residual,
    c0_limit,
    c0_root,
    delta_rms_canonical,
)
from rotbeam.paper.appendix_e import systems_table
from rotbeam.paper.printed import printed_per_threshold, read_claims

#: App. E, Table (c_0): the printed c0 for zeta -> 0 (rotbeam/paper/paper_claims.yaml)
PRINTED_C0 = printed_per_threshold(read_claims()[1], "c0_")

THRESHOLDS = (0.02, 0.04, 0.06, 0.08, 0.10)


def _smallest_positive_root(zeta: float, t: float) -> float:
    """numpy.roots of c^4 + (4 zeta^2 - 2) c^2 + (1 - (1 - t)^2): smallest real c > 0."""
    r = np.roots([1.0, 0.0, 4.0 * zeta**2 - 2.0, 0.0, 1.0 - (1.0 - t) ** 2])
    real = r[np.abs(r.imag) < 1e-9].real
    return float(np.min(real[real > 0]))


@pytest.mark.parametrize("t", THRESHOLDS)
def test_limit_is_exact_root_of_biquadratic(t):
    assert c0_limit(t) == pytest.approx(_smallest_positive_root(0.0, t), rel=1e-10)
    assert c0_root(1e-9, t) == pytest.approx(c0_limit(t), rel=1e-12)
    assert c0_root(0.0, t) == pytest.approx(c0_limit(t), rel=1e-14)


@pytest.mark.parametrize("t", THRESHOLDS)
def test_printed_table_is_the_exact_zeta0_root(t):
    """The printed c0 equal sqrt(t), the exact zeta = 0 root, to the 4 printed decimals."""
    assert abs(PRINTED_C0[t] - _smallest_positive_root(0.0, t)) <= 5e-5


def test_printed_0_19_is_one_minus_0_9_squared():
    assert biquadratic_residual(0.0, 0.0, 0.10) == pytest.approx(0.19, abs=1e-15)


@pytest.mark.parametrize("zeta", [0.0, 0.017, 0.0203, 0.1, 0.3, 0.5])
@pytest.mark.parametrize("t", [0.02, 0.05, 0.10, 0.12])
def test_root_satisfies_biquadratic_and_delta(zeta, t):
    c = c0_root(zeta, t)
    assert biquadratic_residual(c, zeta, t) == pytest.approx(0.0, abs=1e-13)
    assert delta_rms_canonical(c, zeta) == pytest.approx(t, abs=1e-12)
    assert c == pytest.approx(_smallest_positive_root(zeta, t), rel=1e-8)


@pytest.mark.parametrize("zeta", [0.017, 0.2])
def test_root_is_first_crossing_of_a_scan(zeta):
    """Brute force: scan Delta RMS(c0) upward from 0 and refine the first crossing."""
    t = 0.10
    cs = np.linspace(1e-4, 1.0, 4001)
    d = delta_rms_canonical(cs, zeta) - t
    j = int(np.nonzero(d >= 0)[0][0])
    ref = brentq(lambda c: delta_rms_canonical(c, zeta) - t, cs[j - 1], cs[j], xtol=1e-14)
    assert c0_root(zeta, t) == pytest.approx(ref, rel=1e-10)


def test_paper_c0_about_0_31_for_small_damping():
    """App. E: c0 ~ 0.31 for zeta << 1 at threshold 0.1 (exactly sqrt(0.1) = 0.3162 at 0)."""
    for zeta in (0.0, 0.017, 0.0203):
        assert 0.31 <= c0_root(zeta, 0.10) <= 0.3164  # damping raises it: 0.31633 at 0.017


def test_delta_formula_against_time_integration():
    """RMS of the integrated steady state of u'' + 2 zeta u' + u = cos(c0 tau) vs the formula."""
    zeta, c0 = 0.1, 0.6
    period = 2 * math.pi / c0
    sol = solve_ivp(
        lambda tau, y: [y[1], math.cos(c0 * tau) - 2 * zeta * y[1] - y[0]],
        (0.0, 60 * period),
        [0.0, 0.0],
        method="DOP853",
        rtol=1e-11,
        atol=1e-13,
        dense_output=True,
    )
    tau = 59 * period + np.arange(512) / 512 * period  # transient exp(-0.1 * 59 * 10.5) ~ 1e-27
    rms_dyn = float(np.sqrt(np.mean(sol.sol(tau)[0] ** 2)))
    rms_qs = float(np.sqrt(np.mean(np.cos(c0 * tau) ** 2)))
    assert (rms_dyn - rms_qs) / rms_dyn == pytest.approx(delta_rms_canonical(c0, zeta), rel=1e-7)


@pytest.mark.parametrize("t", [0.0, 1.0, -0.1, 1.5, float("nan"), float("inf"), True, "0.1"])
def test_bad_threshold_raises(t):
    with pytest.raises(RotbeamInputError, match="threshold"):
        c0_root(0.01, t)
    with pytest.raises(RotbeamInputError, match="threshold"):
        c0_limit(t)


@pytest.mark.parametrize("zeta", [-0.01, float("nan"), float("inf")])
def test_bad_zeta_raises(zeta):
    with pytest.raises(RotbeamInputError, match="zeta"):
        c0_root(zeta, 0.1)


@pytest.mark.parametrize("zeta", [0.54, 0.70, 0.71, 1.0, 5.0])
def test_no_root_raises_instead_of_nan(zeta):
    """Delta RMS peaks at 1 - 2 zeta sqrt(1 - zeta^2): above zeta ~0.531 it never reaches 0.1."""
    with pytest.raises(RotbeamInputError, match="no c0 reaches"):
        c0_root(zeta, 0.10)


def test_root_just_inside_the_existence_limit_is_finite():
    # 1 - t = 2 zeta sqrt(1 - zeta^2) at t = 0.1: zeta^2 = (1 - sqrt(1 - 0.81)) / 2
    z_max = math.sqrt((1.0 - math.sqrt(1.0 - 0.81)) / 2.0)
    c = c0_root(z_max * (1 - 1e-9), 0.10)
    assert math.isfinite(c) and delta_rms_canonical(c, z_max * (1 - 1e-9)) == pytest.approx(0.1)


def test_the_printed_table_has_every_threshold():
    assert sorted(PRINTED_C0) == list(THRESHOLDS)


def test_systems_table_cantilever_reference_beam():
    """Hand evaluation of Table 1: EI = 1.22e6 * 0.01 * 0.002^3 / 12, rho A = 1170.2 * 2e-5."""
    EI = 1.22e6 * 0.01 * 0.002**3 / 12.0
    rhoA = 1170.2 * 0.01 * 0.002
    L, gamma, b1 = 0.040, 0.039, 1.8751040687119611
    rows = {r["system"]: r for r in systems_table(Beam())}
    cb = rows["cantilever beam"]
    assert cb["k"] == pytest.approx(3 * EI / L**3, rel=1e-12)
    assert cb["zeta"] == pytest.approx(gamma * L**2 / (2 * b1**2 * math.sqrt(EI * rhoA)), rel=1e-12)
    assert cb["zeta"] == pytest.approx(0.0203, abs=1e-4)  # the paper prints ~0.017
    w = b1**2 * math.sqrt(EI / (rhoA * L**4))
    assert cb["f_n_table"] == pytest.approx(w, rel=1e-12)
    assert cb["f_n_hz"] == pytest.approx(Beam().f_n, rel=1e-12)  # 6.52 Hz, printed 6.37 Hz
    assert "rad/s" in cb["f_n_unit"]
    assert math.isnan(rows["mass-spring"]["zeta"]) and math.isnan(rows["pendulum"]["k"])


def test_systems_table_other_rows():
    rows = {
        r["system"]: r
        for r in systems_table(
            mass_spring={"k_s": 100.0, "m": 0.25, "gamma": 1.0},
            pendulum={"m": 0.5, "g": 9.81, "L": 2.0, "gamma": 0.3},
        )
    }
    ms, pd = rows["mass-spring"], rows["pendulum"]
    assert ms["zeta"] == pytest.approx(1.0 / (2 * 5.0)) and ms["f_n_table"] == pytest.approx(20.0)
    assert pd["k"] == pytest.approx(0.5 * 9.81 * 2.0)
    assert pd["zeta"] == pytest.approx(0.3 / (2 * 0.5 * 2.0 * math.sqrt(9.81 * 2.0)))
    assert pd["f_n_hz"] == pytest.approx(math.sqrt(9.81 / 2.0) / (2 * math.pi))
