"""The Python API holds BLAS to one thread around its work and gives the caller's setting back
(rotbeam.config.threads), whoever set it: read from the loaded libraries themselves
(threadpoolctl), not from the environment."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy  # noqa: F401 - the BLAS pools the tests read are loaded
import pytest
import scipy.linalg  # noqa: F401
from threadpoolctl import threadpool_info

import rotbeam
from rotbeam.config.threads import one_blas_thread

#: the public entry points that do numerical work
ENTRY_POINTS = ("simulate", "critical", "effect_budget", "modes")


def blas_threads() -> list[int]:
    """The thread count of every loaded BLAS pool."""
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


#: a caller whose BLAS runs two threads (a fresh Python without the thread variables, as a
#: notebook starts; the suite's own processes hold one thread): inside the work, after it, and
#: after an error inside it
CALLER = """
import json
import numpy, scipy.linalg
from threadpoolctl import threadpool_info, threadpool_limits
from rotbeam.config.threads import one_blas_thread

def blas():
    return sorted({i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"})

def fails():
    raise ValueError

out = {}
with threadpool_limits(limits=2, user_api="blas"):
    out["before"] = blas()
    out["inside"] = one_blas_thread(blas)()
    out["after"] = blas()
    try:
        one_blas_thread(fails)()
    except ValueError:
        out["after_error"] = blas()
print(json.dumps(out))
"""


def test_the_work_runs_on_one_thread_and_the_callers_setting_returns():
    env = {k: v for k, v in os.environ.items() if not k.endswith("_NUM_THREADS")}
    p = subprocess.run([sys.executable, "-c", CALLER], env=env, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    assert out == {"before": [2], "inside": [1], "after": [2], "after_error": [2]}


def test_nested_calls_limit_once():
    """An inner call inside a limited one does not limit again (a sweep's points pay once)."""
    from rotbeam.config import threads

    calls = []
    real = threads._controller

    class Counting:
        def limit(self, limits):
            calls.append(limits)
            return real().limit(limits=limits)

    threads._controller = lambda: Counting()
    try:
        inner = one_blas_thread(lambda: blas_threads())
        outer = one_blas_thread(lambda: inner())
        assert set(outer()) == {1}
    finally:
        threads._controller = real
    assert calls == [1]


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_every_public_entry_point_is_limited(name):
    """Each public function that does numerical work is wrapped (it fails for one that is
    not: `__wrapped__` is what functools.wraps leaves)."""
    assert hasattr(getattr(rotbeam, name), "__wrapped__")


def test_modes_on_one_thread_gives_the_same_answer():
    """The limit changes the cost, not the numbers: the first frequency with and without it."""
    beam = rotbeam.Beam()
    limited = rotbeam.modes(beam, omega=5.0, n_modes=2, N=20)
    free = rotbeam.modes.__wrapped__(beam, omega=5.0, n_modes=2, N=20)
    assert limited.tolist() == free.tolist()
