"""`rotbeam sweep` and the sweeps of the workflow (one implementation, rotbeam.runs.sweeps):
its rows are `rotbeam simulate`'s at the same points, its time budget cuts the line between
points, and the faster paths (continuation from a neighbour's orbit resampled to the scene's
own M, the Floquet step ladder, the shared quasi-static chord) give the benchmark scenes'
numbers to their stated errors."""

from __future__ import annotations

import contextlib
import io
import json
import re
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pandas as pd
import pytest
from conftest import ROOT

import rotbeam.runs.sweeps
from rotbeam.bench.plan import SCENES
from rotbeam.cli import main
from rotbeam.model.params import Beam, Drive
from rotbeam.runs.scene import Scene, simulate
from rotbeam.runs.sweeps import COLUMNS, scan_line, sweep
from rotbeam.solve.floquet import SPREAD_TOL, beam_floquet
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.quasistatic import batched_static, solve_static

#: Newton's step tolerance on the orbit is 1e-10 of its size: two starts that converge to the
#: same collocated orbit give RMS values this close (relative)
RMS_RTOL = 1e-8


def cli(*argv: str) -> tuple[int, str, str]:
    """`rotbeam` in-process: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(list(argv))
    return rc, out.getvalue(), err.getvalue()


def test_sweep_rows_equal_simulate_at_the_same_points(tmp_path):
    """A line through resonance (5 rad/s, 2-14 Hz, N = 12; the peak at 7 Hz needs M = 129, the
    points on either side 17 or 33), each point continued from its neighbour's orbit, against
    `rotbeam simulate` started afresh at every point: the same RMS, quasi-static RMS and Delta
    RMS to Newton's tolerance and the same |mu|max to the multipliers' stated error; the CSV
    holds the same rows as the JSON."""
    out = tmp_path / "line.csv"
    p = subprocess.run(
        [sys.executable, "-m", "rotbeam", "sweep", "--omega0", "5", "--fd-min", "2",
         "--fd-max", "14", "--points", "13", "--N", "12", "--json", "--out", str(out)],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert p.returncode == 0, p.stderr
    line = json.loads(p.stdout)
    assert line["complete"] and line["ran"] == line["points"] == 13 and line["message"] == ""
    rows = line["rows"]
    assert [r["f_d"] for r in rows] == pytest.approx(np.linspace(2, 14, 13).tolist(), rel=1e-12)
    assert max(r["rms_dynamic"] for r in rows) > 5 * rows[0]["rms_dynamic"]  # a resonance
    for r in rows:
        rc, text, err = cli("simulate", "--omega0", "5", "--fd", repr(r["f_d"]), "--N", "12",
                            "--json", "--quiet")  # fmt: skip
        assert rc == 0, err
        one = json.loads(text)
        for key in ("rms_dynamic", "rms_quasistatic", "delta_rms"):
            assert r[key] == pytest.approx(one[key], rel=RMS_RTOL), (r["f_d"], key)
        assert abs(r["floquet_max"] - one["floquet_max"]) <= SPREAD_TOL
        assert (r["converged"], r["status"], r["stable"]) == (True, 0, one["stable"])
        # the same collocation size: continuation starts at the scene's own M0, not the
        # neighbour's (the RMS cannot tell: a resolved orbit's tail is below 1e-6)
        assert re.search(r"M=(\d+)", r["message"])[1] == re.search(r"M=(\d+)", one["message"])[1]
    csv = pd.read_csv(out)
    assert list(csv.columns) == COLUMNS and len(csv) == 13
    assert np.allclose(csv["rms_dynamic"], [r["rms_dynamic"] for r in rows], rtol=1e-12)


def test_the_workflow_sweep_is_the_command_line_sweep():
    """`scan_line` (the workflow's lines) and `rotbeam sweep` run the same code: the same rows
    for the same line, but for the seconds."""
    rc, text, err = cli("sweep", "--omega0", "20", "--fd-min", "1", "--fd-max", "4", "--points",
                        "3", "--N", "8", "--json", "--quiet")  # fmt: skip
    assert rc == 0, err
    by_cli = pd.DataFrame(json.loads(text)["rows"])
    by_workflow = scan_line(Beam(), 20.0, [1.0, 2.5, 4.0], numerics=Numerics(N=8))
    keep = [c for c in COLUMNS if c not in ("seconds", "message")]
    pd.testing.assert_frame_equal(by_cli[keep], by_workflow[keep], check_dtype=False)


def test_budget_cuts_the_line_between_points():
    """numerics.max_seconds is the budget of the whole line: spent before the second point,
    the line stops there with the rows so far, says where, and exits with status 1."""
    rc, text, err = cli("sweep", "--omega0", "5", "--fd-min", "1", "--fd-max", "3", "--points",
                        "4", "--N", "6", "--max-seconds", "1e-9", "--json", "--quiet")  # fmt: skip
    assert rc == 1, err
    line = json.loads(text)
    assert not line["complete"] and line["ran"] < 4 and len(line["rows"]) == line["ran"]
    assert f"cut the line at point {line['ran'] + 1} of 4" in line["message"]
    assert line["message"].startswith("the time budget of 1e-09 s cut the line")
    rc, text, _ = cli("sweep", "--omega0", "5", "--fd-min", "1", "--fd-max", "3", "--points",
                      "4", "--N", "6", "--max-seconds", "1e-9", "--quiet")  # fmt: skip
    assert rc == 1 and "budget" in text and "cut the line" in text


def test_each_point_gets_its_share_of_what_is_left(monkeypatch):
    """A point's steady state may spend what is left of the line's budget divided by the points
    left, so that one point without a steady state cannot take the whole line's."""
    budgets = []
    real = rotbeam.runs.sweeps.simulate

    def recording(scene, **kw):
        budgets.append(kw["time_budget"].seconds)
        return real(scene, **kw)

    monkeypatch.setattr(rotbeam.runs.sweeps, "simulate", recording)
    total, f_ds = 600.0, [1.0, 2.0, 3.0, 4.0]
    line = sweep(Scene(Beam(), Drive(omega0=5.0), numerics=Numerics(N=6, max_seconds=total)),
                 f_ds)  # fmt: skip
    assert line.complete and len(budgets) == 4
    spent = np.cumsum([0.0, *line.rows["seconds"][:-1]])
    for k, budget in enumerate(budgets):
        assert budget <= (total - spent[k]) / (4 - k) * (1 + 1e-9)
        assert budget >= (total - spent[k] - 1.0) / (4 - k)  # up to the bookkeeping between


def test_a_move_is_not_swept(tmp_path):
    """A single move has no drive frequency: one line naming it, exit status 2."""
    move = ROOT / "config" / "scenes" / "sin2_move.csv"
    scene = tmp_path / "s.yaml"
    scene.write_text(f"drive: {{move: {move}}}\n")
    rc, out, err = cli("sweep", "--scene", str(scene), "--fd-min", "1", "--fd-max", "2")
    assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert "periodic drive" in err and "move" in err


@pytest.mark.slow
@pytest.mark.parametrize("label, omega0, f_d", SCENES, ids=[s[0] for s in SCENES])
def test_faster_paths_keep_the_benchmark_scenes_numbers(label, omega0, f_d):
    """At each benchmark scene (N = 40, default numerics): the point reached by continuation
    from a neighbour 10 % below it has simulate's RMS, quasi-static RMS and Delta RMS to
    Newton's tolerance and its |mu|max to SPREAD_TOL; the reported |mu|max is within
    SPREAD_TOL of the same rule converged in the step count (3000 steps); the quasi-static
    series of the shared chord is the per-instant static solution's to 1e-9."""
    scene = Scene(Beam(), Drive(omega0=omega0, f_d=f_d))
    alone = simulate(scene)
    continued = sweep(scene, [0.9 * f_d, f_d]).rows.iloc[-1]
    assert continued["converged"] and alone.converged
    for key in ("rms_dynamic", "rms_quasistatic", "delta_rms"):
        assert continued[key] == pytest.approx(getattr(alone, key), rel=RMS_RTOL), key
    assert abs(continued["floquet_max"] - alone.dynamic.floquet.max_abs) <= SPREAD_TOL
    orbit, model = alone.dynamic.periodic, scene.model()
    converged = beam_floquet(model, orbit.theta, orbit.theta_t, steps=3000)
    assert abs(alone.dynamic.floquet.max_abs - converged.max_abs) <= SPREAD_TOL
    taus = np.arange(16) / 16 * model.dl.period
    lam, lam_dot = model.drive_rows(taus)
    chord = batched_static(model, lam, lam_dot)
    single = np.array([solve_static(model, a, b).theta for a, b in zip(lam, lam_dot, strict=True)])
    assert np.max(np.abs(chord - single)) <= 1e-9 * np.max(np.abs(single))


@pytest.mark.slow
def test_a_point_without_a_periodic_state_takes_only_its_share():
    """100 rad/s just past the fold of the resonant branch (33.72 Hz; the branch from below
    folds at 33.10 Hz, the one from above at 34.07 Hz, and time stepping finds no steady state
    there): in a line of four points with a budget of 8 s the point runs out of its share, not
    of the line's, and the points after it still run."""
    scene = Scene(Beam(), Drive(omega0=100.0), numerics=Numerics(max_seconds=8.0))
    line = sweep(scene, [32.82, 33.72, 34.62, 35.51])
    rows = line.rows.set_index("f_d")
    assert line.complete and len(rows) == 4
    assert not rows.loc[33.72, "converged"] and "time budget" in rows.loc[33.72, "message"]
    assert rows.loc[33.72, "seconds"] < 8.0 / 3 + 1.0
    assert rows.loc[32.82, "converged"] and rows.loc[35.51, "converged"]


def test_scene_file_drive_with_harmonics_sweeps(tmp_path):
    """The scene file's drive (two harmonics) is swept as it is, f_d replaced point by point:
    the rows are simulate's at those points."""
    scene = tmp_path / "two.yaml"
    scene.write_text(
        "drive:\n  omega0: 20\n  harmonics:\n    - {k: 1, amplitude: 1.0, phase: 0.0}\n"
        "    - {k: 3, amplitude: 0.5, phase: 0.7}\nnumerics: {N: 8}\n"
    )
    rc, text, err = cli("sweep", "--scene", str(scene), "--fd-min", "1", "--fd-max", "2",
                        "--points", "2", "--json", "--quiet")  # fmt: skip
    assert rc == 0, err
    rows = json.loads(text)["rows"]
    from rotbeam.runs.scene import load_scene

    base = load_scene(scene)
    for r in rows:
        one = simulate(replace(base, drive=replace(base.drive, f_d=r["f_d"])))
        assert r["rms_dynamic"] == pytest.approx(one.rms_dynamic, rel=RMS_RTOL)
        # the drive's largest swing about its mean, not the sine's field
        x = np.linspace(0.0, 1.0, 100001)
        swing = np.max(np.abs(np.sin(2 * np.pi * x) + 0.5 * np.sin(6 * np.pi * x + 0.7)))
        assert r["amplitude"] == pytest.approx(swing, rel=1e-6)
        assert r["omega0"] == 20.0
