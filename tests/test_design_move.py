"""`rotbeam design-move` and `rotbeam.design_move` against independent answers: the designed
move run again from its CSV by `rotbeam simulate --move`, its angle and limits from the CSV's
samples by finite differences, the rigid-body limit of a stiff beam (closed-form time-optimal
duration), the linear limit (ZVD's residual vanishes; the design is no longer than ZV's), a
spin-up, a payload, the time budget's cut and bad input in one line.

Cheap settings: a grid of N = 8, numerics.rtol = 1e-4 (the residual moves by 1e-5 L), a jerk
limit (steps in the acceleration ring every mode and cost the stepper 20x more)."""

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
    scene = build_scene({"numerics": NUMERICS | {"max_seconds": 1.5}})
    design = rotbeam.design_move(scene, angle=0.3, residual=0.005, baselines=False, **LIMITS)
    assert not design.found
    assert design.message.startswith("cut by the time budget (numerics.max_seconds = 1.5 s)")
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
