"""The one array convention: states over a batch of instants are (m, n), instants first
(docs/numerics.md, "Array shapes").  N = 8 (n = 7) with instant counts other than 7, so that a
transposed array cannot pass for the right one."""

import numpy as np
import pytest

from rotbeam.runs.move import simulate_move
from rotbeam.runs.observables import OBSERVABLES, States
from rotbeam.runs.scene import build_scene, simulate
from rotbeam.solve.floquet import beam_floquet, sampled_orbit
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.periodic import solve_periodic
from rotbeam.solve.quasistatic import quasistatic_series
from rotbeam.solve.spectral import trig_interpolate
from rotbeam.solve.steady import steady_state

N, n = 8, 7
SCENE = {"drive": {"omega0": 5, "f_d": 3}, "numerics": {"N": N}}
#: |mu|max of the orbit below at 200 Magnus steps, as the (n, M) convention computed it
FLOQUET_REFERENCE = 0.757501239919712


@pytest.fixture(scope="module")
def model():
    return build_scene(SCENE).model()


def per_instant(f, theta):
    """f evaluated instant by instant, one state (n,) at a time."""
    return np.array([f(row) for row in theta])


def assert_same(batch, single):
    """Equal to round-off (a batched product may sum in another order than one state's)."""
    np.testing.assert_allclose(batch, single, rtol=0, atol=1e-14 * np.max(np.abs(single)))


def test_collocated_orbit_is_instants_first(model):
    res = solve_periodic(model, 17)
    assert res.converged
    assert res.theta.shape == res.theta_t.shape == (17, n) and res.tau.shape == (17,)
    fl = beam_floquet(model, res.theta, res.theta_t, steps=200)
    assert fl.max_abs == pytest.approx(FLOQUET_REFERENCE, rel=1e-12)
    # the samples of one period, resampled: the same multipliers to the ladder's accuracy
    sampled = beam_floquet(model, *sampled_orbit(model, trig_interpolate(res.theta, 33)), steps=200)
    assert sampled.max_abs == pytest.approx(FLOQUET_REFERENCE, rel=1e-6)


def test_steady_state_and_outputs_are_instants_first(model):
    num = Numerics(N=N, samples_per_period=16)
    ss = steady_state(model, num)
    m = ss.tau.size
    assert ss.converged and m != n and ss.theta.shape == (m, n)
    y = model.midspan(ss.theta)
    assert y.shape == (m,)
    assert_same(y, per_instant(model.midspan, ss.theta))
    x_tip, y_tip = model.tip(ss.theta)
    assert x_tip.shape == y_tip.shape == (m,)
    assert_same(y_tip, per_instant(lambda th: model.tip(th)[1], ss.theta))
    assert model.beam_angles(ss.theta).shape == (m, N - 1)
    x, _ = model.grid.positions(ss.theta)
    assert x.shape == (m, N)
    qs = quasistatic_series(model, ss.tau)
    assert qs.shape == (m, n)
    for obs in OBSERVABLES.values():
        if not obs.rates:
            assert obs(model, build_scene(SCENE).beam, States(ss.tau, ss.theta)).shape == (m,)


def test_scene_result_is_instants_first():
    res = simulate(build_scene(SCENE))
    m = res.tau.size
    assert m != n
    assert res.dynamic.theta.shape == res.theta_quasistatic.shape == (m, n)
    table = res.observables(tuple(OBSERVABLES))
    assert all(np.isfinite(table[name]["rms_dynamic"]) for name in OBSERVABLES)


def test_modal_model_maps_instants_first():
    scene = build_scene({**SCENE, "numerics": {"N": N, "model": "modal", "modes": 3}})
    model = scene.model()
    q = np.random.default_rng(3).normal(size=(5, 3)) * 0.01
    angles = model.beam_angles(q)
    assert angles.shape == (5, N - 1)
    assert_same(angles, per_instant(model.beam_angles, q))
    assert model.midspan(q).shape == (5,)


def test_move_result_is_instants_first(tmp_path):
    path = tmp_path / "ramp.csv"
    t = np.linspace(0.0, 0.02, 9)
    path.write_text("t,omega\n" + "".join(f"{a:.17g},{2.0 + 100.0 * a:.17g}\n" for a in t))
    res = simulate_move(build_scene({"drive": {"move": str(path), "settle": 0.01},
                                     "numerics": {"N": N}}))  # fmt: skip
    m = res.t_s.size
    assert m != n
    assert res.theta.shape == res.theta_t.shape == res.theta_quasistatic.shape == (m, n)
    scene_model = res.scene.model()
    np.testing.assert_array_equal(res.y_dynamic, scene_model.midspan(res.theta))
    table = res.observables(tuple(OBSERVABLES))
    assert all(np.isfinite(table[name]["rms_dynamic"]) for name in OBSERVABLES)
