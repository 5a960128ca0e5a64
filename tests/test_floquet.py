"""Floquet multipliers (rotbeam.solve.floquet) against closed forms, finite differences of the
period map and the harmonic-balance folds of a Duffing oscillator; unstable orbits are never
reported as the steady state."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
from conftest import steady, y_m
from scipy.integrate import solve_ivp

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.modes import dimensionless_frequencies
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects
from rotbeam.solve.certify import CERTIFICATE_SAFETY, accept_certified, monodromy_certificate
from rotbeam.solve.collocated_floquet import CLUSTER_MARGIN, COLLOCATED_METHOD, uniform_decay
from rotbeam.solve.continuation import FirstOrderProblem, continue_branch
from rotbeam.solve.floquet import (
    FIRST_STEPS,
    FIRST_TRY_MAX_INSTANTS,
    SPREAD_TOL,
    STEP_LADDER,
    FloquetResult,
    beam_floquet,
    orbit_floquet,
    top_stands_apart,
)
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.periodic import solve_periodic, solve_periodic_adaptive

NO_EULER = Effects(centrifugal=True, softening=True, euler=False, damping=True)


def _linear_beam(amplitude: float, N: int = 12):
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=20.0, f_d=3.0, amplitude=amplitude),
                                     NO_EULER)  # fmt: skip
    model = DiscreteElastica(dl, N)
    res = solve_periodic(model, 17)
    assert res.converged and np.max(np.abs(res.theta)) == 0.0  # the straight beam
    return dl, model, beam_floquet(model, res.theta, res.theta_t)


def test_linear_beam_multipliers_closed_form():
    """Steady rotation: mu = exp(lambda P), lambda = -eta/2 +- i sqrt(w^2 - eta^2/4), w from the
    eigenproblem of rotbeam.model.modes (its own linear operators, not the Jacobian)."""
    N = 12
    dl, _, fl = _linear_beam(0.0, N)
    w = dimensionless_frequencies(dl.lam0, dl.hub_ratio, N - 1, N, True)
    wd = np.sqrt(w**2 - dl.eta**2 / 4.0)
    assert np.all(w > dl.eta / 2.0)  # all underdamped
    lam = np.concatenate([-dl.eta / 2 + 1j * wd, -dl.eta / 2 - 1j * wd])
    exact = np.exp(lam * dl.period)
    assert np.allclose(np.abs(fl.multipliers), math.exp(-dl.eta * dl.period / 2), rtol=1e-9)
    err = max(float(np.min(np.abs(exact - mu))) for mu in fl.multipliers)
    assert err < 1e-8  # moduli and phases (damped frequencies, mod 2 pi / P)
    assert fl.stable


def test_parametrically_modulated_beam_keeps_mass_proportional_decay():
    """lam(t) = lam0 + alpha sin(w t) without Euler load: the straight beam is a periodic
    orbit of a time-varying linear system; with damping eta M, z = e^{-eta t/2} y and the y
    system is conservative, so away from parametric resonance every |mu| = exp(-eta P / 2)."""
    dl, _, fl = _linear_beam(1.0)
    assert np.allclose(np.abs(fl.multipliers), math.exp(-dl.eta * dl.period / 2), rtol=1e-8)
    # the modulation does move the phases (this is not the steady-rotation case again)
    _, _, steady = _linear_beam(0.0)
    assert (
        np.max(np.abs(np.sort_complex(fl.multipliers) - np.sort_complex(steady.multipliers))) > 1e-3
    )


@pytest.mark.slow
def test_monodromy_against_finite_differences_of_the_period_map():
    """Full nonlinear model below resonance (5 rad/s, 4 Hz, max |theta| 0.15): Phi at 2 M
    steps against central differences of the time-stepped one-period map (Radau, rtol 1e-8,
    eps 1e-4).  Measured: 1.4e-4 of max |Phi| (the differences' own floor is 4e-5) and |mu|max
    to 7e-7.  The default step count gives |mu|max as well.  N = 4 keeps the 12 perturbed runs
    affordable: a perturbation excites the high-frequency modes, which mass-proportional
    damping leaves as undamped as the first."""
    N = 4
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=5.0, f_d=4.0), Effects())
    model = DiscreteElastica(dl, N)
    res = solve_periodic_adaptive(model, tail_tol=1e-6)
    assert res.converged and res.harmonic_tail < 1e-6
    fl = beam_floquet(model, res.theta, res.theta_t, steps=2 * res.M)
    n = model.n

    def rhs(t, z):
        acc = model.acceleration(z[:n], z[n:], dl.lam(t), dl.lam_dot(t))
        return np.concatenate([z[n:], acc])

    def jac(t, z):
        return model.first_order_jacobian(z[:n], z[n:], dl.lam(t), dl.lam_dot(t))

    def period_map(z0):
        sol = solve_ivp(rhs, (0.0, dl.period), z0, method="Radau", rtol=1e-8, atol=1e-11,
                        jac=jac)  # fmt: skip
        return sol.y[:, -1]

    z0 = np.concatenate([res.theta[0], res.theta_t[0]])
    eps = 1e-4
    fd = np.column_stack(
        [(period_map(z0 + eps * e) - period_map(z0 - eps * e)) / (2 * eps) for e in np.eye(2 * n)]
    )
    rel = np.max(np.abs(fl.monodromy - fd)) / np.max(np.abs(fd))
    assert rel < 1e-3
    mu_fd = np.max(np.abs(np.linalg.eigvals(fd)))
    assert abs(fl.max_abs - mu_fd) < 1e-5
    assert abs(beam_floquet(model, res.theta, res.theta_t).max_abs - mu_fd) < 1e-5


# --- Duffing oscillator x'' + c x' + k x + b x^3 = F cos(w t) -----------------------------------
C, K, B, F = 0.1, 1.0, 0.1, 0.3


def _duffing_problem(M: int = 33) -> FirstOrderProblem:
    def rhs(t, z, w):
        return np.array([z[1], -C * z[1] - K * z[0] - B * z[0] ** 3 + F * math.cos(w * t)])

    def jac(t, z, w):
        return np.array([[0.0, 1.0], [-K - 3.0 * B * z[0] ** 2, -C]])

    return FirstOrderProblem(rhs, jac, lambda w: 2.0 * math.pi / w, 2, M)


def _linear_start(problem: FirstOrderProblem, w: float) -> np.ndarray:
    t = np.arange(problem.M) * 2.0 * math.pi / w / problem.M
    A = F / (K - w * w)
    return np.column_stack([A * np.cos(w * t), -A * w * np.sin(w * t)]).ravel()


def _harmonic_balance_folds() -> list[float]:
    """One-harmonic balance [(k - w^2) A + 3/4 b A^3]^2 + (c w A)^2 = F^2: the frequencies where
    w(A) is stationary on the curve (the folds of the backbone-bent resonance)."""
    A = np.linspace(1e-3, 10.0, 400001)
    kap = K + 0.75 * B * A * A
    disc = (2 * kap - C * C) ** 2 - 4 * (kap * kap - F * F / (A * A))
    ok = disc >= 0
    u = ((2 * kap - C * C) + np.sqrt(np.where(ok, disc, 0.0))) / 2.0
    w = np.where(ok & (u > 0), np.sqrt(np.abs(u)), np.nan)
    d = np.sign(np.diff(w))
    idx = np.where(d[:-1] * d[1:] < 0)[0] + 1
    return sorted(float(v) for v in w[idx])


def test_duffing_fold_frequencies_against_harmonic_balance():
    """Continuation through both folds; their frequencies within 0.5 % of the one-harmonic
    balance (the third harmonic, b A^3 / 32 ~ 2 % of A, shifts them by ~0.1 %)."""
    pr = _duffing_problem()
    br = continue_branch(pr, _linear_start(pr, 0.5), 0.5, (0.5, 2.5), ds=0.05, ds_max=0.2)
    folds = sorted(br.folds())
    hb = _harmonic_balance_folds()
    assert len(folds) == 2 and len(hb) == 2
    assert np.allclose(folds, hb, rtol=5e-3)
    # between the folds the branch is the unstable middle one: a real multiplier above +1
    i0, i1 = sorted(b.index for b in br.bifurcations if b.kind == "fold")
    middle = br.points[i0:i1]
    assert middle and all(not q.stable and q.floquet.crossing() == "fold" for q in middle)
    assert all(q.stable for q in br.points[: i0 - 1] + br.points[i1 + 1 :])


def test_unstable_duffing_orbit_is_attracted_away_from():
    """The middle-branch orbit, time stepped from a push along its unstable Floquet vector,
    leaves it and settles on a stable orbit of the same drive (different amplitude)."""
    pr = _duffing_problem()
    br = continue_branch(pr, _linear_start(pr, 0.5), 0.5, (0.5, 2.5), ds=0.05, ds_max=0.2)
    q = next(q for q in br.points if not q.stable)
    Z = q.x.reshape(pr.M, 2)
    fl = orbit_floquet(lambda t, z: pr.jac(t, z, q.p), Z, pr.period(q.p))
    assert fl.max_abs > 1.0
    w, V = np.linalg.eig(fl.monodromy)
    v = np.real(V[:, np.argmax(np.abs(w))])
    P = pr.period(q.p)
    sol = solve_ivp(lambda t, z: pr.rhs(t, z, q.p), (0, 200 * P), Z[0] + 0.01 * v, rtol=1e-9,
                    atol=1e-11, t_eval=np.arange(190, 201) * P)  # fmt: skip
    amp_middle = np.max(np.abs(Z[:, 0]))
    assert np.max(np.abs(np.diff(sol.y[0]))) < 1e-6  # settled (period-1)
    assert abs(abs(sol.y[0, -1]) - abs(Z[0, 0])) > 0.05 * amp_middle  # not the middle orbit


@pytest.mark.slow
@pytest.mark.parametrize("integrate", [False, True])
def test_beam_unstable_orbit_not_reported_as_steady(monkeypatch, integrate):
    """Force the beam's collocated orbit to count as unstable: it is not the steady state
    (integrate=False: status 2; integrate=True: time stepping decides, message says so)."""
    import rotbeam.solve.floquet as floquet

    # the unit circle shrunk to radius 0.5: |mu|max ~ 0.66-0.95 now counts as unstable
    monkeypatch.setattr(floquet.FloquetResult, "stable", property(lambda s: s.max_abs < 0.5))
    monkeypatch.setattr(floquet.FloquetResult, "unstable", property(lambda s: s.max_abs > 0.5))
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=5.0, f_d=2.0), Effects())
    res = steady(dl, Numerics(N=10, integrate=integrate, max_seconds=60))
    assert res.floquet is not None and not res.floquet.stable
    if integrate:
        assert "collocated orbit unstable" in res.message
        assert not res.converged and res.status != 0  # never "verified by one period"
    else:
        assert res.status == 2 and not res.converged and "unstable" in res.message


# --- the monodromy certificate: the orbit's defect and its distance to the true orbit -----------


def _duffing_orbit(M: int, w: float) -> np.ndarray:
    from rotbeam.solve.continuation import newton

    problem = _duffing_problem(M)
    x, ok = newton(problem, _linear_start(problem, w), w)
    assert ok
    return x.reshape(M, 2)


def test_duffing_offset_estimate_against_a_resolved_orbit():
    """A coarse collocation (M = 3, 5, 7) of the Duffing orbit at w = 0.9: the offset the
    certificate predicts, (I - Phi)^-1 defect, against the start of the resolved (M = 65) orbit.
    Measured: within 1.1 % of its norm."""
    w = 0.9
    fine = _duffing_orbit(65, w)
    pr = _duffing_problem()  # its rhs, jac and period do not depend on M
    for M in (3, 5, 7):
        Z = _duffing_orbit(M, w)
        fl = orbit_floquet(lambda t, z: pr.jac(t, z, w), Z, pr.period(w),
                           rhs=lambda t, z: pr.rhs(t, z, w))  # fmt: skip
        off, true = fl.fixed_point_offset(), fine[0] - Z[0]
        assert np.linalg.norm(off - true) < 0.05 * np.linalg.norm(true), (M, off, true)


@pytest.mark.parametrize(
    "N, omega0, f_d, Ms", [(6, 5.0, 4.0, (5, 7, 9)), (10, 100.0, 30.0, (5, 9, 13))]
)
def test_beam_offset_estimate_against_a_resolved_orbit(N, omega0, f_d, Ms):
    """The beam's coarse orbits: the estimated offset's norm against the resolved (M = 65) orbit's
    start, within a factor 1.5 (measured 0.89-1.32) while the offset is above 1e-8 (below, the
    estimate sits on the defect's quadrature floor and overestimates: the safe side)."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=omega0, f_d=f_d), Effects())
    model = DiscreteElastica(dl, N)
    fine = solve_periodic(model, 65)
    for M in Ms:
        r = solve_periodic(model, M)
        assert r.converged
        off = beam_floquet(model, r.theta, r.theta_t).fixed_point_offset()
        true = np.concatenate([fine.theta[0] - r.theta[0], fine.theta_t[0] - r.theta_t[0]])
        ratio = np.linalg.norm(off) / np.linalg.norm(true)
        assert np.linalg.norm(true) > 1e-8 and 1 / 1.5 < ratio < 1.5, (M, ratio)


def test_certified_orbit_is_the_time_verified_one_and_a_failed_certificate_time_steps(monkeypatch):
    """Certified by the monodromy, the steady state is the collocated orbit itself, without a
    period of time stepping: the same samples as when one period verifies it.  A certificate
    that fails (its safety factor made impossible) refines the orbit and hands it to the
    time-stepped check."""
    import rotbeam.solve.certify as certify

    dl = Dimensionless.from_physical(Beam(), Drive(omega0=100.0, f_d=30.0), Effects())
    by_monodromy = steady(dl, Numerics(N=12))
    by_time = steady(dl, Numerics(N=12, certify="time"))
    assert by_monodromy.converged and by_time.converged
    assert "certified by the monodromy" in by_monodromy.message and by_monodromy.periods == 0
    assert "verified by one period" in by_time.message and by_time.periods == 1
    np.testing.assert_array_equal(y_m(dl, by_monodromy), y_m(dl, by_time))
    monkeypatch.setattr(certify, "CERTIFICATE_SAFETY", 1e12)
    refused = steady(dl, Numerics(N=12))
    assert refused.converged and refused.periods >= 1
    assert refused.message.startswith("not certified by the monodromy")
    # refined first (M -> 2M - 1 while the offset halves), then verified: the same periodic
    # state as the M = 17 orbit's, sampled by a finer collocation (measured 1.6e-11)
    assert refused.periodic.M > by_time.periodic.M
    scale = np.max(np.abs(y_m(dl, by_time)))
    assert np.max(np.abs(y_m(dl, refused) - y_m(dl, by_time))) <= 1e-9 * scale


# --- the step count: a first try with its own error estimate ------------------------------------
def _beam_orbit(omega0: float, f_d: float, N: int = 12):
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=omega0, f_d=f_d), Effects())
    model = DiscreteElastica(dl, N)
    res = solve_periodic_adaptive(model, tail_tol=1e-3)
    assert res.converged
    return dl, model, res


@pytest.mark.parametrize("omega0, f_d", [(5.0, 2.0), (50.0, 10.0), (100.0, 5.0)])
def test_first_try_kept_on_calm_orbits_within_its_tolerance_of_converged(omega0, f_d):
    """Calm orbits (below and above resonance, slow and fast rotation): the monodromy keeps its
    first try of FIRST_STEPS steps, and its |mu|max is within SPREAD_TOL of the same rule
    converged in the step count (16 M steps)."""
    dl, model, res = _beam_orbit(omega0, f_d)
    fl = beam_floquet(model, res.theta, res.theta_t)
    converged = beam_floquet(model, res.theta, res.theta_t, steps=16 * res.M)
    assert fl.steps == FIRST_STEPS
    assert fl.coarse is not None and fl.coarse.steps == FIRST_STEPS // 3
    assert abs(fl.max_abs - converged.max_abs) <= SPREAD_TOL
    assert fl.spread <= SPREAD_TOL


def test_resonant_orbit_climbs_the_ladder_within_its_tolerance_of_converged():
    """At resonance (5 rad/s, 7 Hz: the tip swings 0.27 L and J(t) varies fast) the first try
    and its coarse product disagree, so the monodromy takes the counts of STEP_LADDER in turn:
    the one it keeps was checked against the count before it, and its |mu|max is within
    SPREAD_TOL of the same rule converged in the step count (3000 steps)."""
    dl, model, res = _beam_orbit(5.0, 7.0)
    fl = beam_floquet(model, res.theta, res.theta_t)
    assert fl.steps in STEP_LADDER[1:]
    i = STEP_LADDER.index(fl.steps)
    assert fl.coarse is not None and fl.coarse.steps == STEP_LADDER[i - 1]
    assert fl.spread <= SPREAD_TOL
    fixed = beam_floquet(model, res.theta, res.theta_t, steps=fl.steps)
    np.testing.assert_array_equal(fl.monodromy, fixed.monodromy)
    converged = beam_floquet(model, res.theta, res.theta_t, steps=3000)
    assert abs(fl.max_abs - converged.max_abs) <= SPREAD_TOL


def test_a_resonant_step_count_is_not_taken_on_trust():
    """The exponential midpoint rule's error peaks at step counts that alias a bending mode
    onto a low harmonic of the orbit: at 5 rad/s, 8.31 Hz (N = 40) 33 and 66 steps put |mu|max
    4e-3 off, whatever M the orbit has (measured the same at M = 17, 33, 65).  The ladder's
    counts are checked against each other, and what it keeps is within SPREAD_TOL of the rule
    converged in the step count."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=5.0, f_d=1 + 19 * 15 / 39), Effects())
    model = DiscreteElastica(dl, 40)
    res = solve_periodic(model, 33)
    assert res.converged
    converged = beam_floquet(model, res.theta, res.theta_t, steps=2000)
    for steps in (33, 66):  # the peaks: as a fixed count they are far off
        off = beam_floquet(model, res.theta, res.theta_t, steps=steps).max_abs - converged.max_abs
        assert abs(off) > 1e-3
    fl = beam_floquet(model, res.theta, res.theta_t)
    assert abs(fl.max_abs - converged.max_abs) <= SPREAD_TOL


def test_a_first_try_on_an_unresolved_orbit_does_not_stand():
    """An orbit on more instants than FIRST_TRY_MAX_INSTANTS has harmonics that 12 midpoints
    alias: at N = 16, 36.67 rad/s, 13.7 Hz (M = 129, the tip swinging about 1 rad) 12 steps and
    their 4-step cube agree on an unstable |mu|max near 1.2, within a tenth of its distance from
    1.  The pass does not keep that first try: the verdict's pass and the reported one are
    within a tenth of the distance from 1 and within SPREAD_TOL of the rule converged in the
    step count (3000 steps: |mu|max 0.9411, stable)."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=36.67, f_d=13.7), Effects())
    model = DiscreteElastica(dl, 16)
    res = solve_periodic_adaptive(model, tail_tol=1e-3)
    assert res.converged and res.M > FIRST_TRY_MAX_INSTANTS
    converged = beam_floquet(model, res.theta, res.theta_t, steps=3000)
    assert converged.stable
    for steps in (FIRST_STEPS, FIRST_STEPS // 3):  # the trap: both far off, and agreeing
        assert beam_floquet(model, res.theta, res.theta_t, steps=steps).max_abs > 1.1
    verdict = beam_floquet(model, res.theta, res.theta_t, offset_atol=math.inf, mu_tol=math.inf)
    assert verdict.stable and verdict.steps > FIRST_STEPS
    assert abs(verdict.max_abs - converged.max_abs) <= 0.1 * (1.0 - converged.max_abs)
    reported = beam_floquet(model, res.theta, res.theta_t)
    assert abs(reported.max_abs - converged.max_abs) <= SPREAD_TOL


@pytest.mark.parametrize("integrate", [False, True])
def test_floquet_tol_sets_how_far_the_reported_multipliers_are_resolved(integrate):
    """numerics.floquet_tol: above resonance (5 rad/s, 8 Hz, N = 12, an orbit of M = 33: the
    verdict stands at 37 steps, checked against the first try's 12) the default resolves the
    reported |mu|max to SPREAD_TOL of the rule converged in the step count (3000 steps; the
    orbit has more than FIRST_TRY_MAX_INSTANTS instants, but its |mu|max lies in the cluster
    about exp(-eta P / 2), so from more exponential steps, docs/stability.md "Multipliers from
    a collocation"); floquet_tol = 1 stops where the stability verdict and the certificate did
    (37 steps, 1.1e-6 off, within a tenth of its distance from 1), and the orbit and its RMS
    are the same."""
    dl, model, _ = _beam_orbit(5.0, 8.0)
    fine = steady(dl, Numerics(N=12, integrate=integrate))
    loose = steady(dl, Numerics(N=12, integrate=integrate, floquet_tol=1.0))
    assert fine.converged and loose.converged
    orbit = fine.periodic
    converged = beam_floquet(model, orbit.theta, orbit.theta_t, steps=3000)
    assert fine.floquet.spread <= SPREAD_TOL
    assert abs(fine.floquet.max_abs - converged.max_abs) <= SPREAD_TOL
    assert orbit.M > FIRST_TRY_MAX_INSTANTS and loose.floquet.steps == STEP_LADDER[1]
    assert converged.max_abs < uniform_decay(model) * (1.0 + CLUSTER_MARGIN)
    assert COLLOCATED_METHOD not in (fine.floquet.method, loose.floquet.method)
    assert fine.floquet.steps > loose.floquet.steps
    assert abs(loose.floquet.max_abs - converged.max_abs) <= 0.1 * (1.0 - converged.max_abs)
    assert loose.floquet.stable == fine.floquet.stable == converged.stable
    np.testing.assert_array_equal(y_m(dl, loose), y_m(dl, fine))


def _synthetic(defect, coarse_defect):
    """Phi = I / 2 (so the offset is 2 x defect, closed form) with a coarse twin."""
    Phi = 0.5 * np.eye(4)
    coarse = FloquetResult(Phi, 4, 0.0, defect=np.asarray(coarse_defect, dtype=float))
    return FloquetResult(Phi, 12, 0.0, defect=np.asarray(defect, dtype=float), coarse=coarse)


@pytest.mark.parametrize(
    "limit, certified, ambiguous", [(3.5e-6, True, False), (2.5e-6, False, True),
                                    (1.5e-6, False, False)]
)  # fmt: skip
def test_certificate_adds_the_coarse_spread(limit, certified, ambiguous):
    """Offset (I - Phi)^-1 defect = 2e-6, the coarse one 3e-6: certified only when offset plus
    spread (3e-6) is below the limit; with the limit between offset and sum it is ambiguous."""
    fl = _synthetic([1e-6, 0, 0, 0], [1.5e-6, 0, 0, 0])
    cert = monodromy_certificate(fl, np.ones((2, 3)), limit * CERTIFICATE_SAFETY, 1.0)
    assert cert.offset == pytest.approx(2e-6, rel=1e-12)
    assert cert.spread == pytest.approx(1e-6, rel=1e-12)
    assert (cert.certified, cert.ambiguous) == (certified, ambiguous)


def test_ambiguous_certificate_is_decided_with_more_steps(monkeypatch):
    """A limit put between the first try's offset and offset + spread: `accept_certified`
    goes on to the next count of the ladder, whose offset and spread (against the first try)
    are inside the limit, and accepts the orbit with that monodromy (the first try alone would
    have refused it)."""
    import rotbeam.solve.certify as certify

    dl, model, res = _beam_orbit(50.0, 10.0)
    fl = beam_floquet(model, res.theta, res.theta_t)
    wref = max(dl.omega, 1.0)
    first = monodromy_certificate(fl, res.theta, 1.0, wref)
    assert fl.steps == FIRST_STEPS and first.spread > 0.0
    ss_tol = 1e-3
    safety = ss_tol / (first.offset + first.spread / 2)  # limit inside the spread
    monkeypatch.setattr(certify, "CERTIFICATE_SAFETY", safety)
    assert monodromy_certificate(fl, res.theta, ss_tol, wref).ambiguous
    state = accept_certified(model, Numerics(N=12, ss_tol=ss_tol), res, fl)
    finer = orbit_floquet(None, np.concatenate([res.theta, res.theta_t], axis=1), dl.period,
                          steps=STEP_LADDER[1], rows=_rows(model))  # fmt: skip
    assert state.decided and state.status == 0 and state.floquet.steps == STEP_LADDER[1]
    np.testing.assert_array_equal(state.floquet.monodromy, finer.monodromy)
    assert monodromy_certificate(state.floquet, res.theta, ss_tol, wref).certified


def _rows(model):
    """The beam's batched right-hand sides and Jacobians (as `beam_floquet` builds them)."""
    n = model.n

    def rows(t, Z):
        lam, lam_dot = model.drive_rows(t)
        return model.first_order_rows(Z[:, :n], Z[:, n:], lam, lam_dot)

    return rows


def test_failed_certificate_refines_the_orbit_before_time_stepping(monkeypatch):
    """A limit put between the offsets of the first collocated orbit and of the next finer one
    (M -> 2M - 1): the steady state is the finer orbit, certified, with no period of time
    stepping, and its midspan RMS is the time-verified one's (tight ss_tol) to 1e-6."""
    import rotbeam.solve.certify as certify

    dl = Dimensionless.from_physical(Beam(), Drive(omega0=10.0, f_d=7.0), Effects())
    num = Numerics(N=12)
    model = DiscreteElastica(dl, num.N)
    wref = max(dl.omega, 1.0)
    coarse = solve_periodic_adaptive(model, tail_tol=num.tail_tol)
    M = 2 * coarse.M - 1
    finer = solve_periodic(model, M)
    offsets = [
        monodromy_certificate(beam_floquet(model, r.theta, r.theta_t), r.theta, 1.0, wref).offset
        for r in (coarse, finer)
    ]
    assert offsets[1] < offsets[0] / 10  # the finer orbit's defect is far smaller
    limit = math.sqrt(offsets[0] * offsets[1])
    monkeypatch.setattr(certify, "CERTIFICATE_SAFETY", num.ss_tol / limit)
    state = steady(dl, num)
    assert state.converged and state.periods == 0 and state.periodic.M == M
    assert "certified by the monodromy" in state.message
    monkeypatch.undo()
    verified = steady(dl, Numerics(N=12, certify="time", ss_tol=1e-7))
    rms = [float(np.sqrt(np.mean(y_m(dl, s) ** 2))) for s in (state, verified)]
    assert rms[0] == pytest.approx(rms[1], rel=1e-6)


# --- the rule itself: a closed form, its order, and an independent integration -----------------
def _rotating_frame_system():
    """y' = R(t) A R(t)^T y + R(t) c, R(t) = exp(t W) (two planes turning once and twice a
    period): in the turning frame z = R^T y the system is autonomous, z' = (A - W) z + c, and
    R(P) = I, so Phi = exp(P (A - W)) and the forced solution from 0 ends at
    (A - W)^-1 (Phi - I) c.  A zero orbit makes the residual -R(t) c: that solution is the
    defect."""
    from scipy.linalg import expm

    P = 2.0 * math.pi
    G = np.array([[0.0, -1.0], [1.0, 0.0]])
    W = np.block([[G, np.zeros((2, 2))], [np.zeros((2, 2)), 2.0 * G]])
    A = np.array([[-0.1, 1, 0.3, 0], [-4, -0.1, 0, 0.2], [0.5, 0, -0.05, 1], [0, 0.1, -9, -0.05]])
    c = np.array([0.3, -0.2, 0.1, 0.4])

    def jac(t, z):
        R = expm(t * W)
        return R @ A @ R.T

    def rhs(t, z):
        return jac(t, z) @ z + expm(t * W) @ c

    Phi = expm(P * (A - W))
    defect = np.linalg.solve(A - W, (Phi - np.eye(4)) @ c)
    return jac, rhs, P, Phi, defect


def test_monodromy_and_defect_converge_at_second_order_to_a_closed_form():
    """The rotating-frame system: the monodromy and the defect column at S = 96, 192, 384
    steps; each doubling divides both errors by 4 (measured 4.23, 4.06, 4.02 and 4.09, 4.03,
    4.01: the exponential midpoint rule is second order; a first-order rule gives 2), and the
    Richardson combination of the last two agrees with the closed form to 1e-4 of its size
    (measured 1.3e-5; the error at 384 steps alone is 1.6e-3)."""
    jac, rhs, P, Phi, defect = _rotating_frame_system()
    Z = np.zeros((5, 4))
    runs = [orbit_floquet(jac, Z, P, steps=S, rhs=rhs) for S in (96, 192, 384)]
    err_phi = [np.max(np.abs(fl.monodromy - Phi)) for fl in runs]
    err_def = [np.max(np.abs(fl.defect - defect)) for fl in runs]
    for err in (err_phi, err_def):
        assert all(3.6 < a / b < 4.4 for a, b in zip(err, err[1:], strict=False)), err
    rich_phi = (4.0 * runs[2].monodromy - runs[1].monodromy) / 3.0
    rich_def = (4.0 * runs[2].defect - runs[1].defect) / 3.0
    assert np.max(np.abs(rich_phi - Phi)) < 1e-4 * np.max(np.abs(Phi))
    assert np.max(np.abs(rich_def - defect)) < 1e-4 * np.max(np.abs(defect))


@pytest.mark.slow
def test_resonant_beam_multipliers_against_a_time_stepped_variational_equation():
    """At resonance (5 rad/s, 7 Hz, N = 6, M = 129: the ladder climbs to its top) |mu|max of
    the default pass against Phi from the variational equation Y' = J(t) Y integrated by
    solve_ivp (DOP853, rtol 1e-12) on the same interpolated orbit: within 1e-6 (measured
    4.9e-8), the entries of Phi within 1e-4 of max |Phi| (measured 3.2e-5)."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=5.0, f_d=7.0), Effects())
    model = DiscreteElastica(dl, 6)
    res = solve_periodic_adaptive(model, tail_tol=1e-6)
    assert res.converged
    n, rows = model.n, _rows(model)
    Z = np.concatenate([res.theta, res.theta_t], axis=1)
    from rotbeam.solve.floquet import trig_eval

    def jac(t):
        return rows(np.array([t]), trig_eval(Z, dl.period, np.array([t])))[1][0]

    dim = 2 * n
    sol = solve_ivp(lambda t, y: (jac(t) @ y.reshape(dim, dim)).ravel(), (0.0, dl.period),
                    np.eye(dim).ravel(), method="DOP853", rtol=1e-12, atol=1e-13)  # fmt: skip
    Phi = sol.y[:, -1].reshape(dim, dim)
    fl = beam_floquet(model, res.theta, res.theta_t)
    assert fl.steps > FIRST_STEPS
    assert abs(fl.max_abs - np.max(np.abs(np.linalg.eigvals(Phi)))) < 1e-6
    assert np.max(np.abs(fl.monodromy - Phi)) < 1e-4 * np.max(np.abs(Phi))


def _rotations(radius: float, angles: np.ndarray) -> np.ndarray:
    """Block-diagonal 2 x 2 rotations by `angles`, scaled by `radius`: every eigenvalue has
    modulus `radius` (radius e^(+-i angle))."""
    R = np.zeros((2 * angles.size, 2 * angles.size))
    for k, a in enumerate(angles):
        R[2 * k : 2 * k + 2, 2 * k : 2 * k + 2] = radius * np.array(
            [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
        )
    return R


def test_spectral_radius_against_closed_forms():
    """`spectral_radius` (Gelfand's formula by repeated squaring) against matrices whose
    spectral radius is known: equal moduli with no dominant eigenvalue (39 rotations scaled by
    0.93, made non-normal by a basis of condition 1e4, as a calm orbit's monodromy), a Jordan
    block (0.9, size 6: ||J^k|| grows as k^5 0.9^k, the formula's bias in closed form), a
    dominant negative real eigenvalue, a nilpotent matrix (0), a large and a tiny scale (no
    overflow or underflow).  Within 1e-8:
    the rounding of the first squarings sets a floor (4e-9 on the first matrix, where its
    eigenvalues are 3e-11 off), far below the 1e-5 to which the checks compare two counts."""
    from rotbeam.solve.floquet import RADIUS_SQUARINGS, spectral_radius

    rng = np.random.default_rng(7)
    U, _ = np.linalg.qr(rng.standard_normal((78, 78)))
    V = U @ np.diag(np.logspace(0, 4, 78)) @ U.T  # condition 1e4
    calm = V @ _rotations(0.93, rng.uniform(0, math.pi, 39)) @ np.linalg.inv(V)
    assert abs(spectral_radius(calm) - 0.93) <= 1e-8
    # a Jordan block: ||J^k||_max = C(k, 5) 0.9^(k - 5) (its corner), so the formula at
    # k = 2^RADIUS_SQUARINGS lies above 0.9 by the closed-form factor (C(k, 5) / 0.9^5)^(1/k)
    jordan = 0.9 * np.eye(6) + np.diag(np.ones(5), 1)
    k = 2.0**RADIUS_SQUARINGS
    log_corner = sum(math.log(k - i) for i in range(5)) - math.log(120) - 5 * math.log(0.9)
    assert abs(spectral_radius(jordan) - 0.9 * math.exp(log_corner / k)) <= 1e-10
    assert 0.0 < spectral_radius(jordan) - 0.9 <= 3e-8
    d = np.concatenate([[-0.95], rng.uniform(-0.9, 0.9, 20)])
    W = rng.standard_normal((21, 21))
    assert abs(spectral_radius(W @ np.diag(d) @ np.linalg.inv(W)) - 0.95) <= 1e-8
    assert spectral_radius(np.triu(rng.standard_normal((8, 8)), 1)) == 0.0
    assert spectral_radius(np.zeros((3, 3))) == 0.0
    for scale in (1e150, 1e-150):
        assert abs(spectral_radius(scale * calm) / scale - 0.93) <= 1e-8
    with pytest.raises(np.linalg.LinAlgError, match="not finite"):
        spectral_radius(np.array([[1.0, np.nan], [0.0, 1.0]]))


@pytest.mark.parametrize("omega0, f_d", [(100.0, 5.0), (5.0, 7.0)])
def test_spectral_radius_of_beam_monodromies_against_their_eigenvalues(omega0, f_d):
    """On the beam's monodromies (N = 12; a calm orbit, whose multipliers all share one modulus,
    and the resonant one) the spectral radius is the largest |eigenvalue| to 1e-8 (measured
    1.4e-9: the rounding floor of the closed-form test above)."""
    from rotbeam.solve.floquet import spectral_radius

    dl, model, res = _beam_orbit(omega0, f_d)
    for steps in (12, 37):
        Phi = beam_floquet(model, res.theta, res.theta_t, steps=steps).monodromy
        mu = np.abs(np.linalg.eigvals(Phi)).max()
        assert abs(spectral_radius(Phi) - mu) <= 1e-8 * mu


def test_the_ladder_reports_its_radius_and_the_multipliers_on_demand():
    """Every product of the automatic pass, the one it keeps (5 rad/s, 7 Hz: from the ladder;
    100 rad/s, 5 Hz: a first try) and the one it was checked against, carries |mu|max as its
    spectral radius, within 1e-8 of the largest |eigenvalue| of its monodromy; the multipliers
    are those eigenvalues, largest first, computed when asked for and then kept."""
    for omega0, f_d in ((5.0, 7.0), (100.0, 5.0)):
        dl, model, res = _beam_orbit(omega0, f_d)
        fl = beam_floquet(model, res.theta, res.theta_t)
        assert fl.coarse is not None
        for product in (fl.coarse, fl):
            mu = np.linalg.eigvals(product.monodromy)
            assert product.radius is not None and not product._multipliers
            assert abs(product.max_abs - np.abs(mu).max()) <= 1e-8
        np.testing.assert_allclose(np.abs(fl.multipliers), np.sort(np.abs(mu))[::-1],
                                   rtol=1e-12, atol=0)  # fmt: skip
        assert fl.multipliers is fl.multipliers


def test_a_fixed_step_count_reports_the_leading_eigenvalue():
    """A fixed count is reported as the eigenvalues of its monodromy (no radius): max_abs is the
    leading one's modulus to round-off, and the multipliers of an empty monodromy are none."""
    dl, model, res = _beam_orbit(100.0, 5.0)
    fl = beam_floquet(model, res.theta, res.theta_t, steps=12)
    mu = np.linalg.eigvals(fl.monodromy)
    assert fl.radius is None
    assert fl.max_abs == pytest.approx(np.abs(mu).max(), rel=1e-14)
    assert float(np.abs(fl.multipliers[0])) == fl.max_abs
    empty = FloquetResult(np.zeros((0, 0)), 0, 0.0)
    assert empty.multipliers.size == 0 and empty.max_abs == 0.0


def _spectrum(*mu: complex) -> FloquetResult:
    """A product whose multipliers are `mu` (a complex one stands for its conjugate pair too):
    rotation blocks r [[cos, -sin], [sin, cos]] and real entries on a block diagonal."""
    blocks = []
    for m in mu:
        if isinstance(m, complex):
            r, a = abs(m), np.angle(m)
            blocks.append(r * np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]))
        else:
            blocks.append(np.array([[m]]))
    return FloquetResult(scipy.linalg.block_diag(*blocks), steps=1, seconds=0.0)


@pytest.mark.parametrize(
    "mu, stands",
    [
        # a calm orbit: every modulus within the tolerance of the cluster
        ((0.9 * (1 + 5e-6) * 1j, 0.9 + 0j, 0.9 * 1j**0.3), True),
        # a complex pair 5e-5 above the cluster, the next modulus 4e-5 below it: apart
        ((0.9 * (1 + 5e-5) * 1j**0.5, 0.9 * (1 + 1e-5) * 1j**0.2), True),
        # two pairs 5e-5 and 4.5e-5 above the cluster: the counts may swap them
        ((0.9 * (1 + 5e-5) * 1j**0.5, 0.9 * (1 + 4.5e-5) * 1j**0.2), False),
        # a real multiplier and a complex pair 3e-6 apart, both well above the cluster
        ((0.95, 0.95 * (1 - 3e-6) * 1j**0.7), False),
        # alone above the cluster
        ((0.95,), True),
    ],
)
def test_top_stands_apart_from_the_next_modulus(mu, stands):
    """|mu|max stands where it lies within floquet_tol of the cluster (0.9) or more than that
    above every other modulus but its own conjugate's."""
    fl = _spectrum(*mu)
    assert top_stands_apart(fl, 0.9, SPREAD_TOL) is stands
