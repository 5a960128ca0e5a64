"""What the workflow tests share: the repository root, a temporary copy of the workflow (and of
the package, for tests that edit it), a Snakemake runner, and one quick-config run for all."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

# One BLAS thread per pytest worker, set before numpy loads OpenBLAS: the suite runs on two
# workers (-n 2) on two cores, and each worker's default two BLAS threads then spin against the
# other's.  Measured: the Duffing fold test takes 20.8 s of CPU with the default, 2.6 s with one
# thread (the matrices here, n <= 160, gain nothing from threads).  The workflow's jobs set the
# same (Snakefile).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import pytest  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
WORKFLOW_FILES = ("Snakefile", "config", "workflow", "profiles")  # profiles: the workflow profile
QUICK = ("--configfile", "config/quick.yaml")


def copy_workflow(work: Path, package: bool = False) -> Path:
    """The workflow (Snakefile, config, rules, scripts, profile) copied into ``work``; with
    ``package``, rotbeam/ too, at ``work / "rotbeam"`` (run it with ``package_root=work``)."""
    work.mkdir(parents=True, exist_ok=True)
    names = [*WORKFLOW_FILES, *(["rotbeam"] if package else [])]
    for name in names:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, work / name, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy2(src, work / name)
    return work


def snakemake_env(package_root: Path = ROOT, **extra: str) -> dict[str, str]:
    """The environment of a Snakemake run: rotbeam from ``package_root`` (not the installed
    one), one BLAS thread per job."""
    path = os.pathsep.join([str(package_root), *filter(None, [os.environ.get("PYTHONPATH")])])
    return dict(
        os.environ, PYTHONPATH=path, OPENBLAS_NUM_THREADS="1", PYTHONUNBUFFERED="1", **extra
    )


def snakemake(
    work: Path, *args: str, package_root: Path = ROOT, timeout: float = 900, env=None
) -> subprocess.CompletedProcess:
    """``python -m snakemake *args`` in ``work`` (args go as given: put --configfile last, it
    takes every word after it)."""
    return subprocess.run(
        [sys.executable, "-m", "snakemake", *args],
        cwd=work,
        env=env or snakemake_env(package_root),
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def job_counts(text: str) -> dict[str, int]:
    """The job-stats table Snakemake prints before it runs (or with -n): rule -> jobs."""
    jobs, inside = {}, False
    for row in text.splitlines():
        parts = row.split()
        if row.startswith("job ") and "count" in row:
            inside = True
        elif inside and parts and parts[0] == "total":
            break
        elif inside and len(parts) == 2 and parts[1].isdigit():
            jobs[parts[0]] = int(parts[1])
    return jobs


def dry_run_jobs(work: Path, *extra: str, package_root: Path = ROOT) -> dict[str, int]:
    """The jobs a run of the quick config would run now (``snakemake -n``), without ``all``."""
    p = snakemake(work, "-n", "--cores", "1", *extra, *QUICK, package_root=package_root)
    assert p.returncode == 0, p.stderr[-3000:]
    jobs = job_counts(p.stdout)
    jobs.pop("all", None)
    return jobs


@pytest.fixture
def workflow_copy(tmp_path) -> Path:
    """A fresh copy of the workflow (no package copy, no results)."""
    return copy_workflow(tmp_path / "wf")


@pytest.fixture(scope="session")
def quick_run(tmp_path_factory) -> Path:
    """The whole quick config run once (`all` and the designed moves), in a copy of the
    workflow, shared by the tests that read its results (they must not change it: copy it
    first).  Its output is in quick_run.log."""
    work = copy_workflow(tmp_path_factory.mktemp("quick") / "wf")
    # the targets first: --configfile reads a list
    p = snakemake(work, "all", "moves", "--cores", "2", *QUICK)
    (work / "quick_run.log").write_text(p.stdout + p.stderr)
    assert p.returncode == 0, p.stderr[-3000:]
    # the workflow profile is read (greedy job selection: see profiles/default/config.yaml)
    assert "Using workflow specific profile profiles/default" in p.stderr, p.stderr[:3000]
    return work


def elastica(N: int, hub: float, eta: float, effects=None, kappa: float = 0.0, lam: float = 0.0):
    """The DiscreteElastica of the numbers it reads, for tests of its parts: hub ratio, damping,
    effects and, with `extension`, the axial compliance kappa = (h/L)^2 / 12 and the steady
    rotation lam whose tension stretches it (the scene turns steadily at lam)."""
    import math

    from rotbeam.model.elastica import DiscreteElastica
    from rotbeam.model.params import Dimensionless, Effects

    effects = effects if effects is not None else Effects()
    slenderness = math.sqrt(12.0 * kappa) if effects.extension else None
    return DiscreteElastica(Dimensionless(hub, eta, lam, 0.0, 1.0, effects, slenderness), N)


def steady(dl, num=None, **kwargs):
    """`steady_state` of the elastica of scene `dl` on the grid of `num` (default Numerics())."""
    from rotbeam.model.elastica import DiscreteElastica
    from rotbeam.solve.numerics import Numerics
    from rotbeam.solve.steady import steady_state

    num = num if num is not None else Numerics()
    return steady_state(DiscreteElastica(dl, num.N), num, **kwargs)


def y_m(dl, state):
    """The midspan deflection y_m / L at the samples of `steady`'s result (the elastica of scene
    `dl` on the grid of its N - 1 angles): the output the runs evaluate on the states."""
    import numpy as np

    from rotbeam.model.elastica import DiscreteElastica

    return np.atleast_1d(DiscreteElastica(dl, state.theta.shape[1] + 1).midspan(state.theta))


def numerical_first_order_jacobian(model, theta, theta_t, lam: float, lam_dot: float):
    """Central differences (h = 1e-6) of the model's first-order right-hand side (Theta_t,
    acceleration) at the state (theta, theta_t): what `first_order_jacobian` must equal."""
    import numpy as np

    n = model.n

    def F(z):
        return np.concatenate([z[n:], model.acceleration(z[:n], z[n:], lam, lam_dot)])

    z, h = np.concatenate([theta, theta_t]), 1e-6
    return np.array([(F(z + h * e) - F(z - h * e)) / (2 * h) for e in np.eye(2 * n)]).T


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items) -> None:
    """With pytest-xdist (`-n 2 --dist loadgroup`, README's test command): a test file runs on
    one worker (its module fixtures are built once), and every test of the quick run shares one
    worker (the run is built once).  tryfirst: the worker's own hook, which reads the marks into
    the node ids the scheduler groups by, runs before this one otherwise, and the groups are lost
    (measured: test_bench's module fixture built on both workers, 100 s each)."""
    for item in items:
        group = "quick_run" if "quick_run" in item.fixturenames else item.module.__name__
        item.add_marker(pytest.mark.xdist_group(group))
