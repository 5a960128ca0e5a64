"""rotbeam against a third-party Cosserat rod code (PyElastica, tests/peer_pyelastica.py).

Two scenes of the Table 1 beam: 5 rad/s, 2 Hz (clamp strain 0.013 %) and 60 rad/s, 9 Hz (1.9 %).
rotbeam: RMS(y_m)/L with `extension` off and on, as `rotbeam simulate` runs it (N = 40 with
Richardson from N = 20). The rod: n = 40 and 80, extrapolated to n -> oo (second order), started
on rotbeam's stretched orbit (so only the models' difference is transient) and stepped

- at 5 rad/s for 4 s (8 periods) before one RMS period (the transient beats, 1e-5 of RMS by then),
- at 60 rad/s for 24 periods (2.67 s); the rest is taken out with the decay rate every mode of the
  rod shares, sigma = gamma / (2 rho A) = 0.833 / s: r_oo = (r_2 - q r_1) / (1 - q),
  q = exp(-sigma (t_2 - t_1)), from the periods ending at 1.33 s and 2.67 s.

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
from rotbeam.simulate.scene import build_scene, simulate  # noqa: E402

pytestmark = pytest.mark.slow

SCENES = {"slow": (5.0, 2.0), "fast": (60.0, 9.0)}
N_ROD = (40, 80)


def rotbeam_rms(omega0: float, f_d: float, extension: bool):
    """SceneResult of rotbeam simulate at N = 40 with Richardson (from N = 20)."""
    spec = {"drive": {"omega0": omega0, "f_d": f_d}, "effects": {"extension": extension},
            "numerics": {"N": 40, "extrapolate": True}}  # fmt: skip
    return simulate(build_scene(spec))


def orbit_start(beam: Beam, drive: pe.Drive, res):
    """start(rod): rotbeam's orbit (grid N, stretched) at the window's first sample, tau = k P."""
    scene = res.scene
    model = DiscreteElastica.from_dimensionless(scene.dimensionless, scene.numerics.N)
    th = res.dynamic.theta
    m = th.shape[1]
    s, x, y = model.grid.full_shape(th[:, 0])
    _, xp, yp = model.grid.full_shape(th[:, 1])
    _, xm, ym = model.grid.full_shape(th[:, -1])
    dt = 2.0 / (drive.f_d * m)  # central difference over two samples [s]
    return lambda rod: pe.start_from(rod, beam, drive, s, x, y, (xp - xm) / dt, (yp - ym) / dt)


def rod_rms(beam: Beam, name: str, n: int, res_on, matched: bool = False) -> float:
    omega0, f_d = SCENES[name]
    drive = pe.Drive(omega0, f_d)
    start = orbit_start(beam, drive, res_on)
    if name == "slow":
        return pe.run(beam, drive, n, transient=4.0, start=start, matched=matched).rms
    periods = 24
    r = pe.run(beam, drive, n, transient=0.0, periods=periods, start=start, matched=matched)
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
        if name == "fast":  # the rod with rotbeam's couple convention (B kappa, not / e^3)
            row["rod_matched_40"] = rod_rms(beam, name, 40, on, matched=True)
            row["gap_on_matched_40"] = row["rod_matched_40"] / row["rotbeam_on"] - 1
        out[name] = row
    return out


@pytest.fixture(scope="module")
def measured():
    return measure()


# The tolerance on the gap with stretching on is the sum of what is known to differ, each measured
# or estimated, so a gap beyond it is a difference nobody has explained:
# - shear and rotary inertia (Timoshenko, first mode; docs/model.md "Axial stretching"): +0.45 %
#   of RMS at 5 rad/s, 2 Hz and +0.08 % at 60 rad/s, 9 Hz;
# - the rod's couple B kappa / e^3 against rotbeam's B kappa: 0.77 % at 60 rad/s, 9 Hz (measured
#   here: rod_matched_40 against rod_40), 0 at 5 rad/s (strain 1e-4);
# - numerics, measured here: the rod's n = 40 -> 80 change bounds its extrapolation (4.3e-4 and
#   9e-5), the transient 2e-5, rotbeam's N = 40 -> Richardson change bounds its own (7.8e-4 and
#   2.4e-3).
# Measured (CPU 73 s, `python3 tests/test_pyelastica_peer.py`): rotbeam off / on, rod (n -> oo):
#   5 rad/s, 2 Hz:  0.0106481 / 0.0106502, 0.0107239: gap +0.71 % off, +0.69 % on;
#   60 rad/s, 9 Hz: 0.0061254 / 0.0062543, 0.0064637: gap +5.52 % off, +3.35 % on
#   (+2.54 % with the couple matched, n = 40).
TOL_SLOW = 0.0045 + 0.0005 + 0.0008  #: |gap with stretching on| at 5 rad/s, 2 Hz
TOL_FAST = 0.0008 + 0.0077 + 0.0001 + 0.0024  #: |gap with stretching on| at 60 rad/s, 9 Hz


def test_stretching_closes_most_of_the_gap_at_60_rad_s(measured):
    fast = measured["fast"]
    assert fast["gap_off"] > 0 and abs(fast["gap_on"]) < 0.7 * abs(fast["gap_off"])
    # the couple convention is part of it: matching rotbeam's B kappa closes more of the gap
    assert 0 < fast["gap_on_matched_40"] < fast["gap_on"]


def test_rod_converged_in_n(measured):
    for row in measured.values():
        assert row["rod_n_change"] < 1e-3


@pytest.mark.xfail(
    strict=True,
    reason="the sum below omits what a one-off diagnostic measured inside the rod (docs/model.md): "
    "the Coriolis coupling of bending and stretching (1.1 % of RMS at 60 rad/s) and shear beyond "
    "its first-order estimate (0.9-1.2 %); a like-for-like test (the rod with those switched off) "
    "is to replace it; strict, so that a change of the gap shows",
)
def test_gap_with_stretching_within_known_model_differences(measured):
    assert abs(measured["slow"]["gap_on"]) < TOL_SLOW
    assert abs(measured["fast"]["gap_on"]) < TOL_FAST


if __name__ == "__main__":
    import json
    import time

    t0 = time.process_time()
    print(json.dumps(measure(), indent=1))
    print(f"CPU {time.process_time() - t0:.1f} s")
