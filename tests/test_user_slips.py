"""What a new user types by mistake, each refused in one true line or read as meant: a field the
drive does not read, a unit slip, a spreadsheet's byte-order mark, a directory for a file, a
time that does not increase; and what a profile reports as its speed.  Each against an
independent answer: the closed-form clamp strain, the profile's own samples."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import yaml
from test_bad_input import run_main

import rotbeam
from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.params import CLAMP_STRAIN_LIMIT, clamp_strain
from rotbeam.runs.move import simulate_move
from rotbeam.runs.scene import build_scene

S_CURVE = {"shape": "s-curve", "omega_min": 0.0, "omega_max": 20.0, "ramp": 0.2}


def run_cli(*argv: str) -> tuple[int, str, str]:
    return run_main(list(argv))


def refused(rc: int, out: str, err: str, *words: str) -> str:
    assert rc == 2 and out == "" and "Traceback" not in err, (rc, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


def test_a_profile_needs_no_omega0_and_reports_its_mean_speed(tmp_path):
    """README's s-curve from the command line: no omega0 asked for; the JSON's omega0 and
    amplitude are the profile's mean speed and largest swing, from its own samples (0 -> 20
    rad/s, symmetric ramps: mean 10 rad/s, swing 10 rad/s up to the interpolant's overshoot)."""
    path = tmp_path / "s.yaml"
    path.write_text(f"drive: {{f_d: 1.0, profile: {S_CURVE}}}\nnumerics: {{N: 8}}\n")
    rc, out, err = run_cli("simulate", "--scene", str(path), "--json", "--quiet")
    assert rc == 0, err

    res = json.loads(out)
    assert res["omega0"] == pytest.approx(10.0, rel=1e-9)
    assert res["amplitude"] == pytest.approx(10.0, rel=1e-2)


@pytest.mark.parametrize(
    "drive, flag, words",
    [
        ({"f_d": 1.0, "profile": S_CURVE}, ("--omega0", "3"), ("--omega0", "a profile drive")),
        ({"f_d": 1.0, "profile": S_CURVE}, ("--amplitude", "1"), ("--amplitude", "profile")),
        ({"move": "MOVE"}, ("--fd", "3"), ("--fd", "no repetition rate")),
        ({"omega0": 5.0, "f_d": 2.0}, ("--move-start", "quasistatic"), ("only a move",)),
    ],
)
def test_a_flag_the_drive_does_not_read_is_refused(tmp_path, drive, flag, words):
    if drive.get("move") == "MOVE":
        t = np.linspace(0.0, 0.3, 16)
        np.savetxt(tmp_path / "m.csv", np.column_stack([t, 10 * t]), delimiter=",",
                   header="t,omega", comments="")  # fmt: skip
        drive = {"move": str(tmp_path / "m.csv")}
    path = tmp_path / "s.yaml"

    path.write_text(yaml.safe_dump({"drive": drive}))
    refused(*run_cli("simulate", "--scene", str(path), *flag), *words)


def test_the_api_refuses_omega0_with_a_profile_and_the_default_is_not_read():
    samples = build_scene({"drive": {"f_d": 1.0, "profile": S_CURVE}}).drive.profile
    with pytest.raises(RotbeamInputError, match="drive.omega0 = 3"):
        rotbeam.Drive(omega0=3.0, f_d=1.0, profile=samples)
    a = rotbeam.Drive(f_d=1.0, profile=samples)
    assert a.law(1.0) == rotbeam.Drive(omega0=5.0, f_d=1.0, profile=samples).law(1.0)


def test_required_flags_say_so_in_help():
    rc, out, _ = run_cli("simulate", "--help")
    text = " ".join(out.split())
    assert rc == 0
    assert "(required for a sine or harmonics drive" in text
    assert "(required for a periodic drive" in text
    assert "(default 5" not in text and "(default 7" not in text


def test_a_unit_slip_in_E_is_one_line_naming_it():
    """E = 200 Pa for the reference beam at 6 rad/s: the clamp strain from the closed form
    Omega^2 [rho (R_o L + L^2/2)] / E (computed here from the beam's numbers) is above the limit;
    the refusal names it and the likely GPa."""
    beam = rotbeam.Beam(E=200.0)
    by_hand = 36.0 * 1170.2 * (0.115 * 0.04 + 0.5 * 0.04**2) / 200.0
    assert clamp_strain(beam, 6.0) == pytest.approx(by_hand, rel=1e-12)
    assert by_hand > CLAMP_STRAIN_LIMIT
    with pytest.raises(RotbeamInputError, match="stretch the beam by 114 %.*200 GPa"):
        rotbeam.Scene(beam=beam)
    refused(*run_cli("simulate", "--E", "200", "--omega0", "5", "--fd", "2"), "C_max", "GPa")


def test_the_papers_stiffest_scene_is_inside_the_range():
    """C_max = 787 (the paper's largest) strains the Table 1 beam's clamp by 14 % (README)."""
    beam = rotbeam.Beam()
    omega = math.sqrt(787.0 / beam.G)
    assert 0.12 < clamp_strain(beam, omega) < 0.16
    rotbeam.Scene(beam=beam, drive=rotbeam.Drive(omega0=omega - 1.0, f_d=5.0))


def test_a_byte_order_mark_is_not_part_of_the_first_column(tmp_path):
    path = tmp_path / "bom.csv"
    t = np.linspace(0.0, 0.3, 16)
    body = "t,omega\n" + "".join(f"{a},{10 * a}\n" for a in t)
    path.write_bytes(b"\xef\xbb\xbf" + body.encode())
    plain = tmp_path / "plain.csv"
    plain.write_text(body)
    a = build_scene({"drive": {"move": str(path)}}).drive.move
    b = build_scene({"drive": {"move": str(plain)}}).drive.move
    assert a.x == b.x and a.omega == b.omega


def test_a_directory_is_not_a_scene_file(tmp_path):
    refused(*run_cli("simulate", "--scene", str(tmp_path)), "is a directory")
    refused(*run_cli("simulate", "--move", str(tmp_path)), "is a directory", "drive.move")


def test_a_time_that_does_not_increase_prints_numbers(tmp_path):
    path = tmp_path / "back.csv"
    path.write_text("t,omega\n0,0\n0.1,1\n0.16,2\n0.16,3\n0.4,4\n0.5,5\n0.6,6\n0.7,7\n")
    line = refused(*run_cli("simulate", "--move", str(path)), "(0.16 then 0.16)")
    assert "np.float64" not in line


def test_a_long_move_reports_its_progress(tmp_path):
    """progress(done, planned) after every window: increasing, ending at the move plus the
    settling window."""
    t = np.linspace(0.0, 0.3, 31)
    path = tmp_path / "m.csv"
    np.savetxt(path, np.column_stack([t, 10 * np.sin(np.pi * t / 0.3) ** 2]), delimiter=",",
               header="t,omega", comments="")  # fmt: skip
    seen = []
    res = simulate_move(build_scene({"drive": {"move": str(path), "settle": 0.1},
                                     "numerics": {"N": 8}}),
                        progress=lambda done, planned: seen.append((done, planned)))  # fmt: skip
    assert res.converged and len(seen) >= 20
    done = [d for d, _ in seen]
    assert done == sorted(done)
    assert done[-1] == pytest.approx(0.4, rel=1e-9) and seen[-1][1] == pytest.approx(0.4)
