"""The public API, used only through `import rotbeam`, against independent answers: the
non-rotating cantilever's closed-form frequency, App. E's one-mode Delta RMS far below
resonance and its c_0 = sqrt(threshold), the telescoping of the sequential effect shares, a
scene file read back, and one-line input errors."""

from __future__ import annotations

import math

import pytest

import rotbeam


def test_the_public_names_are_there_and_import_lazily():
    import subprocess
    import sys

    code = "import rotbeam, sys; print('rotbeam.runs.scene' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip() == "False"  # `import rotbeam` loads no solver
    for name in ("Beam", "Drive", "Effects", "Numerics", "Scene", "simulate", "critical",
                 "effect_budget", "modes", "judge", "load_scene", "__version__"):  # fmt: skip
        assert name in rotbeam.__all__ and getattr(rotbeam, name) is not None
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        rotbeam.nothing  # noqa: B018


def test_modes_at_rest_are_the_cantilever_closed_form():
    """beta_1^2 sqrt(EI / (rho A L^4)) / 2 pi from Table 1's numbers by hand; second order."""
    E, b, h, rho, L = 1.22e6, 0.010, 0.002, 1170.2, 0.040
    EI, rhoA = E * b * h**3 / 12, rho * b * h
    exact = 1.8751040687119611**2 * math.sqrt(EI / (rhoA * L**4)) / (2 * math.pi)
    f = rotbeam.modes(rotbeam.Beam(), 0.0, 1, N=160)[0]
    assert f == pytest.approx(exact, rel=1e-4)


def test_far_below_resonance_quasistatic_is_good_enough():
    """At f_d = f_0 / 10 the one-mode oscillator (App. E) gives Delta RMS =
    1 - sqrt((1 - c^2)^2 + (2 zeta c)^2) = 0.0099 at c = 0.1; the full model agrees to 5 %."""
    scene = rotbeam.Scene(rotbeam.Beam(), rotbeam.Drive(omega0=5.0, f_d=0.5),
                          numerics=rotbeam.Numerics(N=20))  # fmt: skip
    f0 = rotbeam.modes(rotbeam.Beam(), 6.0, 1, N=80)[0]
    scene = rotbeam.Scene(
        scene.beam, rotbeam.Drive(omega0=5.0, f_d=f0 / 10), numerics=scene.numerics
    )
    res = rotbeam.simulate(scene)
    zeta = rotbeam.Beam().zeta
    c = 0.1
    expected = 1 - math.sqrt((1 - c * c) ** 2 + (2 * zeta * c) ** 2)
    assert res.converged and res.delta_rms == pytest.approx(expected, rel=0.05)
    verdict = rotbeam.judge(res, 0.10)
    assert verdict.quasistatic_ok is True


def test_critical_is_near_the_second_order_systems_c0():
    """f_d* / f_0 of the full model at 5 rad/s within 5 % of App. E's c_0 = sqrt(0.10) for a
    lightly damped beam (the full model is 2-3 % above it: docs/reproduction.md)."""
    scene = rotbeam.Scene(
        rotbeam.Beam(), rotbeam.Drive(omega0=5.0), numerics=rotbeam.Numerics(N=20)
    )
    res = rotbeam.critical(scene, 0.10)
    assert res.found
    assert res.f_d_star / res.f0_hz == pytest.approx(math.sqrt(0.10), rel=0.05)


def test_effect_budget_shares_telescope_and_the_euler_load_is_the_forcing():
    scene = rotbeam.Scene(rotbeam.Beam(), rotbeam.Drive(omega0=5.0, f_d=2.0),
                          numerics=rotbeam.Numerics(N=12))  # fmt: skip
    budget = rotbeam.effect_budget(scene)
    assert sum(budget.sequential.values()) == pytest.approx(1.0, abs=1e-9)
    euler = next(s for s in budget.shares if s.effect == "euler")
    assert euler.share_rms == pytest.approx(1.0, abs=1e-12)  # no forcing, no deflection


def test_a_scene_file_reads_back(tmp_path):
    path = tmp_path / "scene.yaml"
    path.write_text("beam: {L: 0.05}\ndrive: {omega0: 10, f_d: 3}\nnumerics: {N: 16}\n")
    scene = rotbeam.load_scene(path)
    assert scene == rotbeam.build_scene(
        {"beam": {"L": 0.05}, "drive": {"omega0": 10, "f_d": 3}, "numerics": {"N": 16}}
    )
    assert scene.beam.L == 0.05 and scene.numerics.N == 16


def test_bad_input_is_one_line_naming_the_value():
    with pytest.raises(rotbeam.RotbeamInputError, match=r"beam.L must be > 0, got -1"):
        rotbeam.Beam(L=-1.0)
