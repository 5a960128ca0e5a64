"""The beam's branch of periodic orbits in f_d (rotbeam.solve.beam_branch) against what does not
go through the continuation: fixed-f_d collocation from the linear guess, the linear forced
response, and time stepping up and down in f_d (hysteresis between the folds)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import steady, y_m

from rotbeam.model.criterion import rms
from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.modes import linear_forced_response
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects
from rotbeam.runs.nonlinear import branch_model
from rotbeam.solve.beam_branch import BeamBranchProblem, beam_branch
from rotbeam.solve.periodic import solve_periodic


def test_small_amplitude_branch_is_the_fixed_frequency_orbits_and_the_linear_response():
    """a = 0.02 rad/s at Omega_0 = 5 rad/s across the first resonance (N = 6): every branch point
    is the orbit Newton finds at its f_d from the linear guess (to 1e-7), its midspan RMS is the
    linear forced response's within 1 %, f_d grows monotonically (no fold) and all are stable.
    (At a = 0.1 the resonant orbit, y_m / L = 0.067 RMS, is already 3 % off the linear one.)"""
    beam, N = Beam(), 6
    model = branch_model(beam, 5.0, 0.02, 6.0, Effects(), N)
    bb = beam_branch(model, beam.T, (6.0, 7.5), tail_tol=1e-6, ds=0.1, ds_max=0.4)
    pts = bb.branch.points
    assert bb.branch.message.startswith("left the range") and len(pts) > 8
    assert not bb.branch.folds()
    assert all(np.diff([pt.p for pt in pts]) > 0) and all(pt.stable for pt in pts)
    pr = bb.problem
    checked = 0
    for pt in pts[:: max(1, len(pts) // 6)]:
        if pt.p > 7.5:
            continue
        dl = pr.dimensionless(pt.p)
        ref = solve_periodic(
            DiscreteElastica(dl, N), pr.M
        )  # from the linear guess, not from the branch
        assert ref.converged
        X = pt.x.reshape(pr.M, N - 1)
        assert np.max(np.abs(X - ref.theta)) <= 1e-7 * np.max(np.abs(X))
        amp = linear_forced_response(DiscreteElastica(dl, N))[1]
        tau = np.arange(64) * dl.period / 64
        lin = np.real(amp[None, :] * np.exp(1j * dl.omega * tau)[:, None])
        y_lin = rms(pr.model.grid.midspan(lin))
        assert abs(rms(pr.midspan(pt.x, pt.p)) - y_lin) <= 0.01 * y_lin
        checked += 1
    assert checked >= 4


def test_residual_is_zero_only_at_the_orbit_of_its_own_frequency():
    """p is f_d in Hz: an orbit solved at 6 Hz is a zero of the residual at 6 Hz, not at 6.1."""
    template = Dimensionless.from_physical(Beam(), Drive(omega0=5.0, f_d=6.0, amplitude=1.0))
    pr = BeamBranchProblem(DiscreteElastica(template, 6), Beam().T, 17)
    dl = pr.dimensionless(6.0)
    assert math.isclose(dl.omega, 2 * math.pi * 6.0 * Beam().T)
    res = solve_periodic(DiscreteElastica(dl, 6), 17)
    x = res.theta.ravel()
    assert np.max(np.abs(pr.residual(x, 6.0))) < 1e-8
    assert np.max(np.abs(pr.residual(x, 6.1))) > 1e-3
    J = pr.jacobian(x, 6.0)
    h = 1e-7
    e = np.zeros(x.size)
    e[3] = h
    fd = (pr.residual(x + e, 6.0) - pr.residual(x - e, 6.0)) / (2 * h)
    assert np.allclose(J[:, 3], fd, rtol=1e-5, atol=1e-6)
    assert pr.floquet(x, 6.0).stable


@pytest.mark.slow
def test_time_stepping_from_a_given_state_follows_the_beam():
    """steady_state(state0=...) starts where it is told: from the previous run's final state it
    is steady within a few periods at the same RMS, while from rest it needs the transient;
    a state of the wrong size is refused."""
    from rotbeam.model.params import Dimensionless, Drive
    from rotbeam.solve.numerics import Numerics

    dl = Dimensionless.from_physical(Beam(), Drive(omega0=5.0, f_d=2.0, amplitude=1.0))
    num = Numerics(N=6, start="rest")
    first = steady(dl, num)
    assert first.converged and first.state is not None and first.periods > 5
    again = steady(dl, num, state0=first.state)
    assert again.converged and again.periods <= 3 and again.periodic is None
    assert abs(rms(y_m(dl, again)) - rms(y_m(dl, first))) <= 2e-3 * rms(y_m(dl, first))
    with pytest.raises(ValueError, match="state0"):
        steady(dl, num, state0=np.zeros(3))
