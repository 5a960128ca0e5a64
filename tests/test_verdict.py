"""The engineer's answer for one scene (rotbeam.verdict, `rotbeam simulate --threshold --plot`):
the full model's verdict against an independent route (App. E's linear second-order estimate of
the boundary), the flip at the threshold, no verdict without a steady state; f_d* by root finding
against the root of a dense scan.  The CLI (`--threshold`, `--plot`, `rotbeam critical`) is
tested in test_cli.py."""

import math

import numpy as np
import pytest

from rotbeam.analysis.verdict import (
    NO_EULER_LOAD,
    critical,
    critical_start_hz,
    euler_loads,
    judge,
    linear_estimate,
)
from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.criterion import critical_from_scan
from rotbeam.model.modes import damping_ratio, resonance_frequency_hz
from rotbeam.model.params import Beam, Drive, Effects, Harmonic, Samples
from rotbeam.model.secondorder import (
    c0_root,
    delta_rms_canonical,
    delta_rms_harmonics,
    lag_root,
)
from rotbeam.runs.scene import Scene, build_scene, simulate
from rotbeam.runs.sweeps import scan_line
from rotbeam.solve.numerics import Numerics

NUM = Numerics(N=20)


def scene(omega0: float, f_d: float, beam: Beam | None = None) -> Scene:
    return Scene(beam or Beam(), Drive(omega0, 1.0, f_d), Effects(), NUM)


@pytest.mark.parametrize("omega0", [5.0, 50.0])
def test_verdict_agrees_with_the_linear_estimate_away_from_the_boundary(omega0):
    """App. E's oscillator (f_d* = c_0 f_0) and the full nonlinear beam are independent routes to
    the boundary; they differ by a few per cent near it (README), so at half and at twice the
    estimate the two must agree on the side."""
    probe = judge(simulate(scene(omega0, 1.0)))
    estimate = probe.fd_star_estimate_hz
    assert math.isfinite(estimate) and estimate == pytest.approx(probe.c0 * probe.f0_hz)
    below = judge(simulate(scene(omega0, 0.5 * estimate)))
    above = judge(simulate(scene(omega0, 2.0 * estimate)))
    assert below.quasistatic_ok is True and below.delta_rms < 0.10
    assert above.quasistatic_ok is False and above.delta_rms >= 0.10
    assert "good enough" in below.text and "inertia matters" in above.text


def test_verdict_flips_at_the_threshold():
    res = simulate(scene(5.0, 3.0))
    d = res.delta_rms
    assert judge(res, threshold=d * 1.01).quasistatic_ok is True
    assert judge(res, threshold=d * 0.99).quasistatic_ok is False
    # a larger threshold admits more: its linear boundary lies at a higher frequency
    assert judge(res, 0.2).fd_star_estimate_hz > judge(res, 0.05).fd_star_estimate_hz


def test_no_verdict_without_a_steady_state():
    res = simulate(scene(5.0, 2.0, Beam(gamma=0.0)))  # undamped: no steady state exists
    assert not res.converged
    v = judge(res)
    assert v.quasistatic_ok is None and v.text.startswith("no verdict")


def test_overdamped_beam_gets_the_lag_branch_estimate_and_a_verdict():
    """L = 0.1 mm, E = 1 GPa (Fig. 7 grid, zeta = 35.5): the oscillator never exceeds its static
    response by the threshold, so c_0 does not exist; the estimate comes from where it lags."""
    ref = Beam()
    h = 0.01 * 1e-4
    tiny = Beam(L=1e-4, h=h, b=ref.b / ref.h * h, E=1e9)
    v = judge(simulate(scene(5.0, 2.0, tiny)))
    assert math.isnan(v.c0)
    lag = lag_root(tiny.derived()["zeta"], 0.10) * v.f0_hz
    assert v.fd_star_estimate_hz == pytest.approx(lag, rel=1e-12) and "lags" in v.text
    assert v.quasistatic_ok is True  # 2 Hz against f_n = 14.9 kHz and f_d* near 97 Hz


# --- f_d* by root finding (rotbeam critical) ------------------------------------------------------


@pytest.mark.parametrize("omega0", [5.0, 50.0])
def test_critical_equals_the_root_of_a_dense_scan(omega0):
    """Root finding on the full model against the workflow's route: a 21-point scan and the root
    of its PCHIP interpolant (criterion.critical_from_scan)."""
    crit = critical(Scene(Beam(), Drive(omega0=omega0), numerics=NUM), rtol=1e-5)
    assert crit.found and len(crit.visited) <= 12, crit
    df = scan_line(Beam(), omega0, crit.f0_hz * np.linspace(0.2, 0.45, 21), numerics=NUM)
    scan = critical_from_scan(df["f_d"], df["delta_rms"], 0.10)
    assert scan["found"]
    assert crit.f_d_star == pytest.approx(scan["f_d_root"], rel=1e-3)
    # the linear estimate started it close: App. E within 2 % of the full model
    assert crit.estimate_hz == pytest.approx(crit.f_d_star, rel=0.02)


def test_lag_root_solves_the_overdamped_branch():
    """Where App. E's oscillator lags: 1 - sqrt((1 - c^2)^2 + (2 zeta c)^2) = -threshold."""
    for zeta in (0.5, 0.8, 2.0, 35.5):
        for th in (0.05, 0.1, 0.3):
            assert delta_rms_canonical(lag_root(zeta, th), zeta) == pytest.approx(-th, abs=1e-12)


def test_overdamped_critical():
    """The tiny Fig. 7 beam (zeta 35.5) has no App. E root; its boundary is where the dynamic
    response lags the static one by the threshold, and the full model brackets it there."""
    ref = Beam()
    h = 0.01 * 1e-4
    tiny = Beam(L=1e-4, h=h, b=ref.b / ref.h * h, E=1e9)
    crit = critical(Scene(tiny, Drive(omega0=5.0), numerics=NUM))
    assert crit.found
    assert crit.estimate_hz == pytest.approx(lag_root(tiny.derived()["zeta"], 0.1) * crit.f0_hz)
    assert crit.f_d_star == pytest.approx(crit.estimate_hz, rel=0.05)
    below = judge(simulate(scene(5.0, 0.8 * crit.f_d_star, tiny)))
    above = judge(simulate(scene(5.0, 1.25 * crit.f_d_star, tiny)))
    assert below.quasistatic_ok is True and above.quasistatic_ok is False


def test_critical_without_a_steady_state_says_so():
    crit = critical(Scene(Beam(gamma=0.0), Drive(omega0=5.0), numerics=NUM))
    assert not crit.found and math.isnan(crit.f_d_star)
    assert crit.message.startswith("no steady state")


# --- the linear estimate of f_d*: every harmonic of the drive through the damped first mode -------

ZETA = damping_ratio(Beam())  # the reference beam's, 0.0203


@pytest.mark.parametrize("k", [1, 3, 7])
@pytest.mark.parametrize("threshold", [0.05, 0.10, 0.30])
def test_one_harmonic_gives_app_e_c0_over_k(k, threshold):
    """A drive of one harmonic k loads the first mode at k f_d only: the scan and brentq land on
    App. E's closed-form c_0 / k to round-off."""
    drive = Drive(5.0, harmonics=(Harmonic(k, 0.8, 0.3),))
    ratio, note = linear_estimate(drive, ZETA, threshold)
    assert ratio == pytest.approx(c0_root(ZETA, threshold) / k, rel=1e-13, abs=0.0)
    assert note == (" = c_0 f_0" if k == 1 else f" = c_0 f_0 / {k}")


@pytest.mark.parametrize("k", [1, 3])
@pytest.mark.parametrize("zeta", [0.8, 35.5])
def test_one_harmonic_of_an_overdamped_beam_gives_the_lag_root_over_k(k, zeta):
    """Too damped for c_0: the lowest crossing of |Delta RMS| is the closed-form lag branch."""
    ratio, note = linear_estimate(Drive(5.0, harmonics=(Harmonic(k, 1.0, 0.0),)), zeta, 0.10)
    assert ratio == pytest.approx(lag_root(zeta, 0.10) / k, rel=1e-13, abs=0.0)
    assert "lags" in note


def test_the_sum_of_one_harmonic_is_app_e_and_bad_loads_are_refused():
    """One harmonic k = 1 through `delta_rms_harmonics` is App. E's closed form at every ratio;
    loads it cannot use are one-line input errors."""
    c = np.geomspace(0.01, 10.0, 400)
    for zeta in (0.0, 0.0203, 0.8):
        summed = delta_rms_harmonics(c, [1], [2.5], zeta)
        assert np.allclose(summed, delta_rms_canonical(c, zeta), rtol=1e-12, atol=1e-14)
    bad = [((), (), "non-empty"), ((1, 3), (1.0,), "one length"), ((0,), (1.0,), "> 0"),
           ((1, 2), (0.0, 0.0), "every load is 0")]  # fmt: skip
    for orders, loads, words in bad:
        with pytest.raises(RotbeamInputError, match=words):
            delta_rms_harmonics(0.3, orders, loads, 0.02)


def _brute_delta_rms(c: float, zeta: float, harmonics: tuple[Harmonic, ...]) -> float:
    """Delta RMS of u'' + 2 zeta u' + u = f(tau), f = sum_k k a_k cos(k c tau + phase_k) (the
    rate of Omega, in units of the first mode's period / 2 pi), by time integration: the
    periodic orbit from the monodromy matrix, then RMS of u and of its static response u = f
    over 2048 instants of one period.  No transfer function, no orthogonality of harmonics."""
    from scipy.integrate import solve_ivp

    period = 2.0 * math.pi / c

    def load(tau):
        return sum(h.k * h.amplitude * np.cos(h.k * c * tau + h.phase) for h in harmonics)

    def forced(tau, x):
        return [x[1], load(tau) - 2.0 * zeta * x[1] - x[0]]

    def free(tau, x):
        return [x[1], -2.0 * zeta * x[1] - x[0]]

    opts = {"method": "DOP853", "rtol": 1e-10, "atol": 1e-12}
    particular = solve_ivp(forced, (0.0, period), [0.0, 0.0], **opts).y[:, -1]
    monodromy = np.column_stack(
        [solve_ivp(free, (0.0, period), e, **opts).y[:, -1] for e in ([1.0, 0.0], [0.0, 1.0])]
    )
    x0 = np.linalg.solve(np.eye(2) - monodromy, particular)
    tau = np.linspace(0.0, period, 2048, endpoint=False)
    u = solve_ivp(forced, (0.0, period), x0, t_eval=tau, **opts).y[0]
    rms_dyn, rms_qs = np.sqrt(np.mean(u * u)), np.sqrt(np.mean(load(tau) ** 2))
    return abs(rms_dyn - rms_qs) / rms_dyn


@pytest.mark.parametrize(
    "harmonics",
    [
        (Harmonic(1, 1.0, 0.0), Harmonic(3, 0.5, 0.7)),  # README's: harmonic 3 leads
        (Harmonic(1, 1.0, 0.0), Harmonic(9, 0.05, 2.0)),  # a weak 9th rings at its resonance
    ],
    ids=["a1+a3", "a1+a9"],
)
def test_two_harmonics_against_a_time_integration_of_the_oscillator(harmonics):
    """The estimate is where the time-integrated oscillator's Delta RMS reaches 0.10, and below
    it (down to a fifth of it) Delta RMS stays under 0.10: the lowest crossing."""
    ratio, note = linear_estimate(Drive(20.0, harmonics=harmonics), ZETA, 0.10)
    assert "2 harmonics through the first mode" in note
    assert _brute_delta_rms(ratio, ZETA, harmonics) == pytest.approx(0.10, abs=1e-7)
    assert _brute_delta_rms(1.02 * ratio, ZETA, harmonics) > 0.10
    for factor in (0.2, 0.5, 0.8, 0.95, 0.99):
        assert _brute_delta_rms(factor * ratio, ZETA, harmonics) < 0.10


TRAPEZOID = {"shape": "trapezoid", "omega_min": 0.0, "omega_max": 6.0, "ramp": 0.2}
S_CURVE = {"shape": "s-curve", "omega_min": 0.0, "omega_max": 20.0, "ramp": 0.2}


@pytest.mark.parametrize(
    "profile, f_d",
    [  # the trapezoid: 8 full-model runs at 0.17-0.21 Hz, 10-23 s; the s-curve 9 runs, 3-6 s
        pytest.param(TRAPEZOID, 0.5, id="trapezoid", marks=pytest.mark.slow),
        pytest.param(S_CURVE, 1.0, id="s-curve"),
    ],
)
def test_the_estimate_lands_within_a_factor_2_of_critical(profile, f_d):
    """Profiles with corners ring the first mode through their high harmonics far below
    c_0 f_0: the summed estimate lies within a factor 2 of the full model's f_d*."""
    sc = build_scene({"drive": {"f_d": f_d, "profile": profile}, "numerics": {"N": 20}})
    crit = critical(sc)
    assert crit.found, crit.message
    assert crit.estimate_hz == critical_start_hz(sc)
    assert 0.5 < crit.estimate_hz / crit.f_d_star < 2.0
    f0 = resonance_frequency_hz(sc.beam, sc.drive.omega_max)
    assert crit.f_d_star < 0.5 * c0_root(ZETA, 0.10) * f0  # far below the sine's boundary


def _constant_profile(tmp_path) -> str:
    path = tmp_path / "constant.csv"  # 100 samples: the transform leaves ~1e-16 harmonics
    path.write_text("phase,omega\n" + "".join(f"{i / 100},5.3\n" for i in range(100)))
    return str(path)


def test_a_drive_without_an_euler_load_has_no_estimate(tmp_path):
    """A constant speed, as a sine of amplitude 0, a harmonic of amplitude 0 or a constant
    sampled profile: no Euler load, no f_d*; the verdict says so and `critical` refuses."""
    drives = [
        Drive(5.0, 0.0, 2.0),
        Drive(5.0, harmonics=(Harmonic(2, 0.0, 0.0),)),
        build_scene({"drive": {"f_d": 2.0, "profile": _constant_profile(tmp_path)}}).drive,
    ]
    for drive in drives:
        assert euler_loads(drive) == ((), ())
        ratio, note = linear_estimate(drive, ZETA, 0.10)
        assert math.isnan(ratio) and note == NO_EULER_LOAD
        with pytest.raises(RotbeamInputError, match="no Euler load"):
            critical_start_hz(Scene(Beam(), drive, numerics=NUM))
        with pytest.raises(RotbeamInputError, match="no Euler load"):
            critical(Scene(Beam(), drive, numerics=NUM))
    v = judge(simulate(Scene(Beam(), drives[0], Effects(), NUM)))
    assert math.isnan(v.fd_star_estimate_hz) and NO_EULER_LOAD in v.text
    assert "linear estimate" not in v.text


def test_a_move_has_no_estimate():
    t = tuple(0.3 * i / 10 for i in range(11))
    move = Samples(t, tuple(10.0 * math.sin(math.pi * ti / 0.3) ** 2 for ti in t), "move", "sin^2")
    with pytest.raises(RotbeamInputError, match="no repetition rate"):
        euler_loads(Drive(move=move))
