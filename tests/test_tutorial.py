"""The tutorial runs: every script of examples/ (the docs' sphinx-gallery) exits 0 in a fresh
working directory with a non-interactive matplotlib backend and leaves nothing there, and the
ring-down example recovers the gamma its synthetic record was made with (a closed-form damped
oscillator, not rotbeam's model) within the 95 % interval it states."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.py"))
CALIBRATION = ROOT / "examples" / "04_ringdown_calibration.py"
#: the line the calibration example prints for this test
RESULT = re.compile(
    r"^calibration: gamma_true=(\S+) gamma_fit=(\S+) ci95_low=(\S+) ci95_high=(\S+)$", re.M
)


def run_example(path: Path, cwd: Path) -> subprocess.CompletedProcess:
    """``python path`` in ``cwd`` with the Agg backend and this checkout's rotbeam."""
    pythonpath = os.pathsep.join([str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])])
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=pythonpath)
    return subprocess.run(
        [sys.executable, str(path)], cwd=cwd, env=env, capture_output=True, text=True, timeout=300
    )


@pytest.fixture(scope="module")
def ran(tmp_path_factory):
    """Each example run once per module: path -> (completed process, its working directory)."""
    cache: dict[Path, tuple[subprocess.CompletedProcess, Path]] = {}

    def run(path: Path) -> tuple[subprocess.CompletedProcess, Path]:
        if path not in cache:
            cwd = tmp_path_factory.mktemp(path.stem)
            cache[path] = (run_example(path, cwd), cwd)
        return cache[path]

    return run


def test_the_tutorial_has_its_four_examples():
    names = [p.name for p in EXAMPLES]
    assert len(names) >= 4, names
    assert CALIBRATION in EXAMPLES


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_runs(ran, path):
    out, cwd = ran(path)
    assert out.returncode == 0, f"{path.name} exited {out.returncode}:\n{out.stderr[-3000:]}"
    assert not list(cwd.iterdir()), f"{path.name} left files behind: {list(cwd.iterdir())}"


def test_calibration_recovers_the_gamma_the_record_was_made_with(ran):
    out, _ = ran(CALIBRATION)
    assert out.returncode == 0, out.stderr[-3000:]
    found = RESULT.findall(out.stdout)
    assert len(found) == 1, f"expected one 'calibration:' line, got:\n{out.stdout}"
    true, fit, low, high = (float(x) for x in found[0])
    assert low < fit < high
    # an interval as wide as the value would hold anything: the record must pin gamma down
    assert high - low < 0.2 * true, (low, high)
    assert low <= true <= high, f"gamma {true} outside the fit's 95 % interval [{low}, {high}]"
