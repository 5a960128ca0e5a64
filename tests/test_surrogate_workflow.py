"""The surrogate study of the workflow: table builders, figures and the rules' wiring.

Sweep lines here are made by the surrogate itself, so that "surrogate vs full" has a known answer
(the two agree); the physics of the surrogate is tested in tests/test_surrogate.py.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from conftest import ROOT, snakemake

from rotbeam.config.schema import merge_config
from rotbeam.model.criterion import critical_from_scan
from rotbeam.model.modes import resonance_frequency_hz
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects, drive_groups
from rotbeam.model.surrogate import steady_rms
from rotbeam.paper.surrogate_figures import southwell_figure, vs_full_figure
from rotbeam.paper.surrogate_study import (
    peak_of_line,
    southwell_table,
    surrogate_boundary,
    surrogate_curve,
    validity_statement,
    vs_full_table,
)

BEAM = {"L": 0.040, "h": 0.002, "b": 0.010, "E": 1.22e6, "rho": 1170.2, "R": 0.155, "gamma": 0.039}


def surrogate_line(omega0: float, lo: float, hi: float, points: int) -> pd.DataFrame:
    """A sweep line in the format of rotbeam.sweeps.scan_line, computed with the surrogate."""
    b = Beam(**BEAM)
    f0 = resonance_frequency_hz(b, abs(omega0) + 1.0)
    rows = []
    for f in f0 * np.linspace(lo, hi, points):
        d = Drive(omega0, 1.0, float(f))
        s = steady_rms(Dimensionless.from_physical(b, d))
        rows.append({"omega0": omega0, "f_d": float(f), "amplitude": 1.0, "f0_hz": f0,
                     "f_n_hz": b.f_n, **drive_groups(b, d), "rms_dynamic": s["rms_dynamic"],
                     "rms_quasistatic": s["rms_quasistatic"], "delta_rms": s["delta_rms"],
                     "converged": True, "seconds": 0.5, "N": 12})  # fmt: skip
    return pd.DataFrame(rows)


def test_peak_of_line_finds_an_interior_parabola_vertex():
    f = np.linspace(1.0, 10.0, 10)
    line = pd.DataFrame({"f_d": f, "rms_dynamic": 5.0 - (f - 6.3) ** 2, "converged": True})
    pk = peak_of_line(line)
    assert pk["f_peak_hz"] == 6.0 and not pk["peak_at_edge"]
    assert (pk["f_peak_lo_hz"], pk["f_peak_hi_hz"]) == (5.0, 7.0)
    assert pk["f_peak_interp_hz"] == pytest.approx(6.3, rel=1e-12)
    edge = peak_of_line(line.assign(rms_dynamic=f))
    assert edge["peak_at_edge"] and math.isnan(edge["f_peak_interp_hz"])


def test_southwell_table_skips_negative_omega0_and_marks_peaks():
    line = surrogate_line(10.0, 0.8, 1.2, 41)
    table, skipped = southwell_table(BEAM, [0.01, 1.0, 787.0], 1.0, 80, {"w10": line})
    assert skipped == [0.01]  # below G a^2 = 0.0285
    cur = table[table["kind"] == "curve"]
    assert list(cur["C_max"]) == [1.0, 787.0]
    # the Southwell line is a Rayleigh upper bound; +3.77 % at C_max = 787 (N = 80)
    assert cur["rel_error_southwell"].iloc[-1] == pytest.approx(0.0377, abs=5e-4)
    pk = table[table["kind"] == "dynamic_peak"].iloc[0]
    # the surrogate's own resonance: its peak sits at its (Southwell) frequency, within the grid
    assert abs(pk["f_peak_hz"] / pk["f0_southwell_hz"] - 1) < 0.03


def test_surrogate_against_itself_agrees(tmp_path):
    lines = {"a": surrogate_line(10.0, 0.05, 0.6, 23), "b": surrogate_line(100.0, 0.05, 0.6, 23)}
    crit = {
        k: critical_from_scan(v["f_d"], v["delta_rms"], 0.1)["f_d_root"] for k, v in lines.items()
    }
    table, points, speed = vs_full_table(BEAM, lines, crit, 0.1, Effects(), 200, 40, 0.33, 0.05)
    assert np.allclose(points["sur_rms_dynamic"], points["full_rms_dynamic"], rtol=1e-12)
    assert np.allclose(table["rel_diff_grid"], 0.0, atol=1e-9)  # same data, same rule
    assert (table["rel_diff"].abs() < 0.01).all() and table["within_tolerance"].all()
    assert speed["points"] == 46 and speed["full_seconds_per_point_mean"] == pytest.approx(0.5)
    assert 0 < speed["surrogate_seconds_per_point"] < 0.05
    assert "at C_max = " in validity_statement(table, 0.05)
    bnd = surrogate_boundary(BEAM, 1.0, 787.0, 3, 0.1, 1.0, Effects(), 100, 40, 0.33)
    assert np.isfinite(bnd["E_star_surrogate"]).all()
    curves = [surrogate_curve(BEAM, v, Effects(), 20) for v in lines.values()]
    vs_full_figure(list(lines.values()), curves, table, bnd, 0.1, 0.05, 0.33,
                   tmp_path / "v.pdf", tmp_path / "v.png")  # fmt: skip
    sw, _ = southwell_table(BEAM, [0.1, 10.0], 1.0, 40, lines)
    southwell_figure(sw, BEAM, 40, tmp_path / "s.pdf", tmp_path / "s.png")
    assert all((tmp_path / f).stat().st_size > 0 for f in ("v.pdf", "v.png", "s.pdf", "s.png"))


def dry_run(work: Path, *args: str):
    return snakemake(work, "-n", "--cores", "1", *args, timeout=300)


def test_rules_are_wired(workflow_copy):
    targets = ["results/surrogate/southwell.csv", "results/surrogate/vs_full.csv"]
    p = dry_run(workflow_copy, *targets, "--configfile", "config/quick.yaml")
    assert p.returncode == 0, p.stderr[-3000:]
    for rule in ("surrogate_southwell", "surrogate_vs_full", "fig6", "boundary_table"):
        assert f"rule {rule}:" in p.stdout


def test_surrogate_section_is_required_and_checked(workflow_copy, tmp_path):
    yaml = pytest.importorskip("yaml")
    from snakemake.utils import validate

    schema = str(ROOT / "workflow/schemas/config.schema.yaml")
    cfg = merge_config(
        yaml.safe_load((ROOT / "config/config.yaml").read_text()),
        yaml.safe_load((ROOT / "config/quick.yaml").read_text()),
    )
    validate(dict(cfg), schema=schema)
    with pytest.raises(Exception, match="surrogate"):
        validate({k: v for k, v in cfg.items() if k != "surrogate"}, schema=schema)
    bad = tmp_path / "bad.yaml"
    text = (workflow_copy / "config/quick.yaml").read_text()
    bad.write_text(text + "\nsurrogate: {tolerance: 1.5}\n")  # merged over config.yaml
    p = dry_run(workflow_copy, "--configfile", str(bad))
    assert p.returncode != 0 and "tolerance" in p.stdout + p.stderr
