"""One wall-time budget per command: `numerics.max_seconds` bounds every phase, and an answer
the budget cut short says which phase it cut and what the answer rests on."""

from __future__ import annotations

import json
import subprocess
import sys
import time

import pytest

from rotbeam.analysis.effect_budget import effect_budget
from rotbeam.analysis.verdict import critical
from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.runs.response import MIN_SECTION_PERIODS, RESPONSES, UNCLASSIFIED, response_of
from rotbeam.runs.scene import Scene, simulate
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.timebudget import TimeBudget

HARD = "drive: {omega0: 5, f_d: 7, amplitude: 3}\n"  # no stable steady state (docs/stability.md)


def simulate_cli(tmp_path, max_seconds: float) -> tuple[dict, float]:
    """`rotbeam simulate --json` of the hard scene with this budget: its output and wall time."""
    scene = tmp_path / "hard.yaml"
    scene.write_text(HARD + f"numerics: {{max_seconds: {max_seconds}}}\n")
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "rotbeam", "simulate", "--scene", str(scene),
                          "--json"], capture_output=True, text=True, timeout=20 * max_seconds + 60,
                         check=False)  # fmt: skip
    wall = time.perf_counter() - t0
    assert out.returncode == 1, out.stderr  # no steady state: exit status 1, not a traceback
    return json.loads(out.stdout), wall


def test_part_and_cut_message():
    whole = TimeBudget(60.0)
    part = whole.part(0.5)
    assert 29.9 < part.seconds <= 30.0 and part.whole == 60.0
    assert not whole.spent() and TimeBudget(1e-9).spent()
    assert whole.cut("the section").startswith("the time budget of 60 s cut the section after")
    assert "30 s of the command's 60 s" in part.cut("x")


@pytest.mark.slow
def test_hard_scene_keeps_its_budget_and_names_the_cut(tmp_path):
    """The issue's case: a = 3 rad/s, 7 Hz with max_seconds 60 returns within 1.5x of its
    budget with a class of the response and the messages naming what the budget cut."""
    out, wall = simulate_cli(tmp_path, 60.0)
    assert wall < 1.5 * 60.0, wall
    assert out["converged"] is False
    assert "time budget" in out["message"] and "cut the time stepping at N = 40" in out["message"]
    assert out["response"] in RESPONSES, out["response_message"]
    assert out["response_periods"] >= MIN_SECTION_PERIODS


def test_budget_too_small_for_one_period_says_so(tmp_path):
    """A budget far too small for even one period of the classification gives no class."""
    out, wall = simulate_cli(tmp_path, 0.2)
    assert out["response"] == UNCLASSIFIED
    assert "a class needs at least" in out["response_message"]
    assert "time budget" in out["response_message"]
    assert out["rms_dynamic"] != out["rms_dynamic"]  # NaN: no period of the steady state seen


def test_collocation_stops_at_the_budget():
    """The hard scene's collocation at N = 40 (M refined up to 129 and amplitude continuation:
    1.7 s of Newton steps on one core here) stops at a budget of 0.2 s, within the Newton step
    in flight, and says that it cut the collocation."""
    from rotbeam.solve.steady import steady_state

    model = Scene(Beam(), Drive(5.0, 3.0, 7.0)).model(40)
    t0 = time.perf_counter()
    st = steady_state(model, Numerics(N=40), time_budget=TimeBudget(0.2))
    wall = time.perf_counter() - t0
    assert st.status == 1 and not st.converged and st.periods == 0
    assert "cut the collocation at N = 40" in st.message, st.message
    assert wall < 0.2 + 0.3, wall


def test_classification_spent_budget_has_no_class():
    """`response_of` with a spent budget integrates no section period and classifies nothing."""
    scene = Scene(Beam(), Drive(5.0, 3.0, 7.0))
    r = response_of(scene.model(6), scene.beam.T, 2, 40, time_budget=TimeBudget(1e-9))
    assert r.response == UNCLASSIFIED and r.periods <= 1
    assert r.message.startswith(UNCLASSIFIED) and "cut the classification after 0" in r.message


def test_critical_search_stops_at_the_budget():
    scene = Scene(Beam(), Drive(omega0=5.0, f_d=1.0), Effects(), Numerics(N=10))
    res = critical(scene, time_budget=TimeBudget(1e-9))
    assert not res.found and res.visited == []
    assert "cut the search after 0 full-model runs" in res.message


def test_effect_budget_shares_the_budget():
    """With its budget spent the effect budget stops after the scene's own run (which needs
    time stepping here: certify = time), instead of running one simulation per effect."""
    scene = Scene(Beam(), Drive(5.0, 1.0, 2.0), Effects(), Numerics(N=8, certify="time"))
    runs = []
    budget = effect_budget(scene, progress=lambda: runs.append(1), time_budget=TimeBudget(1e-9))
    assert len(runs) == 1 and budget.shares == []
    full = effect_budget(scene, progress=lambda: runs.append(1))  # its own budget: every run
    assert len(runs) > 6 and full.shares


def test_richardson_grids_share_one_budget():
    """The coarse grid of an extrapolated run draws on the same budget as the fine one."""
    num = Numerics(N=8, extrapolate=True, certify="time")
    res = simulate(Scene(Beam(), Drive(5.0, 1.0, 2.0), Effects(), num),
                   time_budget=TimeBudget(1e-9))  # fmt: skip
    assert not res.converged and "time budget" in res.dynamic.message
    assert res.extrapolation["extrapolated"] is False


def test_fit_stops_at_the_budget():
    """`identify` with its budget spent raises FitOutOfTime (not a penalty the trust region
    would walk around) after no steady state."""
    import numpy as np

    from rotbeam.analysis.identify import FitOutOfTime, identify
    from rotbeam.analysis.measurements import ResonanceCurve

    f = np.linspace(3.0, 9.0, 5)
    curve = ResonanceCurve(f_d=f, rms=0.01 / (1.0 + (f - 7.0) ** 2), rms_std=None)
    with pytest.raises(FitOutOfTime, match="cut the fit after 0 steady states"):
        identify(curve, 5.0, time_budget=TimeBudget(1e-9))
