"""Multipliers from a collocation of the variational equation (rotbeam.bench.collocated_multipliers)
against closed forms and the exponential product: the study behind docs/stability.md,
"Multipliers from a collocation"."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects
from rotbeam.solve.certify import orbit_stability, reported_multipliers
from rotbeam.solve.collocated_floquet import (
    COLLOCATED_METHOD,
    collocated_monodromy,
    collocation_tableau,
)
from rotbeam.solve.floquet import (
    FIRST_TRY_MAX_INSTANTS,
    SPREAD_TOL,
    beam_floquet,
    radius_of,
    spectral_radius,
)
from rotbeam.solve.periodic import solve_periodic


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


@pytest.mark.parametrize(
    "omega0, f_d, M, counts", [(5.0, 7.0, 65, (64, 32)), (10.0, 8.30, 33, (32, 16))]
)
def test_reported_multipliers_of_a_fine_orbit_from_radau(omega0, f_d, M, counts):
    """The resonant benchmark scene (M = 65) and the aliasing point of the equally spaced
    steps (10 rad/s, 8.30 Hz at M = 33, where 66 exponential steps are 7.9e-3 off): the
    reported |mu|max comes from Radau collocation (from the first count of 4 n >= M points,
    each checked against the one before: 64 against 32, and 32 against 16) and is within 1e-6
    of the exponential product converged in its step count (3037 steps)."""
    model, res, fl, reported = _reported(omega0, f_d, M)
    assert fl.spread > SPREAD_TOL  # the candidate's count would climb the ladder
    assert reported.method == COLLOCATED_METHOD and reported.defect is None
    assert (reported.steps, reported.coarse.steps) == counts
    converged = beam_floquet(model, res.theta, res.theta_t, steps=3037)
    assert abs(reported.max_abs - converged.max_abs) <= 1e-6
    assert reported.spread <= SPREAD_TOL and reported.stable


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
