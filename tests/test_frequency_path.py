"""A scene next to a resonance peak, solved alone: where Newton fails from the scene's own start
and from the amplitude continuation, its orbit is reached as an upward sweep reaches it
(`rotbeam.solve.periodic.FREQUENCY_PATH`) instead of by tens of periods of time stepping."""

from __future__ import annotations

import pytest

import rotbeam
from rotbeam.runs.scene import build_scene
from rotbeam.solve.periodic import solve_periodic_adaptive

#: N = 16, 5 rad/s: the resonance peak of the first mode is near 6.8 Hz; at 6.75 Hz the scene's
#: own start and the amplitude continuation do not converge
NEAR_PEAK = {"drive": {"omega0": 5, "f_d": 6.75}, "numerics": {"N": 16}}


def test_the_scene_needs_the_path():
    """Without the path, the collocation of this scene alone fails (else the next test would
    not exercise it)."""
    scene = build_scene(NEAR_PEAK)
    num = scene.numerics
    model = scene.model(num.N)
    alone = solve_periodic_adaptive(model, tail_tol=num.tail_tol, from_below=False)
    assert not alone.converged
    reached = solve_periodic_adaptive(model, tail_tol=num.tail_tol)
    assert reached.converged and "continued in the frequency" in reached.message


def test_orbit_continued_from_below_is_the_time_stepped_steady_state():
    """The scene alone reports the certified collocated orbit; time stepping from the
    quasi-static state (73 periods) settles on the same RMS (measured 4.2e-5 apart: the
    steady-state tolerance's order)."""
    direct = rotbeam.simulate(build_scene(NEAR_PEAK))
    assert direct.dynamic.converged
    assert direct.dynamic.message.startswith("collocation orbit")
    assert direct.dynamic.periods == 0
    stepped_scene = build_scene({**NEAR_PEAK, "numerics": {"N": 16, "start": "quasistatic"}})
    stepped = rotbeam.simulate(stepped_scene)
    assert stepped.dynamic.converged and stepped.dynamic.periods > 10
    assert direct.rms_dynamic == pytest.approx(stepped.rms_dynamic, rel=2e-4)
