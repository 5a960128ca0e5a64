"""The workflow's atlas (target `atlas`, workflow/rules/atlas.smk) on a 2 x 3 grid: one job per
Omega_0 line and one that gathers them, the rows `rotbeam.atlas`'s with the same numerics, and
none of it in the default target."""

from __future__ import annotations

import pandas as pd
import yaml
from conftest import QUICK, ROOT, dry_run_jobs, job_counts, snakemake

import rotbeam
from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.runs.atlas import ATLAS_COLUMNS
from rotbeam.runs.scene import Scene
from rotbeam.runs.sweeps import numerics_from_config

TINY = {"atlas": {"omega0": [5.0, 40.0, 2], "f_d": [2.0, 8.0, 3]}}
OUT = ["results/atlas/atlas.csv", "results/atlas/atlas.png"]


def _config() -> dict:
    """config.yaml with quick.yaml over it, key by key (as snakemake merges them)."""
    full = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    quick = yaml.safe_load((ROOT / "config/quick.yaml").read_text())
    for key, value in quick.items():
        if isinstance(value, dict) and isinstance(full.get(key), dict):
            full[key] = {**full[key], **value}
        else:
            full[key] = value
    return full


def test_the_atlas_target_runs_a_job_per_line_and_equals_the_api(workflow_copy):
    (workflow_copy / "config" / "tiny.yaml").write_text(yaml.safe_dump(TINY))
    files = ("--configfile", "config/quick.yaml", "config/tiny.yaml")
    p = snakemake(workflow_copy, "--cores", "2", "atlas", *files, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    jobs = job_counts(p.stdout + p.stderr)
    assert (jobs["atlas_line"], jobs["atlas_gather"]) == (2, 1), jobs
    for f in OUT:
        assert (workflow_copy / f).stat().st_size > 0, f
    rows = pd.read_csv(workflow_copy / OUT[0])
    assert list(rows.columns) == ATLAS_COLUMNS and len(rows) == 6 and rows["ran"].all()

    cfg = _config()
    scene = Scene(Beam(**cfg["beam"]), Drive(amplitude=cfg["atlas"]["amplitude"]),
                  Effects.from_list(cfg["effects"]),
                  numerics_from_config(cfg["numerics"]))  # fmt: skip
    api = rotbeam.atlas(scene, [5.0, 40.0], [2.0, 5.0, 8.0], cfg["main_threshold"], workers=1)
    keep = [c for c in ATLAS_COLUMNS if c not in ("seconds", "message")]
    pd.testing.assert_frame_equal(rows[keep], api.rows[keep], check_dtype=False)


def test_line_seconds_is_each_line_jobs_budget(workflow_copy):
    """`atlas.line_seconds` is the time budget of a line's job in place of numerics.max_seconds:
    with 1 ms every point of both lines is left unanswered, its row saying so, and the gather
    still writes the table and the figure."""
    tiny = {"atlas": {**TINY["atlas"], "line_seconds": 1e-3}}
    (workflow_copy / "config" / "tiny.yaml").write_text(yaml.safe_dump(tiny))
    files = ("--configfile", "config/quick.yaml", "config/tiny.yaml")
    p = snakemake(workflow_copy, "--cores", "2", "atlas", *files, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    rows = pd.read_csv(workflow_copy / OUT[0])
    assert len(rows) == 6 and not rows["converged"].any()
    assert rows["message"].str.contains("time budget of 0.001 s").all(), rows["message"].tolist()
    assert (workflow_copy / OUT[1]).stat().st_size > 0


def test_the_atlas_is_not_in_the_default_target(workflow_copy):
    jobs = dry_run_jobs(workflow_copy)
    assert jobs and not any(rule.startswith("atlas") for rule in jobs), jobs


def test_a_bad_atlas_grid_stops_the_parse_in_one_line(workflow_copy):
    bad = {"atlas": {"omega0": [40.0, 5.0, 3]}}
    (workflow_copy / "config" / "bad.yaml").write_text(yaml.safe_dump(bad))
    p = snakemake(workflow_copy, "-n", "--cores", "1", "atlas", *QUICK, "config/bad.yaml")
    assert p.returncode != 0
    assert "rotbeam: invalid config: atlas.omega0 = [40.0, 5.0, 3]" in p.stderr, p.stderr[-2000:]
