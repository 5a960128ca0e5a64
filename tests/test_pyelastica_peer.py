"""rotbeam against a third-party Cosserat rod code (PyElastica, tests/peer_pyelastica.py).

Two scenes of the Table 1 beam: 5 rad/s, 2 Hz (clamp strain 0.013 %) and 60 rad/s, 9 Hz (1.9 %).
rotbeam: RMS(y_m)/L with `extension` off and on, as `rotbeam simulate` runs it (N = 40 with
Richardson from N = 20). The rod: n = 40 and 80, extrapolated to n -> oo (second order), started
on rotbeam's stretched orbit (so only the models' difference is transient) and stepped

- at 5 rad/s for 4 s (8 periods) before one RMS period (the transient beats, 1e-5 of RMS by then),
- at 60 rad/s for 24 periods (2.67 s); the rest is taken out with the decay rate every mode of the
  rod shares, sigma = gamma / (2 rho A) = 0.833 / s: r_oo = (r_2 - q r_1) / (1 - q),
  q = exp(-sigma (t_2 - t_1)), from the periods ending at 1.33 s and 2.67 s.

At 60 rad/s the rod also runs like for like (`LIKE_FOR_LIKE`: what rotbeam leaves out switched off
inside it) at n = 40 and 80, and must match rotbeam with `extension` on, not off.

Measured (`PYTHONPATH=$PWD python3 tests/test_pyelastica_peer.py`) and why the tolerances are
what they are: see the constants below.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("elastica")

sys.path.insert(0, str(Path(__file__).parent))
import peer_pyelastica as pe  # noqa: E402

from rotbeam.model.elastica import DiscreteElastica  # noqa: E402
from rotbeam.model.params import Beam  # noqa: E402
from rotbeam.runs.scene import build_scene, simulate  # noqa: E402

pytestmark = pytest.mark.slow

SCENES = {"slow": (5.0, 2.0), "fast": (60.0, 9.0)}
N_ROD = (40, 80)
#: the rod with what rotbeam leaves out switched off (docs/model.md, "Where the rod's gap at
#: 60 rad/s comes from"): rotbeam's couple B kappa, shear 10 times stiffer, no Coriolis force of
#: the rod's own motion in the disk's frame
LIKE_FOR_LIKE = {"matched": True, "shear_scale": 10.0, "coriolis": False}


def rotbeam_rms(omega0: float, f_d: float, extension: bool):
    """SceneResult of rotbeam simulate at N = 40 with Richardson (from N = 20)."""
    spec = {"drive": {"omega0": omega0, "f_d": f_d}, "effects": {"extension": extension},
            "numerics": {"N": 40, "extrapolate": True}}  # fmt: skip
    return simulate(build_scene(spec))


def orbit_start(beam: Beam, drive: pe.Drive, res):
    """start(rod): rotbeam's orbit (grid N, stretched) at the window's first sample, tau = k P."""
    scene = res.scene
    model = DiscreteElastica(scene.dimensionless, scene.numerics.N)
    th = res.dynamic.theta
    m = th.shape[0]
    s, x, y = model.grid.full_shape(th[0])
    _, xp, yp = model.grid.full_shape(th[1])
    _, xm, ym = model.grid.full_shape(th[-1])
    dt = 2.0 / (drive.f_d * m)  # central difference over two samples [s]
    return lambda rod: pe.start_from(rod, beam, drive, s, x, y, (xp - xm) / dt, (yp - ym) / dt)


def rod_rms(beam: Beam, name: str, n: int, res_on, **rod) -> float:
    """The rod's RMS(y_m)/L at scene `name`, started on rotbeam's orbit `res_on`; `rod` passes
    `matched`, `shear_scale` and `coriolis` to `pe.run`."""
    omega0, f_d = SCENES[name]
    drive = pe.Drive(omega0, f_d)
    start = orbit_start(beam, drive, res_on)
    if name == "slow":
        return pe.run(beam, drive, n, transient=4.0, start=start, **rod).rms
    periods = 24
    r = pe.run(beam, drive, n, transient=0.0, periods=periods, start=start, **rod)
    per = np.sqrt(np.mean(r.y_m.reshape(periods, -1) ** 2, axis=1))
    sigma = beam.gamma / (2 * beam.rho * beam.A)
    q = math.exp(-sigma * (periods // 2) / f_d)
    return float((per[-1] - q * per[periods // 2 - 1]) / (1 - q))


def measure() -> dict[str, dict[str, float]]:
    beam = Beam()
    out = {}
    for name, (omega0, f_d) in SCENES.items():
        off, on = rotbeam_rms(omega0, f_d, False), rotbeam_rms(omega0, f_d, True)
        rod = {n: rod_rms(beam, name, n, on) for n in N_ROD}
        n1, n2 = N_ROD
        q = (n2 / n1) ** 2
        row = {"rotbeam_off": off.rms_dynamic, "rotbeam_on": on.rms_dynamic,
               "rotbeam_on_N": on.extrapolation["rms_dynamic_N"]}  # fmt: skip
        row |= {f"rod_{n}": v for n, v in rod.items()}
        row["rod"] = (q * rod[n2] - rod[n1]) / (q - 1)
        row["rod_n_change"] = abs(rod[n2] / rod[n1] - 1)  # the extrapolation's error bound
        row["gap_off"] = row["rod"] / row["rotbeam_off"] - 1
        row["gap_on"] = row["rod"] / row["rotbeam_on"] - 1
        row["rotbeam_numerics"] = abs(row["rotbeam_on_N"] / row["rotbeam_on"] - 1)
        if name == "fast":  # the rod like for like (LIKE_FOR_LIKE): rotbeam's model in a rod
            like = {n: rod_rms(beam, name, n, on, **LIKE_FOR_LIKE) for n in N_ROD}
            row |= {f"like_{n}": v for n, v in like.items()}
            row["like_n_change"] = abs(like[n2] / like[n1] - 1)
            row["gap_like_on"] = like[n2] / row["rotbeam_on"] - 1
            row["gap_like_off"] = like[n2] / row["rotbeam_off"] - 1
        out[name] = row
    return out


@pytest.fixture(scope="module")
def measured():
    return measure()


# At 5 rad/s, 2 Hz (clamp strain 1e-4) the rod's gap is its shear: the tolerance is the sum of
# each difference's share, measured once by switching it off inside the rod (docs/model.md:
# shear x 10 -0.64 % plus the tenth it leaves, rotary inertia -0.02 %, couple -0.03 %, Coriolis
# -0.01 %) and the numerics measured here (the rod's n = 40 -> 80 change, rotbeam's N = 40 ->
# Richardson change).
SLOW_MODEL_SHARES = 0.0064 * 1.1 + 0.0002 + 0.0003 + 0.0001
# At 60 rad/s, 9 Hz the rod runs like for like (LIKE_FOR_LIKE) and what still differs is
# - shear: x 10 leaves a tenth of its share, 1.0-1.2 % of RMS (docs/model.md): 0.12 %;
# - rotary inertia, in the rod only: 0.01 % (x 2 in the rod moved RMS by +0.01 %);
# - the drive's modulation of the strain, which rotbeam freezes at the period mean: relative
#   2 a / Omega_0 = 3.3 % of a strain that moves RMS by 2.2 %: 0.07 %;
# - the rod's time step (PositionVerlet at dt_max(n, 10)): 0.07 % (RMS moved 3.3e-4 at n = 80
#   and 3.8e-4 at n = 40 from dt_max(n, 10) to 0.64 of it: 6.4e-4 at second order in dt);
# - numerics measured here: the rod's n = 40 -> 80 change (at n = 160 the rod is 0.03 % from
#   n = 80), rotbeam's N = 40 -> Richardson change.
FAST_LIKE_SHARES = 0.0012 + 0.0001 + 0.0007 + 0.0007
# Measured (CPU 60 s, `python3 tests/test_pyelastica_peer.py`): rotbeam off / on, rod (n -> oo):
#   5 rad/s, 2 Hz:  0.0106481 / 0.0106502, 0.0107239: gap +0.71 % off, +0.69 % on;
#   60 rad/s, 9 Hz: 0.0061254 / 0.0062543, 0.0064637: gap +5.52 % off, +3.35 % on;
#   like for like, n = 40 / 80: 0.0062466 / 0.0062602: gap +0.09 % on, +2.20 % off.


def test_stretching_closes_most_of_the_gap_at_60_rad_s(measured):
    fast = measured["fast"]
    assert fast["gap_off"] > 0 and abs(fast["gap_on"]) < 0.7 * abs(fast["gap_off"])


def test_rod_converged_in_n(measured):
    for row in measured.values():
        assert row["rod_n_change"] < 1e-3


def test_gap_at_5_rad_s_within_the_measured_model_differences(measured):
    slow = measured["slow"]
    tol = SLOW_MODEL_SHARES + slow["rod_n_change"] + slow["rotbeam_numerics"]
    assert abs(slow["gap_on"]) < tol


def test_rod_like_for_like_agrees_with_stretched_rotbeam_at_60_rad_s(measured):
    """With what rotbeam leaves out switched off in the rod, the rod at n = 80 matches rotbeam
    with `extension` on within the sum of what still differs, and not rotbeam without it."""
    fast = measured["fast"]
    tol = FAST_LIKE_SHARES + fast["like_n_change"] + fast["rotbeam_numerics"]
    assert abs(fast["gap_like_on"]) < tol
    assert fast["gap_like_off"] > tol


if __name__ == "__main__":
    import json
    import time

    t0 = time.process_time()
    print(json.dumps(measure(), indent=1))
    print(f"CPU {time.process_time() - t0:.1f} s")
