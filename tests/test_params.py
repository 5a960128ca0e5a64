"""Derived groups of the reference beam against hand-computed closed forms."""

import math

import pytest

from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.params import BETA1, Beam, Dimensionless, Drive, Effects


def test_reference_beam_groups():
    b = Beam()
    A, I2 = 0.01 * 0.002, 0.01 * 0.002**3 / 12
    T = math.sqrt(1170.2 * A * 0.04**4 / (1.22e6 * I2))
    assert b.T == pytest.approx(T, rel=1e-12)
    # f_n from Eq. (natural_freq): 6.52 Hz, not the printed 6.37 Hz (paper README)
    assert b.f_n == pytest.approx(BETA1**2 / (2 * math.pi * T), rel=1e-12)
    assert 6.50 < b.f_n < 6.54
    # zeta of the cantilever row of Table (systems): about 0.020, not the printed 0.017
    assert b.zeta == pytest.approx(
        0.039 * 0.04**2 / (2 * BETA1**2 * math.sqrt(1.22e6 * I2 * 1170.2 * A))
    )
    assert 0.019 < b.zeta < 0.021
    # G inside the 0.028-0.032 band implied by the ranges of Sec. 5
    assert 0.028 < b.G < 0.032
    assert b.delta == pytest.approx(0.04 / 0.155)


def test_dimensionless_groups_map_onto_paper():
    b, d = Beam(), Drive(omega0=10.0, amplitude=1.0, f_d=3.0)
    dl = Dimensionless.from_physical(b, d)
    # C = lam^2/delta and E = lam_t/delta (params docstring)
    tau = 0.37
    t = tau * b.T
    assert dl.lam(tau) ** 2 / b.delta == pytest.approx(b.G * d.omega(t) ** 2, rel=1e-12)
    assert dl.lam_dot(tau) / b.delta == pytest.approx(b.G * d.omega_dot(t), rel=1e-12)


@pytest.mark.parametrize(
    "kwargs, word",
    [
        ({"L": -1.0}, "beam.L"),
        ({"h": 0.05}, "beam.h"),
        ({"R": 0.03}, "beam.R"),
        ({"E": float("nan")}, "beam.E"),
        ({"gamma": -0.1}, "beam.gamma"),
        ({"rho": "heavy"}, "beam.rho"),
    ],
)
def test_bad_beam_values_name_the_key(kwargs, word):
    with pytest.raises(RotbeamInputError, match=word):
        Beam(**kwargs)


@pytest.mark.parametrize(
    "kwargs, word",
    [
        ({"f_d": 0.0}, "drive.f_d"),
        ({"amplitude": -1.0}, "drive.amplitude"),
        ({"omega0": float("inf")}, "drive.omega0"),
    ],
)
def test_bad_drive_values(kwargs, word):
    with pytest.raises(RotbeamInputError, match=word):
        Drive(**kwargs)


def test_effects_from_list():
    e = Effects.from_list("centrifugal,euler")
    assert e.active() == ["centrifugal", "euler"]
    with pytest.raises(RotbeamInputError, match="gravity"):
        Effects.from_list("gravity")
