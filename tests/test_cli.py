"""The console script: JSON output, time series, one-line errors with exit status 2."""

import json
import subprocess
import sys

import pandas as pd
import pytest


def run(*args):
    return subprocess.run(
        [sys.executable, "-m", "rotbeam", *args], capture_output=True, text=True, timeout=300
    )


def test_simulate_json_and_out(tmp_path):
    out = tmp_path / "series.csv"
    p = run("simulate", "--omega0", "5", "--fd", "2", "--N", "16", "--json", "--out", str(out))
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    for key in ("rms_dynamic", "rms_quasistatic", "delta_rms", "f_n_hz", "seconds"):
        assert key in d
    assert 0 < d["rms_quasistatic"] < d["rms_dynamic"] < 0.1
    df = pd.read_csv(out)
    assert {"tau", "y_m_dynamic", "y_m_quasistatic"} <= set(df.columns) and len(df) > 10


def test_scene_file_with_flag_override(tmp_path):
    scene = tmp_path / "s.yaml"
    scene.write_text("beam: {E: 2.0e6}\ndrive: {omega0: 5, f_d: 40}\nnumerics: {N: 12}\n")
    p = run("simulate", "--scene", str(scene), "--fd", "2", "--json")
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    assert d["f_d"] == 2.0 and d["N"] == 12
    assert d["f_n_hz"] == pytest.approx(6.5199 * (2.0 / 1.22) ** 0.5, rel=1e-4)


@pytest.mark.parametrize(
    "args, words",
    [
        (["simulate", "--omega0", "5", "--fd", "-2"], "drive.f_d"),
        (["simulate", "--omega0", "5", "--fd", "nan"], "--fd"),
        (["simulate", "--omega0", "5", "--fd", "2", "--N", "2"], "numerics.N"),
        (["simulate", "--omega0", "5", "--fd", "2", "--R", "0.01"], "beam.R"),
        (["simulate", "--omega0", "5", "--fd", "2", "--effects", "magic"], "magic"),
        (["simulate", "--omega0", "5"], "--fd"),
        (["simulate", "--scene", "/nonexistent.yaml"], "does not exist"),
        (["modes", "--k", "0"], "--k"),
        (["modes", "--dimensionless", "--hub-ratio", "-1"], "--hub-ratio"),
    ],
)
def test_bad_input_is_one_line_exit_2(args, words):
    p = run(*args)
    assert p.returncode == 2
    assert "Traceback" not in p.stderr
    assert len(p.stderr.strip().splitlines()) == 1 and words in p.stderr


def test_unknown_scene_key(tmp_path):
    scene = tmp_path / "s.yaml"
    scene.write_text("beam: {Young: 2.0e6}\n")
    p = run("simulate", "--scene", str(scene), "--omega0", "1", "--fd", "1")
    assert p.returncode == 2 and "Young" in p.stderr


def test_modes_dimensionless_matches_beta1():
    p = run("modes", "--dimensionless", "--lambda", "0", "--k", "2", "--N", "160", "--json")
    assert p.returncode == 0
    w = json.loads(p.stdout)["frequencies_dimensionless"]
    assert w[0] == pytest.approx(1.8751040687**2, rel=1e-4)
    assert w[1] == pytest.approx(4.6940911330**2, rel=1e-3)


# --- the verdict (rotbeam.analysis.verdict): --threshold and --plot ------------------------------


def test_cli_verdict_json_and_plot(tmp_path):
    plot = tmp_path / "answer.png"
    p = run("simulate", "--omega0", "5", "--fd", "7", "--N", "16", "--json", "--plot", str(plot))
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    assert d["quasistatic_ok"] is False and d["threshold"] == 0.10
    assert d["delta_rms"] >= 0.10 and "inertia matters" in d["verdict"]
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and plot.stat().st_size > 20_000
    assert not list(tmp_path.glob(".*part*"))  # written through a temporary name


@pytest.mark.parametrize(
    "flags, words",
    [
        (["--threshold", "1.5"], ["--threshold", "(0, 1)", "1.5"]),
        (["--threshold", "0"], ["--threshold", "(0, 1)"]),
        (["--threshold", "nan"], ["--threshold", "finite"]),
        (["--plot", "answer.txt"], ["--plot", ".png", "answer.txt"]),
    ],
)
def test_cli_bad_threshold_or_plot_is_one_line_exit_2(flags, words):
    p = run("simulate", "--omega0", "5", "--fd", "2", *flags)
    assert p.returncode == 2 and "Traceback" not in p.stderr
    assert len(p.stderr.strip().splitlines()) == 1
    assert all(w in p.stderr for w in words), p.stderr


def test_cli_critical_json():
    p = run("critical", "--omega0", "5", "--N", "16", "--json")
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    assert d["found"] and d["threshold"] == 0.10 and d["evaluations"] == len(d["visited"]) <= 12
    # the f_d* of the reference beam at 5 rad/s: c = f_d*/f_0 between App. E's c_0 (0.316) -2 %
    # and the full run's fitted c (0.323) +2 %
    assert 0.31 < d["c"] < 0.33 and d["f_d_star"] == pytest.approx(d["c"] * d["f0_hz"])
    f, delta = zip(*d["visited"], strict=True)
    assert min(delta) < 0.10 < max(delta)  # the root was bracketed by full-model runs


@pytest.mark.parametrize(
    "flags, words",
    [
        (["--omega0", "5", "--threshold", "1"], ["--threshold", "(0, 1)"]),
        (["--omega0", "5", "--ftol", "0.5"], ["--ftol", "[1e-08, 0.1]", "0.5"]),
        (["--omega0", "5", "--fd", "2"], ["unrecognized arguments: --fd 2"]),
        ([], ["drive.omega0", "missing", "--omega0"]),
        (["--omega0", "5", "--N", "2"], ["numerics.N", "[3, 2000]"]),
    ],
)
def test_cli_critical_bad_flags_are_one_line_exit_2(flags, words):
    p = run("critical", *flags)
    assert p.returncode == 2 and "Traceback" not in p.stderr
    assert len(p.stderr.strip().splitlines()) == 1
    assert all(w in p.stderr for w in words), p.stderr


def test_simulate_without_steady_state_classifies_on_the_response_grid(tmp_path):
    """A run from rest stopped after two periods (no steady state: exit 1) is classified on the
    grid --response-N asks for, over the periods --response-periods asks for (4: the fewest a
    class rests on); the class is one of the four words and the exponent is finite (the class of
    so short a run is not the point: tests/test_nonlinear.py checks the classifier)."""
    import math

    scene = tmp_path / "s.yaml"
    scene.write_text(
        "drive: {omega0: 5, f_d: 2}\n"
        "numerics: {N: 4, start: rest, max_periods: 2, extrapolate: false}\n"
    )
    p = run("simulate", "--scene", str(scene), "--json", "--response-N", "4",
            "--response-periods", "4")  # fmt: skip
    assert p.returncode == 1, p.stderr
    d = json.loads(p.stdout)
    assert d["response"] in ("periodic", "subharmonic", "quasiperiodic", "chaotic")
    assert d["response_N"] == 4 and d["response_periods"] == 8, d["response_message"]
    assert math.isfinite(d["lyapunov_max"])
    assert p.stderr == ""  # no terminal: no progress bar


def in_a_terminal(*argv: str) -> tuple[int, str, str]:
    """The command with stderr on a pseudo-terminal (stdout a pipe): (exit, stdout, stderr)."""
    import os
    import pty

    main, child = pty.openpty()
    p = subprocess.Popen([sys.executable, "-m", "rotbeam", *argv], stdout=subprocess.PIPE,
                         stderr=child, text=True)  # fmt: skip
    os.close(child)
    err = b""
    while True:
        try:
            chunk = os.read(main, 4096)
        except OSError:  # the child closed the terminal
            break
        if not chunk:
            break
        err += chunk
    out = p.stdout.read()
    p.wait(timeout=120)
    os.close(main)
    return p.returncode, out, err.decode(errors="replace")


def test_progress_bar_in_a_terminal_and_not_with_quiet(tmp_path):
    """On a terminal the classification's periods show as a tqdm bar on stderr (8 of 8), and
    the JSON on stdout stays one clean object; --quiet draws nothing."""
    scene = tmp_path / "s.yaml"
    scene.write_text(
        "drive: {omega0: 5, f_d: 2}\n"
        "numerics: {N: 4, start: rest, max_periods: 2, extrapolate: false}\n"
    )
    argv = ("simulate", "--scene", str(scene), "--json", "--response-N", "4",
            "--response-periods", "4")  # fmt: skip
    rc, out, err = in_a_terminal(*argv)
    assert rc == 1 and json.loads(out)["response_periods"] == 8
    assert "response (N = 4)" in err and "8/8" in err
    rc, out, err = in_a_terminal(*argv, "--quiet")
    assert rc == 1 and json.loads(out)["response_periods"] == 8
    assert err == ""
