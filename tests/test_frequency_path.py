"""A scene next to a resonance peak, solved alone: where Newton fails from the scene's own start
and from the amplitude continuation, its orbit is reached as an upward sweep reaches it
(`rotbeam.solve.periodic.FREQUENCY_PATH`) or, past the fold where that branch ends, as a
downward sweep reaches it (`FREQUENCY_PATH_ABOVE`), instead of by tens of periods of time
stepping."""

from __future__ import annotations

import json

import pytest
from test_bad_input import run_main

import rotbeam
from rotbeam.runs.scene import build_scene
from rotbeam.solve.periodic import (
    FREQUENCY_PATH,
    FREQUENCY_PATH_ABOVE,
    REFINE_MAXITER,
    _frequency_continuation,
    refined,
    solve_periodic,
    solve_periodic_adaptive,
)

#: N = 16, 5 rad/s: the resonance peak of the first mode is near 6.8 Hz; at 6.75 Hz the scene's
#: own start and the amplitude continuation do not converge
NEAR_PEAK = {"drive": {"omega0": 5, "f_d": 6.75}, "numerics": {"N": 16}}
#: N = 8, 36.67 rad/s, 13.7 Hz (f_d / f_0 = 0.95): the branch followed up from 0.9 f_d ends at
#: a fold near 0.975 f_d, and the resonant orbit, the tip swinging about 1 rad, is reached
#: only from above
PAST_FOLD = {"drive": {"omega0": 36.67, "f_d": 13.7}, "numerics": {"N": 8}}

SCENES = [(NEAR_PEAK, FREQUENCY_PATH), (PAST_FOLD, FREQUENCY_PATH_ABOVE)]


@pytest.mark.parametrize("spec, path", SCENES, ids=["from below", "from above"])
def test_the_scene_needs_the_path(spec, path):
    """Without the frequency continuation the collocation of the scene alone fails (else the
    next test would not exercise it); the scene past the fold is not reached from below."""
    scene = build_scene(spec)
    num = scene.numerics
    model = scene.model(num.N)
    alone = solve_periodic_adaptive(model, tail_tol=num.tail_tol, by_frequency=False)
    assert not alone.converged
    if path is FREQUENCY_PATH_ABOVE:
        below = _frequency_continuation(model, 17, num.tail_tol, 129, 1e-10, FREQUENCY_PATH)
        assert below is None
    reached = solve_periodic_adaptive(model, tail_tol=num.tail_tol)
    assert reached.converged
    assert f"continued in the frequency from {path[0]:g} f_d" in reached.message


@pytest.mark.parametrize("spec, path", SCENES, ids=["from below", "from above"])
def test_orbit_continued_in_the_frequency_is_the_time_stepped_steady_state(spec, path):
    """The scene alone reports the certified collocated orbit; time stepping from the
    quasi-static state (73 periods from below, 150 from above) settles on the same RMS
    (measured 4.2e-5 apart for both: the steady-state tolerance's order)."""
    direct = rotbeam.simulate(build_scene(spec))
    assert direct.dynamic.converged
    assert direct.dynamic.message.startswith("collocation orbit")
    assert direct.dynamic.periods == 0
    numerics = {**spec["numerics"], "start": "quasistatic"}
    stepped = rotbeam.simulate(build_scene({**spec, "numerics": numerics}))
    assert stepped.dynamic.converged and stepped.dynamic.periods > 10
    assert direct.rms_dynamic == pytest.approx(stepped.rms_dynamic, rel=2e-4)


#: PAST_FOLD carrying half the beam's mass at its tip (0.47 g; the beam's own is 0.94 g): the
#: payload lowers the resonance, and at 11.75 Hz the orbit is again reached only from above
PAST_FOLD_PAYLOAD = {**PAST_FOLD, "drive": {"omega0": 36.67, "f_d": 11.75},
                     "beam": {"tip_mass": 4.7e-4}}  # fmt: skip


def test_a_payload_past_the_fold_from_the_command_line_and_python():
    """With a payload the path from above reaches the orbit too; the command line answers as
    the API does, and time stepping from the orbit's state (`certify: time`, Radau) stays on it:
    the RMS of its window within 1e-6 of the orbit's (measured 1.3e-7; time stepping from the
    quasi-static state takes 381 periods, 188 s, to settle 9.4e-6 from it)."""
    scene = build_scene(PAST_FOLD_PAYLOAD)
    num = scene.numerics
    reached = solve_periodic_adaptive(scene.model(num.N), tail_tol=num.tail_tol)
    assert reached.converged
    assert f"continued in the frequency from {FREQUENCY_PATH_ABOVE[0]:g} f_d" in reached.message
    direct = rotbeam.simulate(scene)
    assert direct.dynamic.converged and direct.dynamic.periods == 0
    rc, out, err = run_main(["simulate", "--omega0", "36.67", "--fd", "11.75", "--tip-mass",
                             "4.7e-4", "--N", "8", "--json"])  # fmt: skip
    assert rc == 0, err
    assert json.loads(out)["rms_dynamic"] == direct.rms_dynamic
    numerics = {**PAST_FOLD_PAYLOAD["numerics"], "certify": "time"}
    stepped = rotbeam.simulate(build_scene({**PAST_FOLD_PAYLOAD, "numerics": numerics}))
    assert stepped.dynamic.converged and stepped.dynamic.periods > 0
    assert direct.rms_dynamic == pytest.approx(stepped.rms_dynamic, rel=1e-6)


def test_a_refinement_stops_at_its_cap_where_its_start_resolves_nothing():
    """At 5 rad/s, 6.85 Hz (N = 40) the linear guess converges on 17 instants to an orbit with
    harmonic tail 8.6e-2 that is no coarse image of the resonant one: its refinement ends
    unconverged after REFINE_MAXITER Newton steps (23 without the cap), and the scene still
    reaches its resonant orbit on 129 instants.  From the resolved orbit at 7 Hz the refinement
    meets its tolerance well inside the cap."""
    for f_d, resolved in ((6.85, False), (7.0, True)):
        scene = build_scene({"drive": {"omega0": 5, "f_d": f_d}})
        model = scene.model(scene.numerics.N)
        coarse = solve_periodic(model, 17)
        assert coarse.converged
        finer = refined(model, coarse)
        assert finer.converged is resolved
        if resolved:
            assert finer.iterations <= REFINE_MAXITER // 2
        else:
            assert finer.iterations == REFINE_MAXITER and coarse.harmonic_tail > 5e-2
    result = rotbeam.simulate(build_scene({"drive": {"omega0": 5, "f_d": 6.85}}))
    assert result.converged and result.dynamic.periodic.M == 129 and result.dynamic.periods == 0
