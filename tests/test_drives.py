"""Drives beyond the paper's sine: harmonics, a sampled period, a single move; each against an
independent answer (the sine itself, linear superposition, the quasi-static limit of a slow
move, the straight beam of a move without acceleration) and every bad input as one line."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotbeam.config.errors import RotbeamInputError
from rotbeam.model.params import Beam, Drive, Harmonic
from rotbeam.runs.move import simulate_move
from rotbeam.runs.scene import build_scene, simulate

N = {"N": 12}


def scene(drive: dict, numerics: dict = N):
    return build_scene({"drive": drive, "numerics": numerics})


def test_a_harmonic_of_zero_amplitude_changes_nothing():
    sine = simulate(scene({"omega0": 20.0, "f_d": 2.5, "amplitude": 1.0}))
    with_zero = simulate(scene({"omega0": 20.0, "f_d": 2.5, "harmonics": [
        {"k": 1, "amplitude": 1.0}, {"k": 3, "amplitude": 0.0, "phase": 0.7}]}))  # fmt: skip
    assert with_zero.rms_dynamic == sine.rms_dynamic
    assert with_zero.rms_quasistatic == sine.rms_quasistatic


def sine_profile(tmp_path, samples: int, omega0: float = 20.0, a: float = 1.0):
    phase = np.arange(samples) / samples
    path = tmp_path / f"sine{samples}.csv"
    np.savetxt(path, np.column_stack([phase, omega0 + a * np.sin(2 * np.pi * phase)]),
               delimiter=",", header="phase,omega", comments="")  # fmt: skip
    return path


def test_a_sampled_sine_is_the_sine_drive_to_the_interpolants_error(tmp_path):
    """The trigonometric interpolant of a sampled period is exact for a band-limited profile:
    16 samples of the sine give the sine drive's answer to round-off (1e-12)."""
    ref = simulate(scene({"omega0": 20.0, "f_d": 2.5}))
    res = simulate(scene({"f_d": 2.5, "profile": str(sine_profile(tmp_path, 16))}))
    assert res.rms_dynamic == pytest.approx(ref.rms_dynamic, rel=1e-12)
    assert res.rms_quasistatic == pytest.approx(ref.rms_quasistatic, rel=1e-12)


def test_unequal_sample_phases_are_resampled_by_a_periodic_spline(tmp_path):
    """48 samples of a sine at jittered phases: the spline's error (fourth order in the
    spacing, 2e-6 here) is what separates the answer from the sine drive's."""
    rng = np.random.default_rng(4)
    phase = np.sort((np.arange(48) + rng.uniform(-0.3, 0.3, 48)) / 48) % 1.0
    phase.sort()
    path = tmp_path / "jitter.csv"
    np.savetxt(path, np.column_stack([phase, 20.0 + np.sin(2 * np.pi * phase)]), delimiter=",",
               header="phase,omega", comments="")  # fmt: skip
    ref = simulate(scene({"omega0": 20.0, "f_d": 2.5}))
    res = simulate(scene({"f_d": 2.5, "profile": str(path)}))
    assert res.rms_dynamic == pytest.approx(ref.rms_dynamic, rel=1e-4)
    assert res.rms_dynamic != ref.rms_dynamic


def test_small_amplitude_responses_add_up():
    """At small amplitude the model is linear in the drive's swing: the response to two
    harmonics is the sum of the responses to each (same instants) up to a second-order rest,
    which falls in proportion to the amplitude (measured 2.3e-4 of the response at 1e-3 rad/s,
    2.3e-5 at 1e-4)."""

    def defect(a: float) -> float:
        a1, a3 = {"k": 1, "amplitude": a}, {"k": 3, "amplitude": a / 2, "phase": 0.7}
        runs = [simulate(scene({"omega0": 20.0, "f_d": 2.5, "harmonics": h}))
                for h in ([a1, a3], [a1], [a3])]  # fmt: skip
        both, one, three = (r.y_dynamic for r in runs)
        return float(np.max(np.abs(both - one - three)) / np.max(np.abs(both)))

    big, small = defect(1e-3), defect(1e-4)
    assert 9.0 < big / small < 11.0
    assert small < 1e-4


def move_file(tmp_path, duration: float, top: float = 10.0, samples: int = 101):
    t = np.linspace(0.0, duration, samples)
    path = tmp_path / f"move{duration:g}.csv"
    np.savetxt(path, np.column_stack([t, top * np.sin(np.pi * t / duration) ** 2]),
               delimiter=",", header="t,omega", comments="")  # fmt: skip
    return path


def test_a_slow_move_is_quasistatic(tmp_path):
    """A move 4 and 16 first-mode periods long (the sin^2 speed of the README), from rest: the
    residual vibration falls and the dynamic peak tends to the quasi-static one as the move
    slows, both like 1/duration or faster relative to the peak.  sin^2 starts and ends with a
    jump in jerk: the Euler load ramps up from zero with a slope ~ 1/duration^2, and a mode at
    rest under a ramp lags the static response by slope / omega^3, a share ~ 1/(omega
    duration) of the peak (measured: residual 0.23, 0.063; peak 0.28, 0.044)."""
    T1 = 1.0 / Beam().f_n
    out = []
    for periods in (4, 16):
        res = simulate_move(scene({"move": str(move_file(tmp_path, periods * T1)),
                                   "settle": 2 * T1}))  # fmt: skip
        assert res.converged
        out.append((res.residual_ym / res.peak_ym, abs(res.peak_ym / res.peak_ym_quasistatic - 1)))
    (r4, p4), (r16, p16) = out
    assert r16 < 0.3 * r4
    assert p16 < 0.3 * p4 and p16 < 0.05


def test_a_move_without_acceleration_has_no_euler_response(tmp_path):
    t = np.linspace(0.0, 0.5, 11)
    path = tmp_path / "constant.csv"
    np.savetxt(path, np.column_stack([t, np.full_like(t, 15.0)]), delimiter=",",
               header="t,omega", comments="")  # fmt: skip
    res = simulate_move(scene({"move": str(path), "settle": 0.1}))
    assert res.converged
    assert res.peak_ym == 0.0 and res.residual_ym == 0.0 and res.peak_ym_quasistatic == 0.0


def test_general_drive_groups_come_from_the_largest_speed_and_acceleration():
    """C_max and E_max of a two-harmonic drive: G max Omega^2 and G max |dOmega/dt| over the
    period, against a dense sampling of Omega(t) here."""
    sc = scene({"omega0": 20.0, "f_d": 2.5, "harmonics": [{"k": 1, "amplitude": 1.0},
                {"k": 3, "amplitude": 0.5, "phase": 0.7}]})  # fmt: skip
    t = np.linspace(0.0, 0.4, 200001)
    w = 20 + np.sin(2 * np.pi * 2.5 * t) + 0.5 * np.sin(2 * np.pi * 7.5 * t + 0.7)
    wd = 2 * np.pi * 2.5 * np.cos(2 * np.pi * 2.5 * t) + 0.5 * 2 * np.pi * 7.5 * np.cos(
        2 * np.pi * 7.5 * t + 0.7)  # fmt: skip
    s = simulate(sc).summary()
    G = sc.beam.G
    assert s["C_max"] == pytest.approx(G * np.max(w) ** 2, rel=1e-6)
    assert s["E_max"] == pytest.approx(G * np.max(np.abs(wd)), rel=1e-5)


def write(tmp_path, name: str, header: str, rows) -> str:
    path = tmp_path / name
    path.write_text(header + "\n" + "\n".join(",".join(str(v) for v in r) for r in rows) + "\n")
    return str(path)


@pytest.mark.parametrize(
    "kind, make, words",
    [
        (
            "not closed",
            lambda p: {
                "f_d": 1.0,
                "profile": write(
                    p, "open.csv", "phase,omega", [(k / 10, 10 + k) for k in range(10)]
                ),
            },
            ["does not close on itself", "jumps by 9"],
        ),  # fmt: skip
        (
            "few samples",
            lambda p: {
                "f_d": 1.0,
                "profile": write(p, "few.csv", "phase,omega", [(k / 5, 10) for k in range(5)]),
            },
            ["5 samples", "at least 8"],
        ),  # fmt: skip
        (
            "nan",
            lambda p: {
                "f_d": 1.0,
                "profile": write(
                    p,
                    "nan.csv",
                    "phase,omega",
                    [(k / 10, "nan" if k == 3 else 10) for k in range(10)],
                ),
            },
            ["sample 3", "finite"],
        ),  # fmt: skip
        (
            "time back",
            lambda p: {
                "move": write(
                    p,
                    "back.csv",
                    "t,omega",
                    [(t, 1.0) for t in (0, 0.1, 0.2, 0.15, 0.3, 0.4, 0.5, 0.6, 0.7)],
                )
            },
            ["t does not increase at sample 3", "0.2", "0.15"],
        ),  # fmt: skip
        (
            "text",
            lambda p: {"move": write(p, "text.csv", "t,omega", [(0, 1), (0.1, "x")])},
            ["line 3", "'x' is not a number"],
        ),  # fmt: skip
        (
            "column",
            lambda p: {"move": write(p, "col.csv", "time,omega", [(0, 1)])},
            ["no column t", "time, omega"],
        ),  # fmt: skip
        (
            "k zero",
            lambda p: {"omega0": 5.0, "harmonics": [{"k": 0, "amplitude": 1.0}]},
            ["drive.harmonics[0].k", "an integer >= 1", "got 0"],
        ),  # fmt: skip
        (
            "k twice",
            lambda p: {
                "omega0": 5.0,
                "harmonics": [{"k": 1, "amplitude": 1.0}, {"k": 1, "amplitude": 0.5}],
            },
            ["repeats a harmonic"],
        ),  # fmt: skip
        (
            "amplitude and harmonics",
            lambda p: {"omega0": 5.0, "amplitude": 1.0, "harmonics": [{"k": 1, "amplitude": 1.0}]},
            ["amplitude and harmonics"],
        ),  # fmt: skip
        (
            "ramp",
            lambda p: {
                "f_d": 1.0,
                "profile": {"shape": "trapezoid", "omega_min": 0, "omega_max": 10, "ramp": 0.7},
            },
            ["ramp = 0.7", "(0, 0.5]"],
        ),  # fmt: skip
    ],
)
def test_bad_drive_is_one_line_naming_it(tmp_path, kind, make, words):
    with pytest.raises(RotbeamInputError) as err:
        scene(make(tmp_path))
    text = str(err.value)
    assert "\n" not in text
    for w in words:
        assert w in text, (w, text)


def test_negative_payload_is_one_line():
    with pytest.raises(RotbeamInputError, match=r"beam.tip_mass must be >= 0, got -0.001"):
        build_scene({"beam": {"tip_mass": -0.001}, "drive": {"omega0": 5, "f_d": 2}})


def test_cli_move_json_has_the_move_keys(tmp_path):
    import json
    import subprocess
    import sys

    T1 = 1.0 / Beam().f_n
    path = move_file(tmp_path, 2 * T1)
    p = subprocess.run([sys.executable, "-m", "rotbeam", "simulate", "--move", str(path),
                        "--settle", str(T1), "--N", "8", "--json"],
                       capture_output=True, text=True, timeout=300)  # fmt: skip
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    for key in ("peak_ym", "peak_ym_quasistatic", "rms_dynamic", "rms_quasistatic", "delta_rms",
                "residual_ym", "settling_time_s", "verdict"):  # fmt: skip
        assert key in out and out[key] is not None
    assert math.isfinite(out["peak_ym"]) and out["peak_ym"] > 0


def test_disk_angle_is_the_integral_of_the_speed(tmp_path):
    """Drive.angle: for the sine, phi = Omega_0 t + a (1 - cos 2 pi f_d t) / (2 pi f_d) (its
    closed form); for two harmonics and a sampled profile, the trapezoid rule of Omega over a
    fine grid (a second quadrature)."""
    sine = Drive(omega0=5.0, amplitude=1.0, f_d=2.0)
    t = 0.37
    w = 2 * math.pi * 2.0
    assert sine.angle(t) == pytest.approx(5.0 * t + (1 - math.cos(w * t)) / w, rel=1e-14)
    two = Drive(omega0=20.0, f_d=2.5, harmonics=(Harmonic(1, 1.0, 0.0), Harmonic(3, 0.5, 0.7)))
    profile = build_scene(
        {
            "drive": {
                "f_d": 1.0,
                "profile": {"shape": "trapezoid", "omega_min": 0.0, "omega_max": 20.0, "ramp": 0.2},
            }
        }
    ).drive
    ts = np.linspace(0.0, 1.3, 20001)
    for drive in (two, profile):
        trapezoid = np.trapezoid([drive.omega(x) for x in ts], ts)
        assert drive.angle(1.3) == pytest.approx(trapezoid, rel=1e-7)


def test_scene_files_names_the_csv_files_a_scene_reads():
    """The workflow's user_scenes inputs: a sampled profile (plain or {file, harmonics}) and a
    move; a named shape, a sine or a malformed spec read none."""
    from rotbeam.runs.scene import scene_files

    assert scene_files({"drive": {"profile": "p.csv", "move": "m.csv"}}) == ["p.csv", "m.csv"]
    assert scene_files({"drive": {"profile": {"file": "q.csv", "harmonics": 5}}}) == ["q.csv"]
    assert scene_files({"drive": {"profile": {"shape": "s-curve"}}}) == []
    assert scene_files({"drive": {"omega0": 5}}) == [] and scene_files({"drive": 3}) == []


def chain_move_peak(beam: Beam, duration: float, top: float, n_links: int) -> float:
    """The largest |y_m| / L during the sin^2 move Omega = top sin^2(pi t / duration) of the
    rigid-link chain (tests/chain_model.py), started at rest in the straight state, with the
    exact law (no spline)."""
    from chain_model import ChainModel
    from scipy.integrate import solve_ivp

    T = beam.T
    chain = ChainModel(n_links, beam.delta, eta=beam.eta)
    w, d = top * T, duration / T

    def loads(tau: float) -> tuple[float, float]:
        x = math.pi * tau / d
        return w * math.sin(x) ** 2, w * math.pi / d * math.sin(2 * x)

    n = n_links
    tau = np.linspace(0.0, d, 801)
    sol = solve_ivp(lambda t, z: chain.rhs(z, *loads(t)), (0.0, d), np.zeros(2 * n),
                    method="Radau", jac=lambda t, z: chain.jac(z, *loads(t)), rtol=1e-7,
                    atol=1e-9, t_eval=tau)  # fmt: skip
    assert sol.success
    y_m = np.array([chain.nodes(phi)[1][n // 2] for phi in sol.y[:n].T])
    return float(np.max(np.abs(y_m)))


def test_a_move_starts_at_rest_as_the_chain_model_does(tmp_path):
    """README's sin^2 move (10 rad/s, 0.3 s): the beam at rest before the move.  Its peak |y_m|
    during the move, Richardson-extrapolated from N = 10 and 20, against the rigid-link chain
    (an independent discretisation, second order too) started at rest, extrapolated from 10 and
    20 links: 0.1 % apart (measured 0.003 %; the pairs themselves are 1.2 % and 0.7 % apart).
    Started in the quasi-static state and rate of the first sample (`move_start: quasistatic`)
    the peak is 17 % lower: the test fails if a move starts moving."""
    path = move_file(tmp_path, 0.3, samples=301)

    def peak(N: int, **drive) -> float:
        res = simulate_move(scene({"move": str(path), "settle": 0.01, **drive}, {"N": N}))
        assert res.converged
        return res.peak_ym

    coarse, fine = peak(10), peak(20)
    ours = (4 * fine - coarse) / 3
    chain = [chain_move_peak(Beam(), 0.3, 10.0, n) for n in (10, 20)]
    ref = (4 * chain[1] - chain[0]) / 3
    assert ours == pytest.approx(ref, rel=1e-3)
    assert peak(20, move_start="quasistatic") < 0.9 * fine


def test_a_move_from_a_steady_speed_starts_straight(tmp_path):
    """A move from 20 to 30 rad/s: before it the disk turns steadily at 20 rad/s, the radially
    clamped beam is straight (the centrifugal load alone bends it nowhere), so y_m = 0 and its
    rate 0 at t = 0; the Euler load then bends it, y_m of the sign of -dOmega/dt (Eq. ForceE)."""
    t = np.linspace(0.0, 0.4, 81)
    path = tmp_path / "up.csv"
    np.savetxt(path, np.column_stack([t, 20 + 10 * np.sin(np.pi * t / 0.8) ** 2]),
               delimiter=",", header="t,omega", comments="")  # fmt: skip
    res = simulate_move(scene({"move": str(path), "settle": 0.01}))
    assert res.y_dynamic[0] == 0.0
    assert abs(res.y_dynamic[1]) < 1e-3 * res.peak_ym  # zero rate: y_m grows like t^2 at first
    assert np.sign(res.y_dynamic[len(res.y_dynamic) // 4]) == -np.sign(res.omega[-1] - 20)


@pytest.mark.parametrize("beam", [{}, {"tip_mass": 4.68e-4, "tip_inertia": 1e-8}],
                         ids=["bare", "payload"])  # fmt: skip
def test_compiled_move_runs_are_the_numpy_models_stepped_by_radau(beam, monkeypatch):
    """A slew on the modal model (2 modes) goes by the compiled DOP853 march, on the full model
    by Radau with the compiled right-hand side (`rotbeam.runs.move._compiled_suits`).  With the
    kernels refused (the numpy models, Radau): the full model at the same rtol gives the same
    residual and peak to 1e-9 L and every sample to 1e-7 L (the right-hand sides differ by
    round-off, which Radau's steps carry to 8e-9 L by the end), the modal model at rtol 1e-8
    the same within 1e-6 L of the march's (measured: 1e-7)."""
    from rotbeam.analysis.motion import Limits, rigid_slew
    from rotbeam.analysis.move_check import check_move
    from rotbeam.model.elastica import DiscreteElastica
    from rotbeam.model.modal import ModalModel
    from rotbeam.runs import move

    motion = rigid_slew(1.0, Limits(10.0, 100.0, 4000.0))

    def run(model: str, **numerics):
        sc = build_scene({"beam": beam, "numerics": {"N": 12, "model": model, "modes": 2,
                                                     "rtol": 1e-5, **numerics}})  # fmt: skip
        return sc, check_move(sc, motion, 8.0, "y_m", 0.25)

    runs = {}
    for model in ("elastica", "modal"):
        sc, runs[model] = run(model)
        chosen = move._compiled_suits(sc.model(), 1.0 / (move.PER_PERIOD * 8.0) / sc.beam.T)
        assert chosen == (model == "modal")
    for cls in (DiscreteElastica, ModalModel):
        monkeypatch.setattr(cls, "kernel", lambda self, tangent=True: (None, "off"))
    cases = (("elastica", 1e-9, 1e-7, {}), ("modal", 1e-6, 1e-6, {"rtol": 1e-8}))
    for model, tol, series_tol, numerics in cases:
        got, ref = runs[model], run(model, **numerics)[1]
        assert ref.converged and got.converged
        assert ref.residual > 1e-3  # the move rings: the comparison is not of zeros
        assert abs(got.residual - ref.residual) < tol, model
        assert abs(got.peak - ref.peak) < tol, model
        np.testing.assert_array_equal(got.t_s, ref.t_s)  # the same instants, the same series
        np.testing.assert_allclose(got.values, ref.values, rtol=0, atol=series_tol,
                                   err_msg=model)  # fmt: skip


def test_the_drive_at_many_instants_is_its_closed_form(tmp_path):
    """`DriveLaw.rows` (what the collocation and the Floquet passes read, summed as arrays for a
    sum of harmonics) against lam = Omega T and its derivative written out for two harmonics,
    at instants over several periods, and against the instant-by-instant law for a move."""
    T, f_d = 0.05, 2.5
    two = Drive(omega0=20.0, f_d=f_d, harmonics=(Harmonic(1, 1.0, 0.0), Harmonic(3, 0.5, 0.7)))
    tau = np.linspace(-0.3, 7.0, 401) / (f_d * T)
    lam, lam_dot = two.law(T).rows(tau)
    w = 2 * math.pi * f_d * T
    expected = T * (20.0 + np.sin(w * tau) + 0.5 * np.sin(3 * w * tau + 0.7))
    expected_dot = T * (w * np.cos(w * tau) + 1.5 * w * np.cos(3 * w * tau + 0.7))
    assert np.max(np.abs(lam - expected)) <= 1e-14 * np.max(np.abs(expected))
    assert np.max(np.abs(lam_dot - expected_dot)) <= 1e-13 * np.max(np.abs(expected_dot))
    move = scene({"move": str(move_file(tmp_path, 0.5))})
    law = move.drive.law(T)
    tau = np.linspace(0.0, 0.6 / T, 37)
    lam, lam_dot = law.rows(tau)
    assert np.array_equal(lam, [law.lam(t) for t in tau])
    assert np.array_equal(lam_dot, [law.lam_dot(t) for t in tau])
