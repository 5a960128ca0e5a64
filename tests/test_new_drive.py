"""New kinds of drive, defined in this file alone: registered, they run through `simulate`,
`simulate_move`, a scene file and the command line with no change under rotbeam/ (docs/model.md,
"Drives").

A rounded square wave, Omega = Omega_0 + a tanh(s sin(2 pi f_d t)) / tanh(s), and a single
sin^2 run, each with dOmega/dt in closed form; their answers are checked against the same speed
sampled (a profile of every harmonic, the README's 61-sample move) and against the sine, the
square wave's limit as s -> 0.  The registry refuses an unknown kind, a field the kind does not
read and a bad value of its own field in one line.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from test_bad_input import one_clear_line, run_main

from rotbeam import Drive, Scene, simulate
from rotbeam.config.errors import RotbeamInputError
from rotbeam.config.parameters import SECTIONS, Param
from rotbeam.model.drives import KINDS, DriveKind, kind_class, register, unregister
from rotbeam.model.params import Harmonic, Samples
from rotbeam.runs.move import simulate_move
from rotbeam.runs.scene import build_scene
from rotbeam.solve.numerics import Numerics

NUMERICS = Numerics(N=10)
ROOT = Path(__file__).resolve().parents[1]


class SmoothSquare(DriveKind):
    """Omega_0 + a tanh(s sin(2 pi f_d t)) / tanh(s): a square wave rounded by s > 0."""

    name = "smooth-square"
    own = {"sharpness": Param("real", None, "s of the rounded square wave (larger: squarer)", "",
                              0, lo_open=True, optional=True)}  # fmt: skip
    fields = ("omega0", "amplitude", "f_d", "sharpness")
    description = "Omega_0 + a tanh(s sin(2 pi f_d t)) / tanh(s)"

    def omega(self, t: float) -> float:
        d, x = self.drive, 2.0 * math.pi * self.drive.f_d * t
        return d.omega0 + d.amplitude * math.tanh(d.sharpness * math.sin(x)) / math.tanh(
            d.sharpness
        )

    def omega_dot(self, t: float) -> float:
        d, x = self.drive, 2.0 * math.pi * self.drive.f_d * t
        s, w = d.sharpness, 2.0 * math.pi * d.f_d
        return d.amplitude * s * w * math.cos(x) / math.cosh(s * math.sin(x)) ** 2 / math.tanh(s)


class Sin2Move(DriveKind):
    """A single run from rest, Omega = top sin^2(pi t / 0.3 s) for 0.3 s, then top/0 held."""

    name = "sin2-move"
    own = {"top": Param("real", None, "the move's top speed", "rad/s", optional=True)}
    fields = ("top", "settle", "move_start")
    periodic = False

    def period(self) -> float:
        return 0.3

    def omega(self, t: float) -> float:
        return self.drive.top * math.sin(math.pi * min(max(t, 0.0), 0.3) / 0.3) ** 2

    def omega_dot(self, t: float) -> float:
        inside = 0.0 <= t <= 0.3
        return self.drive.top * math.pi / 0.3 * math.sin(2 * math.pi * t / 0.3) if inside else 0.0


@pytest.fixture(scope="module", autouse=True)
def registered():
    """The kinds registered for this file's tests, and the registry as it was after them."""
    register(SmoothSquare)
    register(Sin2Move)
    yield
    unregister("smooth-square")
    unregister("sin2-move")
    assert not {"smooth-square", "sin2-move"} & set(KINDS)
    assert not {"sharpness", "top"} & set(SECTIONS["drive"])


def square(s: float, **kw) -> Drive:
    return Drive(**{"omega0": 5.0, "amplitude": 1.0, "f_d": 2.0, **kw}, extra={"sharpness": s})


def sampled(drive: Drive, n: int = 256) -> Drive:
    """The same speed as a sampled profile of n samples, every harmonic kept (n / 2): its
    harmonics decay as exp(-0.72 k) at s = 2, so the interpolant is the speed to round-off."""
    phase = np.arange(n) / n
    omega = [drive.as_kind.omega(x / drive.f_d) for x in phase]
    return Drive(f_d=drive.f_d, profile=Samples(tuple(phase), tuple(omega), "profile", "s", n // 2))


def test_the_kind_is_chosen_by_its_field_and_its_numbers_are_the_closed_form():
    d = square(2.0)
    assert d.kind == "smooth-square" and d.periodic and kind_class(d.kind) is SmoothSquare
    s, w = 2.0, 2.0 * math.pi * 2.0
    # the odd wave: mean Omega_0, largest |Omega| Omega_0 + a (at a quarter period), largest
    # |dOmega/dt| a s w / tanh(s) (at t = 0); the generic sampled extremes hit both instants
    assert d.mean_speed == pytest.approx(5.0, abs=1e-12)
    assert d.swing == pytest.approx(1.0, rel=1e-12)
    assert d.omega_max == pytest.approx(6.0, rel=1e-12)
    assert d.omega_dot_max == pytest.approx(s * w / math.tanh(s), rel=1e-12)
    law, T = d.law(0.01), 0.01
    tau = 0.123
    assert law.lam(tau) == pytest.approx(d.as_kind.omega(tau * T) * T, rel=1e-14)
    assert law.period == pytest.approx(1.0 / 2.0 / T, rel=1e-14)
    h = 1e-5  # lam_dot against a central difference of lam: (dOmega/dt) T^2
    assert law.lam_dot(tau) == pytest.approx((law.lam(tau + h) - law.lam(tau - h)) / (2 * h),
                                             rel=1e-7)  # fmt: skip


def test_simulate_matches_the_same_speed_as_a_sampled_profile():
    d = square(2.0)
    new = simulate(Scene(drive=d, numerics=NUMERICS))
    ref = simulate(Scene(drive=sampled(d), numerics=NUMERICS))
    assert new.converged and ref.converged
    for name in ("rms_dynamic", "rms_quasistatic", "delta_rms"):
        assert getattr(new, name) == pytest.approx(getattr(ref, name), rel=1e-9), name


def test_a_slightly_rounded_wave_is_the_sine():
    """tanh(s y) / tanh(s) = y (1 + s^2 (1 - y^2) / 3 + O(s^4)): at s = 1e-3 the speed is the
    sine's to 3.4e-7 of a, and so are the responses (they are smooth in the drive)."""
    new = simulate(Scene(drive=square(1e-3), numerics=NUMERICS))
    sine = simulate(Scene(drive=Drive(5.0, 1.0, 2.0), numerics=NUMERICS))
    for name in ("rms_dynamic", "rms_quasistatic", "delta_rms"):
        assert getattr(new, name) == pytest.approx(getattr(sine, name), rel=1e-6), name


def test_a_scene_file_and_the_flags_run_it(tmp_path):
    path = tmp_path / "square.yaml"
    path.write_text("drive: {omega0: 5, amplitude: 1, f_d: 2, sharpness: 2}\nnumerics: {N: 10}\n")
    py = simulate(Scene(drive=square(2.0), numerics=NUMERICS))
    for argv in (["simulate", "--scene", str(path), "--json"],
                 ["simulate", "--omega0", "5", "--fd", "2", "--sharpness", "2", "--N", "10",
                  "--json"]):  # fmt: skip
        rc, out, err = run_main(argv)
        assert rc == 0, err
        got = json.loads(out)
        assert got["rms_dynamic"] == py.rms_dynamic and got["delta_rms"] == py.delta_rms


def test_the_registry_refuses_in_one_line(tmp_path):
    with pytest.raises(RotbeamInputError, match=r"drive kind 'sawtooth' is unknown; allowed: .*"
                       r"smooth-square"):  # fmt: skip
        kind_class("sawtooth")
    with pytest.raises(RotbeamInputError) as unused:
        square(2.0, move_start="quasistatic")
    assert str(unused.value) == (
        "drive.move_start = 'quasistatic': a smooth-square drive does not read it (only a move "
        "starts from rest); allowed with a smooth-square: omega0, amplitude, f_d, sharpness"
    )
    with pytest.raises(RotbeamInputError, match=r"^drive\.sharpness must be > 0, got -1\.0$"):
        square(-1.0)
    with pytest.raises(RotbeamInputError, match=r"harmonics and sharpness given together"):
        Drive(5.0, f_d=2.0, harmonics=(Harmonic(1, 1.0),), extra={"sharpness": 2.0})
    with pytest.raises(ValueError, match="allowed: a new name"):
        register(SmoothSquare)
    rc, _, err = run_main(["simulate", "--omega0", "5", "--fd", "2", "--sharpness", "2",
                           "--move-start", "quasistatic"])  # fmt: skip
    one_clear_line(rc, err, ["--move-start", "smooth-square drive does not read it"])
    path = tmp_path / "bad.yaml"
    path.write_text("drive: {omega0: 5, f_d: 2, sharpness: 0}\n")
    rc, _, err = run_main(["simulate", "--scene", str(path)])
    one_clear_line(rc, err, ["drive.sharpness", "> 0", "0"])


def test_a_single_run_matches_the_sampled_move():
    """The README's move, 10 sin^2(pi t / 0.3 s), given in closed form and as 61 samples
    (config/scenes/sin2_move.csv, a not-a-knot spline: within 0.03 % of the exact law's residual
    vibration, docs/model.md "Drives")."""
    numerics = {"N": 10}
    new = simulate_move(build_scene({"drive": {"top": 10.0, "settle": 1.0}, "numerics": numerics}))
    csv = str(ROOT / "config/scenes/sin2_move.csv")
    ref = simulate_move(build_scene({"drive": {"move": csv, "settle": 1.0}, "numerics": numerics}))
    assert not new.scene.drive.periodic and new.move_s == pytest.approx(0.3, rel=1e-12)
    for name in ("peak_ym", "rms_dynamic", "rms_quasistatic", "residual_ym"):
        assert getattr(new, name) == pytest.approx(getattr(ref, name), rel=3e-4), name
