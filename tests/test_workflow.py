"""End to end: the quick config through Snakemake in a temporary copy of the workflow."""

import json
from pathlib import Path

import pandas as pd
import pytest
from conftest import dry_run_jobs, job_counts, snakemake

pytestmark = pytest.mark.slow  # the quick config end to end: minutes
SIMULATIONS = ("sweep_line", "sweep_boundary_lines", "sweep_grid_column", "sweep_convergence",
               "scene_series", "shapes")  # fmt: skip


def targets(workdir: Path) -> list[Path]:
    figs = [
        "fig1/drive_profiles",
        "fig2/shapes_lab_frame",
        "fig3/resonance",
        "fig4/dynamic_vs_quasistatic",
        "fig5/phase_diagram",
        "fig6/critical_frequency",
        "fig7/collapse",
        "figB8/convergence",
        "figD9/thresholds",
        "figE10/c0_vs_zeta",
    ]
    tables = ["table1", "systems", "c0_threshold", "c_per_threshold", "boundary_ref"]
    out = [workdir / "results" / f"{f}.{e}" for f in figs for e in ("pdf", "png")]
    out += [workdir / "results" / "tables" / f"{t}.{e}" for t in tables for e in ("csv", "md")]
    out += [
        workdir / "results" / "surrogate" / f"{s}.{e}"
        for s in ("southwell", "vs_full")
        for e in ("csv", "md", "pdf", "png")
    ]
    out += [
        workdir / "results" / "reproduction" / f"c_hypotheses.{e}"
        for e in ("csv", "md", "pdf", "png")
    ]
    out += [workdir / "results" / "moves" / f for f in ("designs.csv", "designs.md",
                                                         "design.pdf", "design.png",
                                                         "reference_slew.csv")]  # fmt: skip
    return out


def test_every_target_exists_and_is_not_empty(quick_run):
    missing = [str(t) for t in targets(quick_run) if not t.is_file() or t.stat().st_size == 0]
    assert not missing


def test_the_designed_move_meets_its_tolerance_and_its_file_runs(quick_run):
    """results/moves/: the design meets the tolerance and is shorter than ZVD; its move file,
    run again by `rotbeam simulate --move`, gives the table's residual."""
    import subprocess
    import sys

    table = pd.read_csv(quick_run / "results" / "moves" / "designs.csv")
    rows = table.set_index("move")
    assert list(rows.index) == ["designed", "rigid", "zv", "zvd"]
    assert rows.loc["designed", "meets"] and rows.loc["designed", "residual"] <= 0.005
    assert rows.loc["designed", "duration_s"] < rows.loc["zvd", "duration_s"]
    cmd = [
        sys.executable,
        "-m",
        "rotbeam",
        "simulate",
        "--move",
        str(quick_run / "results" / "moves" / "reference_slew.csv"),
        "--N",
        "8",
        "--rtol",
        "1e-4",
        "--settle",
        repr(float(table["settle_s"].iloc[0])),
        "--json",
        "--quiet",
    ]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True)
    assert json.loads(out.stdout)["residual_ym"] == pytest.approx(
        rows.loc["designed", "residual"], rel=1e-6
    )


def test_fitted_c_per_threshold(quick_run):
    t = pd.read_csv(quick_run / "results/tables/c_per_threshold.csv").sort_values("threshold")
    c, err = t["ref_c_root"].to_numpy(), t["ref_c_root_stderr"].to_numpy()
    assert ((c > 0) & (c < 1)).all() and (err >= 0).all() and pd.notna(err).all()
    assert (c[1:] > c[:-1]).all(), "a larger threshold must give a larger c"
    fit = json.loads((quick_run / "results/fig6/fit.json").read_text())
    assert 0 < fit["c"] < 1 and fit["c_stderr"] < 0.1


def test_nothing_to_do_after_a_complete_run(quick_run):
    assert dry_run_jobs(quick_run) == {}


def test_changing_a_threshold_reruns_no_simulation(quick_run):
    jobs = dry_run_jobs(quick_run, "--config", "thresholds=[0.05,0.2]")
    assert jobs.get("boundary_table") == 1 and jobs.get("boundary_grid") == 1
    assert jobs.get("c_per_threshold", 0) == 1
    for sim in SIMULATIONS:
        assert sim not in jobs, jobs


def test_c_hypotheses_table_has_every_hypothesis_and_threshold(quick_run):
    import yaml

    t = pd.read_csv(quick_run / "results/reproduction/c_hypotheses.csv")
    assert list(t.columns[:4]) == ["hypothesis", "threshold", "c", "c_err"]
    cfg = yaml.safe_load((quick_run / "config/quick.yaml").read_text())["c_hypotheses"]
    full = yaml.safe_load((quick_run / "config/config.yaml").read_text())["c_hypotheses"]
    grid = full["grid"]
    rules = [f"grid_{s:g}Hz" for s in grid["step_hz"]] + [f"grid_{s:g}f0" for s in grid["step_f0"]]
    names = cfg["hypotheses"] + [f"{h}+{r}" for h in grid["hypotheses"] for r in rules]
    assert list(dict.fromkeys(t["hypothesis"])) == names
    for _, sub in t.groupby("hypothesis", sort=False):
        assert sub["threshold"].tolist() == full["thresholds"]
    ours = t[t["hypothesis"] == "ours"]
    assert (ours["c"] < ours["c_paper"] - 0.05).all()  # the gap the study is about


def test_c_hypotheses_rerun_on_their_own_config_only(quick_run):
    jobs = dry_run_jobs(quick_run, "--config", "c_hypotheses={'points': 9}")
    assert jobs.get("c_hypotheses") == 1, jobs
    for sim in SIMULATIONS:  # none reruns
        assert sim not in jobs, jobs
    for other in ("thresholds=[0.05,0.2]", "numerics={'N': 14}", "boundary={'points': 9}"):
        assert "c_hypotheses" not in dry_run_jobs(quick_run, "--config", other), other


def test_changing_the_grid_reruns_simulations(quick_run):
    """The grid N reruns every sweep but Fig. B.8's, whose lines set their own N."""
    jobs = dry_run_jobs(quick_run, "--config", "numerics={'N': 14}")
    assert jobs.get("sweep_line", 0) > 0 and jobs.get("sweep_grid_column", 0) > 0
    assert "sweep_convergence" not in jobs, jobs
    jobs = dry_run_jobs(quick_run, "--config", "numerics={'rtol': 1.0e-6}")
    assert jobs.get("sweep_convergence") == 1, jobs


def test_a_new_E_runs_only_its_grid_columns(quick_run):
    """One sweep job per (E, L) column of the Fig. 7 grid: a new E adds one per L, nothing else
    simulates again."""
    jobs = dry_run_jobs(quick_run, "--config", "fig7={'E': [1.0e+5, 1.0e+9, 1.0e+7]}")
    assert jobs.get("sweep_grid_column") == 2, jobs  # the quick config's two L
    assert not (set(SIMULATIONS) - {"sweep_grid_column"}) & set(jobs), jobs


def test_bad_config_stops_before_any_job(tmp_path, quick_run):
    bad = tmp_path / "bad.yaml"
    bad.write_text((quick_run / "config/quick.yaml").read_text() + "\nmain_threshold: 1.5\n")
    p = snakemake(quick_run, "-n", "--cores", "1", "--configfile", str(bad), timeout=300)
    assert p.returncode != 0
    assert "main_threshold" in (p.stdout + p.stderr)


def test_every_job_logs_what_it_read_wrote_and_how_long(quick_run):
    """Each job of the run left a non-empty log (one per job) that names every output it wrote,
    and every result file is named by a log."""
    jobs = job_counts((quick_run / "quick_run.log").read_text())
    jobs.pop("all")
    jobs.pop("moves")  # the targets run: rules without a job of their own
    logs = sorted((quick_run / "logs").rglob("*.log"))
    assert len(logs) == sum(jobs.values()), (jobs, logs)
    written = set()
    for log in logs:
        text = log.read_text()
        assert "reading" in text and "done in" in text, (log, text[-2000:])
        names = [row.split(" wrote ", 1)[1].rsplit(" (", 1)[0] for row in text.splitlines()
                 if " wrote results/" in row]  # fmt: skip
        assert names and all(Path(quick_run, n).is_file() for n in names), (log, text[-2000:])
        written.update(names)
    results = {
        str(f.relative_to(quick_run))
        for f in (quick_run / "results").rglob("*")
        if f.is_file() and f.name != "README.md"
    }
    assert results == written, results ^ written
