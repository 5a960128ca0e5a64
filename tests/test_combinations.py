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
  equation (`tip_loaded_root`, a closed form).

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


def test_the_matrix_is_whole():
    """4 commands x 5 drives x 3 beams x 3 effects, and how many refuse (the note's count)."""
    refused = [c for c in CELLS if refusal(c[0], c[1], c[3]) is not None]
    assert len(CELLS) == 180
    assert len(refused) == 3 * (3 * 3) + 3 * 1 + 2 * 4 * 3  # move x 3 commands; auto: 54
