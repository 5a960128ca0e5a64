"""Every combination a user can type: command x drive x beam x effects, through the command line
and the Python API, generated.  Each cell either answers, the same through both interfaces, and
its answer is checked against something independent, or refuses in one line that is true for
what the user typed (exit status 2 on the command line, `RotbeamInputError` from the API).

The independent checks, by command:

* simulate, a periodic drive: the quasi-static RMS, Richardson-extrapolated from N = 8 and 16,
  against the rigid-link chain's (tests/chain_model.py, 16 and 32 links, extrapolated; the
  payload's mass and rotary inertia in it), 0.2 % apart (measured 0.01-0.04 %; the rotary
  inertia alone moves it 0.3 %); the chain is inextensible, so where `--effects auto` keeps
  the extension the tolerance adds the extension's share of RMS that the budget measured;
* simulate, a move: the beam starts at rest (y_m = 0 and zero rate at t = 0, the radially
  clamped beam straight at a steady speed);
* critical: a separate run at the f_d* it found has Delta RMS = threshold (to the search's
  tolerance in f_d);
* effects: with the Euler load switched off the beam stays straight (RMS(y_m) = 0: the radial
  clamp's centrifugal load bends it nowhere), so the Euler load's share is 1;
* sweep: every row equals `simulate` of the scene alone at its f_d;
* modes: the first frequency at rest against the tip-loaded cantilever's characteristic
  equation (`tip_loaded_root`, a closed form);
* atlas (every drive, beam and effects): the last row against `simulate` started afresh at its
  point; a profile or a move (their own speeds) and auto (a budget at one frequency) refused;
* design-move (every beam, a list of effects with the payload): the move file it writes run
  again by `simulate_move` gives its residual, and integrates to its angle; auto refused.

The matrix and the reason of each refusal: `CELLS` and `REFUSALS`; `test_the_matrix_is_whole`
holds the count.  Every cell is in the quick subset (N = 8, drives off resonance: the matrix
takes 34 s on two workers).
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import yaml
from chain_model import ChainModel
from test_bad_input import run_main

import rotbeam
from rotbeam.analysis.effect_budget import auto_scene
from rotbeam.analysis.verdict import critical_start_hz
from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.params import tip_loaded_root
from rotbeam.runs.move import simulate_move
from rotbeam.runs.scene import build_scene, quasistatic_midspan
from rotbeam.runs.sweeps import sweep

NUMERICS = {"N": 8, "max_seconds": 120.0}
DRIVES = {
    "sine": {"omega0": 20.0, "amplitude": 1.0, "f_d": 1.0},
    "harmonics": {"omega0": 20.0, "f_d": 1.0, "harmonics": [
        {"k": 1, "amplitude": 1.0}, {"k": 3, "amplitude": 0.5, "phase": 0.7}]},
    "profile": {"f_d": 1.0, "profile": "profile.csv"},
    "named profile": {"f_d": 1.0, "profile": {"shape": "s-curve", "omega_min": 15.0,
                                              "omega_max": 25.0, "ramp": 0.5}},
    "move": {"move": "move.csv", "settle": 0.2},
}  # fmt: skip
BEAMS = {
    "bare": {},
    "tip mass": {"tip_mass": 2.34e-4},  # a quarter of the beam's mass
    "tip mass and inertia": {"tip_mass": 2.34e-4, "tip_inertia": 1.5e-8},
}
EFFECTS = {"default": None, "list": "centrifugal,euler,coriolis,damping", "auto": "auto"}
COMMANDS = ("simulate", "critical", "effects", "sweep")
#: the sweep's line [Hz].  The drives stay below the first mode's resonances, also with an
#: effect switched off (harmonic 3 of 1 Hz at 3 Hz; the payload beams' f_1 is 5.4 Hz at rest and
#: 8.2 Hz at 21.5 rad/s): a cell is a combination, not a hard case
LINE: dict[str, tuple[float, float]] = {}

#: (command, drive, effects) -> the words of the one-line refusal, and why it is the truth
REFUSALS = {
    ("critical", "move"): "a single move has no repetition rate",
    ("sweep", "move"): "a sweep needs a periodic drive",
    ("effects", "move"): "a single move has no periodic steady state",
    ("simulate", "move", "auto"): "a move takes neither --effects auto",
    ("effects", "auto"): "rotbeam effects computes the budget that auto reads",
    ("sweep", "auto"): "effects: auto runs an effect budget at one drive frequency",
}

#: id(scene) -> the extension's share of RMS, for the scenes `--effects auto` chose
EXTENSION: dict[int, float] = {}

CELLS = [(c, d, b, e) for c in COMMANDS for d in DRIVES for b in BEAMS for e in EFFECTS]


def refusal(command: str, drive: str, effects: str) -> str | None:
    """The refusal's words of a cell, None where it answers."""
    for key in ((command, drive, effects), (command, effects), (command, drive)):
        if key in REFUSALS:
            return REFUSALS[key]
    return None


def write_files(folder: Path) -> None:
    """The drive files the cells read: one sampled period (a smooth profile, 32 samples) and
    a sin^2 move, 10 -> 20 -> 10 rad/s in 0.3 s."""
    x = np.arange(32) / 32
    w = 20.0 + np.sin(2 * np.pi * x) + 0.3 * np.sin(4 * np.pi * x + 0.4)
    np.savetxt(folder / "profile.csv", np.column_stack([x, w]), delimiter=",",
               header="phase,omega", comments="")  # fmt: skip
    t = np.linspace(0.0, 0.3, 61)
    np.savetxt(folder / "move.csv", np.column_stack([t, 10 + 10 * np.sin(np.pi * t / 0.3) ** 2]),
               delimiter=",", header="t,omega", comments="")  # fmt: skip


def spec(drive: str, beam: str, effects: str) -> dict:
    out = {"beam": dict(BEAMS[beam]), "drive": dict(DRIVES[drive]), "numerics": dict(NUMERICS)}
    if effects == "list":
        out["effects"] = rotbeam.Effects.from_list(EFFECTS["list"]).__dict__.copy()
    return out


def cli_args(command: str, drive: str, effects: str, path: Path) -> list[str]:
    args = [command, "--scene", str(path), "--json", "--quiet"]
    if effects == "auto":
        args += ["--effects", "auto"]
    if command == "sweep":
        lo, hi = LINE.get(drive, (0.8, 1.2))
        args += ["--fd-min", str(lo), "--fd-max", str(hi), "--points", "2"]
    return args


def api(command: str, drive: str, effects: str, scene):
    """The same request through the Python API: (the answer, the scene it ran)."""
    if command == "simulate":
        if scene.drive.move is not None:
            if effects == "auto":
                raise RotbeamInputError(REFUSALS["simulate", "move", "auto"])
            return simulate_move(scene), scene
        if effects == "auto":
            scene, _, budget = auto_scene(scene)
            EXTENSION[id(scene)] = next(
                abs(s.share_rms) for s in budget.shares if s.effect == "extension"
            )
        return rotbeam.simulate(scene), scene
    if command == "critical":
        if effects == "auto":
            start = critical_start_hz(scene)
            auto = auto_scene(replace(scene, drive=replace(scene.drive, f_d=start)))[0]
            scene = replace(scene, effects=auto.effects)
        return rotbeam.critical(scene), scene
    if command == "effects":
        if effects == "auto":  # the API has no auto budget of a budget: what the CLI says
            raise RotbeamInputError(REFUSALS["effects", "auto"])
        return rotbeam.effect_budget(scene), scene
    if effects == "auto":
        raise RotbeamInputError(REFUSALS["sweep", "auto"])
    return sweep(scene, np.linspace(*LINE.get(drive, (0.8, 1.2)), 2)), scene


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("cells")
    write_files(out)
    return out


@pytest.mark.parametrize("cell", CELLS, ids=["-".join(c) for c in CELLS])
def test_cell(cell, folder, tmp_path):
    command, drive, beam, effects = cell
    path = tmp_path / "scene.yaml"
    s = spec(drive, beam, effects)
    for key in ("profile", "move"):  # the scene file reads its drive file next to it
        if isinstance(s["drive"].get(key), str):
            s["drive"][key] = str(folder / s["drive"][key])
    path.write_text(yaml.safe_dump(s))
    rc, out, err = run_main(cli_args(command, drive, effects, path))
    words = refusal(command, drive, effects)
    if words is not None:
        assert rc == 2 and out == "" and "Traceback" not in err, (rc, err)
        assert len(err.strip().splitlines()) == 1 and words in err, err
        with pytest.raises(RotbeamInputError, match=words.split("(")[0][:40]):
            api(command, drive, effects, build_scene(s, folder))
        return
    assert rc in (0, 1) and "Traceback" not in err, err
    answer = json.loads(out)
    result, ran = api(command, drive, effects, build_scene(s, folder))
    CHECKS[command](answer, result, ran)


def check_simulate(answer: dict, result, scene) -> None:
    if scene.drive.move is not None:
        assert answer["peak_ym"] == pytest.approx(result.peak_ym, rel=1e-9)
        # at rest before the move: the straight beam, then y_m grows like t^2
        assert result.y_dynamic[0] == 0.0
        assert abs(result.y_dynamic[1]) < 1e-3 * result.peak_ym
        return
    assert answer["rms_dynamic"] == pytest.approx(result.rms_dynamic, rel=1e-9)
    assert answer["effects"] == ",".join(scene.effects.active())
    ours = richardson(result.rms_quasistatic, qs_rms(scene, result.tau, 16))
    chain = richardson(*(chain_qs_rms(scene, result.tau, n) for n in (16, 32)))
    stretch = EXTENSION.get(id(scene), 0.0) if scene.effects.extension else 0.0
    assert ours == pytest.approx(chain, rel=2e-3 + stretch)


def richardson(coarse: float, fine: float) -> float:
    return (4.0 * fine - coarse) / 3.0


def qs_rms(scene, taus: np.ndarray, N: int) -> float:
    """The quasi-static RMS of the scene on N intervals at the given instants."""
    return float(np.sqrt(np.mean(quasistatic_midspan(scene.model(N), taus)[1] ** 2)))


def chain_qs_rms(scene, taus: np.ndarray, n: int) -> float:
    """The same from the rigid-link chain: its static state at each instant's loads."""
    b, eff, dl = scene.beam, scene.effects, scene.dimensionless
    mu, j = b.payload_ratios
    chain = ChainModel(n, b.delta, eta=b.eta, centrifugal=eff.centrifugal,
                       softening=eff.softening, euler=eff.euler, coriolis=eff.coriolis,
                       tip_mass=mu, tip_inertia=j)  # fmt: skip
    ys, phi = [], None
    for t in taus:
        phi = chain.static_angles(dl.lam(t), dl.lam_dot(t), phi)
        ys.append(chain.nodes(phi)[1][n // 2])
    return float(np.sqrt(np.mean(np.square(ys))))


def check_critical(answer: dict, result, scene) -> None:
    assert answer["found"] and result.found, result.message
    assert answer["f_d_star"] == pytest.approx(result.f_d_star, rel=1e-9)
    at = rotbeam.simulate(replace(scene, drive=replace(scene.drive, f_d=result.f_d_star)))
    assert at.delta_rms == pytest.approx(result.threshold, abs=5e-3)


def check_effects(answer: dict, result, scene) -> None:
    euler = next(s for s in result.shares if s.effect == "euler")
    assert euler.rms < 1e-9 * result.rms  # no Euler load: the straight beam
    assert euler.share_rms == pytest.approx(1.0, abs=1e-9)
    row = next(r for r in answer["effects"] if r["effect"] == "euler")
    assert row["share_rms"] == pytest.approx(euler.share_rms, rel=1e-9)


def check_sweep(answer: dict, result, scene) -> None:
    rows = answer["rows"]
    assert [r["rms_dynamic"] for r in rows] == pytest.approx(
        list(result.rows["rms_dynamic"]), rel=1e-9
    )
    for r in rows:
        alone = rotbeam.simulate(replace(scene, drive=replace(scene.drive, f_d=r["f_d"])))
        assert r["rms_dynamic"] == pytest.approx(alone.rms_dynamic, rel=1e-4)


CHECKS = {"simulate": check_simulate, "critical": check_critical, "effects": check_effects,
          "sweep": check_sweep}  # fmt: skip


@pytest.mark.parametrize("beam", BEAMS)
def test_modes_cell(beam, tmp_path):
    """`rotbeam modes` takes a beam and a speed, nothing of a drive: at rest its first
    frequency is the tip-loaded cantilever's, b^2 f_s (the scheme is second order in the tip
    mass, first order in its rotary inertia: 1e-3 and 5e-3 at N = 40)."""
    path = tmp_path / "beam.yaml"
    path.write_text(yaml.safe_dump({"beam": BEAMS[beam]}))
    rc, out, err = run_main(["modes", "--scene", str(path), "--json"])
    assert rc == 0, err
    b = rotbeam.Beam(**BEAMS[beam])
    f1 = json.loads(out)["frequencies_hz"][0]
    assert f1 == pytest.approx(rotbeam.modes(b, 0.0, 1)[0], rel=1e-12)
    exact = tip_loaded_root(*b.payload_ratios) ** 2 * b.f_s
    assert f1 == pytest.approx(exact, rel=5e-3 if b.tip_inertia else 1e-3)


@pytest.mark.parametrize("flag", [["--move", "m.csv"], ["--fd", "2"], ["--effects", "auto"]])
def test_modes_refuses_what_it_does_not_read(flag):
    rc, out, err = run_main(["modes", *flag])
    assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1, err
    assert "unrecognized arguments" in err and flag[0] in err


#: the atlas's grid: two lines about 10 and 20 rad/s, 0.8 and 1.2 Hz (below every resonance)
ATLAS_AXES = ([10.0, 20.0], [0.8, 1.2])
ATLAS_ARGS = ["--omega0-min", "10", "--omega0-max", "20", "--fd-min", "0.8", "--fd-max", "1.2",
              "--points", "2,2", "--workers", "1"]  # fmt: skip
#: the designed move: a slew through 0.1 rad within limits that a jerk limit keeps smooth
DESIGN = {"angle": 0.1, "max_speed": 5.0, "max_accel": 50.0, "max_jerk": 5000.0,
          "residual": 0.005}  # fmt: skip
DESIGN_ARGS = ["--angle", "0.1", "--max-speed", "5", "--max-accel", "50", "--max-jerk", "5000",
               "--residual", "0.005", "--rtol", "1e-4", "--no-baselines"]  # fmt: skip
#: (command, drive or effects) -> the words of the one-line refusal of the atlas and the design
GRID_REFUSALS = {
    ("atlas", "profile"): "a profile has its own speeds",
    ("atlas", "named profile"): "a profile has its own speeds",
    ("atlas", "move"): "a move has its own speeds",
    ("atlas", "auto"): "auto runs an effect budget at one drive frequency",
    ("design-move", "auto"): "auto is not read here",
}
#: a design costs two searches (one per interface) and a rerun, 10-20 s a cell: every beam
#: with the default effects, the payload with a list, and the refusal of auto
GRID_CELLS = [("atlas", d, b, e) for d in DRIVES for b in BEAMS for e in EFFECTS] + [
    *(("design-move", "sine", b, "default") for b in BEAMS),
    ("design-move", "sine", "tip mass", "list"),
    ("design-move", "sine", "bare", "auto"),
]


def scene_file(folder: Path, tmp_path: Path, drive: str, beam: str, effects: str) -> Path:
    """The cell's scene file, its drive files named by absolute path."""
    s = spec(drive, beam, effects)
    for key in ("profile", "move"):
        if isinstance(s["drive"].get(key), str):
            s["drive"][key] = str(folder / s["drive"][key])
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump(s))
    return path


@pytest.mark.parametrize("cell", GRID_CELLS, ids=["-".join(c) for c in GRID_CELLS])
def test_grid_cell(cell, folder, tmp_path):
    """The atlas and the motion design over the same drives, beams and effects: a refusal in
    one line from both interfaces, or the same answer from both, checked independently (an
    atlas row against `rotbeam.simulate` started afresh at its point; the designed move's file
    run again by `simulate_move`, its residual and angle)."""
    command, drive, beam, effects = cell
    path = scene_file(folder, tmp_path, drive, beam, effects)
    args = [command, "--scene", str(path), "--json", "--quiet"]
    args += ["--effects", "auto"] if effects == "auto" else []
    args += ATLAS_ARGS if command == "atlas" else [*DESIGN_ARGS, "--out", str(tmp_path / "m.csv")]
    rc, out, err = run_main(args)
    scene = build_scene(spec(drive, beam, effects), folder)
    words = GRID_REFUSALS.get((command, effects)) or GRID_REFUSALS.get((command, drive))
    if words is not None:
        assert rc == 2 and out == "" and "Traceback" not in err, (rc, err)
        assert len(err.strip().splitlines()) == 1 and words in err, err
        if effects != "auto":  # the API takes a list of effects only: auto is a CLI word
            with pytest.raises(RotbeamInputError, match=words):
                rotbeam.atlas(scene, *ATLAS_AXES, workers=1)
        return
    assert rc == 0 and "Traceback" not in err, err
    answer = json.loads(out)
    if command == "atlas":
        check_atlas(answer, rotbeam.atlas(scene, *ATLAS_AXES, workers=1), scene)
    else:
        scene = replace(scene, numerics=replace(scene.numerics, rtol=1e-4))
        design = rotbeam.design_move(scene, baselines=False, **DESIGN)
        again = spec(drive, beam, effects)  # the move file in the cell's scene, run again
        again["drive"] = {"move": str(tmp_path / "m.csv"), "settle": design.settle_s}
        again["numerics"]["rtol"] = 1e-4
        check_design(answer, design, build_scene(again), tmp_path / "m.csv")


def check_atlas(answer: dict, atlas, scene) -> None:
    rows = atlas.rows
    assert len(rows) == 4 and rows["ran"].all() and rows["converged"].all()
    cli_rows = answer["rows"]
    assert [r["delta_rms"] for r in cli_rows] == pytest.approx(list(rows["delta_rms"]), rel=1e-9)
    last = rows.iloc[-1]  # the last point of the last line: continued the furthest
    drive = replace(scene.drive, omega0=float(last["omega0"]), f_d=float(last["f_d"]))
    alone = rotbeam.simulate(replace(scene, drive=drive))
    assert last["rms_dynamic"] == pytest.approx(alone.rms_dynamic, rel=1e-6)
    assert last["rms_quasistatic"] == pytest.approx(alone.rms_quasistatic, rel=1e-9)


def check_design(answer: dict, design, rerun, csv: Path) -> None:
    assert answer["found"] and design.found, design.message
    assert answer["duration_s"] == pytest.approx(design.duration_s, rel=1e-9)
    assert answer["residual"] == pytest.approx(design.check.residual, rel=1e-9)
    assert answer["residual"] <= DESIGN["residual"]
    again = simulate_move(rerun)
    assert again.converged, again.message
    assert again.residual_ym == pytest.approx(answer["residual"], rel=1e-6)
    t, omega = (np.loadtxt(csv, delimiter=",", skiprows=1, usecols=(i,)) for i in (0, 1))
    assert float(np.sum(np.diff(t) * (omega[1:] + omega[:-1]) / 2)) == pytest.approx(
        DESIGN["angle"], rel=1e-5
    )


def test_the_matrix_is_whole():
    """4 commands x 5 drives x 3 beams x 3 effects, and how many refuse (the note's count);
    the atlas over the same 45, the design over 5 (`GRID_CELLS`)."""
    refused = [c for c in CELLS if refusal(c[0], c[1], c[3]) is not None]
    assert len(CELLS) == 180
    assert len(refused) == 3 * (3 * 3) + 3 * 1 + 2 * 4 * 3  # move x 3 commands; auto: 54
    grid_refused = [c for c in GRID_CELLS if c[3] == "auto" or c[:2] in GRID_REFUSALS]
    assert len(GRID_CELLS) == 5 * 3 * 3 + 5 and len(grid_refused) == 3 * 3 * 3 + 2 * 3 + 1
