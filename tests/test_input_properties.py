"""Property-based checks of input validation (hypothesis): valid beams and drives give finite
groups and a finite linearised frequency; invalid ones give RotbeamInputError naming the key."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.modes import modes
from rotbeam.model.params import Beam, Drive

pos = st.floats(min_value=1e-3, max_value=1e3)
KEYS = ["L", "h", "b", "E", "rho", "R", "gamma"]


@st.composite
def valid_beams(draw):
    L = draw(st.floats(1e-4, 1e-1))
    return Beam(
        L=L,
        h=L * draw(st.floats(1e-3, 0.5)),
        b=L * draw(st.floats(1e-3, 1.0)),
        E=draw(st.floats(1e4, 1e11)),
        rho=draw(st.floats(10.0, 2e4)),
        R=L * draw(st.floats(1.01, 1e3)),
        gamma=draw(st.floats(0.0, 10.0)),
    )


@settings(max_examples=40, deadline=None)
@given(beam=valid_beams(), omega=st.floats(0.0, 300.0))
def test_valid_beams_give_finite_groups(beam, omega):
    assert all(math.isfinite(v) for v in beam.derived().values())
    f = modes(beam, omega, 1, N=12)[0]
    assert math.isfinite(f) and f >= beam.f_n * 0.99


bad_values = st.one_of(
    st.floats(max_value=0.0, allow_nan=False),
    st.just(float("nan")),
    st.just(float("inf")),
    st.text(max_size=3),
    st.none(),
)


@settings(max_examples=60, deadline=None)
@given(key=st.sampled_from(KEYS), value=bad_values)
def test_invalid_beam_values_name_the_key(key, value):
    if key == "gamma" and isinstance(value, float) and value == 0.0:
        return  # zero damping is allowed
    with pytest.raises(RotbeamInputError, match=f"beam.{key}"):
        Beam(**{key: value})


@settings(max_examples=40, deadline=None)
@given(key=st.sampled_from(["omega0", "amplitude", "f_d"]), value=bad_values)
def test_invalid_drive_values_name_the_key(key, value):
    if key == "omega0" and isinstance(value, float) and math.isfinite(value):
        return  # any finite mean speed is allowed, negative included
    if key == "amplitude" and isinstance(value, float) and value == 0.0:
        return  # a = 0 is allowed (no Euler load)
    with pytest.raises(RotbeamInputError, match=f"drive.{key}"):
        Drive(**{key: value})
