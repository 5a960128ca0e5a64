"""The modal reduced model (`rotbeam.model.modal`) through every solver.

Three independent checks: with every mode kept the modal model is the elastica in other
coordinates, so each command must give the elastica's answer (to the solvers' tolerances); its
frequencies are Rayleigh-Ritz estimates of the elastica's (exact at the rotation the modes are
taken at, upper bounds converging in n elsewhere); its RMS converges to the elastica's as n
grows, and n = 1 is the one-mode surrogate of Sec. 6 where that applies (small amplitude).
"""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from test_bad_input import run_main

import rotbeam
from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.modal import ModalModel
from rotbeam.model.modes import linear_frequencies
from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.model.surrogate import steady_rms
from rotbeam.runs.move import simulate_move
from rotbeam.runs.scene import Scene, simulate
from rotbeam.runs.sweeps import sweep
from rotbeam.solve.numerics import Numerics

N = 10
BARE = Beam()
PAYLOAD = Beam(tip_mass=0.004, tip_inertia=2e-6)


def _scene(beam=BARE, drive=None, model="elastica", modes=3, tail_tol=1e-8, **num) -> Scene:
    drive = drive if drive is not None else Drive(omega0=10.0, amplitude=3.0, f_d=4.0)
    num = Numerics(N=N, model=model, modes=modes, tail_tol=tail_tol, samples_per_period=256,
                   **num)  # fmt: skip
    return Scene(beam, drive, Effects(), num)


def _pair(scene: Scene) -> tuple[Scene, Scene]:
    """The scene on the elastica and on its modal model with every mode."""
    full = replace(scene, numerics=replace(scene.numerics, model="elastica"))
    modal = replace(scene, numerics=replace(scene.numerics, model="modal", modes=N - 1))
    return full, modal


@pytest.mark.parametrize("beam, drive", [(Beam(), Drive(omega0=10.0, amplitude=3.0, f_d=4.0)),
                                         (PAYLOAD, Drive(omega0=10.0, amplitude=1.0, f_d=3.0))],
                         ids=["bare", "payload"])  # fmt: skip
@pytest.mark.parametrize("certify", ["monodromy", "time"])
def test_every_mode_simulates_the_elastica(beam, drive, certify):
    full, modal = (simulate(s) for s in _pair(_scene(beam, drive, certify=certify)))
    assert full.dynamic.converged and modal.dynamic.converged
    for key in ("rms_dynamic", "rms_quasistatic", "delta_rms"):
        assert getattr(modal, key) == pytest.approx(getattr(full, key), rel=1e-6)
    assert modal.dynamic.floquet.max_abs == pytest.approx(full.dynamic.floquet.max_abs, rel=1e-6)
    names = ("tip", "root_moment", "tip_acceleration")
    obs_full, obs_modal = full.observables(names), modal.observables(names)
    for name in names:
        for key in ("rms_dynamic", "peak_dynamic", "peak_quasistatic"):
            assert obs_modal[name][key] == pytest.approx(obs_full[name][key], rel=1e-7)


def test_every_mode_sweeps_and_finds_f_d_star_as_the_elastica():
    full, modal = _pair(_scene(drive=Drive(omega0=10.0, amplitude=2.0, f_d=2.0)))
    a, b = sweep(full, [2.0, 3.0]), sweep(modal, [2.0, 3.0])
    np.testing.assert_allclose(b.rows["delta_rms"], a.rows["delta_rms"], rtol=1e-6)
    ca, cb = rotbeam.critical(full, 0.2), rotbeam.critical(modal, 0.2)
    assert cb.f_d_star == pytest.approx(ca.f_d_star, rel=1e-4)


def test_every_mode_runs_a_move_as_the_elastica(tmp_path):
    path = tmp_path / "move.csv"
    t = np.linspace(0.0, 0.3, 31)
    omega = 4.0 * np.sin(np.pi * t / 0.6) ** 2
    rows = [f"{a!r},{w!r}\n" for a, w in zip(t.tolist(), omega.tolist(), strict=True)]
    path.write_text("t,omega\n" + "".join(rows))
    spec = {"beam": {}, "drive": {"move": str(path), "settle": 0.2},
            "numerics": {"N": N, "model": "elastica"}}  # fmt: skip
    full = rotbeam.build_scene(spec)
    modal = rotbeam.build_scene({**spec, "numerics": {"N": N, "model": "modal", "modes": N - 1}})
    a, b = simulate_move(full), simulate_move(modal)
    assert a.converged and b.converged
    assert b.peak_ym == pytest.approx(a.peak_ym, rel=1e-4)
    assert b.residual_ym == pytest.approx(a.residual_ym, rel=1e-3, abs=1e-6)


def test_effect_budget_on_the_modal_model_is_the_elastica_s():
    full, modal = _pair(_scene(drive=Drive(omega0=10.0, amplitude=2.0, f_d=3.0)))
    a, b = rotbeam.effect_budget(full), rotbeam.effect_budget(modal)
    sa = {s.effect + s.method: s.share_rms for s in a.shares}
    sb = {s.effect + s.method: s.share_rms for s in b.shares}
    assert sa.keys() == sb.keys()
    for name in sa:
        assert sb[name] == pytest.approx(sa[name], rel=1e-4, abs=1e-8)


def _full_model(lam0: float, beam=BARE) -> DiscreteElastica:
    scene = _scene(beam, Drive(omega0=lam0 / beam.T, amplitude=0.5, f_d=3.0))
    return DiscreteElastica(scene.dimensionless, 40)


@pytest.mark.parametrize("beam", [Beam(), PAYLOAD], ids=["bare", "payload"])
def test_modal_frequencies_are_ritz_estimates_of_the_elastica_s(beam):
    lam0 = 1.5  # the modes are those at lam0; compare at rest, at lam0 and at 2 lam0
    full = _full_model(lam0, beam)
    exact = {lam: linear_frequencies(full, lam, 3) for lam in (0.0, lam0, 2 * lam0)}
    errors = {}
    for n in (3, 5, 8):
        modal = ModalModel(full, n)
        for lam, w in exact.items():
            wm = linear_frequencies(modal, lam, 3)
            assert np.all(wm >= w * (1 - 1e-10))  # Rayleigh-Ritz: from above
            errors[n, lam] = float(np.max(wm / w - 1))
        np.testing.assert_allclose(linear_frequencies(modal, lam0, 3), exact[lam0], rtol=1e-9)
    for lam in (0.0, 2 * lam0):
        assert errors[8, lam] < errors[3, lam] < 0.05
        assert errors[8, lam] < 1e-3


def test_modal_rms_converges_to_the_elastica_s_as_n_grows():
    scene = replace(_scene(drive=Drive(omega0=5.0, amplitude=1.0, f_d=5.0)),
                    numerics=Numerics(N=24))  # fmt: skip
    full = simulate(scene)
    errors = []
    for n in (1, 3, 5, 8, 12):  # measured 1.3e-2, 1.4e-4, 1.3e-5, 6.4e-7, 8.1e-8
        res = simulate(replace(scene, numerics=Numerics(N=24, model="modal", modes=n)))
        errors.append(abs(res.rms_dynamic / full.rms_dynamic - 1))
    assert errors == sorted(errors, reverse=True)
    assert errors[0] > 1e-3 and errors[-1] < 1e-6


@pytest.mark.parametrize("omega0, amplitude, f_d", [(5.0, 0.5, 3.0), (10.0, 1.0, 4.0),
                                                    (2.0, 0.3, 2.0)])  # fmt: skip
def test_one_mode_is_the_surrogate_at_small_amplitude(omega0, amplitude, f_d):
    scene = Scene(Beam(), Drive(omega0=omega0, amplitude=amplitude, f_d=f_d), Effects(),
                  Numerics(N=40, model="modal", modes=1))  # fmt: skip
    res, ref = simulate(scene), steady_rms(scene.dimensionless)
    assert res.rms_dynamic == pytest.approx(ref["rms_dynamic"], rel=0.01)
    assert res.rms_quasistatic == pytest.approx(ref["rms_quasistatic"], rel=0.01)
    assert res.delta_rms == pytest.approx(ref["delta_rms"], abs=0.005)


def test_cli_model_modal_is_the_api():
    flags = ["--N", str(N), "--model", "modal", "--modes", "3", "--json"]
    code, out, err = run_main(["simulate", "--omega0", "10", "--amplitude", "3", "--fd", "4",
                               *flags])  # fmt: skip
    assert code == 0, err
    d = json.loads(out)
    drive = Drive(omega0=10.0, amplitude=3.0, f_d=4.0)
    res = simulate(Scene(Beam(), drive, Effects(), Numerics(N=N, model="modal", modes=3)))
    assert d["rms_dynamic"] == pytest.approx(res.rms_dynamic, rel=1e-9)


@pytest.mark.parametrize("flags, bad", [(["--modes", "0"], "0"), (["--modes", "10"], "10"),
                                        (["--model", "chain"], "chain")])  # fmt: skip
def test_cli_refuses_modes_out_of_range_in_one_line(flags, bad):
    code, out, err = run_main(["simulate", "--omega0", "10", "--fd", "4", "--N", str(N),
                               "--model", "modal", *flags])  # fmt: skip
    assert code == 2
    line = err.strip().splitlines()[-1]
    assert bad in line and ("modes" in line or "model" in line), err


def test_modes_out_of_range_from_python_is_one_line():
    with pytest.raises(RotbeamInputError, match="numerics.modes = 12"):
        Numerics(N=N, model="modal", modes=12)
    with pytest.raises(RotbeamInputError, match="allowed 1 to 9"):
        ModalModel(DiscreteElastica(_scene().dimensionless, N), 10)


COMMANDS = {
    "simulate": ["simulate", "--fd", "3", "--observe", "root_moment"],
    "critical": ["critical"],
    "effects": ["effects", "--fd", "3"],
    "sweep": ["sweep", "--fd-min", "2", "--fd-max", "4", "--points", "3"],
}


def _numbers(value) -> list[float]:
    """Every float of a JSON answer but the timings, in order."""
    if isinstance(value, dict):
        keys = [k for k in value if "second" not in k and k not in ("message", "note")]
        return [x for k in keys for x in _numbers(value[k])]
    if isinstance(value, list):
        return [x for v in value for x in _numbers(v)]
    return [float(value)] if isinstance(value, float) else []


@pytest.mark.parametrize("command", list(COMMANDS))
def test_every_command_line_on_every_mode_is_the_elastica_s(command):
    common = ["--omega0", "10", "--amplitude", "1", "--N", str(N), "--json"]
    code, out, err = run_main([*COMMANDS[command], *common])
    assert code == 0, err
    code_m, out_m, err_m = run_main([*COMMANDS[command], *common, "--model", "modal",
                                     "--modes", str(N - 1)])  # fmt: skip
    assert code_m == 0, err_m
    full, modal = _numbers(json.loads(out)), _numbers(json.loads(out_m))
    assert len(full) == len(modal) > 2
    np.testing.assert_allclose(modal, full, rtol=1e-4, atol=1e-9)
