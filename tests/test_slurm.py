"""The workflow on a real Slurm through profiles/slurm: a single-node cluster on this
machine (tests/slurm_cluster.py: munged, slurmctld and slurmd of Debian's slurm-wlm, started here
and stopped by PID), snakemake-executor-plugin-slurm, and part of the quick config: the four
boundary lines of the reference beam and the Fig. 3 line, with the boundary table after them,
and the quick config's atlas (3 x 4: a job per Omega_0 line, then the gather).

The lines must go through sbatch as grouped jobs (as many Slurm jobs as the profile's group size
implies, each COMPLETED), the boundary table must run where snakemake runs (a localrule), and
every number must equal a local run's.  .ci/run installs slurm-wlm and munge; on CI (CI=true)
a missing Slurm or plugin is a failure, elsewhere a skip that says what to install."""

import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
import yaml

sys.path.insert(0, str(Path(__file__).parent))
from slurm_cluster import SlurmCluster, missing_programs  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
#: five simulation jobs: the boundary lines (sweep_boundary_lines), Fig. 3's line (sweep_line)
#: and the atlas's three lines (atlas_line)
LINES = [f"results/sims/ref/cmax{c}.csv" for c in (1, 10, 100, 787)] + ["results/sims/ref/fig3.csv"]
ATLAS = "results/atlas/atlas.csv"
SIM_JOBS = 5
BOUNDARY = "results/boundary/ref.csv"
NUMBERS = ["f_d", "f0_hz", "rms_dynamic", "rms_quasistatic", "delta_rms"]

pytestmark = pytest.mark.slow


def _unavailable(reason: str):
    if os.environ.get("CI"):
        pytest.fail(f"{reason}; .ci/run installs it (apt-get install slurm-wlm munge)")
    pytest.skip(reason)


def workflow_copy(work: Path) -> Path:
    work.mkdir()
    shutil.copy(ROOT / "Snakefile", work)
    for d in ("config", "workflow", "profiles"):
        shutil.copytree(ROOT / d, work / d)
    return work


def snakemake(work: Path, env: dict, *args: str) -> subprocess.CompletedProcess:
    # the workflow imports this checkout's rotbeam, in the jobs too (sbatch exports the env)
    env = dict(env, OPENBLAS_NUM_THREADS="1", PYTHONPATH=str(ROOT))
    # --configfile takes every word after it: it goes last
    cmd = [sys.executable, "-m", "snakemake", *args, "--configfile", "config/quick.yaml"]
    return subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    if os.geteuid() != 0:
        pytest.skip("the test cluster's daemons run as root")
    if missing := missing_programs():
        _unavailable(f"Slurm is not installed (missing {', '.join(missing)})")
    try:
        import snakemake_executor_plugin_slurm  # noqa: F401
    except ImportError:
        _unavailable("snakemake-executor-plugin-slurm is not installed (the test extra)")
    with SlurmCluster(tmp_path_factory.mktemp("slurm")) as c:
        yield c


def test_lines_through_slurm_equal_local_lines(cluster, tmp_path):
    remote = workflow_copy(tmp_path / "slurm")
    before = {j["id"] for j in cluster.jobs()}
    p = snakemake(remote, cluster.env, BOUNDARY, ATLAS, *LINES, "--profile", "profiles/slurm")
    assert p.returncode == 0, p.stderr[-4000:] + "\n" + cluster.logs()

    # the lines went through Slurm, grouped as the profile says, and every job completed
    profile = yaml.safe_load((ROOT / "profiles/slurm/config.yaml").read_text())
    group_size = profile["group-components"][profile["groups"]["sweep_line"]]
    assert profile["groups"]["atlas_line"] == profile["groups"]["sweep_line"]
    jobs = [j for j in cluster.jobs() if j["id"] not in before]
    assert len(jobs) == math.ceil(SIM_JOBS / group_size), jobs
    assert {j["state"] for j in jobs} == {"COMPLETED"}, jobs
    log = p.stdout + p.stderr
    reported = set(re.findall(r"submitted with SLURM jobid (\d+)", log))
    assert reported == {j["id"] for j in jobs}, (reported, jobs)
    # the boundary table and the atlas's gather ran where snakemake runs
    assert "localrule boundary_table:" in log
    assert "localrule atlas_gather:" in log

    local = workflow_copy(tmp_path / "local")
    p = snakemake(local, os.environ, BOUNDARY, ATLAS, *LINES, "--cores", "2")
    assert p.returncode == 0, p.stderr[-4000:]
    for line in LINES:
        a, b = pd.read_csv(remote / line), pd.read_csv(local / line)
        assert len(a) == len(b) > 0 and a["converged"].all()
        pd.testing.assert_frame_equal(a[NUMBERS], b[NUMBERS], rtol=1e-9, atol=0)
    pd.testing.assert_frame_equal(pd.read_csv(remote / BOUNDARY), pd.read_csv(local / BOUNDARY))
    a, b = pd.read_csv(remote / ATLAS), pd.read_csv(local / ATLAS)
    assert len(a) == len(b) == 12 and a["ran"].all()
    pd.testing.assert_frame_equal(a[NUMBERS + ["omega0"]], b[NUMBERS + ["omega0"]], rtol=1e-9,
                                  atol=0)  # fmt: skip
