"""Dynamic steady state: convergence in N, the periodic solver, the reference beam's resonance."""

import numpy as np
import pytest
from conftest import steady, y_m
from scipy.integrate import solve_ivp

from rotbeam.model.criterion import rms
from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.grid import Grid
from rotbeam.model.modes import modes
from rotbeam.model.params import Beam, Dimensionless, Drive
from rotbeam.runs.scene import Scene, simulate
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.periodic import solve_periodic, solve_periodic_adaptive

BEAM = Beam()


def dl_of(omega0, f_d, amplitude=1.0, beam=BEAM):
    return Dimensionless.from_physical(beam, Drive(omega0, amplitude, f_d))


def test_rms_converges_in_N_with_second_order():
    """RMS(y_m) at Omega_0 = 5 rad/s, f_d = 2 Hz for N = 10, 20, 40, 80: measured order ~ 2."""
    dl = dl_of(5.0, 2.0)
    vals = []
    for N in (10, 20, 40, 80):
        res = solve_periodic(DiscreteElastica(dl, N), M=17)
        assert res.converged
        vals.append(rms(Grid.build(N).midspan(res.theta)))
    d = np.abs(np.diff(vals))
    order = np.log2(d[:-1] / d[1:])
    assert np.all((order > 1.7) & (order < 2.3)), (vals, order)


def test_periodic_state_is_a_fixed_point_of_the_period_map():
    dl = dl_of(10.0, 4.0)
    res = solve_periodic(DiscreteElastica(dl, 20), M=33)
    assert res.converged and res.harmonic_tail < 1e-6
    m = DiscreteElastica(dl, 20)
    n = m.n

    def rhs(t, z):
        a = m.acceleration(z[:n], z[n:], dl.lam(t), dl.lam_dot(t))
        return np.concatenate([z[n:], a])

    z0 = np.concatenate([res.theta[0], res.theta_t[0]])
    scale = np.abs(z0).max()
    atol = 1e-10 * scale * np.r_[np.ones(n), np.full(n, dl.omega)]
    sol = solve_ivp(
        rhs,
        (0, dl.period),
        z0,
        method="Radau",
        rtol=1e-10,
        atol=atol,
        jac=lambda t, z: m.first_order_jacobian(z[:n], z[n:], dl.lam(t), dl.lam_dot(t)),
    )
    assert sol.success
    drift = np.max(np.abs(sol.y[:, -1] - z0)) / np.max(np.abs(z0))
    assert drift < 1e-6


def test_periodic_start_agrees_with_long_integration():
    """Two routes to the steady state: collocation + verification, and a long time integration
    from the quasi-static state (from rest the excited grid modes make Radau crawl)."""
    dl = dl_of(5.0, 2.0)
    a = steady(dl, Numerics(N=20, start="periodic", ss_tol=1e-4))
    b = steady(dl, Numerics(N=20, start="quasistatic", ss_tol=1e-5))
    assert a.converged and b.converged
    assert b.periods > 3 * a.periods  # the transient from rest is long
    assert rms(y_m(dl, a)) == pytest.approx(rms(y_m(dl, b)), rel=2e-4)


def test_zero_amplitude_gives_zero_deflection():
    r = simulate(Scene(drive=Drive(20.0, 0.0, 5.0), numerics=Numerics(N=10)))
    assert r.rms_dynamic == 0.0 and r.rms_quasistatic == 0.0 and r.delta_rms == 0.0


def test_reference_beam_resonance_near_7_hz():
    """Fig. 3a: the resonance curve at Omega_0 = 5 rad/s peaks near f_d = 7 Hz (coarse)."""
    f0 = modes(BEAM, 5.0, 1, N=80)[0]
    assert 6.5 < f0 < 7.0
    fds = np.array([4.0, 5.5, 6.5, 7.0, 7.5, 8.5, 10.0])
    vals = []
    for fd in fds:
        res = solve_periodic_adaptive(DiscreteElastica(dl_of(5.0, fd), 20), tail_tol=1e-3)
        assert res.converged
        vals.append(rms(Grid.build(20).midspan(res.theta)))
    assert 6.5 <= fds[int(np.argmax(vals))] <= 7.5
    assert max(vals) > 4 * vals[0] and max(vals) > 4 * vals[-1]


def test_verified_orbit_is_reported_from_the_collocation():
    """A converged collocated orbit that one period of time stepping confirms is reported as the
    collocation's own trigonometric samples (not the stepper's), equal to a tight long run."""
    from rotbeam.solve.spectral import trig_interpolate

    dl = dl_of(5.0, 2.0)
    num = Numerics(N=20, ss_tol=1e-2, rtol=1e-2, tail_tol=1e-2, certify="time")
    a = steady(dl, num)
    assert a.converged and a.periods == 1 and "verified" in a.message
    samples = trig_interpolate(a.periodic.theta, num.samples_per_period)
    np.testing.assert_allclose(a.theta, samples, rtol=0, atol=1e-14)
    tight = steady(dl, Numerics(N=20, start="quasistatic", ss_tol=1e-6, rtol=1e-8))
    assert tight.converged
    assert rms(y_m(dl, a)) == pytest.approx(rms(y_m(dl, tight)), rel=1e-5)


@pytest.mark.slow
def test_verification_rejects_an_inaccurate_orbit(monkeypatch):
    """Near resonance (7 Hz) a collocation allowed a coarse harmonic tail (M = 17: 0.14 % off in
    RMS) fails the monodromy certificate at ss_tol 1e-5.  The run refines the orbit (M -> 2M - 1)
    until the certificate passes and lands on the resolved steady state, not on the coarse
    collocation; with no refinement allowed, the orbit fails the one-period check too and time
    stepping at the tight tolerance reaches the same state."""
    import rotbeam.solve.certify as certify

    dl = dl_of(5.0, 7.0)
    coarse = steady(dl, Numerics(N=20, integrate=False, tail_tol=0.05))
    assert coarse.periodic.M == 17
    num = Numerics(N=20, tail_tol=0.05, ss_tol=1e-5, rtol=1e-7)
    refined = steady(dl, num)
    assert refined.converged and refined.periods == 0 and refined.periodic.M > 17
    assert "certified by the monodromy" in refined.message
    monkeypatch.setattr(certify, "REFINE_M_MAX", 17)
    checked = steady(dl, num)
    assert checked.converged and checked.periods > 1 and "verified" not in checked.message
    assert checked.message.startswith("not certified by the monodromy")  # nor by its monodromy
    ref = steady(dl, Numerics(N=20, tail_tol=1e-8, integrate=False))
    assert ref.periodic.harmonic_tail < 1e-6
    err_coarse = abs(rms(y_m(dl, coarse)) - rms(y_m(dl, ref))) / rms(y_m(dl, ref))
    assert err_coarse > 5e-4  # the certificate had something to catch
    for state in (refined, checked):
        assert abs(rms(y_m(dl, state)) - rms(y_m(dl, ref))) / rms(y_m(dl, ref)) < 1e-4


def test_no_coarse_run_when_the_fine_grid_has_no_steady_state():
    """Richardson needs both grids' steady states: when grid N has none (here: from rest, given
    2 periods), the N / 2 run is skipped, and the result says so instead of extrapolating."""
    from rotbeam.runs.scene import build_scene

    num = {"N": 6, "start": "rest", "max_periods": 2, "extrapolate": True}
    res = simulate(build_scene({"drive": {"omega0": 5.0, "f_d": 2.0}, "numerics": num}))
    assert not res.converged
    assert res.extrapolation == {
        "N_coarse": 3,
        "extrapolated": False,
        "note": "not extrapolated: no steady state at N = 6 (N = 3 not run)",
    }
