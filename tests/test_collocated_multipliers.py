"""Multipliers from a collocation of the variational equation (rotbeam.bench.collocated_multipliers)
against closed forms and the exponential product: the study behind docs/stability.md,
"Multipliers from a collocation"."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects
from rotbeam.runs.nonlinear import NonlinearSpec, branch_arm
from rotbeam.runs.scene import Scene, simulate
from rotbeam.solve.certify import orbit_stability, reported_multipliers, window_stability
from rotbeam.solve.collocated_floquet import (
    CLUSTER_MARGIN,
    COLLOCATED_METHOD,
    collocated_monodromy,
    collocated_multipliers,
    collocation_tableau,
    uniform_decay,
)
from rotbeam.solve.floquet import (
    FIRST_TRY_MAX_INSTANTS,
    SPREAD_TOL,
    STEP_LADDER,
    beam_floquet,
    radius_of,
    sampled_orbit,
    spectral_radius,
)
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.periodic import PeriodicResult, solve_periodic
from rotbeam.solve.spectral import trig_interpolate


@pytest.mark.parametrize("kind, stages", [("gauss", 2), ("gauss", 4), ("radau", 2), ("radau", 4)])
def test_tableau_integrates_polynomials_of_its_order(kind, stages):
    """The integration matrix is exact on polynomials of degree < s: sum_j a_ij c_j^m =
    c_i^(m+1) / (m + 1), and the weights integrate them over [0, 1]; Radau ends at c = 1 with
    its weights as the last row (stiffly accurate)."""
    c, A, b = collocation_tableau(kind, stages)
    for m in range(stages):
        np.testing.assert_allclose(A @ c**m, c ** (m + 1) / (m + 1), atol=1e-13)
        assert abs(b @ c**m - 1.0 / (m + 1)) <= 1e-13
    if kind == "radau":
        assert c[-1] == pytest.approx(1.0, abs=1e-14)
        np.testing.assert_allclose(A[-1], b, atol=1e-14)


def _straight_beam(N: int = 12):
    """Steady rotation without Euler load: the orbit is the straight beam, every multiplier's
    modulus is exp(-eta P / 2) (tests/test_floquet.py)."""
    effects = Effects(centrifugal=True, softening=True, euler=False, damping=True)
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=20.0, f_d=3.0, amplitude=0.0), effects)
    model = DiscreteElastica(dl, N)
    res = solve_periodic(model, 17)
    assert res.converged and np.max(np.abs(res.theta)) == 0.0
    return dl, model, res


def test_radau_keeps_the_decay_gauss_puts_the_stiff_modes_on_the_circle():
    """On the straight beam (closed form |mu| = exp(-eta P / 2) for every mode) the L-stable
    Radau collocation gives |mu|max to 1e-8 at 64 intervals (its stiff modes tend to 0, below
    the resolved first modes; measured 3e-9), while Gauss collocation (|R| -> 1 along the
    imaginary axis) puts the unresolved stiff modes near the unit circle at 16 to 64 intervals
    (measured 0.99999 to 0.9998, against 0.7575)."""
    dl, model, res = _straight_beam()
    exact = math.exp(-dl.eta * dl.period / 2.0)
    radau, _ = collocated_monodromy(model, res.theta, res.theta_t, 64, "radau")
    assert abs(spectral_radius(radau) - exact) <= 1e-8
    for intervals in (16, 32, 64):
        gauss, _ = collocated_monodromy(model, res.theta, res.theta_t, intervals, "gauss")
        assert spectral_radius(gauss) > 0.999 > exact + 0.2


def test_radau_converges_to_the_exponential_product_on_a_resonant_orbit():
    """At 5 rad/s, 7 Hz (N = 12, M = 33: the tip swinging near resonance) Radau's |mu|max
    converges to the exponential midpoint product converged in its step count (3000 steps):
    within 1e-7 at 128 intervals, the doubling from 64 cutting the error at least 16-fold
    (measured 1.9e-6 and 1.2e-8; at 32 intervals, which sample J(t) too coarsely for this
    orbit, it is 2.5e-4, above the 3.8e-5 of 16).  At N = 12 the stiffest mode turns by a few
    radians an interval of 128, so there its fixed-point offset (I - Phi)^-1 defect agrees with
    the product's to 1e-2 (measured 3.9e-4), unlike at N = 40 (below)."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=5.0, f_d=7.0))
    model = DiscreteElastica(dl, 12)
    res = solve_periodic(model, 33)
    assert res.converged
    ref = beam_floquet(model, res.theta, res.theta_t, steps=3000)
    errors = []
    for intervals in (64, 128):
        Phi, e = collocated_monodromy(model, res.theta, res.theta_t, intervals, "radau")
        errors.append(abs(spectral_radius(Phi) - ref.max_abs))
    assert errors[1] <= 1e-7 and errors[1] <= errors[0] / 16
    w_ref = np.linalg.solve(np.eye(Phi.shape[0]) - ref.monodromy, ref.defect)
    w = np.linalg.solve(np.eye(Phi.shape[0]) - Phi, e)
    assert np.max(np.abs(w - w_ref)) <= 1e-2 * np.max(np.abs(w_ref))


def test_radau_offset_misses_the_stiff_part_at_n40():
    """At N = 40 (100 rad/s, 5 Hz, a calm orbit) Radau at 64 intervals has |mu|max within 2e-6
    of the exponential first try (measured 1.6e-6 below the converged product), but its
    fixed-point offset (I - Phi)^-1 defect is off by more than half of the first try's: the
    stiff modes it annihilates carry the offset's stiff part (measured 1.0 of it at 16 to 128
    intervals), so the certificate keeps the exponentials."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=100.0, f_d=5.0))
    model = DiscreteElastica(dl, 40)
    res = solve_periodic(model, 17)
    assert res.converged
    first = beam_floquet(model, res.theta, res.theta_t)
    assert first.steps == 12
    w_first = first.fixed_point_offset()
    Phi, e = collocated_monodromy(model, res.theta, res.theta_t, 64, "radau")
    assert abs(spectral_radius(Phi) - first.max_abs) <= 2e-6
    w = np.linalg.solve(np.eye(Phi.shape[0]) - Phi, e)
    assert np.max(np.abs(w - w_first)) > 0.5 * np.max(np.abs(w_first))


def _reported(omega0: float, f_d: float, M: int, N: int = 40):
    """The candidate check's multipliers of an orbit and those reported to floquet_tol."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=omega0, f_d=f_d))
    model = DiscreteElastica(dl, N)
    res = solve_periodic(model, M)
    assert res.converged
    fl = orbit_stability(model, res, candidate=True)
    return model, res, fl, reported_multipliers(model, res, fl, SPREAD_TOL)


def test_reported_multipliers_of_a_resonant_orbit_from_radau():
    """The resonant benchmark scene (5 rad/s, 7 Hz, M = 65; |mu|max 6e-4 above the cluster):
    the reported |mu|max comes from Radau collocation (from the first count of 4 n >= M points,
    64 checked against 32) and is within 1e-6 of the exponential product converged in its step
    count (3037 steps)."""
    model, res, fl, reported = _reported(5.0, 7.0, 65)
    assert fl.spread > SPREAD_TOL  # the candidate's count would climb the ladder
    assert reported.method == COLLOCATED_METHOD and reported.defect is None
    assert (reported.steps, reported.coarse.steps) == (64, 32)
    converged = beam_floquet(model, res.theta, res.theta_t, steps=3037)
    assert abs(reported.max_abs - converged.max_abs) <= 1e-6
    assert reported.spread <= SPREAD_TOL and reported.stable


def test_the_aliasing_point_is_resolved_by_the_ladder():
    """10 rad/s, 8.30 Hz at M = 33, where 66 equally spaced exponential steps are 7.9e-3 off:
    its |mu|max stands 1.5e-5 above exp(-eta P / 2), inside the cluster where a mode the
    collocation does not resolve could carry it, so the exponential ladder reports it, within
    1e-6 of its product at 3037 steps (measured 5e-9 at 112 steps)."""
    model, res, fl, reported = _reported(10.0, 8.30, 33)
    assert fl.spread > SPREAD_TOL
    assert reported.method != COLLOCATED_METHOD and reported.steps > fl.steps
    converged = beam_floquet(model, res.theta, res.theta_t, steps=3037)
    assert converged.max_abs < uniform_decay(model) * (1.0 + CLUSTER_MARGIN)
    assert abs(reported.max_abs - converged.max_abs) <= 1e-6


def test_no_collocation_where_the_candidate_stays_inside_the_cluster(monkeypatch):
    """At 5 rad/s, 7.5 Hz (M = 33) the candidate's |mu|max and spread together (measured
    2.3e-5 and 5.2e-5) stay within CLUSTER_MARGIN of exp(-eta P / 2): the collocation is not
    tried, and the ladder resolves |mu|max within 1e-6 of its product at 3037 steps."""
    import rotbeam.solve.certify as certify

    def refuse(*args):
        raise AssertionError("the collocation was tried")

    model, res, fl, _ = _reported(5.0, 7.5, 33)
    assert fl.spread > SPREAD_TOL
    assert fl.max_abs + fl.spread < uniform_decay(model) * (1.0 + CLUSTER_MARGIN)
    monkeypatch.setattr(certify, "collocated_multipliers", refuse)
    reported = reported_multipliers(model, res, fl, SPREAD_TOL)
    converged = beam_floquet(model, res.theta, res.theta_t, steps=3037)
    assert reported.steps > fl.steps and abs(reported.max_abs - converged.max_abs) <= 1e-6


#: the five benchmark scenes of docs/numerics.md (Omega_0 [rad/s], f_d [Hz], M)
BENCHMARK_SCENES = [(5.0, 2.0, 17), (5.0, 7.0, 65), (5.0, 15.0, 17), (100.0, 5.0, 17),
                    (100.0, 30.0, 17)]  # fmt: skip


@pytest.mark.parametrize("omega0, f_d, M", BENCHMARK_SCENES)
def test_radau_at_128_intervals_equals_the_converged_product_at_the_benchmark_scenes(
    omega0, f_d, M
):
    """At each benchmark scene (N = 40) Radau's |mu|max at 128 intervals is within 1e-6 of the
    exponential product at 3037 steps (measured within 5e-8 at the counts that stand), and
    only the resonant scene's stands above the cluster: the calm ones are left to the
    exponentials (None)."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=omega0, f_d=f_d))
    model = DiscreteElastica(dl, 40)
    res = solve_periodic(model, M)
    assert res.converged
    converged = beam_floquet(model, res.theta, res.theta_t, steps=3037)
    Phi, _ = collocated_monodromy(model, res.theta, res.theta_t, 128)
    assert abs(spectral_radius(Phi) - converged.max_abs) <= 1e-6
    above = converged.max_abs >= uniform_decay(model) * (1.0 + CLUSTER_MARGIN)
    assert above == (f_d == 7.0)
    reported = collocated_multipliers(model, res.theta, res.theta_t, SPREAD_TOL)
    assert (reported is not None) == above


def test_reported_multipliers_of_a_calm_orbit_stay_exponential():
    """An orbit of at most FIRST_TRY_MAX_INSTANTS instants whose first try does not stand to
    floquet_tol goes on up the exponential ladder (37 steps are cheaper than two Radau counts)."""
    model, res, fl, reported = _reported(5.0, 9.0, 17, N=12)
    assert res.M <= FIRST_TRY_MAX_INSTANTS and fl.spread > SPREAD_TOL  # measured 3.6e-4
    assert reported.method != COLLOCATED_METHOD and reported.steps > fl.steps


def test_the_ladder_decides_where_radau_disagrees_or_cannot_check(monkeypatch):
    """Where Radau's |mu|max lies farther from the candidate's than its resolution (a stiff mode
    the collocation annihilated would make it too low), or no two interval counts agree, the
    reported multipliers come from the exponential ladder."""
    import rotbeam.solve.certify as certify

    model, res, fl, radau = _reported(5.0, 7.0, 65)
    assert radau.method == COLLOCATED_METHOD
    off = radius_of(radau.monodromy * 0.9, radau.steps)  # |mu|max 10 % low
    off.method, off.coarse = COLLOCATED_METHOD, radau.coarse
    for answer in (off, None):
        monkeypatch.setattr(certify, "collocated_multipliers", lambda *a, answer=answer: answer)
        reported = reported_multipliers(model, res, fl, SPREAD_TOL)
        assert reported.method != COLLOCATED_METHOD and reported.steps > fl.steps
        assert abs(reported.max_abs - radau.max_abs) <= 1e-5


@pytest.fixture(scope="module")
def large_branch():
    """The nonlinear study's arm from below at a = 3 rad/s (N = 6, M = 65; max |Theta| 1.3 to
    2.7 rad), followed past its first fold and first period doubling."""
    spec = NonlinearSpec(omega0=5.0, amplitude=3.0, f_lo=6.0, f_hi=8.0, N=6, beyond=18)
    bb = branch_arm(Beam(), spec, "from_below", Effects())
    kinds = [b.kind for b in bb.branch.bifurcations]
    assert kinds[0] == "fold" and "period doubling" in kinds
    return bb


def _first(bb, kind: str) -> int:
    """Index of the branch point after the first bifurcation of that kind."""
    return next(b.index for b in bb.branch.bifurcations if b.kind == kind)


def _branch_orbit(bb, index: int):
    """(model, Theta, Theta_t) of a branch point."""
    point = bb.branch.points[index]
    col = bb.problem.collocation(point.p)
    theta = point.x.reshape(bb.problem.M, col.model.n)
    return col.model, theta, col.D @ theta


def _converged(model, theta, theta_t) -> tuple[float, complex]:
    """|mu|max and the multiplier nearest -1 of the exponential midpoint product, Richardson
    extrapolated from 9111 and 27333 steps (order 2; the two counts differ by 6e-5 at the
    period doubling)."""
    out = []
    for steps in (9111, 27333):
        mu = beam_floquet(model, theta, theta_t, steps=steps).multipliers
        out.append((np.max(np.abs(mu)), mu[np.argmin(np.abs(mu + 1.0))]))
    (r1, m1), (r2, m2) = out
    return r2 + (r2 - r1) / 8.0, m2 + (m2 - m1) / 8.0


def test_radau_next_to_the_fold_and_at_the_period_doubling(large_branch):
    """On the large orbits of the nonlinear study (a = 3 rad/s, N = 6), where the exponential
    ladder's 1012 steps are up to 5.5e-3 off, Radau's |mu|max (256 and 1024 intervals) is within
    1e-6 of the converged product next to the first fold and at the first period doubling, and
    there its multiplier nearest -1 is too (measured 2e-8, 4e-10 and 1.5e-7)."""
    fold, doubling = _first(large_branch, "fold"), _first(large_branch, "period doubling")
    for index in (fold - 1, doubling):
        model, theta, theta_t = _branch_orbit(large_branch, index)
        radius, near = _converged(model, theta, theta_t)
        reported = collocated_multipliers(model, theta, theta_t, SPREAD_TOL)
        assert reported is not None and reported.steps >= 256
        assert abs(reported.max_abs - radius) <= 1e-6
        if index == doubling:
            mu = reported.multipliers
            assert abs(mu[np.argmin(np.abs(mu + 1.0))] - near) <= 1e-6 and near.real < -1.0
            ladder = beam_floquet(model, theta, theta_t)
            assert abs(ladder.max_abs - radius) > 1e-3  # what the collocation gains here


def test_branch_points_carry_multipliers_resolved_to_the_tolerance(large_branch):
    """A branch point's multipliers are resolved like a reported orbit's, without the offset:
    at the period doubling and next to the fold they are Radau's, within 1e-6 of the
    converged product (where the ladder is 5e-3 off), and at the arm's first point, inside the
    cluster, the ladder's, within `floquet_tol` (there 37 and 112 steps agree within 1e-5 and
    miss |mu|max by 2.4e-5: only the offsets' comparison asks for more)."""
    branch = large_branch.branch
    fold, doubling = _first(large_branch, "fold"), _first(large_branch, "period doubling")
    for index, method in ((fold - 1, COLLOCATED_METHOD), (doubling, COLLOCATED_METHOD), (0, None)):
        fl = branch.points[index].floquet
        radius, _ = _converged(*_branch_orbit(large_branch, index))
        if method is None:
            assert fl.method != COLLOCATED_METHOD and abs(fl.max_abs - radius) <= SPREAD_TOL
        else:
            assert fl.method == method and abs(fl.max_abs - radius) <= 1e-6


def test_the_orbit_time_stepping_settled_on_gets_resolved_multipliers(large_branch):
    """`window_stability` on one period of 64 samples (resampled to 65 instants, as a window's
    are): on the large orbit of the period doubling Radau's |mu|max, within 1e-6 of the
    converged product where the ladder is 1e-3 off; on the arm's calm first orbit the ladder's,
    within `floquet_tol`."""
    doubling = _first(large_branch, "period doubling")
    for index in (doubling, 0):
        model, theta, _ = _branch_orbit(large_branch, index)
        samples = trig_interpolate(theta, 64)
        radius, _ = _converged(model, *sampled_orbit(model, samples))
        fl = window_stability(model, samples, SPREAD_TOL)
        if index == doubling:
            assert fl.method == COLLOCATED_METHOD and abs(fl.max_abs - radius) <= 1e-6
            ladder = beam_floquet(model, *sampled_orbit(model, samples))
            assert abs(ladder.max_abs - radius) > 1e-3
        else:
            assert fl.method != COLLOCATED_METHOD and abs(fl.max_abs - radius) <= SPREAD_TOL


def test_radau_is_not_reported_inside_the_cluster(large_branch):
    """Where the large orbit's |mu|max stands within CLUSTER_MARGIN of exp(-eta P / 2) (a
    point of the arm's calm start: every mode within 1e-4 of it, the largest not the first
    mode), Radau's 32 and 64 intervals agree within 1e-5 but miss |mu|max by more than that:
    the mode carrying it is still annihilated.  `collocated_multipliers` leaves such an orbit
    to the exponentials."""
    model, theta, theta_t = _branch_orbit(large_branch, 5)
    radius, _ = _converged(model, theta, theta_t)
    assert radius < uniform_decay(model) * (1.0 + CLUSTER_MARGIN)
    coarse, fine = (
        spectral_radius(collocated_monodromy(model, theta, theta_t, c)[0]) for c in (32, 64)
    )
    assert abs(fine - coarse) <= SPREAD_TOL and radius - fine > SPREAD_TOL
    assert collocated_multipliers(model, theta, theta_t, SPREAD_TOL) is None


def test_a_payload_leaves_the_multipliers_to_the_exponentials():
    """With a tip mass the damping (per unit length of the beam) is not proportional to the
    mass, the modes do not share one decay and no cluster is known: no Radau result, and the
    reported multipliers of the resonant scene come from the exponential ladder."""
    dl = Dimensionless.from_physical(Beam(tip_mass=0.002), Drive(omega0=5.0, f_d=7.0))
    model = DiscreteElastica(dl, 40)
    assert uniform_decay(model) is None
    res = solve_periodic(model, 65)
    assert res.converged
    fl = orbit_stability(model, res, candidate=True)
    assert collocated_multipliers(model, res.theta, res.theta_t, SPREAD_TOL) is None
    assert reported_multipliers(model, res, fl, SPREAD_TOL).method != COLLOCATED_METHOD


def test_reported_multipliers_where_two_moduli_above_the_cluster_swap():
    """The nonlinear study's orbit at a = 3 rad/s, 6 Hz, N = 6 (M = 65): its two largest moduli
    stand 6.9e-5 and 2.1e-5 (relative) above the cluster; at 112 steps they read 4.1e-5 and
    3.6e-5, and 37 and 112 steps agree on |mu|max to 4e-6 while both miss it by 2.4e-5.  The
    reported |mu|max goes on until it stands apart from the next modulus (`top_stands_apart`)
    and lies within floquet_tol of the product Richardson-extrapolated from 9111 and 27333
    steps."""
    scene = Scene(beam=Beam(), drive=Drive(omega0=5.0, amplitude=3.0, f_d=6.0),
                  numerics=Numerics(N=6))  # fmt: skip
    result = simulate(scene)
    orbit, reported = result.dynamic.periodic, result.dynamic.floquet
    assert result.dynamic.periods == 0 and orbit.M == 65
    model = scene.model()
    fine = [beam_floquet(model, orbit.theta, orbit.theta_t, steps=s).max_abs for s in (9111, 27333)]
    converged = fine[1] + (fine[1] - fine[0]) / 8.0  # Magnus-2: error ~ h^2
    decay = uniform_decay(model)
    assert decay + 5 * SPREAD_TOL < converged < decay * (1.0 + CLUSTER_MARGIN)
    assert abs(reported.max_abs - converged) <= scene.numerics.floquet_tol


def test_a_candidate_at_the_ladders_end_is_reported_from_radau(large_branch):
    """The stable orbits of the a = 3 rad/s arm past its first fold whose candidate check
    climbed to the ladder's last count (1012 steps) without standing to floquet_tol (spread
    5e-4 to 1e-3; |mu|max 7e-5 to 1.2e-4 off): where Radau answers, the reported |mu|max is
    Radau's, within 1e-6 of the converged product."""
    checked = 0
    for index in range(len(large_branch.branch.points)):
        model, theta, theta_t = _branch_orbit(large_branch, index)
        M = theta.shape[0]
        orbit = PeriodicResult(np.arange(M) / M * model.dl.period, theta, theta_t, True, 0, 0.0,
                               0.0, M, "")  # fmt: skip
        fl = orbit_stability(model, orbit, candidate=True)
        if not (fl.stable and fl.steps == STEP_LADDER[-1] and fl.spread > SPREAD_TOL):
            continue
        if collocated_multipliers(model, theta, theta_t, SPREAD_TOL) is None:
            continue
        radius, _ = _converged(model, theta, theta_t)
        assert abs(fl.max_abs - radius) > SPREAD_TOL  # the candidate misses it
        reported = reported_multipliers(model, orbit, fl, SPREAD_TOL)
        assert reported.method == COLLOCATED_METHOD and abs(reported.max_abs - radius) <= 1e-6
        checked += 1
    assert checked >= 2
