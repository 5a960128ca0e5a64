"""The large-drive resonance (rotbeam.runs.nonlinear, workflow target `nonlinear`): where the
branch of periodic orbits loses stability against what time stepping does, which goes through
neither the continuation nor the Floquet multipliers."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from conftest import steady, y_m

from rotbeam.model.criterion import rms
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects
from rotbeam.runs.nonlinear import (
    NonlinearSpec,
    branch_arm,
    first_instability,
    fold_row,
    follow_sweep,
    hysteresis,
    largest_jump,
    loss_tail,
    resolved_arm,
)

# a = 2 rad/s at Omega_0 = 5 rad/s on a coarse grid: the arm from below loses stability at a
# fold near 6.85 Hz (docs/stability.md); the sweep runs across it in 0.05 Hz steps
SPEC = NonlinearSpec(omega0=5.0, amplitude=2.0, f_lo=6.75, f_hi=6.9, N=6, beyond=4,
                     max_points=80, sweep_step=0.05, rtol=1e-4, ss_tol=1e-2,
                     max_periods=200)  # fmt: skip
#: a = 3 rad/s, where the middle branch past the fold is far enough from the stable orbits to
#: tell where time stepping takes a point of it (at a = 2 the pushed point settles 1e-3 from its
#: start, on a stable orbit that neither arm traces)
SPEC_A3 = replace(SPEC, amplitude=3.0, f_hi=6.9)


def _rows(f, y):
    return [{"f_d": a, "rms_ym": b} for a, b in zip(f, y, strict=True)]


def test_largest_jump_and_hysteresis_on_made_up_sweeps():
    up = _rows([1.0, 1.1, 1.2, 1.3], [0.1, 0.2, 0.05, 0.04])
    down = _rows([1.3, 1.2, 1.1, 1.0], [0.04, 0.05, 0.06, 0.1])
    j = largest_jump(up)
    assert (j["f_before"], j["f_after"]) == (1.1, 1.2) and j["jump"] == pytest.approx(-0.15)
    assert j["share"] == pytest.approx(0.15 / 0.16)
    assert hysteresis(up, down) == [1.1]  # 0.2 against 0.06, > 10 % of 0.2
    assert hysteresis(up, up) == []


@pytest.fixture(scope="module")
def arm():
    return branch_arm(Beam(), SPEC, "from_below", Effects())


@pytest.fixture(scope="module")
def arm_a3():
    return branch_arm(Beam(), SPEC_A3, "from_below", Effects())


@pytest.mark.slow  # 99 s measured (the points past the fold cost 20-60 s each)
def test_the_up_sweep_leaves_the_arm_at_its_fold(arm):
    """The arm from below (continuation, multipliers) first loses stability at a fold; the
    up-sweep by time stepping, each point started from the previous one's final state, stays on
    the arm's stable orbits (RMS within 2 %) up to the fold and is off it at the next step, on a
    steady orbit that swings further (max |Theta| above every orbit of the arm)."""
    rows = follow_sweep(Beam(), SPEC, "up", Effects())
    row = fold_row(arm, "from_below", rows, SPEC)
    assert row["loss_kind"] == "fold" and row["agrees"], row
    off = next(r for r in rows if r["f_d"] == row["sweep_first_off"])
    theta_arm = max(np.max(np.abs(pt.x)) for pt in arm.branch.points)
    assert off["status"] == 0 and off["max_theta"] > theta_arm, (off, theta_arm)


@pytest.mark.slow
def test_a_point_past_the_fold_is_left_by_time_stepping(arm_a3):
    """The branch point three after the first unstable one (the middle branch, a real
    multiplier > 1), time-stepped from its own start pushed by 1e-3 of its size, ends on a
    stable orbit: the arm's stable orbit below the fold at the same f_d (its RMS five times
    closer to that one's than to the start's; they differ by ~0.3 %); a stable point of the same
    arm, pushed alike, ends at its own RMS (1e-3; its start state is 1.7e-3 off the time-stepped
    orbit's at N = 6, the collocation's own error).
    ss_tol 1e-5: a looser criterion calls the slow departure steady."""
    from rotbeam.solve.numerics import Numerics

    spec, pr, pts = SPEC_A3, arm_a3.problem, arm_a3.branch.points
    i = next(k for k, pt in enumerate(pts) if not pt.stable)
    num = Numerics(N=spec.N, rtol=1e-6, ss_tol=1e-5, max_periods=300, max_tau=1e9,
                   max_seconds=1e9)  # fmt: skip
    for pt, stays in ((pts[i - 2], True), (pts[i + 3], False)):
        mu = pt.floquet.multipliers[0]
        assert stays or (abs(mu.imag) < 1e-9 and mu.real > 1.0)
        X = pt.x.reshape(pr.M, pr.model.n)
        z0 = np.concatenate([X[0], (pr.collocation(pt.p).D @ X)[0]])
        dl = Dimensionless.from_physical(
            Beam(), Drive(omega0=spec.omega0, f_d=pt.p, amplitude=spec.amplitude), Effects()
        )
        ss = steady(dl, num, state0=z0 * (1.0 + 1e-3))
        assert ss.status == 0 and ss.floquet is not None and ss.floquet.stable, ss.message
        if stays:
            own = rms(pr.midspan(pt.x, pt.p))
            assert abs(rms(y_m(dl, ss)) / own - 1.0) < 1e-3, (pt.p, rms(y_m(dl, ss)), own)
            continue
        # the stable orbit of the arm below its fold at the same f_d, against the start's
        below = [q for q in pts[:i] if q.stable]
        f = np.array([q.p for q in below])
        y = np.array([rms(pr.midspan(q.x, q.p)) for q in below])
        stable_rms = float(np.interp(pt.p, f, y))
        reached, start = rms(y_m(dl, ss)), rms(pr.midspan(pt.x, pt.p))
        assert abs(reached - stable_rms) * 5 < abs(reached - start), (reached, stable_rms, start)


@pytest.mark.slow
def test_nonlinear_target_on_the_quick_config(workflow_copy):
    """`snakemake nonlinear` with config/quick.yaml (one amplitude, N = 6): every output, the
    folds table's row of the arm from below agreeing with its sweep, and nothing of `all` run."""
    import json

    import pandas as pd
    from conftest import QUICK, job_counts, snakemake

    p = snakemake(workflow_copy, "--cores", "1", "nonlinear", *QUICK)
    assert p.returncode == 0, p.stderr[-3000:]
    out = workflow_copy / "results" / "nonlinear"
    for name in ("branches.csv", "branches.pdf", "branches.png", "folds.csv", "folds.md",
                 "response.json", "response.csv", "response.png"):  # fmt: skip
        assert (out / name).stat().st_size > 0, name
    rules = {"nonlinear", "nonlinear_amplitude", "nonlinear_collect", "nonlinear_response"}
    assert set(job_counts(p.stdout + p.stderr)) == rules
    folds = pd.read_csv(out / "folds.csv")
    below = folds[folds["arm"] == "from_below"].iloc[0]
    assert below["loss_kind"] == "fold" and bool(below["agrees"])
    rows = pd.read_csv(out / "branches.csv")
    assert set(rows["kind"]) == {"branch", "sweep"} and set(rows["arm"]) >= {"from_below", "up"}
    resp = json.loads((out / "response.json").read_text())
    assert resp["response"] in ("periodic", "subharmonic", "quasiperiodic", "chaotic")


@pytest.mark.slow  # 20 s measured
def test_an_arm_is_followed_again_until_its_loss_is_resolved():
    """At a = 2 rad/s the arm from above starts on 33 instants (its first orbit, at 8 Hz, is
    small); at its first loss of stability the orbit's harmonic tail is above 1e-2 and the loss
    reads 7.013 Hz.  `resolved_arm` follows it again on 65 and 129 instants: the tail falls
    (2.6e-4 at 129) and the loss, 6.9310 and 6.9304 Hz, agrees between the two within 1 mHz (a
    second discretisation), 80 mHz below the one on 33 instants."""
    spec = NonlinearSpec(omega0=5.0, amplitude=2.0, f_lo=6.0, f_hi=8.0, N=6, beyond=15)
    first = branch_arm(Beam(), spec, "from_above", Effects())
    assert first.problem.M == 33 and loss_tail(first) > 1e-2
    bb, coarse = resolved_arm(Beam(), spec, "from_above", Effects())
    assert (coarse.problem.M, bb.problem.M) == (65, 129)
    assert loss_tail(bb) < loss_tail(coarse) < loss_tail(first)
    f, f_coarse, f_first = (first_instability(b)["f_loss"] for b in (bb, coarse, first))
    assert abs(f - f_coarse) < 1e-3 and f_first - f > 0.05
    row = fold_row(bb, "from_above", [], spec, coarse)
    assert (row["M"], row["M_coarse"], row["f_loss_coarse"]) == (129, 65, f_coarse)
    assert row["tail"] == loss_tail(bb)
