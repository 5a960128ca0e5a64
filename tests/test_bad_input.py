"""Issue #6: bad input gets ONE line naming the key, the value and what is allowed; the command
line exits with status 2 and the workflow stops before any job, never with a traceback.

Entry points: `rotbeam simulate` flags and `--scene` files, `rotbeam modes`, and the workflow
config (checked by `rotbeam.studies.validate_config`, the function `workflow/rules/common.smk`
calls; a few cases go through `snakemake` itself).  Table-driven over the classes of bad input,
then property-based (hypothesis) over random valid and invalid flags, scenes and configs.
"""

import contextlib
import copy
import io
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
import yaml
from conftest import ROOT, snakemake_env
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from rotbeam.cli import main
from rotbeam.config.errors import RotbeamInputError
from rotbeam.config.parameters import SECTIONS
from rotbeam.config.scenefile import load_yaml
from rotbeam.config.schema import merge_config
from rotbeam.paper.studies import (
    convergence_lines,
    fig7_beams,
    grid_columns,
    lines_from_config,
    validate_config,
)

SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
FULL = load_yaml((ROOT / "config" / "config.yaml").read_text())
# what the workflow runs with --configfile config/quick.yaml: quick.yaml merged over config.yaml
QUICK = merge_config(FULL, load_yaml((ROOT / "config" / "quick.yaml").read_text()))
NAN, INF = math.nan, math.inf


def run_main(argv: list[str]) -> tuple[int, str, str]:
    """rotbeam.cli.main in-process; (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            rc = main(argv)
        except SystemExit as exc:  # argparse's own errors
            rc = exc.code
    return rc, out.getvalue(), err.getvalue()


def one_clear_line(rc: int, err: str, words) -> str:
    assert rc == 2, err
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


# --- the command line ---------------------------------------------------------------------------

SIM = ["simulate", "--omega0", "5", "--fd", "2", "--N", "6"]

CLI_CASES = {
    # negative
    "fd negative": (["simulate", "--omega0", "5", "--fd", "-2"], ["--fd", "drive.f_d", "-2.0"]),
    "omega0 negative is allowed, sci. notation": (
        ["simulate", "--omega0", "-2.5e1", "--fd", "-1e-3"], ["--fd", "drive.f_d", "-0.001", "> 0"]
    ),
    "amplitude negative": (SIM + ["--amplitude", "-1"], ["--amplitude", "-1.0", ">= 0"]),
    "R negative": (SIM + ["--R", "-1"], ["--R", "beam.R", "-1.0", "> 0"]),
    "response grid too coarse": (SIM + ["--response-N", "3"], ["--response-N", "3", "[4, 80]"]),
    "N negative": (SIM[:5] + ["--N", "-5"], ["--N", "numerics.N", "-5", "[3, 2000]"]),
    "modes hub-ratio negative": (
        ["modes", "--dimensionless", "--hub-ratio", "-1"], ["--hub-ratio", "-1.0", ">= 0"]
    ),
    # zero
    "fd zero": (["simulate", "--omega0", "5", "--fd", "0"], ["--fd", "0.0", "> 0"]),
    "R zero": (SIM + ["--R", "0"], ["--R", "0.0", "> 0"]),
    "rtol zero": (SIM + ["--rtol", "0"], ["--rtol", "0.0", "[1e-13, 0.1]"]),
    "modes k zero": (["modes", "--k", "0"], ["--k", "0", ">= 1"]),
    "modes k past the grid": (["modes", "--k", "40"], ["--k", "40", "[1, N-1=39]"]),
    # NaN and inf
    "fd nan": (["simulate", "--omega0", "5", "--fd", "nan"], ["--fd", "'nan'", "finite"]),
    "omega0 nan": (["simulate", "--omega0", "NaN", "--fd", "2"], ["--omega0", "'NaN'", "finite"]),
    "rtol nan": (SIM + ["--rtol", "nan"], ["--rtol", "'nan'", "finite"]),
    "fd inf": (["simulate", "--omega0", "5", "--fd", "inf"], ["--fd", "'inf'", "finite"]),
    "amplitude inf": (SIM + ["--amplitude", "1e999"], ["--amplitude", "'1e999'", "finite"]),
    "R -inf": (SIM + ["--R", "-inf"], ["--R", "'-inf'", "finite"]),
    "modes omega nan": (["modes", "--omega", "nan"], ["--omega", "'nan'", "finite"]),
    "modes lambda inf": (["modes", "--dimensionless", "--lambda", "inf"], ["--lambda", "'inf'"]),
    # wrong type
    "fd text": (["simulate", "--omega0", "5", "--fd", "abc"], ["--fd", "'abc'", "a number"]),
    "N float": (SIM[:5] + ["--N", "2.5"], ["--N", "'2.5'", "integer"]),
    "N text": (SIM[:5] + ["--N", "ten"], ["--N", "'ten'", "integer"]),
    "method unknown": (SIM + ["--method", "Euler"], ["--method", "'Euler'", "Radau"]),
    "effects unknown": (SIM + ["--effects", "magic"], ["--effects", "magic", "centrifugal"]),
    "modes k text": (["modes", "--k", "x"], ["--k", "'x'", "integer"]),
    "out suffix": (SIM + ["--out", "x.txt"], ["--out", "'x.txt'", ".csv or .parquet"]),
    # missing
    "fd missing": (["simulate", "--omega0", "5"], ["drive.f_d", "missing", "--fd"]),
    "omega0 missing": (["simulate", "--fd", "2"], ["drive.omega0", "missing", "--omega0"]),
    "scene file missing": (
        ["simulate", "--scene", "/nonexistent/s.yaml"], ["scene file", "/nonexistent/s.yaml"]
    ),
    "fd value missing": (["simulate", "--omega0", "5", "--fd"], ["--fd", "expected one argument"]),
    # a sweep's line
    "sweep fd-min missing": (
        ["sweep", "--omega0", "5", "--fd-max", "3"], ["--fd-min", "missing", "> 0"]
    ),
    "sweep fd-max not above fd-min": (
        ["sweep", "--omega0", "5", "--fd-min", "3", "--fd-max", "3"],
        ["--fd-max", "3.0", "> --fd-min"],
    ),
    "sweep fd-min zero": (
        ["sweep", "--omega0", "5", "--fd-min", "0", "--fd-max", "3"], ["--fd-min", "0.0", "> 0"]
    ),
    "sweep one point": (
        ["sweep", "--omega0", "5", "--fd-min", "1", "--fd-max", "3", "--points", "1"],
        ["--points", "1", ">= 2"],
    ),
    "sweep points text": (
        ["sweep", "--omega0", "5", "--fd-min", "1", "--fd-max", "3", "--points", "x"],
        ["--points", "'x'", "integer"],
    ),
    "sweep omega0 missing": (
        ["sweep", "--fd-min", "1", "--fd-max", "3"], ["drive.omega0", "missing", "--omega0"]
    ),
    "sweep out suffix": (
        ["sweep", "--omega0", "5", "--fd-min", "1", "--fd-max", "3", "--out", "x.txt"],
        ["--out", "'x.txt'", ".csv"],
    ),
    "sweep effects auto": (
        ["sweep", "--omega0", "5", "--fd-min", "1", "--fd-max", "3", "--effects", "auto"],
        ["effects: auto", "allowed", "list of effects"],
    ),
    "sweep takes no --fd": (
        ["sweep", "--omega0", "5", "--fd", "2"], ["--fd", "could match --fd-min, --fd-max"]
    ),
    # unknown
    "unknown flag": (SIM + ["--bogus", "3"], ["--bogus", "3", "unrecognized", "--help"]),
    "unknown command": (["frob"], ["'frob'", "simulate", "modes"]),
    # empty
    "effects empty": (SIM + ["--effects", ""], ["--effects", "''", "names no effect"]),
    "effects comma": (SIM + ["--effects", ","], ["--effects", "','", "names no effect"]),
    # N too small, values too large
    "N too small": (SIM[:5] + ["--N", "2"], ["--N", "numerics.N", "2", "[3, 2000]"]),
    "modes N too small": (["modes", "--N", "2"], ["--N", "2", "[3, 2000]"]),
    "modes N too large": (["modes", "--N", "3000"], ["--N", "3000", "[3, 2000]"]),
    "rtol too large": (SIM + ["--rtol", "2"], ["--rtol", "2.0", "[1e-13, 0.1]"]),
    "R inside the beam": (SIM + ["--R", "0.01"], ["--R", "beam.R", "0.01", "> beam.L"]),
    "modes R inside the beam": (["modes", "--R", "0.01"], ["--R", "beam.R", "0.01"]),
    "omega0 overflows": (
        ["simulate", "--omega0", "1e300", "--fd", "2"], ["drive.omega0", "1e+300", "C_max <= 1e+12"]
    ),
    "fd overflows": (
        ["simulate", "--omega0", "5", "--fd", "1e300"], ["drive.f_d", "1e+300", "E_max <= 1e+12"]
    ),
    "modes omega overflows": (["modes", "--omega", "1e160"], ["--omega", "1e+160", "C <= 1e+12"]),
}  # fmt: skip


@pytest.mark.parametrize("argv, words", CLI_CASES.values(), ids=CLI_CASES.keys())
def test_cli_bad_input_is_one_line_exit_2(argv, words):
    rc, out, err = run_main(argv)
    one_clear_line(rc, err, words)
    assert out == ""


@pytest.mark.parametrize(
    "argv, words",
    [
        (["simulate", "--omega0", "5", "--fd", "nan"], ["--fd", "'nan'"]),
        (["simulate", "--omega0", "5", "--fd", "2", "--effects", ""], ["--effects"]),
        (["modes", "--omega", "1e160"], ["--omega"]),
    ],
)
def test_cli_subprocess_one_line_exit_2(argv, words):
    """The console entry point itself (no warnings, no traceback on stderr)."""
    p = subprocess.run(
        [sys.executable, "-m", "rotbeam", *argv], capture_output=True, text=True, timeout=120
    )
    one_clear_line(p.returncode, p.stderr, words)


# --- scene files --------------------------------------------------------------------------------

DRIVE = "drive: {omega0: 5, f_d: 2}\n"

SCENE_CASES = {
    "L negative": (DRIVE + "beam: {L: -1}", ["beam.L", "-1.0", "> 0"]),
    "E zero": (DRIVE + "beam: {E: 0}", ["beam.E", "0.0", "> 0"]),
    "gamma negative": (DRIVE + "beam: {gamma: -0.1}", ["beam.gamma", "-0.1", ">= 0"]),
    "f_d zero": ("drive: {omega0: 5, f_d: 0}", ["drive.f_d", "0.0", "> 0"]),
    "rho nan": (DRIVE + "beam: {rho: .nan}", ["beam.rho", "nan", "finite"]),
    "f_d nan": ("drive: {omega0: 5, f_d: .NaN}", ["drive.f_d", "nan", "finite"]),
    "R inf": (DRIVE + "beam: {R: .inf}", ["beam.R", "inf", "finite"]),
    "omega0 -inf": ("drive: {omega0: -.inf, f_d: 2}", ["drive.omega0", "-inf", "finite"]),
    "rtol nan": (DRIVE + "numerics: {rtol: .nan}", ["numerics.rtol", "nan", "finite"]),
    "max_seconds inf": (
        DRIVE + "numerics: {max_seconds: .inf}", ["numerics.max_seconds", "inf", "finite"]
    ),
    "E text": (DRIVE + "beam: {E: abc}", ["beam.E", "'abc'", "a number"]),
    "E quoted number": (DRIVE + "beam: {E: '2e6'}", ["beam.E", "'2e6'", "a number"]),
    "E null": (DRIVE + "beam: {E: null}", ["beam.E", "None", "a number"]),
    "E bool": (DRIVE + "beam: {E: true}", ["beam.E", "True", "a number"]),
    "E list": (DRIVE + "beam: {E: [1, 2]}", ["beam.E", "[1, 2]", "a number"]),
    "N float": (DRIVE + "numerics: {N: 12.0}", ["numerics.N", "12.0", "integer"]),
    "N text": (DRIVE + "numerics: {N: '12'}", ["numerics.N", "'12'", "integer"]),
    "max_seconds bool": (
        DRIVE + "numerics: {max_seconds: true}", ["numerics.max_seconds", "True", "a number"]
    ),
    "integrate text": (
        DRIVE + "numerics: {integrate: 'yes'}", ["numerics.integrate", "'yes'", "true or false"]
    ),
    "effect text": (DRIVE + "effects: {euler: 'no'}", ["effects.euler", "'no'", "true or false"]),
    "method unknown": (DRIVE + "numerics: {method: X}", ["numerics.method", "'X'", "Radau"]),
    "unknown key": (DRIVE + "beam: {Young: 2}", ["beam.Young", "2", "unknown key", "L, h, b, E"]),
    "unknown section": (DRIVE + "motor: {x: 1}", ["motor", "unknown scene section", "beam, drive"]),
    "section not a mapping": (DRIVE + "beam: 3", ["beam = 3", "mapping"]),
    "effects as a list": (DRIVE + "effects: [euler]", ["effects = ['euler']", "mapping"]),
    "drive missing": ("beam: {E: 2.0e6}", ["drive.omega0", "missing", "--omega0"]),
    "f_d missing": ("drive: {omega0: 5}", ["drive.f_d", "missing", "--fd"]),
    "empty file": ("", ["drive.omega0", "missing"]),
    "N too small": (DRIVE + "numerics: {N: 2}", ["numerics.N", "2", "[3, 2000]"]),
    "h not below L": (DRIVE + "beam: {h: 0.05}", ["beam.h", "0.05", "< beam.L"]),
    "R inside the beam": (DRIVE + "beam: {R: 0.03}", ["beam.R", "0.03", "> beam.L"]),
    "omega0 overflows": ("drive: {omega0: 1.0e300, f_d: 2}", ["drive.omega0", "1e+300", "C_max"]),
    "not a mapping": ("- 1\n- 2", ["must hold a mapping of sections", "[1, 2]"]),
    "not YAML": ("beam: {L: [", ["not valid YAML", "line 2"]),
}  # fmt: skip


@pytest.mark.parametrize("text, words", SCENE_CASES.values(), ids=SCENE_CASES.keys())
def test_scene_file_bad_input_is_one_line_exit_2(tmp_path, text, words):
    scene = tmp_path / "scene.yaml"
    scene.write_text(text + "\n")
    rc, out, err = run_main(["simulate", "--scene", str(scene), "--json"])
    one_clear_line(rc, err, words)


def test_flag_overrides_a_bad_scene_value_and_a_bad_flag_is_named(tmp_path):
    scene = tmp_path / "scene.yaml"
    scene.write_text("drive: {omega0: 5, f_d: -1}\nnumerics: {N: 6}\n")
    rc, out, err = run_main(["simulate", "--scene", str(scene), "--fd", "0.5", "--json"])
    assert rc == 0, err
    assert json.loads(out)["f_d"] == 0.5
    rc, out, err = run_main(["simulate", "--scene", str(scene), "--fd", "-3"])
    one_clear_line(rc, err, ["argument --fd", "drive.f_d", "-3.0"])


# --- the workflow config ------------------------------------------------------------------------

DELETE = object()


def with_value(path: tuple, value):
    cfg = copy.deepcopy(QUICK)
    node = cfg
    for k in path[:-1]:
        node = node[k]
    if value is DELETE:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return cfg


def config_message(cfg) -> str:
    with pytest.raises(RotbeamInputError) as info:
        validate_config(cfg, SCHEMA)
    msg = str(info.value)
    assert "\n" not in msg and "Traceback" not in msg
    return msg


CONFIG_CASES = {
    "L negative": (("beam", "L"), -1, ["beam.L", "-1", "> 0"]),
    "E zero": (("beam", "E"), 0, ["beam.E", "0", "> 0"]),
    "amplitude zero": (("amplitude",), 0.0, ["amplitude", "0.0", "> 0"]),
    "fig5 e_max negative": (("fig5", "e_max"), [2.0, -1.0], ["fig5.e_max[1]", "-1.0", "> 0"]),
    "rho nan": (("beam", "rho"), NAN, ["beam.rho", "nan", "> 0"]),
    "R inf": (("beam", "R"), INF, ["beam.R", "inf", "finite"]),
    "fig1 omega0 -inf": (("fig1", "omega0"), -INF, ["fig1.omega0", "-inf", "finite number"]),
    "max_seconds inf": (("numerics", "max_seconds"), INF, ["numerics.max_seconds", "inf", "> 0"]),
    "threshold nan": (("thresholds",), [0.05, NAN], ["thresholds[1]", "nan", "(0, 1)"]),
    "amplitude 'nan' (--config)": (("amplitude",), "nan", ["amplitude", "nan", "> 0"]),
    "E text": (("beam", "E"), "abc", ["beam.E", "'abc'", "> 0"]),
    "E null": (("beam", "E"), None, ["beam.E", "None", "> 0"]),
    "E bool": (("beam", "E"), True, ["beam.E", "True", "> 0"]),
    "N float": (("numerics", "N"), 12.5, ["numerics.N", "12.5", "integer"]),
    "method unknown": (("numerics", "method"), "Euler", ["numerics.method", "'Euler'", "Radau"]),
    "integrate text": (("numerics", "integrate"), "yes", ["numerics.integrate", "'yes'", "true"]),
    "effects unknown": (("effects",), ["magic"], ["effects[0]", "'magic'", "centrifugal"]),
    "beam not a mapping": (("beam",), 3, ["beam", "3", "mapping with keys L, h"]),
    "missing key": (("beam", "L"), DELETE, ["beam.L", "missing", "> 0"]),
    "missing section": (("fig4",), DELETE, ["fig4", "missing", "omega0, lo, hi"]),
    "unknown key": (("beam", "Young"), 2e6, ["beam.Young", "2000000.0", "unknown key", "L, h"]),
    "unknown top-level key": (("fig8",), {"a": 1}, ["fig8", "{'a': 1}", "unknown key", "fig7"]),
    "unknown numerics key": (("numerics", "grid"), 3, ["numerics.grid", "3", "unknown", "rtol"]),
    "main_threshold 1.5": (("main_threshold",), 1.5, ["main_threshold", "1.5", "(0, 1)"]),
    "main_threshold 0": (("main_threshold",), 0, ["main_threshold", "0", "(0, 1)"]),
    "threshold 1": (("thresholds",), [0.05, 1.0], ["thresholds[1]", "1.0", "(0, 1)"]),
    "c0 threshold negative": (("c0_thresholds",), [-0.1], ["c0_thresholds[0]", "-0.1", "(0, 1)"]),
    "tolerance 1": (("surrogate", "tolerance"), 1, ["surrogate.tolerance", "1", "(0, 1)"]),
    "thresholds empty": (("thresholds",), [], ["thresholds", "[]", "non-empty"]),
    "thresholds repeated": (("thresholds",), [0.1, 0.1], ["thresholds", "[0.1, 0.1]", "distinct"]),
    "effects empty": (("effects",), [], ["effects", "[]", "non-empty"]),
    "fig4 omega0 empty": (("fig4", "omega0"), [], ["fig4.omega0", "[]", "non-empty"]),
    "c_max empty": (("boundary", "c_max"), [], ["boundary.c_max", "[]", "non-empty"]),
    "fig4 range reversed": (("fig4", "lo"), 1.5, ["fig4.lo = 1.5", "fig4.hi = 1.4", "lo < hi"]),
    "boundary range empty": (("boundary", "hi"), 0.1, ["boundary.hi = 0.1", "lo < hi"]),
    "fig3 range reversed": (("fig3", "f_d_max"), 0.5, ["fig3.f_d_max = 0.5", "f_d_min < f_d_max"]),
    "nonlinear range reversed": (
        ("nonlinear", "f_hi"), 5.0, ["nonlinear.f_lo = ", "nonlinear.f_hi = 5.0", "f_lo < f_hi"]
    ),
    "fig7 L beyond R": (("fig7", "L"), [1e-3, 0.2], ["fig7.L[1]", "0.2", "beam.R"]),
    "N too small": (("numerics", "N"), 2, ["numerics.N", "2", "[3, 2000]"]),
    "convergence N too small": (("convergence", "N"), [5, 2], ["convergence.N[1]", "2", "[3,"]),
    "convergence N one grid": (("convergence", "N"), [5], ["convergence.N", "[5]", "2 or more"]),
    "frames zero": (("fig2", "frames"), 0, ["fig2.frames", "0", "[1, 64]"]),
    "move scene N text": (
        ("move_designs", 0, "scene", "numerics", "N"), "abc",
        ["move_designs[0].scene.numerics.N", "'abc'", "integer"],
    ),
    "move scene E zero": (
        ("move_designs", 0, "scene", "beam"), {"E": 0}, ["move_designs[0].scene.beam.E", "> 0"]
    ),
    "move angle and speeds": (
        ("move_designs", 0, "omega_end"), 5.0, ["move_designs[0].", "--angle", "not both"]
    ),
    "move speed beyond limit": (
        ("move_designs", 0), {"name": "s", "omega_start": 0.0, "omega_end": 20.0,
                              "max_speed": 10.0, "max_accel": 100.0},
        ["move_designs[0].omega_end = 20.0", "max_speed = 10"],
    ),
    "move box unknown": (
        ("move_designs", 0, "robust"), "Young=+-5%", ["move_designs[0].", "Young"]
    ),
    "zeta_max too large": (("figE10", "zeta_max"), 0.6, ["figE10.zeta_max", "0.6", "0.53]"]),
    "h_over_L 1": (("fig7", "h_over_L"), [1.0], ["fig7.h_over_L[0]", "1.0", "(0, 1)"]),
}  # fmt: skip


@pytest.mark.parametrize("path, value, words", CONFIG_CASES.values(), ids=CONFIG_CASES.keys())
def test_config_bad_input_is_one_line(path, value, words):
    msg = config_message(with_value(path, value))
    for w in words:
        assert w in msg, (w, msg)


def test_shipped_configs_are_valid():
    for cfg in (FULL, QUICK):
        assert validate_config(cfg, SCHEMA)["beam"] == cfg["beam"]


SNAKEMAKE_CASES = {
    "threshold outside (0, 1)": ("main_threshold: 1.5\n", [], ["main_threshold = 1.5", "(0, 1)"]),
    "N too small": ("numerics: {N: 2}\n", [], ["numerics.N = 2", "[3, 2000]"]),
    "NaN in YAML": ("beam: {rho: .nan}\n", [], ["beam.rho = nan", "> 0"]),
    "reversed range": ("fig4: {lo: 1.0, hi: 0.5}\n", [], ["fig4.lo = 1.0", "fig4.hi = 0.5"]),
    "unknown key": ("beam: {Young: 2.0e+6}\n", [], ["beam.Young", "unknown key"]),
    "string via --config": ("", ["--config", "amplitude=fast"], ["amplitude = 'fast'", "> 0"]),
}  # fmt: skip


def test_workflow_stops_before_any_job_with_the_message(workflow_copy, tmp_path):
    """`snakemake -n` (and one real run) with a bad config: exit 2, one line, no job, no output.

    The cases run concurrently (each is a parse that stops at validation)."""
    env = snakemake_env()  # this checkout's rotbeam
    procs = {}
    for k, (name, (overlay, extra, _)) in enumerate(SNAKEMAKE_CASES.items()):
        bad = tmp_path / f"bad{k}.yaml"
        bad.write_text(overlay or "{}\n")
        dry = ["-n"] if k else []  # the first one is a real run: nothing may start
        cmd = [sys.executable, "-m", "snakemake", *dry, "--cores", "1", *extra]
        cmd += ["--configfile", "config/quick.yaml", str(bad)]
        procs[name] = subprocess.Popen(
            cmd, cwd=workflow_copy, env=env, text=True,
            stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        )  # fmt: skip
    for name, (_, _, words) in SNAKEMAKE_CASES.items():
        out, err = procs[name].communicate(timeout=300)
        assert procs[name].returncode == 2, (name, err[-2000:])
        assert "Traceback" not in err and "job" not in out.lower(), (name, out, err)
        ours = [line for line in err.splitlines() if line.startswith("rotbeam:")]
        assert len(ours) == 1, (name, err)
        for w in words:
            assert w in ours[0], (name, w, ours[0])
    assert not (workflow_copy / "results").exists()
    assert not (workflow_copy / "logs").exists()


# --- property-based -----------------------------------------------------------------------------


@st.composite
def valid_configs(draw):
    cfg = copy.deepcopy(QUICK)
    cfg["beam"]["E"] = draw(st.floats(1e5, 1e9))
    cfg["beam"]["gamma"] = draw(st.floats(0.0, 1.0))
    cfg["amplitude"] = draw(st.floats(0.01, 5.0))
    th = draw(st.lists(st.floats(0.001, 0.99), min_size=1, max_size=5, unique=True))
    cfg["thresholds"], cfg["main_threshold"] = th, draw(st.sampled_from(th))
    lo = draw(st.floats(0.01, 2.0))
    cfg["fig4"].update(lo=lo, hi=min(3.0, lo + draw(st.floats(0.01, 2.0))))
    cfg["fig4"]["points"] = draw(st.integers(3, 50))
    cfg["boundary"]["c_max"] = draw(st.lists(st.floats(0.1, 1e3), min_size=1, max_size=4))
    f_min = draw(st.floats(0.1, 10.0))
    cfg["fig3"].update(f_d_min=f_min, f_d_max=f_min + draw(st.floats(0.1, 20.0)))
    cfg["numerics"]["N"] = draw(st.integers(6, 200))
    cfg["numerics"]["rtol"] = draw(st.floats(1e-10, 1e-2))
    return cfg


@settings(max_examples=30, deadline=None)
@given(cfg=valid_configs())
def test_valid_configs_pass_and_give_finite_lines(cfg):
    checked = validate_config(cfg, SCHEMA)
    for spec in [*lines_from_config(checked).values(), *convergence_lines(checked).values()]:
        assert math.isfinite(spec["omega0"]) and spec["omega0"] >= 0
        assert all(math.isfinite(f) and f > 0 for f in spec.get("f_d", [1.0]))
    columns, _ = grid_columns(fig7_beams(checked))  # one sweep job per (E, L) column
    assert sum(map(len, columns.values())) == len(fig7_beams(checked))


def numeric_leaves(value, path=()):
    if isinstance(value, dict):
        for k, v in value.items():
            yield from numeric_leaves(v, (*path, k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from numeric_leaves(v, (*path, i))
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield path


LEAVES = list(numeric_leaves(QUICK))
ALWAYS_BAD = [NAN, INF, -INF, "abc", None, True, [], {}]
#: (section, key) of the registry's optional fields: None is their default (e.g. drive.settle)
OPTIONAL = {
    (sec, key) for sec, params in SECTIONS.items() for key, p in params.items() if p.optional
}


def dotted(path) -> str:
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else p)
    return out


@settings(max_examples=60, deadline=None)
@given(path=st.sampled_from(LEAVES), value=st.sampled_from(ALWAYS_BAD))
def test_invalid_config_values_name_key_and_value(path, value):
    assume(not (value is None and tuple(path[-2:]) in OPTIONAL))
    msg = config_message(with_value(path, value))
    assert msg.startswith(dotted(path)), (path, msg)
    assert repr(value) in msg, msg
    assert "must be" in msg


@settings(max_examples=25, deadline=None)
@given(
    omega0=st.floats(-15.0, 20.0),
    amplitude=st.floats(0.0, 2.0),
    f_d=st.floats(0.3, 5.0),
    E=st.floats(0.8e6, 3e6),
    gamma=st.floats(0.02, 0.2),
    N=st.integers(6, 10),
)
def test_valid_scenes_give_finite_results(omega0, amplitude, f_d, E, gamma, N):
    scene = {
        "beam": {"E": E, "gamma": gamma},
        "drive": {"omega0": omega0, "amplitude": amplitude, "f_d": f_d},
        "numerics": {"N": N, "integrate": False, "max_seconds": 60.0},
    }
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "scene.yaml"
        path.write_text(yaml.safe_dump(scene))
        rc, out, err = run_main(["simulate", "--scene", str(path), "--json"])
    assert rc in (0, 1), err  # 1: no verified steady state, still reported
    res = json.loads(out)
    for key in ("C_max", "E_max", "f_n_hz", "rms_quasistatic"):
        assert math.isfinite(res[key]), (key, res)
    if rc == 0:
        assert math.isfinite(res["rms_dynamic"]) and math.isfinite(res["delta_rms"])


NUMBER_BAD = [NAN, INF, "abc", None, True, [1.0]]
POSITIVE_BAD = [-1.0, 0.0, *NUMBER_BAD]
SCENE_BAD = {
    **{("beam", k): POSITIVE_BAD for k in ("L", "h", "b", "E", "rho", "R")},
    ("beam", "gamma"): [-1.0, *NUMBER_BAD],
    ("drive", "omega0"): NUMBER_BAD,
    ("drive", "amplitude"): [-1.0, *NUMBER_BAD],
    ("drive", "f_d"): POSITIVE_BAD,
    ("numerics", "N"): [2, 0, -3, 2001, 6.5, NAN, "abc", None, True],
    **{("numerics", k): [0.0, -1.0, 1.0, *NUMBER_BAD] for k in ("rtol", "ss_tol", "tail_tol")},
    ("numerics", "floquet_tol"): [0.0, -1.0, 1e-10, 2.0, *NUMBER_BAD],
    **{("numerics", k): POSITIVE_BAD for k in ("max_seconds", "max_tau")},
    **{("numerics", k): [0, 1.5, "abc", None, True] for k in ("rms_periods", "max_periods")},
    ("numerics", "samples_per_period"): [4, 8.5, "abc", None, True],
    **{("numerics", k): ["nope", 1.0, None] for k in ("method", "start")},
    ("numerics", "integrate"): ["yes", 1.0, None],
    **{("effects", k): ["yes", 1.0, None] for k in ("centrifugal", "euler", "damping")},
}


@st.composite
def invalid_scenes(draw):
    section, key = draw(st.sampled_from(sorted(SCENE_BAD)))
    value = draw(st.sampled_from(SCENE_BAD[(section, key)]))
    scene = {"drive": {"omega0": 5.0, "f_d": 2.0}, "numerics": {"N": 6}}
    scene.setdefault(section, {})[key] = value
    return section, key, value, scene


def value_shown(value) -> list[str]:
    """How a bad value may be shown: as given, or as the float it was read as."""
    shown = [repr(value)]
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        shown.append(repr(float(value)))
    return shown


@settings(max_examples=60, deadline=None)
@given(case=invalid_scenes())
def test_invalid_scenes_name_key_and_value(case):
    section, key, value, scene = case
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "scene.yaml"
        path.write_text(yaml.safe_dump(scene))
        rc, out, err = run_main(["simulate", "--scene", str(path), "--json"])
    line = one_clear_line(rc, err, [f"{section}.{key}"])
    assert any(v in line for v in value_shown(value)), line


@pytest.mark.parametrize("value", [0.0, 1e-10, 2.0])
def test_floquet_tol_outside_its_range_is_one_line(tmp_path, value):
    """numerics.floquet_tol in [1e-9, 1], from a scene file and from --floquet-tol (the
    property test above draws it among every key, not always outside its range)."""
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump({"drive": {"omega0": 5.0, "f_d": 2.0},
                                    "numerics": {"floquet_tol": value}}))  # fmt: skip
    for argv in (["simulate", "--scene", str(path)], [*SIM, "--floquet-tol", repr(value)]):
        rc, _, err = run_main(argv)
        line = one_clear_line(rc, err, ["numerics.floquet_tol", "[1e-09, 1]"])
        assert repr(value) in line, line


FLAGS = {  # flag: (scene key, valid values, bad values)
    "--omega0": ("drive.omega0", st.floats(-15.0, 20.0), ["nan", "inf", "x", "", "1e300"]),
    "--fd": ("drive.f_d", st.floats(0.3, 5.0), ["-1", "0", "nan", "-inf", "x", "1e300"]),
    "--amplitude": ("drive.amplitude", st.floats(0.0, 2.0), ["-1", "nan", "1e999", "x"]),
    "--N": ("numerics.N", st.integers(6, 10), ["2", "0", "-1", "2001", "2.5", "x", ""]),
    "--R": ("beam.R", st.floats(0.05, 1.0), ["0", "-1", "0.01", "nan", "x"]),
    "--rtol": ("numerics.rtol", st.floats(1e-6, 1e-3), ["0", "-1e-5", "1", "nan", "x"]),
    "--method": ("numerics.method", st.sampled_from(["Radau", "BDF"]), ["Euler", ""]),
    "--effects": (
        "effects", st.sampled_from(["all", "centrifugal,euler,damping"]), ["magic", "", ","]
    ),
}  # fmt: skip
REQUIRED = ("--omega0", "--fd")


@st.composite
def flag_sets(draw, bad: bool):
    chosen = set(draw(st.lists(st.sampled_from(sorted(FLAGS)), unique=True))) | set(REQUIRED)
    argv = ["simulate", "--json"]
    for flag in sorted(chosen):
        argv += [flag, str(draw(FLAGS[flag][1]))]
    if not bad:
        return argv, None, None
    flag = draw(st.sampled_from(sorted(chosen)))
    text = draw(st.sampled_from(FLAGS[flag][2]))
    return argv + [flag, text], flag, text


@settings(max_examples=20, deadline=None)
@given(case=flag_sets(bad=False))
def test_valid_flag_sets_give_finite_results(case):
    """Random valid flags on top of a scene file that keeps the run cheap (collocation only)."""
    argv, _, _ = case
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "scene.yaml"
        path.write_text("numerics: {N: 6, integrate: false, max_seconds: 30}\n")
        rc, out, err = run_main(argv + ["--scene", str(path)])
    assert rc in (0, 1), err
    res = json.loads(out)
    for key in ("C_max", "E_max", "rms_quasistatic"):
        assert math.isfinite(res[key]), (key, res)


@settings(max_examples=60, deadline=None)
@given(case=flag_sets(bad=True))
def test_invalid_flags_name_flag_and_value(case):
    argv, flag, text = case
    rc, out, err = run_main(argv)
    line = one_clear_line(rc, err, [])
    assert flag in line or FLAGS[flag][0] in line, line
    try:
        shown = [repr(text), repr(float(text)), text]
    except ValueError:
        shown = [repr(text)]
    assert any(v in line for v in shown), line


@pytest.mark.parametrize(
    "args, words",
    [
        (["--column", "E9_L9"], ["--column E9_L9", "E100000_L0.01"]),
        (["--column"], ["--column needs a column id"]),
        (["--column", "E100000_L0.01", "nope.yaml"], ["config nope.yaml", "no such file"]),
        (["x"], ["repeats = 'x'", ">= 1"]),
        (["0"], ["repeats = 0", ">= 1"]),
    ],
)
def test_floquet_steps_bench_names_the_bad_argument(args, words, monkeypatch):
    """`python3 -m rotbeam.paper.floquet_steps` with a bad argument: one line naming it and what
    is allowed, before any simulation."""
    from rotbeam.paper import floquet_steps

    monkeypatch.chdir(ROOT)
    with pytest.raises(SystemExit) as exc:
        floquet_steps.main(args)
    message = str(exc.value)
    assert message.startswith("floquet_steps: ") and "\n" not in message
    for word in words:
        assert word in message
