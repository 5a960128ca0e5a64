"""`rotbeam design-move` and `rotbeam.design_move` against independent answers: the designed
move run again from its CSV by `rotbeam simulate --move`, its angle and limits from the CSV's
samples by finite differences, the rigid-body limit of a stiff beam (closed-form time-optimal
duration), the linear limit (ZVD's residual vanishes; the design is no longer than ZV's), a
spin-up, a payload, the time budget's cut and bad input in one line.

Cheap settings: a grid of N = 8, numerics.rtol = 1e-4 (the residual within 2e-5 L of
rtol = 1e-8's), a jerk limit (steps in the acceleration ring every mode and cost the stepper
20x more)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import rotbeam
from rotbeam.analysis.move_check import integrated_angle
from rotbeam.cli.main import main
from rotbeam.config.errors import RotbeamInputError
from rotbeam.config.scenefile import read_columns
from rotbeam.runs.scene import build_scene

NUMERICS = {"N": 8, "rtol": 1e-4}
LIMITS = {"max_speed": 10.0, "max_accel": 100.0, "max_jerk": 20000.0}


def _scene(**beam):
    return build_scene({"beam": beam, "numerics": NUMERICS})


@pytest.fixture(scope="module")
def slew(tmp_path_factory):
    design = rotbeam.design_move(_scene(), angle=0.3, residual=0.005, baselines=False, **LIMITS)
    path = tmp_path_factory.mktemp("design") / "move.csv"
    design.write_csv(path)
    return design, path


def _samples(path):
    cols = read_columns(path, ("t", "omega"), "move")
    return np.asarray(cols["t"]), np.asarray(cols["omega"])


def test_the_design_meets_the_tolerance_and_reports_its_keys(slew):
    design, path = slew
    out = design.summary()
    assert design.found and out["residual"] <= 0.005
    for key in ("duration_s", "residual", "peak", "angle_rad", "robust_residual", "profile_csv",
                "seconds", "baselines"):  # fmt: skip
        assert key in out
    assert out["profile_csv"] == str(path) and out["robust_residual"] is None
    # shorter than the textbook ZV shaping of the rigid S-curve at the first mode at rest
    td = 1 / (design.f_hz * math.sqrt(1 - design.zeta**2))
    zv = 2 * math.sqrt(0.3 / 100) + 100 / 20000 + td / 2
    assert design.duration_s < zv


def test_the_csv_run_by_simulate_gives_the_reported_residual(slew, capsys):
    design, path = slew
    code = main(["simulate", "--move", str(path), "--N", "8", "--rtol", "1e-4",
                      "--settle", repr(design.settle_s), "--json", "--quiet"])  # fmt: skip
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert out["residual_ym"] == pytest.approx(design.check.residual, rel=1e-6)
    assert out["peak_ym"] == pytest.approx(design.check.peak, rel=1e-6)


def test_the_integrated_angle_is_the_requested_one(slew):
    design, path = slew
    t, omega = _samples(path)
    trapezoid = float(np.sum(np.diff(t) * (omega[1:] + omega[:-1]) / 2))
    assert trapezoid == pytest.approx(0.3, rel=1e-5)  # an independent rule, second order
    assert design.angle_rad == pytest.approx(0.3, rel=1e-7)
    assert integrated_angle(t, omega) == pytest.approx(design.angle_rad, rel=1e-12)


def test_every_limit_holds_at_every_sample(slew):
    _, path = slew
    t, omega = _samples(path)
    assert omega[0] == 0.0 and abs(omega[-1]) < 1e-9
    assert np.max(np.abs(omega)) <= LIMITS["max_speed"] * (1 + 1e-9)
    accel = np.diff(omega) / np.diff(t)  # mean accelerations between samples
    assert np.max(np.abs(accel)) <= LIMITS["max_accel"] * (1 + 1e-9)
    mid = (t[1:] + t[:-1]) / 2
    jerk = np.diff(accel) / np.diff(mid)
    assert np.max(np.abs(jerk)) <= LIMITS["max_jerk"] * (1 + 1e-6)
    # the limits are used, not just kept: the acceleration reaches its limit
    assert np.max(np.abs(accel)) > 0.99 * LIMITS["max_accel"]


def test_a_stiff_beam_takes_the_rigid_time_optimal_move(slew):
    """E x 25: f_1 = 33 Hz.  The design is never shorter than the rigid S-curve's closed-form
    duration 2 sqrt(angle / a) + a / j (speed limit not reached) and at most half a first-mode
    period longer: it tends to it as the beam stiffens (the reference beam's is 58 % longer)."""
    angle = 0.3
    rigid = 2 * math.sqrt(angle / 100) + 100 / 20000
    stiff = rotbeam.design_move(_scene(E=1.22e6 * 25), angle=angle, residual=0.005,
                                baselines=False, **LIMITS)  # fmt: skip
    assert stiff.found and stiff.f_hz > 30
    assert rigid * (1 - 1e-9) <= stiff.duration_s <= rigid + 0.5 / stiff.f_hz
    assert stiff.duration_s / rigid - 1 < 0.5 * (slew[0].duration_s / rigid - 1)


def test_the_time_budget_cuts_the_search_and_says_what_it_found():
    """0.8 s of a search that takes about 2 s on one core."""
    scene = build_scene({"numerics": NUMERICS | {"max_seconds": 0.8}})
    design = rotbeam.design_move(scene, angle=0.3, residual=0.005, baselines=False, **LIMITS)
    assert not design.found
    assert design.message.startswith("cut by the time budget (numerics.max_seconds = 0.8 s)")
    assert ("least residual" in design.message) or ("before the first run" in design.message)


@pytest.mark.slow
def test_the_linear_limit_zvd_vanishes_and_the_design_is_no_longer_than_zv():
    """Small angle, slow: the beam is linear and its frequency stays at rest's; ZVD (and ZV)
    leave < 1 % of the rigid move's residual, as linear theory says, the design is no longer
    than ZV's; at a large fast slew ZV's share grows (stiffening, nonlinearity)."""
    small = rotbeam.design_move(_scene(), angle=0.02, max_speed=1.0, max_accel=5.0,
                                max_jerk=200.0, residual=5e-4)  # fmt: skip
    b = small.baselines
    assert b["zvd"].residual < 0.01 * b["rigid"].residual
    assert b["zv"].residual < 0.01 * b["rigid"].residual
    assert small.found and small.duration_s <= b["zv"].duration_s
    big = rotbeam.design_move(_scene(), angle=0.3, residual=0.005, **LIMITS)
    share = big.baselines["zv"].residual / big.baselines["rigid"].residual
    assert share > 5 * b["zv"].residual / b["rigid"].residual


@pytest.mark.slow
def test_a_spin_up_and_a_payload():
    spin = rotbeam.design_move(_scene(), omega_start=0.0, omega_end=20.0, max_speed=20.0,
                               max_accel=100.0, max_jerk=20000.0, residual=0.005,
                               baselines=False)  # fmt: skip
    assert spin.found and spin.omega[-1] == pytest.approx(20.0, abs=1e-9)
    assert spin.duration_s >= 20 / 100 + 100 / 20000
    # the baselines' mode is the final speed's: stiffened above the resting 6.5 Hz
    assert spin.f_hz > 7.0
    # the rigid S-curve's acceleration phase (0.205 s) is much longer than a first-mode period
    # (0.11-0.15 s): two pulses a period apart beat the textbook ZV's half period added to it
    td = 1 / (spin.f_hz * math.sqrt(1 - spin.zeta**2))
    assert spin.kind.startswith("pulses")
    assert spin.duration_s < 20 / 100 + 100 / 20000 + td / 2
    payload = rotbeam.design_move(_scene(tip_mass=4.68e-4, tip_inertia=1e-8), angle=0.3,
                                  residual=0.005, baselines=False, **LIMITS)  # fmt: skip
    assert payload.found and payload.f_hz == pytest.approx(3.74, rel=0.03)
    assert payload.zeta == pytest.approx(0.0115, rel=0.05)


@pytest.mark.slow
def test_a_tolerance_no_move_meets_says_so_with_the_best_found():
    scene = build_scene({"numerics": {"N": 8, "rtol": 1e-6}})
    design = rotbeam.design_move(scene, angle=0.3, residual=1.5e-5, baselines=False, **LIMITS)
    assert not design.found
    assert design.message.startswith("no move within the limits meets residual 1.5e-05: the best "
                                      "found is ")  # fmt: skip
    assert "at duration" in design.message and "\n" not in design.message


@pytest.mark.parametrize(
    "args, match",
    [
        (["--angle", "0.3", "--max-speed", "0", "--max-accel", "100"],
         r"argument --max-speed: max_speed = 0.0: allowed a finite number > 0"),
        (["--angle", "0.3", "--max-speed", "10", "--max-accel", "-1"],
         r"argument --max-accel: max_accel = -1.0: allowed a finite number > 0"),
        (["--angle", "0.3", "--max-speed", "10", "--max-accel", "100", "--max-jerk", "0"],
         r"argument --max-jerk: max_jerk = 0.0: allowed a finite number > 0"),
        (["--angle", "-0.3", "--max-speed", "10", "--max-accel", "100"],
         r"argument --angle: angle = -0.3: allowed a finite number > 0 rad"),
        (["--omega-start", "0", "--omega-end", "25", "--max-speed", "20", "--max-accel", "100"],
         r"argument --omega-end: omega_end = 25.0 rad/s: allowed \|omega_end\| <= max_speed"),
        (["--angle", "1", "--omega-start", "0", "--omega-end", "5", "--max-speed", "20",
          "--max-accel", "100"], r"give either --angle .* not both and not neither"),
        (["--angle", "1", "--max-speed", "10", "--max-accel", "100", "--residual", "0"],
         r"argument --residual: residual = 0.0: allowed a finite number > 0"),
        (["--angle", "1", "--max-speed", "10", "--max-accel", "100", "--observable", "x"],
         r"'x'"),
        (["--angle", "1", "--max-speed", "10", "--max-accel", "100", "--robust", "E=5%"],
         r"argument --robust: robust 'E=5%': expected name=\+-X% or name=\+-X"),
        (["--angle", "1", "--max-speed", "10", "--max-accel", "100", "--out", "m.txt"],
         r"argument --out: 'm.txt'; allowed: a .csv file"),
    ],
)  # fmt: skip
def test_bad_input_is_one_line(args, match, capsys):
    code = main(["design-move", *args, "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert err.startswith("rotbeam: error: ")
    import re

    assert re.search(match, err), err


def test_a_tolerance_below_what_the_run_resolves_is_refused():
    scene = build_scene({"numerics": {"N": 8, "rtol": 1e-3}})
    match = r"residual = 0.0001: below what the run resolves, .* \(100 x numerics.rtol = 0.001"
    with pytest.raises(RotbeamInputError, match=match):
        rotbeam.design_move(scene, angle=0.3, residual=1e-4, baselines=False, **LIMITS)


@pytest.mark.slow
def test_a_robust_design_holds_at_every_corner_and_costs_duration(slew):
    """E +-5 %, gamma +-25 %: the design holds at all four corners, each run again
    independently (a scene with E and gamma set by hand, through `rotbeam.runs`), and is no
    shorter than the nominal design."""
    from rotbeam.analysis.move_check import move_scene
    from rotbeam.runs.move import simulate_move

    robust = rotbeam.design_move(_scene(), angle=0.3, residual=0.005,
                                 robust="E=+-5%,gamma=+-25%", baselines=False,
                                 **LIMITS)  # fmt: skip
    labels = {"E+ gamma+", "E+ gamma-", "E- gamma+", "E- gamma-"}
    assert robust.found and set(robust.corner_residuals) == labels
    assert robust.robust_residual == max(robust.corner_residuals.values()) <= 0.005
    for label in labels:
        e = 1.22e6 * (1.05 if "E+" in label else 0.95)
        gamma = 0.039 * (1.25 if "gamma+" in label else 0.75)
        scene = move_scene(_scene(E=e, gamma=gamma), robust.t, robust.omega, robust.settle_s)
        again = simulate_move(scene).residual_ym
        assert again == pytest.approx(robust.corner_residuals[label], rel=1e-6)
        assert again <= 0.005
    assert robust.duration_s >= slew[0].duration_s


def _search(robust=None):
    """A search of the cheap slew (nothing run yet), with the box's corners if given."""
    from rotbeam.analysis.motion import Limits
    from rotbeam.analysis.move_box import corners, parse_box
    from rotbeam.analysis.move_design import _request, _Search
    from rotbeam.solve.timebudget import TimeBudget

    scene = _scene()
    limits = Limits(LIMITS["max_speed"], LIMITS["max_accel"], LIMITS["max_jerk"])
    request = _request(0.3, None, None, limits, 0.005, "y_m")
    boxed = corners(scene, parse_box(robust))
    return _Search(scene, limits, request, boxed, None, TimeBudget(60.0))


def test_the_corners_are_checked_worst_first_until_one_misses(monkeypatch):
    """The full model runs the corner of largest inner residual first, then the next, and stops
    at the first that misses: a design that fails at a corner costs one corner run, not four."""
    from types import SimpleNamespace

    from rotbeam.analysis.move_design import Evaluation

    search = _search("E=+-5%,gamma=+-25%")
    fam = search.families[0]
    params = search.start(fam, True)
    ev = Evaluation(fam, params, 1.0, 0.2, 0.001, (), 0.0)
    inner = [0.002, 0.004, 0.001, 0.003]  # corners 0..3 on the inner model
    for k, r in enumerate(inner):
        search.runs[(k + 1, fam, params)] = (r, (0j, 0j))
    full = {0: 0.004, 1: 0.0045, 2: 0.001, 3: 0.006}  # corner 3 misses on the full model
    ran = []

    def fake_full(motion, scene=None):
        k = [s for _, s in search.boxed].index(scene)
        ran.append(k)
        return SimpleNamespace(residual=full[k])

    monkeypatch.setattr(search, "full", fake_full)
    got = search._corners(ev)
    assert ran == [1, 3]  # inner 0.004 first, then 0.003, which misses: no more runs
    assert list(got.values()) == [0.0045, 0.006]
    full[3] = 0.002  # all hold: every corner, worst inner first
    ran.clear()
    got = search._corners(ev)
    assert ran == [1, 3, 0, 2] and len(got) == 4


def test_a_second_mode_train_starts_from_the_root_without_it():
    """A +m2 family starts at the unknowns of the least residual found for the same family
    without the train (once that was searched), and its train at half the second period."""
    from rotbeam.analysis.move_design import Evaluation

    search = _search()
    base = next(f for f in search.families if f.second_s == 0 and f.kind == "zv")
    m2 = next(f for f in search.families if f.second_s > 0 and f.kind == "zv"
              and f.ramp == base.ramp)  # fmt: skip
    linear = search.start(m2)
    root = (0.9 * linear[0], 0.1)
    for params, residual in ((linear[:2], 0.01), (root, 0.002), ((linear[0], 0.3), 0.004)):
        search.evaluations.append(Evaluation(base, params, 1.0, 0.2, residual, (), 0.0))
    search.floors[base] = 0.001
    assert search.start(m2) == (*root, m2.second_s, math.log(m2.second_ratio))
    assert search.start(m2, True) == linear  # the families' order does not run the search


@pytest.mark.parametrize("beam", [
    pytest.param({}, id="bare"),
    pytest.param({"tip_mass": 4.68e-4, "tip_inertia": 1e-8}, id="payload", marks=pytest.mark.slow),
])  # fmt: skip
def test_the_stepper_error_is_a_small_share_of_what_a_design_resolves(beam):
    """The move stepper's residual and peak at rtol = 1e-5 and 1e-4 (its absolute tolerance
    set by rtol, `rotbeam.runs.move.ATOL_SHARE`) against a run at rtol = 1e-7: within 1/30 of
    the least residual a design resolves (RESOLVE x rtol x peak)."""
    from rotbeam.analysis.motion import Limits, rigid_slew
    from rotbeam.analysis.move_check import check_move
    from rotbeam.analysis.move_design import RESOLVE, first_mode
    from rotbeam.analysis.shapers import for_mode, shape

    def run(rtol):
        scene = build_scene({"beam": beam, "numerics": {"N": 8, "rtol": rtol}})
        return check_move(scene, move, 8.0, "y_m", 2 / f)

    f, zeta = first_mode(build_scene({"beam": beam, "numerics": {"N": 8}}), 0.0)
    limits = Limits(LIMITS["max_speed"], LIMITS["max_accel"], LIMITS["max_jerk"])
    move = shape(rigid_slew(0.3, limits), for_mode("zv", f, zeta))
    ref = run(1e-7)
    for rtol in (1e-5, 1e-4):
        got = run(rtol)
        floor = RESOLVE * rtol * got.peak
        assert abs(got.residual - ref.residual) < floor / 30
        assert abs(got.peak - ref.peak) < floor / 30


def test_two_trains_start_from_one_train_rooted_at_each_target_corner(monkeypatch):
    """zv2 starts from the root of one ZV train alone (no second-mode train) at each of its two
    target corners, in the targets' order, their log K split apart (off K_1 = K_2, where the
    trains' amplitudes are singular in them): the unknowns (s_1, log K_1, s_2, log K_2)."""
    from types import SimpleNamespace

    from rotbeam.analysis.move_design import SPLIT_LOG_RATIO

    search = _search("E=+-5%,gamma=+-25%")
    zv2 = next(f for f in search.families if f.kind == "zv2" and f.second_s == 0)
    asked = []

    def fake_root(fam):
        asked.append(fam)
        return SimpleNamespace(params=(0.07 + fam.at / 1000, -0.1 * fam.at)), None, None

    monkeypatch.setattr(search, "_root", fake_root)
    a, b = search.targets(zv2)
    assert a != b
    split = SPLIT_LOG_RATIO
    assert search.start(zv2) == pytest.approx(
        (0.07 + a / 1000, -0.1 * a + split, 0.07 + b / 1000, -0.1 * b - split), abs=1e-15
    )
    assert [(f.kind, f.at, f.second_s, f.ramp) for f in asked] == [
        ("zv", a, 0.0, zv2.ramp), ("zv", b, 0.0, zv2.ramp)]  # fmt: skip
    # the targets: the corners of the longest and of the shortest half period met
    halves = search.halves[1:]
    assert (a, b) == (1 + halves.index(max(halves)), 1 + halves.index(min(halves)))


@pytest.mark.parametrize("rigid, skipped", [(1.0, True), (0.01, False)])
def test_one_train_is_not_searched_where_it_misses_the_box_in_linear_theory(
    monkeypatch, rigid, skipped
):
    """With a box, zv (and zv+m2) is skipped where pi eps / 2 of the rigid move's inner
    residual exceeds the tolerance, eps the box's half spread of half periods; zv2 is not."""
    from types import SimpleNamespace

    search = _search("E=+-5%,gamma=+-25%")
    eps = (max(search.halves) - min(search.halves)) / (2 * search.halves[0])
    assert 0.01 < eps < 0.05  # E +-5 %: about +-2.5 % in the first frequency
    assert (0.5 * math.pi * eps * rigid > 0.005) == skipped
    monkeypatch.setattr(search, "_run", lambda scene, motion: SimpleNamespace(residual=rigid))
    searched = []

    def fake_root(fam):
        searched.append(fam)
        raise StopIteration  # searched: no need to go on

    monkeypatch.setattr(search, "_root", fake_root)
    for fam in search.families:
        try:
            assert search._search(fam) == []
        except StopIteration:
            pass
    kinds = {f.name for f in searched}
    assert ("zv" in kinds or "zv+m2" in kinds) != skipped and "zv2" in kinds


def test_a_second_mode_train_is_judged_by_the_least_first_mode_part():
    """Whether a +m2 family is worth a search: what a second-mode train leaves of the family
    without it, its residual less the second mode's amplitude, the least over all its
    candidates; not the least-residual candidate's, which may hold more of the first mode."""
    from rotbeam.analysis.move_design import Evaluation

    search = _search()
    base = next(f for f in search.families if f.second_s == 0 and f.kind == "zv")
    start = search.start(base, True)
    # (residual, second mode's amplitude): the least residual leaves 0.011 of the first mode,
    # the other candidate 0.003
    for k, (residual, second) in enumerate(((0.013, 0.002), (0.015, 0.012))):
        params = (start[0] * (1 + 0.01 * k), start[1])
        search.evaluations.append(Evaluation(base, params, 1.0, 0.2, residual, (), 0.0))
        search.runs[(0, base, params)] = (residual, (0j, complex(second, 0.0)))
    assert search._floor(base) == pytest.approx(0.003)
