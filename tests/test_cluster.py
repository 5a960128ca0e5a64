"""The workflow runs unchanged through a cluster executor: snakemake-executor-plugin-cluster-generic
with a stand-in batch system that runs each job script in the background on this machine.

A cluster run differs from a local one in ways that only such a run shows: there is no --cores
(`workflow.cores` raises; the benchmark rule used it for its threads and every cluster run died
at parse time), every job is a fresh snakemake process that rebuilds its params from the config,
and the jobs share only files.  The lines computed this way must equal the same lines computed
locally."""

from pathlib import Path

import pandas as pd
import pytest
from conftest import QUICK, copy_workflow, snakemake

pytest.importorskip("snakemake_executor_plugin_cluster_generic")

#: two jobs: Fig. 3's line (sweep_line) and the boundary lines (sweep_boundary_lines)
LINES = ["results/sims/ref/fig3.csv", "results/sims/ref/cmax100.csv"]
SUBMIT = """#!/usr/bin/env bash
# stand-in batch system: run the job script in the background, print its job id
nohup bash "$1" > "$1.out" 2>&1 &
echo "$!"
"""


def workflow_copy(work: Path) -> Path:
    copy_workflow(work)
    submit = work / "submit.sh"
    submit.write_text(SUBMIT)
    submit.chmod(0o755)
    return work


CLUSTER = ["--executor", "cluster-generic", "--cluster-generic-submit-cmd", "./submit.sh"]


@pytest.mark.slow
def test_cluster_jobs_equal_local_jobs(tmp_path):
    """Two sweep lines submitted through the executor equal the same lines run locally.  (A dry
    run does not catch the missing --cores: snakemake then assumes one core.)"""
    cluster = workflow_copy(tmp_path / "cluster")
    p = snakemake(cluster, *LINES, *CLUSTER, "--jobs", "2", *QUICK, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    submitted = (p.stdout + p.stderr).count("with external jobid")
    assert submitted == len(LINES), "the jobs did not go through the executor"
    local = workflow_copy(tmp_path / "local")
    p = snakemake(local, *LINES, "--cores", "2", *QUICK, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    for line in LINES:
        a, b = pd.read_csv(cluster / line), pd.read_csv(local / line)
        assert len(a) == len(b) > 0 and a["converged"].all()
        numbers = ["f_d", "f0_hz", "rms_dynamic", "rms_quasistatic", "delta_rms"]
        pd.testing.assert_frame_equal(a[numbers], b[numbers], rtol=1e-9, atol=0)
