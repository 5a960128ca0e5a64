"""The atlas of the phase plane (`rotbeam atlas`, `rotbeam.atlas`): its rows are `rotbeam
simulate`'s at the same points, the command line and the API give the same rows, a time budget
that cuts it says which lines and points it reached, bad input is one line, and the f_d*
boundary it draws lies between the grid points around `rotbeam critical`'s f_d*."""

from __future__ import annotations

import contextlib
import io
import json
import time

import numpy as np
import pandas as pd
import pytest

import rotbeam
import rotbeam.runs.atlas
from rotbeam.cli import main
from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.params import Beam, Drive
from rotbeam.runs.atlas import ATLAS_COLUMNS, NOT_RUN, grid_axes
from rotbeam.runs.scene import Scene
from rotbeam.solve.floquet import SPREAD_TOL
from rotbeam.solve.numerics import Numerics

#: two starts that converge to the same collocated orbit give RMS values this close (relative):
#: Newton's step tolerance on the orbit is 1e-10 of its size (tests/test_sweep.py)
RMS_RTOL = 1e-8
N = 12
#: a 2 x 3 grid: 5 rad/s crosses the threshold between 2 and 5 Hz (f_d* = 2.16 Hz), 40 rad/s
#: between 5 and 8 Hz
OMEGA0S, F_DS = [5.0, 40.0], [2.0, 5.0, 8.0]
GRID = ["--omega0-min", "5", "--omega0-max", "40", "--fd-min", "2", "--fd-max", "8",
        "--points", "2,3", "--N", str(N)]  # fmt: skip
#: what differs between two runs of the same point: wall time, and the message's timings
VARYING = ("seconds", "message")


def cli(*argv: str) -> tuple[int, str, str]:
    """`rotbeam` in-process: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(list(argv))
    return rc, out.getvalue(), err.getvalue()


def scene(**numerics) -> Scene:
    return Scene(Beam(), Drive(omega0=1.0, f_d=1.0), numerics=Numerics(N=N, **numerics))


@pytest.fixture(scope="module")
def by_api():
    """The 2 x 3 atlas through the API, its lines in two processes."""
    return rotbeam.atlas(scene(), OMEGA0S, F_DS, workers=2)


def test_an_atlas_row_equals_simulate_at_the_same_point(by_api):
    """Every row of the atlas (a sweep line per Omega_0, each point continued from its
    neighbour, in a worker process) against `rotbeam simulate` started afresh at that point:
    the same RMS of both models and Delta RMS to Newton's tolerance, |mu|max to the
    multipliers' stated error, the same status."""
    rows = by_api.rows
    assert len(rows) == 6 and rows["ran"].all() and by_api.complete and by_api.message == ""
    assert by_api.workers == 2
    assert sorted(zip(rows["omega0"], rows["f_d"], strict=True)) == [
        (w, f) for w in OMEGA0S for f in F_DS
    ]
    for r in rows.to_dict(orient="records"):
        rc, text, err = cli("simulate", "--omega0", repr(r["omega0"]), "--fd", repr(r["f_d"]),
                            "--N", str(N), "--json", "--quiet")  # fmt: skip
        assert rc == 0, err
        one = json.loads(text)
        for key in ("rms_dynamic", "rms_quasistatic", "delta_rms"):
            assert r[key] == pytest.approx(one[key], rel=RMS_RTOL), (r["omega0"], r["f_d"], key)
        assert abs(r["floquet_max"] - one["floquet_max"]) <= SPREAD_TOL
        assert (r["converged"], r["status"]) == (one["converged"], one["status"])


def test_command_line_and_api_give_the_same_rows(by_api, tmp_path):
    """`rotbeam atlas --json --out` (linearly spaced grid from the flags, every line in this
    process) and `rotbeam.atlas` (two processes): the same rows but for the timings; the CSV
    holds the JSON's rows; the boundary is the API's."""
    out = tmp_path / "atlas.csv"
    rc, text, err = cli("atlas", *GRID, "--workers", "1", "--json", "--quiet", "--out", str(out))
    assert rc == 0, err
    got = json.loads(text)
    assert got["summary"]["complete"] and got["summary"]["ran"] == 6
    keep = [c for c in ATLAS_COLUMNS if c not in VARYING]
    by_cli = pd.DataFrame(got["rows"])
    assert list(by_cli.columns) == ATLAS_COLUMNS
    pd.testing.assert_frame_equal(by_cli[keep], by_api.rows[keep], check_dtype=False)
    csv = pd.read_csv(out)
    pd.testing.assert_frame_equal(csv[keep], by_cli[keep], check_dtype=False)
    assert pd.DataFrame(got["boundary"])["f_d_root"].to_numpy() == pytest.approx(
        by_api.boundary["f_d_root"].to_numpy(), rel=1e-9
    )


def test_a_cut_atlas_says_which_lines_and_points_it_reached(monkeypatch, tmp_path):
    """The atlas's budget (numerics.max_seconds) spent by its first line: that line's rows
    are answers, the other lines' rows are there, marked not run (status NOT_RUN, NaN, the
    reason), and the message and the exit status say where the budget cut it."""
    real = rotbeam.runs.atlas.run_line
    budget = 1.0

    def slow_first_line(scene, omega0, f_ds, time_budget=None, progress=None):
        line = real(scene, omega0, f_ds, time_budget, progress)
        time.sleep(budget)  # the atlas's whole budget is spent here
        return line

    monkeypatch.setattr(rotbeam.runs.atlas, "run_line", slow_first_line)
    out = tmp_path / "cut.csv"
    rc, text, err = cli("atlas", "--omega0-min", "5", "--omega0-max", "15", "--fd-min", "1",
                        "--fd-max", "3", "--points", "3,3", "--N", "6", "--max-seconds",
                        str(budget), "--workers", "1", "--quiet", "--out", str(out))  # fmt: skip
    assert rc == 1, err
    rows = pd.read_csv(out)
    assert len(rows) == 9  # every grid point has its row
    first, rest = rows[rows["line"] == 0], rows[rows["line"] > 0]
    assert first["ran"].all() and first["converged"].all()
    assert not rest["ran"].any() and (rest["status"] == NOT_RUN).all()
    assert rest["rms_dynamic"].isna().all()
    assert rest["message"].str.startswith("not run: the atlas's time budget of 1 s").all()
    assert "1 of 3 lines whole" in text
    assert "line 2 (Omega_0 = 10 rad/s): 0 of 3 points answered, 0 cut short, 3 not run" in text
    assert "line 3 (Omega_0 = 15 rad/s): 0 of 3 points answered, 0 cut short, 3 not run" in text
    assert "line 1 " not in text


def test_a_message_names_five_cut_lines_and_counts_the_rest():
    """A budget that cuts many lines (near a resonance every line has points whose time
    stepping its share ends) gives a message of the points cut in all, five lines named and
    the number of the others, not a line of text per cut line."""
    from rotbeam.runs.atlas import LISTED_LINES, cut_notes, where_cut

    records = []
    for line in range(8):
        for k in range(4):  # point 3 of every line cut short, line 7's last also not run
            cut, not_run = k == 3, line == 7 and k == 2
            why = "the time budget of 2 s ended it" if cut else ""
            records.append({"line": line, "omega0": 5.0 + line, "ran": not not_run,
                            "converged": not (cut or not_run), "message": why})  # fmt: skip
    lines, notes = where_cut(records)
    assert lines == list(range(8)) and LISTED_LINES == 5
    text = cut_notes(records, notes)
    assert text.startswith("8 points cut short, 1 not run; line 1 (Omega_0 = 5 rad/s): 3 of 4")
    assert "line 5 (Omega_0 = 9 rad/s)" in text and "line 6 " not in text
    assert text.endswith("; and 3 more lines")
    one = [r for r in records if r["line"] == 0]  # a single point: no plural
    assert cut_notes(one, where_cut(one)[1]).startswith("1 point cut short, 0 not run; line 1")


def test_each_line_gets_its_share_of_what_is_left(monkeypatch):
    """A line may spend what is left of the atlas's budget times the workers over the lines
    left, so that one line with a hard point cannot take the whole atlas's (one worker, four
    lines: a quarter, then a third of what is left, ...)."""
    shares = []
    real = rotbeam.runs.atlas.run_line

    def recording(scene, omega0, f_ds, time_budget=None, progress=None):
        shares.append((time.time(), time_budget.seconds))
        return real(scene, omega0, f_ds, time_budget, progress)

    monkeypatch.setattr(rotbeam.runs.atlas, "run_line", recording)
    total = 600.0
    start = time.time()
    a = rotbeam.atlas(scene(max_seconds=total), [5.0, 10.0, 15.0, 20.0], [1.0, 2.0], workers=1)
    assert a.complete and len(shares) == 4
    for k, (at, seconds) in enumerate(shares):
        left = total - (at - start)
        assert seconds == pytest.approx(left / (4 - k), rel=1e-3), (k, seconds, left)


def test_a_budget_spent_before_any_line_leaves_every_row_marked():
    """A budget of 1e-9 s (two processes): no line runs, every point has a marked row and the
    summary counts them."""
    a = rotbeam.atlas(scene(max_seconds=1e-9), OMEGA0S, F_DS, workers=2)
    s = a.summary()
    assert (s["ran"], s["not_run"], s["complete"]) == (0, 6, False)
    assert (a.rows["status"] == NOT_RUN).all() and "0 of 2 lines whole" in a.message


@pytest.mark.parametrize(
    "flags, words",
    [
        (["--points", "1,3"], ["--points", "'1,3'", "integers >= 2"]),
        (["--points", "3"], ["--points", "'3'", "I,J"]),
        (["--points", "2,x"], ["--points", "'2,x'"]),
        (["--omega0-max", "5"], ["--omega0-max", "5.0", "> --omega0-min (5.0)"]),
        (["--fd-min", "-1"], ["--fd-min", "-1.0", "> 0"]),
        (["--fd-max", "1"], ["--fd-max", "1.0", "> --fd-min (2.0)"]),
        (["--omega0", "3"], ["--omega0", "--omega0-min and --omega0-max"]),
        (["--threshold", "1.5"], ["--threshold", "1.5", "(0, 1)"]),
        (["--workers", "0"], ["--workers", "0", ">= 1"]),
        (["--out", "a.txt"], ["--out", "a.txt", ".csv"]),
        (["--plot", "a.gif"], ["a.gif"]),
        (["--omega0-max", "nan"], ["--omega0-max", "nan"]),
    ],
)
def test_bad_input_is_one_line_naming_the_value(flags, words):
    """A bad flag: exit status 2, one line on stderr naming the flag, the value and what is
    allowed, before any point runs (stdout empty)."""
    argv = list(GRID)
    for flag, value in zip(flags[::2], flags[1::2], strict=True):
        if flag in argv:
            argv[argv.index(flag) + 1] = value
        else:
            argv += [flag, value]
    with pytest.raises(SystemExit) if "nan" in flags else contextlib.nullcontext():
        rc, out, err = cli("atlas", *argv, "--quiet")
    if "nan" in flags:
        return  # argparse's own one line (its type), tested in test_cli
    assert rc == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("rotbeam: error:"), err
    for w in words:
        assert w in err, (w, err)


def test_missing_bounds_and_a_drive_without_omega0_are_refused(tmp_path):
    rc, _, err = cli("atlas", "--omega0-min", "5", "--fd-min", "1", "--fd-max", "2", "--points",
                     "2,2", "--quiet")  # fmt: skip
    assert rc == 2 and "--omega0-max is missing" in err and err.count("\n") == 1
    with pytest.raises(RotbeamInputError, match="allowed for an atlas: a sine"):
        shape = {"shape": "trapezoid", "omega_min": 0.0, "omega_max": 5.0, "ramp": 0.2}
        profile = rotbeam.build_scene({"drive": {"f_d": 1.0, "profile": shape}})
        rotbeam.atlas(profile, OMEGA0S, F_DS, workers=1)


@pytest.mark.parametrize(
    "omega0s, f_ds, words",
    [
        ([5.0], F_DS, ["omega0s", "at least 2"]),
        (OMEGA0S, [2.0, 2.0, 3.0], ["f_ds", "strictly increasing"]),
        (OMEGA0S, [0.0, 2.0], ["f_ds", "> 0"]),
        ([5.0, np.inf], F_DS, ["omega0s", "finite"]),
    ],
)
def test_the_api_refuses_a_bad_axis_in_one_line(omega0s, f_ds, words):
    with pytest.raises(RotbeamInputError) as exc:
        rotbeam.atlas(scene(), omega0s, f_ds, workers=1)
    assert "\n" not in str(exc.value) and all(w in str(exc.value) for w in words), exc.value


@pytest.mark.parametrize(
    "omega0, f_d, words",
    [
        ([5.0, 5.0, 3], [1.0, 2.0, 3], ["atlas.omega0", "first < last"]),
        ([5.0, 9.0, 1], [1.0, 2.0, 3], ["atlas.omega0", ">= 2"]),
        ([5.0, 9.0, 2], [0.0, 2.0, 3], ["atlas.f_d", "> 0"]),
        ([5.0, 9.0, 2.5], [1.0, 2.0, 3], ["atlas.omega0", "integer"]),
    ],
)
def test_the_config_grid_is_checked(omega0, f_d, words):
    with pytest.raises(RotbeamInputError) as exc:
        grid_axes(omega0, f_d)
    assert all(w in str(exc.value) for w in words), exc.value


def test_the_boundary_lies_between_the_grid_points_around_critical(by_api, tmp_path):
    """Each line's f_d* (the root of its interpolated Delta RMS) lies between the two grid
    points around the crossing, and so does `rotbeam critical`'s f_d* at that Omega_0 (root
    finding on fresh runs, no grid); the figure is written."""
    png = tmp_path / "atlas.png"
    rotbeam.plot_atlas(by_api, png)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    for b in by_api.boundary.to_dict(orient="records"):
        assert b["found"], b
        k = F_DS.index(b["f_d_grid"])  # the first grid point at or above the threshold
        assert k > 0, b
        lo, hi = F_DS[k - 1], F_DS[k]
        rc, text, err = cli("critical", "--omega0", repr(b["omega0"]), "--N", str(N), "--json",
                            "--quiet")  # fmt: skip
        assert rc == 0, err
        f_star = json.loads(text)["f_d_star"]
        assert lo < f_star < hi, (b["omega0"], lo, f_star, hi)
        assert lo < b["f_d_root"] < hi, b
    line = by_api.rows[by_api.rows["omega0"] == OMEGA0S[0]]
    d = line["delta_rms"].to_numpy()
    assert d[0] < by_api.threshold <= d[1]  # 5 rad/s crosses between 2 and 5 Hz


def test_summary_counts_and_the_grid_shape(by_api):
    s = by_api.summary()
    assert s["points"] == "2 x 3" and s["ran"] == s["converged"] == 6 and s["not_run"] == 0
    assert s["lines"] == s["lines_with_boundary"] == 2
    assert by_api.grid().shape == (2, 3)
    assert by_api.grid()[1, 2] == pytest.approx(
        by_api.rows.query("omega0 == 40 and f_d == 8")["delta_rms"].iloc[0]
    )
