"""The effect budget (rotbeam.analysis.effect_budget, `rotbeam effects`): the Euler load is the
only forcing (limit case), the sequential shares telescope to 1, and the centrifugal share
against a one-mode estimate from the eigenproblem of rotbeam.model.modes."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest

from rotbeam.analysis.effect_budget import effect_budget
from rotbeam.model.modes import modes
from rotbeam.model.params import Beam
from rotbeam.runs.scene import build_scene


def scene(omega0: float, f_d: float, N: int = 12):
    return build_scene({"drive": {"omega0": omega0, "f_d": f_d}, "numerics": {"N": N}})


def test_euler_load_is_the_forcing_and_sequential_shares_add_to_one():
    """Without the Euler load the straight beam stays straight (RMS 0 exactly), so its
    one-at-a-time share is 1 and the sequential shares, which end with it, sum to 1."""
    b = effect_budget(scene(5.0, 2.0))
    rows = {r.effect: r for r in b.shares}
    assert set(rows) == {"centrifugal", "softening", "euler", "coriolis", "damping", "extension"}
    assert rows["euler"].rms == 0.0 and rows["euler"].share_rms == 1.0
    assert rows["coriolis"].method == "switched on" and not rows["coriolis"].on_in_scene
    assert rows["damping"].method == "first order in gamma"
    assert list(b.sequential) == ["softening", "centrifugal", "euler"]
    assert b.rms_last == 0.0
    assert sum(b.sequential.values()) == pytest.approx(1.0, abs=1e-12)
    # the first sequential step is the same run as the one-at-a-time switch
    assert b.sequential["softening"] == pytest.approx(rows["softening"].share_rms, rel=1e-12)


@pytest.mark.parametrize("omega0", [5.0, 10.0])
def test_centrifugal_share_against_one_mode_estimate(omega0):
    """Below resonance (2 Hz) the response is mostly the first mode: RMS ~ 1 / |w_1^2 - w_d^2|,
    with w_1 stiffened by rotation (at the mean of Omega^2 over the drive, Omega_0^2 + a^2 / 2).
    Switching centrifugal (and softening) off takes w_1 back to the non-rotating value, so
    its share is 1 - |f_1(Omega)^2 - f_d^2| / |f_1(0)^2 - f_d^2|.  Measured: -0.0741 against
    -0.0790 at 5 rad/s, -0.292 against -0.311 at 10 rad/s (6 % under the estimate at both: the
    higher modes and the mode shape's change are not in it)."""
    f_d, beam = 2.0, Beam()
    f0 = modes(beam, 0.0, 1, N=80)[0]
    fw = modes(beam, math.sqrt(omega0**2 + 0.5), 1, N=80)[0]
    estimate = 1.0 - abs(fw**2 - f_d**2) / abs(f0**2 - f_d**2)
    rows = {r.effect: r for r in effect_budget(scene(omega0, f_d, N=20)).shares}
    assert rows["centrifugal"].share_rms < 0  # stiffening: RMS grows without it
    assert rows["centrifugal"].share_rms == pytest.approx(estimate, rel=0.15)


def test_effects_cli_json_and_bad_input():
    run = [sys.executable, "-m", "rotbeam", "effects", "--omega0", "5", "--fd", "15"]
    p = subprocess.run(run + ["--N", "8", "--json"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    assert {r["effect"] for r in out["effects"]} >= {"centrifugal", "euler", "damping"}
    assert sum(out["sequential"]["shares"].values()) == pytest.approx(1.0, abs=1e-12)
    bad = subprocess.run(run[:-1] + ["-3"], capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "--fd" in bad.stderr


def test_auto_effects_tol_zero_keeps_every_effect_and_default_drops_coriolis():
    from rotbeam.analysis.effect_budget import auto_effects

    b = effect_budget(scene(5.0, 2.0))
    every = auto_effects(b, 0.0)
    assert every.dropped == [] and all(vars(every.effects).values())
    auto = auto_effects(b)  # 0.1 % of RMS
    coriolis = next(r for r in b.shares if r.effect == "coriolis")
    stretch = next(r for r in b.shares if r.effect == "extension")
    assert abs(coriolis.share_rms) < 1e-3 and abs(stretch.share_rms) < 1e-3  # at 5 rad/s
    assert auto.dropped == ["coriolis", "extension"]
    assert auto.dropped_share == abs(coriolis.share_rms) + abs(stretch.share_rms)
    assert auto.effects.damping and any("damping kept" in n for n in auto.notes)
    assert auto.effects.centrifugal and auto.effects.euler


def test_simulate_effects_auto_cli():
    run = [sys.executable, "-m", "rotbeam", "simulate", "--omega0", "5", "--fd", "2",
           "--N", "8", "--json", "--effects"]  # fmt: skip
    p = subprocess.run(run + ["auto"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    assert "coriolis" not in out["effects"]
    assert out["effects_auto"]["dropped"] == ["coriolis", "extension"]
    bad = subprocess.run(run + ["auto:2"], capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and "[0, 1)" in bad.stderr and bad.stderr.count("\n") == 1


def _cli(*argv: str, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "rotbeam", *argv], capture_output=True,
                          text=True, timeout=timeout)  # fmt: skip


@pytest.mark.slow  # several CLI runs, each with its budget
def test_critical_effects_auto_cli():
    """`rotbeam critical --effects auto` budgets the effects at the search's start (the linear
    estimate of f_d*): at 5 rad/s Coriolis and extension are below 0.1 % of RMS and dropped;
    TOL = 0 keeps every effect; a bad TOL is one line and exit 2."""
    run = ["critical", "--omega0", "5", "--N", "8", "--json", "--effects"]
    out = json.loads((p := _cli(*run, "auto")).stdout or "{}")
    assert p.returncode == 0, p.stderr
    auto = out["effects_auto"]
    assert auto["dropped"] == ["coriolis", "extension"] and auto["tol"] == 1e-3
    assert auto["budget_f_d"] == pytest.approx(out["estimate_hz"], rel=1e-12)
    assert out["effects"] == "centrifugal,softening,euler,damping"
    every = json.loads((p := _cli(*run, "auto:0")).stdout or "{}")
    assert p.returncode == 0, p.stderr
    assert every["effects_auto"]["dropped"] == []
    assert every["effects"] == "centrifugal,softening,euler,coriolis,damping,extension"
    # the dropped effects were worth < 0.1 % of RMS, so f_d* moves by less than its tolerance
    assert every["f_d_star"] == pytest.approx(out["f_d_star"], rel=2e-3)
    for bad in ("auto:-0.1", "auto:1", "auto:x"):
        p = _cli(*run, bad, timeout=120)
        assert p.returncode == 2 and p.stderr.count("\n") == 1 and "[0, 1)" in p.stderr, bad


@pytest.mark.slow  # several CLI runs, each with its budget
def test_scene_file_effects_auto(tmp_path):
    """A scene file's `effects: auto` (or `{auto: TOL}`) is `--effects auto[:TOL]`; an explicit
    --effects list wins over it; a bad TOL names effects.auto in one line, exit 2."""
    from rotbeam.config.scenefile import split_auto

    assert split_auto({"effects": "auto"}) == ({}, 1e-3)
    assert split_auto({"effects": {"auto": 0, "coriolis": True}}) == (
        {"effects": {"coriolis": True}}, 0.0)  # fmt: skip
    assert split_auto({"effects": {"coriolis": True}}) == ({"effects": {"coriolis": True}}, None)

    def scene_file(effects: str) -> str:
        path = tmp_path / f"s{len(list(tmp_path.iterdir()))}.yaml"
        path.write_text(f"drive: {{omega0: 5, f_d: 2}}\nnumerics: {{N: 8}}\neffects: {effects}\n")
        return str(path)

    out = json.loads(
        (p := _cli("simulate", "--scene", scene_file("auto"), "--json")).stdout or "{}"
    )
    assert p.returncode == 0, p.stderr
    assert out["effects_auto"]["dropped"] == ["coriolis", "extension"]
    assert out["effects"] == "centrifugal,softening,euler,damping"
    zero = scene_file("{auto: 0}")
    out = json.loads((p := _cli("simulate", "--scene", zero, "--json")).stdout or "{}")
    assert p.returncode == 0, p.stderr
    assert out["effects_auto"]["dropped"] == [] and "extension" in out["effects"]
    listed = _cli("simulate", "--scene", zero, "--json", "--effects", "centrifugal,euler,damping")
    out = json.loads(listed.stdout or "{}")
    assert "effects_auto" not in out and out["effects"] == "centrifugal,euler,damping"
    for bad in ("{auto: 2}", "{auto: yes}", "auto:-1"):
        p = _cli("simulate", "--scene", scene_file(bad), timeout=120)
        assert p.returncode == 2 and p.stderr.count("\n") == 1 and "effects" in p.stderr, bad
        assert "[0, 1)" in p.stderr, bad
