"""Quasi-static solvers: discrete Newton vs the continuum BVP vs linear closed forms."""

import numpy as np
import pytest
from conftest import elastica

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.params import Dimensionless, Effects
from rotbeam.model.static_bvp import solve_static_bvp
from rotbeam.solve import quasistatic
from rotbeam.solve.quasistatic import anderson_mix, quasistatic_series, shared_chord, solve_static


def linear_cantilever(s, hub, lam_dot):
    """y'''' = -lam_dot (r_o + s), clamped-free: uniform plus linearly increasing load."""
    uniform = (s**4 - 4 * s**3 + 6 * s**2) / 24
    linear = (s**5 - 10 * s**3 + 20 * s**2) / 120
    return -lam_dot * (hub * uniform + linear)


@pytest.mark.parametrize("lam_dot", [1e-6, 1e-3])
def test_small_euler_load_matches_linear_beam(lam_dot):
    hub = 2.875
    eff = Effects(centrifugal=False)
    errs = []
    for N in (20, 40, 80):
        m = elastica(N, hub, 0.0, eff)
        res = solve_static(m, 0.0, lam_dot)
        assert res.converged
        y = m.grid.midspan(res.theta)
        errs.append(abs(y / linear_cantilever(0.5, hub, lam_dot) - 1))
    assert errs[-1] < 2e-4
    assert errs[0] / errs[1] > 3.0 and errs[1] / errs[2] > 3.0  # second order
    bvp = solve_static_bvp(hub, 0.0, lam_dot, eff, tol=1e-10)
    assert bvp.success
    # geometric nonlinearity is O(theta^2) ~ lam_dot^2 relative
    rel = 1e-8 + lam_dot**2
    assert bvp.y_at(0.5) == pytest.approx(linear_cantilever(0.5, hub, lam_dot), rel=rel)


@pytest.mark.parametrize("lam, lam_dot", [(0.5, 0.3), (3.0, 20.0), (8.0, 40.0), (0.0, 12.0)])
def test_discrete_newton_agrees_with_bvp(lam, lam_dot):
    """Large deflections included: the two solvers share no code beyond the equations."""
    hub = 2.875
    bvp = solve_static_bvp(hub, lam, lam_dot, tol=1e-10)
    assert bvp.success, bvp.message
    ref_mid, ref_tip = bvp.y_at(0.5), bvp.y[-1]
    errs = []
    for N in (40, 80):
        m = elastica(N, hub, 0.0)
        res = solve_static(m, lam, lam_dot)
        assert res.converged, res.message
        _, y = m.grid.positions(res.theta)
        errs.append(max(abs(y[N // 2 - 1] / ref_mid - 1), abs(y[-1] / ref_tip - 1)))
    assert errs[1] < 1e-3
    assert errs[0] / errs[1] > 3.0


def test_quasistatic_series_is_periodic_and_continuous():
    dl = Dimensionless(hub_ratio=2.875, eta=0.14, lam0=2.0, alpha=0.5, omega=1.3)
    m = DiscreteElastica(dl, 20)
    taus = np.linspace(0, dl.period, 33)
    th = quasistatic_series(m, taus)
    np.testing.assert_allclose(th[0], th[-1], atol=1e-12)
    y = m.grid.midspan(th)
    assert np.all(np.isfinite(y)) and np.ptp(y) > 0


def test_zero_load_gives_zero_deflection():
    m = elastica(20, 2.875, 0.14)
    res = solve_static(m, 5.0, 0.0)
    assert res.converged
    np.testing.assert_array_equal(res.theta, 0.0)


@pytest.mark.parametrize(
    "omega0,f_d,a",
    [(5.0, 2.0, 1.0), (5.0, 2.0, 1.8), (5.0, 2.0, 5.0), (200.0, 20.0, 1.0), (5.0, 2.0, 50.0)],
)
def test_batched_static_equals_continuation(monkeypatch, omega0, f_d, a):
    """All instants in one batched Newton give the same quasi-static series as the robust path
    (sequential continuation in time), down to Newton's tolerance: small angles (chord Newton),
    just below its 0.1 rad limit (a = 1.8: 0.09 rad), across it and large (plain Newton)."""
    from rotbeam.runs.scene import build_scene
    from rotbeam.solve import quasistatic

    dl = build_scene({"drive": {"omega0": omega0, "f_d": f_d, "amplitude": a}}).dimensionless
    model = DiscreteElastica(dl, 30)
    taus = np.arange(32) / 32 * dl.period
    lam = np.array([dl.lam(t) for t in taus])
    lam_dot = np.array([dl.lam_dot(t) for t in taus])
    fast = quasistatic.batched_static(model, lam, lam_dot)
    assert fast is not None
    monkeypatch.setattr(quasistatic, "batched_static", lambda *args, **kw: None)
    slow = quasistatic.quasistatic_series(model, taus)
    np.testing.assert_allclose(fast, slow, rtol=0, atol=1e-12 * np.max(np.abs(slow)))


def test_anderson_mix_solves_linear_contractions_as_gmres_does():
    """x -> T x + c at three instants with their own 2 x 2 contractions (spectral radius 0.9,
    0.99 and 0.5, one of them non-normal): mixed with the two iterates before it (depth 2),
    each instant reaches its own fixed point (I - T)^-1 c to 1e-12 within 5 iterations, as
    GMRES does in two dimensions; the plain iteration is 0.99^5 of the way off at the slowest."""
    T = np.array([[[0.9, 0.0], [0.0, -0.3]], [[0.99, 0.5], [0.0, 0.2]], [[0.5, 0.0], [0.1, 0.5]]])
    c = np.array([[1.0, 2.0], [-1.0, 0.5], [3.0, 1.0]])
    fixed = np.linalg.solve(np.eye(2)[None] - T, c[..., None])[..., 0]
    x, history = np.zeros((3, 2)), []
    for _ in range(5):
        step = np.einsum("mij,mj->mi", T, x) + c - x
        history = [*history, (x + step, step)][-3:]
        x = anderson_mix(history)
    np.testing.assert_allclose(x, fixed, rtol=0, atol=1e-12 * np.max(np.abs(fixed)))
    plain = np.zeros((3, 2))
    for _ in range(5):
        plain = np.einsum("mij,mj->mi", T, plain) + c
    assert np.max(np.abs(plain - fixed)) > 1.0


@pytest.mark.parametrize("omega0, f_d, a", [(5.0, 7.0, 3.0), (5.0, 15.0, 3.0), (100.0, 5.0, 1.0)])
def test_accelerated_chord_meets_newton_in_fewer_residuals(monkeypatch, omega0, f_d, a):
    """The shared chord at 64 instants (N = 40) with its iterates mixed (`ANDERSON_DEPTH`)
    against the same chord unmixed (depth 0): the same equilibria as each instant's own Newton
    (`solve_static`) to 1e-11 of the largest angle, in fewer residuals of all instants
    (measured 7 against 14 at 5 rad/s, 7 Hz and 6 against 8 at 100 rad/s, 5 Hz); at 5 rad/s,
    15 Hz the unmixed chord stops after 3 as not contracting (handing over to the batched
    Newton), the mixed one converges in 8."""
    from rotbeam.runs.scene import build_scene

    dl = build_scene({"drive": {"omega0": omega0, "f_d": f_d, "amplitude": a}}).dimensionless
    model = DiscreteElastica(dl, 40)
    lam, lam_dot = model.drive_rows(np.arange(64) * dl.period / 64)
    newton = np.array([solve_static(model, lk, ldk).theta
                       for lk, ldk in zip(lam, lam_dot, strict=True)])  # fmt: skip
    calls = []

    def counted(*args, **kwargs):
        calls.append(1)
        return DiscreteElastica.static_rows(model, *args, **kwargs)

    monkeypatch.setattr(model, "static_rows", counted)
    counts = {}
    for depth in (0, quasistatic.ANDERSON_DEPTH):
        monkeypatch.setattr(quasistatic, "ANDERSON_DEPTH", depth)
        calls.clear()
        theta, converged = shared_chord(model, lam, lam_dot)
        counts[depth] = (len(calls), converged)
    assert converged
    np.testing.assert_allclose(theta, newton, rtol=0, atol=1e-11 * np.max(np.abs(newton)))
    plain, mixed = counts[0], counts[quasistatic.ANDERSON_DEPTH]
    assert mixed[0] < plain[0] or not plain[1]
