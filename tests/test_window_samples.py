"""The RMS window's samples follow the drive's and the response's harmonics, and the verdict's
figure draws the response by its own frequency (rotbeam.solve.steady.window_samples,
rotbeam.runs.scene.SceneResult.dense_series, rotbeam.report.verdict_plot)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotbeam.analysis.verdict import judge
from rotbeam.model.criterion import delta_rms, rms
from rotbeam.model.drive import profile_samples
from rotbeam.model.modes import resonance_frequency_hz
from rotbeam.model.params import Drive, Samples
from rotbeam.report.verdict_plot import largest_speed_text, plot_samples, verdict_figure
from rotbeam.runs.scene import build_scene, quasistatic_midspan, simulate
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.quasistatic import solve_static
from rotbeam.solve.spectral import highest_harmonic, trig_interpolate
from rotbeam.solve.steady import window_samples

#: the trapezoid of the tests: 0 -> 6 rad/s in a fifth of the period and back from phase 1/2
TOP, RAMP, F_D = 6.0, 0.2, 0.5


def trapezoid_csv(tmp_path, samples: int = 512) -> str:
    """One period of the trapezoid, sampled (the file a logged profile would be)."""
    phase, omega = profile_samples("trapezoid", 0.0, TOP, RAMP, samples)
    path = tmp_path / "trap.csv"
    path.write_text(
        "phase,omega\n" + "".join(f"{x!r},{w!r}\n" for x, w in zip(phase, omega, strict=True))
    )
    return path.name


def trapezoid_scene(tmp_path, harmonics: int = 256, **numerics):
    spec = {"drive": {"f_d": F_D, "profile": {"file": trapezoid_csv(tmp_path),
                                               "harmonics": harmonics}},
            "numerics": numerics}  # fmt: skip
    return build_scene(spec, tmp_path)


def exact_trapezoid_quasistatic_rms(model, T: float, nodes: int = 24) -> float:
    """RMS of y_m / L of the quasi-static response to the exact piecewise-linear trapezoid.

    Omega and dOmega/dt in closed form; the static equilibrium (rotbeam's Newton, no drive law,
    no sampling of the window) at Gauss-Legendre nodes of each of the four smooth pieces of the
    period (dOmega/dt jumps at the corners, so does the response).
    """
    x, w = np.polynomial.legendre.leggauss(nodes)
    pieces = [(0.0, RAMP, 1.0), (RAMP, 0.5, 0.0), (0.5, 0.5 + RAMP, -1.0), (0.5 + RAMP, 1.0, 0.0)]
    total, theta = 0.0, None
    for lo, hi, slope in pieces:
        for xi, wi in zip(x, w, strict=True):
            phase = lo + (hi - lo) * (xi + 1.0) / 2.0
            omega = TOP * min(max(phase / RAMP, 0.0), 1.0)
            omega -= TOP * min(max((phase - 0.5) / RAMP, 0.0), 1.0)
            omega_dot = slope * TOP / RAMP * F_D  # [rad/s^2]
            res = solve_static(model, omega * T, omega_dot * T * T, theta)
            assert res.converged
            theta = res.theta
            total += wi * (hi - lo) / 2.0 * float(model.midspan(theta)) ** 2
    return math.sqrt(total)


def test_highest_harmonic_of_a_known_sum():
    tau = np.arange(128) / 128 * 2 * math.pi
    X = np.stack([0.5 + np.sin(tau) + 1e-2 * np.cos(20 * tau), np.sin(tau + 0.3)], axis=1)
    assert highest_harmonic(X, 1e-3) == 20
    assert highest_harmonic(X, 1e-1) == 1
    assert highest_harmonic(np.ones((16, 3)), 1e-3) == 0


def test_trig_interpolate_counts_the_nyquist_cosine_once():
    """Eight samples of 1 + sin t + 0.3 cos 4t (4 = the Nyquist harmonic) on 64 instants."""
    coarse = np.arange(8) / 8 * 2 * math.pi
    fine = np.arange(64) / 64 * 2 * math.pi

    def f(t):
        return 1.0 + np.sin(t) + 0.3 * np.cos(4 * t)

    assert trig_interpolate(f(coarse), 64) == pytest.approx(f(fine), abs=1e-12)
    below = 1.0 + np.sin(fine) + 0.3 * np.cos(3 * fine)  # below the Nyquist harmonic of 8
    assert trig_interpolate(below, 8) == pytest.approx(below[::8], abs=1e-12)


def test_window_samples_follow_the_drive_harmonics(tmp_path):
    num = Numerics()
    sine = build_scene({"drive": {"omega0": 5.0, "f_d": 2.0}}).dimensionless
    assert window_samples(sine, num) == num.samples_per_period == 64
    high = build_scene({"drive": {"omega0": 20.0, "f_d": 1.0, "harmonics": [
        {"k": 1, "amplitude": 1.0}, {"k": 40, "amplitude": 0.01}]}}).dimensionless  # fmt: skip
    assert window_samples(high, num) == 256  # 4 x 40 = 160, rounded up to a power of two
    trapezoid = trapezoid_scene(tmp_path).dimensionless
    assert window_samples(trapezoid, num) == 1024  # harmonics up to 255 (odd ones)
    assert window_samples(trapezoid, Numerics(samples_per_period=4096)) == 4096


def test_trapezoid_quasistatic_rms_is_the_exact_trapezoids(tmp_path):
    """The 256-harmonic trapezoid's quasi-static RMS against the exact trapezoid's (closed-form
    Omega and dOmega/dt, Gauss nodes on each piece), and against 64 instants, which alias.

    The collocated orbit is reported as it is (integrate: false): time stepping the
    256-harmonic drive costs ~45 s at any N, and the quasi-static twin does not depend on it.
    """
    scene = trapezoid_scene(tmp_path, N=12, integrate=False)
    res = simulate(scene)
    assert res.dynamic.samples_per_period == 1024 and res.tau.size == 1024
    model = scene.model()
    exact = exact_trapezoid_quasistatic_rms(model, scene.beam.T)
    assert res.rms_quasistatic == pytest.approx(exact, rel=5e-3)
    sixty_four = rms(quasistatic_midspan(model, np.arange(64) / 64 * model.dl.period)[1])
    assert abs(sixty_four / exact - 1.0) > 0.02  # what 64 instants gave: the test can fail


def test_trapezoid_delta_rms_is_the_finer_windows(tmp_path):
    """Delta RMS of the default window against the same orbit and quasi-static twin sampled
    by hand at 512 and at 2048 instants (the dynamic RMS barely moves; the twin at 64 did)."""
    scene = trapezoid_scene(tmp_path, N=12, integrate=False)
    res = simulate(scene)
    model, orbit = scene.model(), res.dynamic.periodic
    P = model.dl.period

    def by_hand(m: int) -> float:
        y_dyn = model.midspan(trig_interpolate(orbit.theta, m))
        y_qs = quasistatic_midspan(model, np.arange(m) / m * P)[1]
        return delta_rms(rms(y_dyn), rms(y_qs))

    fine = by_hand(2048)
    assert res.delta_rms == pytest.approx(fine, abs=2e-3)
    assert by_hand(512) == pytest.approx(fine, abs=2e-3)
    assert abs(by_hand(64) - fine) > 5e-3  # what 64 instants gave: the test can fail


def test_verdict_plot_draws_32_points_per_first_mode_period():
    """A slow drive: the window's 64 instants a period are ~5 a vibration cycle; the figure
    draws at least 32, and passes through every computed sample."""
    scene = build_scene({"drive": {"omega0": 5.0, "f_d": 0.5}, "numerics": {"N": 8}})
    res = simulate(scene)
    assert res.converged and res.dynamic.samples_per_period == 64
    f1 = resonance_frequency_hz(scene.beam, scene.drive.omega_max)
    assert 64 * F_D / f1 < 6  # the window alone: under 6 points a vibration cycle
    fig = verdict_figure(res, judge(res))
    dyn, qs = fig.axes[0].lines[:2]
    t = dyn.get_xdata()
    periods_of_mode = res.scene.numerics.rms_periods / F_D * f1
    assert len(t) / periods_of_mode >= 32
    assert len(qs.get_xdata()) == len(t)
    step = plot_samples(res) // 64
    assert np.asarray(dyn.get_ydata())[::step] == pytest.approx(res.y_dynamic, abs=1e-12)
    assert np.asarray(qs.get_ydata())[::step] == pytest.approx(res.y_quasistatic, abs=1e-12)


def test_title_gives_the_profiles_own_largest_speed(tmp_path):
    """6 rad/s for the 6 rad/s trapezoid, and the 32-harmonic interpolant's overshoot beside
    it (its largest value from its own Fourier partial sum, evaluated here at 2^16 phases)."""
    phase, omega = profile_samples("trapezoid", 0.0, TOP, RAMP, 512)
    c = np.fft.rfft(omega) / 512
    c[1:] *= 2.0
    x = np.arange(2**16) / 2**16
    partial = c[0].real + sum((c[k] * np.exp(2j * math.pi * k * x)).real for k in range(1, 33))
    drive = Drive(f_d=F_D, profile=Samples(phase, omega, "profile", "trap.csv"))
    overshoot = float(np.max(partial))
    assert overshoot > TOP * 1.001  # the Gibbs overshoot shows at four digits
    assert largest_speed_text(drive) == (
        f"largest speed 6 rad/s ({overshoot:.4g} after the 32-harmonic interpolant)"
    )
    # a band-limited profile sampled at its peak: the samples' largest is the interpolant's
    x16 = np.arange(16) / 16
    sine = Samples(tuple(x16), tuple(3.0 + 3.0 * np.sin(2 * math.pi * x16)), "profile", "s.csv")
    assert largest_speed_text(Drive(f_d=1.0, profile=sine)) == "largest speed 6 rad/s"
