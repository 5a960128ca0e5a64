"""`rotbeam modes`: its table says what its JSON says, and both are the frequencies at the
requested speed, against the non-rotating cantilever's closed form and a published table."""

import json
import math
import subprocess
import sys

import pytest
from test_modes_published import WRIGHT_ATOL, WRIGHT_HUB0

from rotbeam.model.params import Beam

BETA = (1.8751040687119611, 4.6940911329741745)  # cantilever roots, 1 + cos b cosh b = 0


def run(*args: str) -> subprocess.CompletedProcess:
    p = subprocess.run([sys.executable, "-m", "rotbeam", "modes", *args], capture_output=True,
                       text=True, timeout=300)  # fmt: skip
    assert p.returncode == 0, p.stderr
    return p


def table(text: str) -> tuple[list[str], list[list[float]]]:
    """The header line of the table and its rows (mode number first), from the printed text."""
    lines = text.splitlines()
    head = next(i for i, line in enumerate(lines) if line.split()[:1] == ["mode"])
    rows = []
    for line in lines[head + 1 :]:
        cells = line.split()
        if not cells or not cells[0].isdigit():
            break
        rows.append([float(c) for c in cells])
    return lines[head], rows


def value(text: str, name: str) -> float:
    """The number after `name` on its line of the printed text."""
    line = next(line for line in text.splitlines() if line.startswith(name))
    return float(line[len(name) :].split()[0])


@pytest.mark.parametrize("flags", [["--omega", "30"], ["--omega", "0", "--no-softening"]])
def test_the_table_is_the_json(flags):
    """One row a mode: number, f [Hz], 2 pi f [rad/s], f / f_n, each the JSON's to the printed
    six digits; the lines below name f_n and zeta with their meaning."""
    text = run("--k", "3", *flags).stdout
    out = json.loads(run("--k", "3", "--json", *flags).stdout)
    head, rows = table(text)
    assert "f [Hz]" in head and "[rad/s]" in head and "f / f_n" in head
    assert [r[0] for r in rows] == [1, 2, 3]
    f = out["frequencies_hz"]
    assert [r[1] for r in rows] == pytest.approx(f, rel=1e-5)
    assert [r[2] for r in rows] == pytest.approx([2 * math.pi * x for x in f], rel=1e-5)
    assert [r[3] for r in rows] == pytest.approx([x / out["f_n_hz"] for x in f], rel=1e-3)
    assert out["f_1_hz"] == f[0]
    assert value(text, "f_n [Hz]") == pytest.approx(out["f_n_hz"], rel=1e-5)
    assert value(text, "zeta") == pytest.approx(out["zeta"], rel=1e-3)
    assert f"Omega = {float(flags[1]):g} rad/s" in text and out["plane"] in text


def test_at_rest_the_rows_are_the_cantilevers_closed_form():
    """At Omega = 0 the frequencies are beta_n^2 f_s, f_s = sqrt(EI / (rho A L^4)) / (2 pi) from
    the beam's fields (N = 160: the second-order grid's error is ~2e-5 and ~2e-4 for modes 1, 2);
    f_n_hz is the first of them in the continuum and zeta is eta / (2 beta_1^2)."""
    b = Beam()
    EI, rhoA = b.E * b.b * b.h**3 / 12, b.rho * b.b * b.h
    f_s = math.sqrt(EI / (rhoA * b.L**4)) / (2 * math.pi)
    out = json.loads(run("--omega", "0", "--k", "2", "--N", "160", "--json").stdout)
    assert out["frequencies_hz"][0] == pytest.approx(BETA[0] ** 2 * f_s, rel=5e-5)
    assert out["frequencies_hz"][1] == pytest.approx(BETA[1] ** 2 * f_s, rel=5e-4)
    assert out["f_n_hz"] == pytest.approx(BETA[0] ** 2 * f_s, rel=1e-12)
    eta = b.gamma * b.L**2 / math.sqrt(rhoA * EI)
    assert out["zeta"] == pytest.approx(eta / (2 * BETA[0] ** 2), rel=1e-12)


def test_the_first_frequency_is_at_the_requested_speed():
    """At Omega = 30 rad/s f_1 is the rotating beam's, not f_n at rest: far above it, and the
    in-plane and flapwise rows keep f_in^2 = f_flap^2 - (Omega / 2 pi)^2 (the softening is
    -Omega^2 times the mass, exactly)."""
    omega = 30.0
    inplane = json.loads(run("--omega", str(omega), "--k", "2", "--json").stdout)
    flap = json.loads(run("--omega", str(omega), "--k", "2", "--no-softening", "--json").stdout)
    assert inplane["f_1_hz"] > 1.5 * inplane["f_n_hz"]
    for fi, ff in zip(inplane["frequencies_hz"], flap["frequencies_hz"], strict=True):
        assert fi**2 == pytest.approx(ff**2 - (omega / (2 * math.pi)) ** 2, rel=1e-9)


@pytest.mark.parametrize("lam", [3.0, 6.0, 12.0])
def test_dimensionless_rows_are_the_published_rotating_table(lam):
    """--dimensionless, hub 0, flapwise: the printed rows' w, extrapolated from N = 80 and 160,
    are Wright et al. (1982) via Bir (2009) to their printed 3 decimals
    (tests/test_modes_published.py)."""
    published = next(row[1:] for row in WRIGHT_HUB0 if row[0] == lam)
    flags = ["--dimensionless", "--lambda", str(lam), "--hub-ratio", "0", "--k", "2",
             "--no-softening"]  # fmt: skip
    coarse, fine = (table(run(*flags, "--N", n).stdout)[1] for n in ("80", "160"))
    for k, w in enumerate(published):
        extrapolated = fine[k][1] + (fine[k][1] - coarse[k][1]) / 3
        assert abs(extrapolated - w) <= WRIGHT_ATOL
        assert fine[k][2] == pytest.approx(fine[k][1] / BETA[0] ** 2, rel=1e-3)
