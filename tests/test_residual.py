"""The equation of motion as a residual (`DiscreteModel.residual_rows`): its blocks against
finite differences of the residual itself, and the first-order form the solvers step against
the residual (its acceleration makes R vanish; its Jacobian is -M^-1 times the blocks).  Over
models with every load switched on: payload mass and inertia, Coriolis, extension, damping."""

from __future__ import annotations

import numpy as np
import pytest

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects

MODELS = {
    "paper": ({}, {}),
    "payload": ({"tip_mass": 4.68e-4, "tip_inertia": 1e-8}, {}),
    "coriolis": ({}, {"coriolis": True}),
    "extension and payload": ({"tip_mass": 2.34e-4}, {"extension": True, "coriolis": True}),
    "undamped": ({}, {"damping": False}),
}


def model_of(name: str, N: int = 9) -> DiscreteElastica:
    beam, effects = MODELS[name]
    dl = Dimensionless.from_physical(Beam(**beam), Drive(omega0=30.0, amplitude=3.0, f_d=4.0),
                                     Effects(**effects))  # fmt: skip
    return DiscreteElastica(dl, N)


def states(model, m: int = 3, seed: int = 0):
    """Random states of a bent, moving beam (angles up to 0.6 rad) and the drive at m instants."""
    rng = np.random.default_rng(seed)
    n = model.n
    tau = rng.uniform(0.0, model.dl.period, m)
    lam, lam_dot = model.drive_rows(tau)
    return (rng.uniform(-0.6, 0.6, (m, n)), rng.uniform(-2, 2, (m, n)),
            rng.uniform(-5, 5, (m, n)), lam, lam_dot)  # fmt: skip


@pytest.mark.parametrize("name", MODELS)
def test_the_blocks_are_the_residuals_derivatives(name):
    model = model_of(name)
    q, qt, qtt, lam, lam_dot = states(model)
    dq, dqt, mass = model.residual_rows(q, qt, qtt, lam, lam_dot).blocks()
    h = 1e-6
    for which, block in ((0, dq), (1, dqt), (2, mass)):
        for k in range(model.n):
            args = [q.copy(), qt.copy(), qtt.copy()]
            args[which][:, k] += h
            up = model.residual_rows(*args, lam, lam_dot).R
            args[which][:, k] -= 2 * h
            down = model.residual_rows(*args, lam, lam_dot).R
            fd = (up - down) / (2 * h)
            assert np.allclose(block[:, :, k], fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max()), (
                which,
                k,
            )


@pytest.mark.parametrize("name", MODELS)
def test_the_first_order_form_solves_the_residual(name):
    """first_order_rows (derived from the residual) zeroes R, its acceleration is the time
    stepper's (`acceleration`, the equation written for one instant), and its Jacobian is the
    finite difference of its right-hand side."""
    model = model_of(name)
    q, qt, _, lam, lam_dot = states(model, seed=1)
    n = model.n
    F, J = model.first_order_rows(q, qt, lam, lam_dot)
    rows = model.residual_rows(q, qt, F[:, n:], lam, lam_dot)
    scale = np.abs(model.residual_rows(q, qt, 0 * qt, lam, lam_dot).R).max()
    assert np.abs(rows.R).max() < 1e-11 * scale
    for k in range(q.shape[0]):
        one = model.acceleration(q[k], qt[k], lam[k], lam_dot[k])
        assert np.allclose(F[k, n:], one, rtol=1e-11, atol=1e-11 * np.abs(one).max())
    h = 1e-5  # F = -M^-1 R reaches ~1e3 at N = 9: a smaller step drowns in round-off
    z = np.concatenate([q, qt], axis=1)
    for j in range(2 * n):
        up, down = z.copy(), z.copy()
        up[:, j] += h
        down[:, j] -= h
        fd = (
            model.first_order_rows(up[:, :n], up[:, n:], lam, lam_dot)[0]
            - model.first_order_rows(down[:, :n], down[:, n:], lam, lam_dot)[0]
        ) / (2 * h)
        assert np.allclose(J[:, :, j], fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max()), j
