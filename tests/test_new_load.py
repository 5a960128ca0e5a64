"""Two new loads defined in this file alone, attached to a `DiscreteElastica` as parts, with no
change under rotbeam/: a steady uniform transverse load q (a body force `Load.forces`) and a
linear viscous drag on the transverse velocity (a rate-dependent term `Load.rows`).

Each part's blocks are checked against finite differences of its residual, and its physics
against a closed form: the static tip deflection of a cantilever under a uniform load,
q L^4 / (8 EI), at the grid's second order; the drag's decay of the first mode, which at small
amplitude is the viscous damping's (docs/model.md, "Loads as parts").
"""

from __future__ import annotations

import numpy as np
import pytest

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.loads import Load, default_parts
from rotbeam.model.params import Dimensionless, Effects
from rotbeam.model.rows import matvec_rows
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.steady import steady_state
from rotbeam.solve.stepping import compiled_cover

HUB = 2.875


class SteadyTransverseLoad(Load):
    """A uniform force q per unit mass across the radius, steady in the rotating frame (a steady
    aerodynamic pressure on the bare beam: q per unit length in units of EI/L^3)."""

    def __init__(self, q: float) -> None:
        self.q = q

    def forces(self, model, x, y, lam, lam_dot):
        """F_y = q at every node; constant, so no slopes."""
        return None, np.full_like(y, self.q)


class TransverseDrag(Load):
    """A linear viscous drag -c y_t per unit length of the beam, across the radius.

    F_y = -c y_t with y_t = P (cos Theta * Theta_t) enters the residual as the load torque
    -cos Theta * Q F_y = c cos Theta * W (cos Theta * Theta_t), W the beam's own (no payload).
    """

    def __init__(self, c: float) -> None:
        self.c = c

    def rows(self, model, theta, theta_t, lam, lam_dot, jacobian=False):
        """c C W C Theta_t and its blocks."""
        g = model.grid
        W = g.W if g.W_beam is None else g.W_beam
        cos, sin = np.cos(theta), np.sin(theta)
        u = (cos * theta_t) @ W.T  # W (cos Theta * Theta_t), shape (m, n)
        torque = self.c * cos * u
        if not jacobian:
            return torque, None, None
        d_rates = self.c * cos[:, :, None] * W[None] * cos[:, None, :]
        d_angles = -self.c * cos[:, :, None] * W[None] * (sin * theta_t)[:, None, :]
        idx = np.arange(model.n)
        d_angles[:, idx, idx] -= self.c * sin * u
        return torque, d_angles, d_rates


def _dl(lam0: float = 6.0, alpha: float = 2.0, omega: float = 1.3, **kw) -> Dimensionless:
    return Dimensionless(HUB, 0.2, lam0, alpha, omega, **kw)


def _state(n: int, m: int = 3, seed: int = 2):
    rng = np.random.default_rng(seed)
    th, tt, ta = (s * rng.standard_normal((m, n)) for s in (0.4, 1.0, 1.0))
    return th, tt, ta, 0.5 + rng.random(m), rng.standard_normal(m)


def _fd(f, x: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """d f / d x by central differences, row by row: shape (m, len(f), n)."""
    cols = []
    for k in range(x.shape[1]):
        e = np.zeros_like(x)
        e[:, k] = h
        cols.append((f(x + e) - f(x - e)) / (2 * h))
    return np.stack(cols, axis=2)


PARTS = {"uniform load": SteadyTransverseLoad(3.0), "drag": TransverseDrag(0.7)}


@pytest.mark.parametrize("payload", [False, True], ids=["bare", "payload"])
@pytest.mark.parametrize("name", list(PARTS))
def test_the_parts_blocks_are_its_residuals_derivatives(name, payload):
    """The part's own term (the model with it minus the model without) against finite
    differences of the same difference, in the angles and in the rates."""
    kw = {"tip_mass": 0.3, "tip_inertia": 0.01} if payload else {}
    bare = DiscreteElastica(_dl(effects=Effects(coriolis=True), **kw), 8)
    loaded = bare.with_parts(PARTS[name])
    th, tt, ta, lam, ld = _state(bare.n)

    def term(a, b):
        return loaded.residual_rows(a, b, ta, lam, ld).R - bare.residual_rows(a, b, ta, lam, ld).R

    assert np.max(np.abs(term(th, tt))) > 0.1  # the part adds a term that matters here
    with_part = loaded.residual_rows(th, tt, ta, lam, ld, True).blocks()
    without = bare.residual_rows(th, tt, ta, lam, ld, True).blocks()
    for k, fd in enumerate((_fd(lambda a: term(a, tt), th), _fd(lambda b: term(th, b), tt))):
        np.testing.assert_allclose(with_part[k] - without[k], fd, atol=1e-7)
    # the matrix-free product and the static residual carry the part too
    rows = loaded.residual_rows(th, tt, ta, lam, ld)
    p, q = np.ones_like(th), tt[::-1]
    direct = matvec_rows(with_part[0], p) + matvec_rows(with_part[1], q)
    np.testing.assert_allclose(rows.apply(p, q), direct, rtol=1e-12, atol=1e-12)
    zero = np.zeros_like(th)
    at_rest = loaded.residual_rows(th, zero, zero, lam, ld, True)
    R, J = loaded.static_rows(th, lam, ld, True)
    np.testing.assert_array_equal(R, at_rest.R)
    np.testing.assert_allclose(J, at_rest.blocks()[0], rtol=1e-14, atol=1e-12)


def _static(model: DiscreteElastica, lam: float = 0.0) -> np.ndarray:
    """Newton on the static residual with its exact Jacobian, from the straight beam."""
    theta = np.zeros((1, model.n))
    for _ in range(30):
        R, J = model.static_rows(theta, [lam], [0.0], True)
        step = np.linalg.solve(J[0], R[0])
        theta = theta - step
        if np.max(np.abs(step)) < 1e-15:
            break
    return theta[0]


def test_uniform_load_tip_deflection_converges_at_second_order_to_qL4_over_8EI():
    """A non-rotating cantilever under a small uniform load q (units of EI/L^3) deflects at the
    tip by q / 8 (q L^4 / (8 EI)); the grid's error falls by 4 per doubling of N.  At
    q = 1e-5 the large-deflection correction is O(q^2) relative, below 1e-9."""
    q = 1e-5
    dl = Dimensionless(HUB, 0.0, 0.0, 0.0, 1.0)  # at rest: lam = lam_dot = 0
    errors = []
    for N in (10, 20, 40, 80):
        model = DiscreteElastica(dl, N, parts=[SteadyTransverseLoad(q)])
        _, y_tip = model.grid.tip(_static(model))
        errors.append(float(y_tip) / q - 1.0 / 8.0)
    errors = np.array(errors)
    rates = errors[:-1] / errors[1:]
    assert np.all((rates > 3.8) & (rates < 4.2)), (errors, rates)
    assert abs(errors[-1]) * 8.0 < 2.0 / 80**2  # relative error O(1/N^2) (measured: -1 / N^2)


def test_drag_decays_the_first_mode_as_viscous_damping_at_rest():
    """On the straight beam y_t = P Theta_t, so the drag's linear damping is c W = c M(0):
    proportional to the mass, the first mode's modal damping coefficient is c exactly, as the
    scene's viscous damping eta = c gives."""
    c = 0.37
    dl = Dimensionless(HUB, c, 0.0, 0.0, 1.0, Effects.from_list("none"))
    drag = DiscreteElastica(dl, 16, parts=[TransverseDrag(c)])
    viscous = DiscreteElastica(dl, 16, parts=default_parts(Effects.from_list("damping")))
    w_drag, c_drag = drag.first_mode_decay(0.0)
    w_visc, c_visc = viscous.first_mode_decay(0.0)
    assert c_drag == pytest.approx(c, rel=1e-12)
    assert c_visc == pytest.approx(c, rel=1e-12)
    assert w_drag == pytest.approx(w_visc, rel=1e-12)
    assert drag.damped


def test_the_new_loads_run_through_the_steady_state():
    """The loaded beam at rest (no drive) with the drag as its only damping: the steady state
    (collocated, certified, time-stepped on the numpy path) is the static deflection, whose
    midspan is the cantilever's closed form 17 q L^4 / (384 EI) to the grid's error, O(1/N^2)
    relative (measured -1.18 / N^2 at N = 10-80 on this grid, so 1.5 / N^2 bounds it)."""
    q, N = 0.01, 20
    dl = Dimensionless(HUB, 0.0, 0.0, 0.0, 2.0)
    model = DiscreteElastica(dl, N, parts=[SteadyTransverseLoad(q), TransverseDrag(1.0)])
    reason = compiled_cover(model)
    assert "SteadyTransverseLoad" in reason and "\n" not in reason
    res = steady_state(model, Numerics(N=N))
    assert res.converged, res.message
    static = float(model.midspan(_static(model)))
    np.testing.assert_allclose(model.midspan(res.theta), static, rtol=1e-6)
    assert static == pytest.approx(17.0 * q / 384.0, rel=1.5 / N**2)


def test_at_keeps_the_attached_loads():
    model = DiscreteElastica(_dl(), 8).with_parts(SteadyTransverseLoad(1.0))
    other = model.at(_dl(lam0=2.0, effects=Effects.from_list("centrifugal,damping")))
    assert [p.name for p in other.parts] == ["Centrifugal", "Damping", "SteadyTransverseLoad"]
