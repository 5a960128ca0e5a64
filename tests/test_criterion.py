"""The verdict and the f_d* search on another observable (`--criterion`, `judge(...,
criterion=)`, `critical(..., criterion=)`), and the observables in the user scenes' table.

y_m stays the default and its answers do not move; another criterion's Delta RMS is that
observable's over the same window; the search's root is where a separate run's Delta RMS of
the criterion meets the threshold; in the linear regime each observable's Delta RMS and f_d*
agree with the clamped-free beam's modal series, where only a one-mode response would give
every observable the same answer (docs/model.md, "The verdict on another observable")."""

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import rotbeam
from rotbeam.analysis.scenes import COLUMNS, judge_scenes
from rotbeam.analysis.verdict import criterion_delta_rms, judge_move
from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.modes import damping_ratio, resonance_frequency_hz
from rotbeam.runs.move import simulate_move
from rotbeam.runs.observables import OBSERVABLES
from rotbeam.runs.scene import build_scene, simulate

ROOT = Path(__file__).resolve().parents[1]
ALLOWED = "allowed: y_m, tip, root_moment, root_stress, tip_acceleration"


def run(*args):
    return subprocess.run([sys.executable, "-m", "rotbeam", *args], capture_output=True,
                          text=True, timeout=300)  # fmt: skip


def sine(omega0=5.0, f_d=2.0, N=10, amplitude=1.0):
    return build_scene({"drive": {"omega0": omega0, "amplitude": amplitude, "f_d": f_d},
                        "numerics": {"N": N}})  # fmt: skip


def test_y_m_is_the_default_and_its_answers_do_not_move():
    res = simulate(sine())
    plain, named = rotbeam.judge(res, 0.1), rotbeam.judge(res, 0.1, criterion="y_m")
    assert plain == named and named.criterion == "y_m"
    assert named.delta_rms == res.delta_rms  # the scene's own number, bit for bit
    assert f"Delta RMS {res.delta_rms:.3g} < 0.1 (" in named.text and " of " not in named.text
    a, b = rotbeam.critical(sine(), 0.1), rotbeam.critical(sine(), 0.1, criterion="y_m")
    assert (a.f_d_star, a.visited, a.message) == (b.f_d_star, b.visited, b.message)
    # the CLI: --criterion y_m changes no key of the default output
    base = ("simulate", "--omega0", "5", "--fd", "2", "--N", "10", "--json")
    d0, d1 = (json.loads(run(*base, *extra).stdout) for extra in ((), ("--criterion", "y_m")))
    assert {k for k in d0 if d0[k] != d1[k]} <= {"seconds"}
    assert d1["criterion"] == "y_m" and d1["criterion_delta_rms"] == d1["delta_rms"]


def test_root_moment_verdict_is_the_observables_delta_rms():
    res = simulate(sine())
    table = res.observables("root_moment,root_stress")
    v = rotbeam.judge(res, 0.1, criterion="root_moment")
    assert v.delta_rms == table["root_moment"]["delta_rms"]
    assert v.criterion == "root_moment" and "Delta RMS of root_moment" in v.text
    assert "the first mode's" in v.text
    # the stress is the moment times h / (2 I): the same Delta RMS
    stress = rotbeam.judge(res, 0.1, criterion="root_stress").delta_rms
    assert stress == pytest.approx(v.delta_rms, rel=1e-12)
    assert abs(v.delta_rms / res.delta_rms - 1) > 0.03  # a different number from y_m's
    p = run("simulate", "--omega0", "5", "--fd", "2", "--N", "10", "--criterion", "root_moment",
            "--json")  # fmt: skip
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    assert d["criterion"] == "root_moment"
    assert d["criterion_delta_rms"] == d["observables"]["root_moment"]["delta_rms"]
    assert d["criterion_delta_rms"] == pytest.approx(v.delta_rms, rel=1e-12)
    assert d["delta_rms"] == pytest.approx(res.delta_rms, rel=1e-12)  # the summary's: y_m's


def test_critical_on_root_moment_meets_a_separate_run():
    """rotbeam critical --criterion root_moment, then rotbeam simulate at its f_d*: the
    criterion's Delta RMS there is the threshold to the search's tolerance in f_d."""
    ftol = 1e-3
    p = run("critical", "--omega0", "5", "--N", "10", "--criterion", "root_moment",
            "--ftol", str(ftol), "--json")  # fmt: skip
    assert p.returncode == 0, p.stderr
    c = json.loads(p.stdout)
    assert c["found"] and c["criterion"] == "root_moment"
    f_star = c["f_d_star"]
    p = run("simulate", "--omega0", "5", "--fd", repr(f_star), "--N", "10", "--criterion",
            "root_moment", "--json")  # fmt: skip
    d = json.loads(p.stdout)["criterion_delta_rms"]
    # the slope dDelta/df_d from the search's own runs bounds Delta's error at rtol ftol
    (f1, d1), (f2, d2) = sorted(c["visited"], key=lambda v: abs(v[0] - f_star))[1:3]
    slope = abs((d2 - d1) / (f2 - f1))
    assert abs(d - 0.1) <= slope * ftol * f_star
    # and it is not y_m's root
    y = rotbeam.critical(sine(), 0.1, ftol)
    assert f_star > y.f_d_star * (1 + 10 * ftol)


def modal_delta_rms(beam, f0, zeta, f_d, modes=30):
    """Delta RMS of y_m, tip and the root moment of the linear clamped-free beam under the Euler
    load rho A Omega-dot (R_o + s), one harmonic at f_d: mode j carries the share w_j of each
    observable's static value and its response is H_j = 1 / (1 - r_j^2 + 2 i zeta r_j),
    r_j = f_d / f_j, f_j = f0 (beta_j / beta_1)^2, so RMS_dyn / RMS_qs = |sum_j w_j H_j|."""
    x = np.linspace(0.0, 1.0, 40001)
    betas = [brentq(lambda z: math.cos(z) + 1 / math.cosh(z), (j + 0.5) * math.pi - 0.5,
                    (j + 0.5) * math.pi + 0.5) for j in range(modes)]  # fmt: skip
    share = {"y_m": [], "tip": [], "root_moment": []}
    for b in betas:
        s = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
        one_minus_s = (math.sin(b) - math.cos(b) - math.exp(-b)) / (math.sinh(b) + math.sin(b))
        # cosh bx - s sinh bx = e^-bx (1 + s) / 2 + e^bx (1 - s) / 2, without cancellation
        phi = (np.exp(-b * x) * (2 - one_minus_s) / 2 + np.exp(b * x) * one_minus_s / 2
               - np.cos(b * x) + s * np.sin(b * x))  # fmt: skip
        q = np.trapezoid((beam.hub_ratio + x) * phi, x) / np.trapezoid(phi * phi, x) / b**4
        share["y_m"].append(q * np.interp(0.5, x, phi))
        share["tip"].append(q * phi[-1])
        share["root_moment"].append(q * 2 * b**2)  # phi''(0) = 2 beta^2
    r = f_d / f0 / (np.asarray(betas) / betas[0]) ** 2
    H = 1.0 / (1.0 - r**2 + 2j * zeta * r)
    out = {}
    for name, w in share.items():
        ratio = abs(np.sum(np.asarray(w) * H)) / abs(np.sum(w))
        out[name] = abs(ratio - 1.0) / ratio
    return out, {name: w[0] / sum(w) for name, w in share.items()}


def test_linear_regime_follows_the_modal_series_not_one_mode():
    """Omega_0 = 0 and a small sine: each observable's Delta RMS (at N = 20) and f_d* agree with
    the modal series to the grid's O(1/N^2); the first-mode shares differ (root moment 0.91,
    y_m 0.98, tip 1.01 at R_o / L = 2.875), so f_d* does too, and only the tip's lies within
    1 % of the first mode's estimate c_0 f_0."""
    A, N = 0.02, 20
    scene = sine(omega0=0.0, amplitude=A, N=N)
    beam = scene.beam
    f0, zeta = resonance_frequency_hz(beam, A), damping_ratio(beam)
    res = simulate(scene)
    want, w1 = modal_delta_rms(beam, f0, zeta, 2.0)
    assert w1["root_moment"] < 0.92 and 0.97 < w1["y_m"] < 1.0 < w1["tip"]
    for name, d in want.items():
        assert criterion_delta_rms(res, name) == pytest.approx(d, rel=5e-3), name
    stars = {}
    for name in want:
        cr = rotbeam.critical(scene, 0.1, 1e-4, criterion=name)
        f_modal = brentq(lambda f, n=name: modal_delta_rms(beam, f0, zeta, f)[0][n] - 0.1,
                         1.0, 3.0, rtol=1e-8)  # fmt: skip
        assert cr.f_d_star == pytest.approx(f_modal, rel=3e-3), name
        stars[name] = cr.f_d_star
        estimate = cr.estimate_hz
    assert stars["tip"] < stars["y_m"] < stars["root_moment"]
    assert stars["root_moment"] / estimate > 1.03
    assert abs(stars["tip"] / estimate - 1) < 0.01


def test_a_bad_criterion_is_one_line():
    res = simulate(sine(N=6))
    with pytest.raises(RotbeamInputError, match=f"'bending' is not an observable; {ALLOWED}"):
        rotbeam.judge(res, 0.1, criterion="bending")
    with pytest.raises(RotbeamInputError, match=ALLOWED):
        rotbeam.critical(sine(N=6), 0.1, criterion="tip,y_m")
    for cmd in (("simulate", "--fd", "2"), ("critical",)):
        p = run(*cmd, "--omega0", "5", "--N", "6", "--criterion", "bending")
        assert p.returncode == 2 and "Traceback" not in p.stderr
        assert len(p.stderr.strip().splitlines()) == 1 and ALLOWED in p.stderr
    p = run("simulate", "--omega0", "5", "--fd", "2", "--N", "6", "--criterion", "tip",
            "--uncertainty", "gamma=0.039+-0.008")  # fmt: skip
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1
    assert "--criterion tip" in p.stderr


def test_help_names_the_criterion_and_every_observable():
    for cmd in ("simulate", "critical"):
        text = " ".join(run(cmd, "--help").stdout.split())
        help_text = text[text.index("--criterion NAME judge") :][:300]
        assert all(name in help_text for name in OBSERVABLES), cmd


def test_a_move_judged_on_the_root_moment(tmp_path):
    path = tmp_path / "ramp.csv"
    t = np.linspace(0.0, 0.02, 9)
    path.write_text("t,omega\n" + "".join(f"{a:.17g},{2.0 + 100.0 * a:.17g}\n" for a in t))
    res = simulate_move(build_scene({"drive": {"move": str(path), "settle": 0.01},
                                     "numerics": {"N": 6}}))  # fmt: skip
    assert judge_move(res, 0.1) == judge_move(res, 0.1, "y_m")
    assert judge_move(res, 0.1).delta_rms == res.delta_rms
    v = judge_move(res, 0.1, "root_moment")
    assert v.delta_rms == res.observables("root_moment")["root_moment"]["delta_rms"]
    assert "Delta RMS of root_moment" in v.text


#: two tiny scenes: a sine and a move (the config's sin^2 move, a short settling window)
SPECS = {
    "sine": {"drive": {"omega0": 5, "f_d": 2}, "numerics": {"N": 8}},
    "move": {"drive": {"move": "scenes/sin2_move.csv", "settle": 0.05}, "numerics": {"N": 8}},
}


def test_user_scenes_table_carries_the_observables():
    observe = ["y_m", "tip", "root_moment", "tip_acceleration"]
    table = judge_scenes(SPECS, 0.1, ROOT / "config", observe)
    named = ["rms_dynamic_{}", "rms_quasistatic_{}", "delta_rms", "peak_dynamic_{}",
             "peak_quasistatic_{}", "residual_{}"]  # fmt: skip
    units = {"y_m": "L", "tip": "L", "root_moment": "N_m", "tip_acceleration": "m_s2"}
    want = [f"{o}_{c.format(units[o])}" for o in observe for c in named]
    assert list(table.columns) == COLUMNS + want
    sine_row, move_row = table.iloc[0], table.iloc[1]
    # y_m's columns repeat the table's own (one path through the observables, one not)
    for row in (sine_row, move_row):
        assert row["y_m_rms_dynamic_L"] == pytest.approx(row["rms_dynamic"], rel=1e-12)
        assert row["y_m_delta_rms"] == pytest.approx(row["delta_rms"], rel=1e-12)
        for o in observe:
            dyn, qs = row[f"{o}_rms_dynamic_{units[o]}"], row[f"{o}_rms_quasistatic_{units[o]}"]
            assert row[f"{o}_delta_rms"] == pytest.approx(abs(dyn - qs) / dyn, rel=1e-12)
            assert row[f"{o}_peak_dynamic_{units[o]}"] >= dyn  # a peak is at least the RMS
    assert move_row["y_m_peak_dynamic_L"] == move_row["peak_ym"]
    assert move_row["y_m_residual_L"] == move_row["residual_ym"]
    assert math.isnan(sine_row["tip_residual_L"]) and move_row["tip_residual_L"] > 0
    # the sine's root moment against the same scene simulated alone
    alone = simulate(build_scene(SPECS["sine"])).observables("root_moment")["root_moment"]
    assert sine_row["root_moment_rms_dynamic_N_m"] == alone["rms_dynamic"]


def test_user_scenes_table_without_observables_and_a_bad_name():
    table = judge_scenes({"sine": SPECS["sine"]}, 0.1, ROOT / "config")
    assert list(table.columns) == COLUMNS
    assert list(judge_scenes({"sine": SPECS["sine"]}, 0.1, ROOT / "config", []).columns) == COLUMNS
    with pytest.raises(RotbeamInputError, match=f"user_scenes_observe: .*'bending'.*{ALLOWED}"):
        judge_scenes({"sine": SPECS["sine"]}, 0.1, ROOT / "config", ["tip", "bending"])
