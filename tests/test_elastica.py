"""The discrete model against closed forms and finite differences."""

import numpy as np
import pytest
from conftest import elastica, numerical_first_order_jacobian

from rotbeam.model.grid import Grid
from rotbeam.model.params import Effects


@pytest.mark.parametrize("N", [5, 16, 40])
@pytest.mark.parametrize("hub", [0.0, 2.875])
def test_straight_beam_centrifugal_tension_closed_form(N, hub):
    """n_x(s) = lam^2 [r_o (1 - s) + (1 - s^2)/2] on the straight spinning beam (exact here:
    the load is linear in s, so the trapezoid sums of Q P integrate it exactly)."""
    lam = 1.7
    m = elastica(N, hub, 0.1)
    z = np.zeros(m.n)
    nx, ny = m.tension(z, z, z, lam, 0.0)
    s = m.grid.s[:-1]
    exact = lam**2 * (hub * (1 - s) + (1 - s**2) / 2)
    np.testing.assert_allclose(nx, exact, rtol=1e-13, atol=1e-13)
    np.testing.assert_array_equal(ny, 0.0)
    # the printed bracket 1 + (delta - 1) s - delta s^2 / 4 of Eq. (Disc_tension_x) differs
    delta = 1 / (1 + hub)
    printed = lam**2 / delta * (1 + (delta - 1) * s - delta * s**2 / 4)
    assert np.max(np.abs(printed - exact)) > 0.1


def test_straight_beam_is_an_equilibrium_without_euler_load():
    m = elastica(20, 2.875, 0.1)
    z = np.zeros(m.n)
    acc = m.acceleration(z, z, 3.0, 0.0)
    np.testing.assert_array_equal(acc, 0.0)


@pytest.mark.parametrize("coriolis", [False, True])
def test_first_order_jacobian_matches_finite_differences(coriolis):
    m = elastica(12, 2.875, 0.14, Effects(coriolis=coriolis))
    rng = np.random.default_rng(1)
    th, tt = 0.5 * rng.normal(size=m.n), rng.normal(size=m.n)
    J = m.first_order_jacobian(th, tt, 1.3, 0.7)
    Jn = numerical_first_order_jacobian(m, th, tt, 1.3, 0.7)
    np.testing.assert_allclose(J, Jn, rtol=1e-6, atol=1e-6 * np.abs(Jn).max())


@pytest.mark.parametrize("effects", [Effects(), Effects(coriolis=True, extension=True)])
def test_batched_first_order_rows_equal_the_per_instant_ones(effects):
    """`first_order_rows` at m instants at once (what the Floquet pass uses) gives the
    time stepper's per-instant `acceleration` to round-off, and rows taken one instant at a
    time the same Jacobians."""
    m = elastica(12, 2.875, 0.14, effects, 1e-2, 3.0)
    rng = np.random.default_rng(2)
    th, tt = 0.7 * rng.normal(size=(5, m.n)), rng.normal(size=(5, m.n))
    lam, lam_dot = rng.normal(size=5), rng.normal(size=5)
    F, J = m.first_order_rows(th, tt, lam, lam_dot)
    for k in range(5):
        Jk = m.first_order_rows(th[k : k + 1], tt[k : k + 1], lam[k : k + 1], lam_dot[k : k + 1])[
            1
        ][0]
        ak = m.acceleration(th[k], tt[k], lam[k], lam_dot[k])
        np.testing.assert_allclose(J[k], Jk, rtol=0, atol=1e-12 * np.abs(Jk).max())
        np.testing.assert_allclose(F[k], np.concatenate([tt[k], ak]), rtol=0,
                                   atol=1e-12 * np.abs(ak).max())  # fmt: skip


def test_mass_matrix_tends_to_symmetric_kernel():
    """W -> 1 - max(s, s') (the continuum kernel of int_s^1 int_0^s'' ds' ds'')."""
    for N in (20, 80):
        g = Grid.build(N)
        s = g.s[:-1]
        kernel = (1 - np.maximum.outer(s, s)) * g.ds
        err = np.abs(g.W - kernel).max() / g.ds
        assert err < 1.0 / N


def test_nonrotating_frequency_second_order():
    """First cantilever frequency beta_1^2 = 3.51602, error ~ N^-2."""
    import scipy.linalg as sla

    errs = []
    for N in (20, 40, 80):
        g = Grid.build(N)
        w = np.sqrt(np.sort(sla.eigvals(g.K, g.W).real)[0])
        errs.append(abs(w - 1.8751040687119611**2))
    order = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all((order > 1.8) & (order < 2.2)), order


@pytest.mark.parametrize("softening,euler", [(False, True), (True, True), (True, False)])
def test_load_torque_rows_equal_the_single_instant_forms(softening, euler):
    """Loads and their Jacobians at m instants at once equal those taken one instant at a time."""
    m = elastica(16, 2.875, 0.1, Effects(softening=softening, euler=euler))
    rng = np.random.default_rng(3)
    theta = rng.normal(scale=0.5, size=(7, m.n))
    lam, lam_dot = rng.normal(size=7), rng.normal(size=7)
    rows, jac = m.load_torque_rows(theta, lam, lam_dot, jacobian=True)
    np.testing.assert_array_equal(m.load_torque_rows(theta, lam, lam_dot), rows)
    for j in range(7):
        one, one_jac = m.load_torque_rows(
            theta[j : j + 1], lam[j : j + 1], lam_dot[j : j + 1], True
        )
        np.testing.assert_allclose(rows[j], one[0], atol=1e-14)
        np.testing.assert_allclose(jac[j], one_jac[0], atol=1e-13)
