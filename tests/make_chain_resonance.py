"""Rebuild tests/data/chain_resonance.csv: a resonance curve RMS(y_m)(f_d) of a beam whose E and
gamma differ from Table 1, computed with the independent rigid-link chain (tests/chain_model.py),
for the identification tests (tests/test_calibration.py).  Noise-free; the tests add noise.

    OPENBLAS_NUM_THREADS=1 PYTHONPATH=$PWD python3 tests/make_chain_resonance.py

Truth: Table 1 beam with E = 1.0 MPa, gamma = 0.05 N s/m^2 (R = 0.155 m); drive Omega_0 = 5
rad/s, a = 1 rad/s.  Chain of 20 links (first frequency 0.11 % below the continuum at 6 rad/s:
3.7221 against 3.7262), Radau at rtol 1e-6, atol 1e-8 (1e-8 costs 6x more CPU; the tests add
2 % noise) from the static state past exp(-eta tau / 2) < 1e-5, RMS over 4 periods of 64
samples.  8 points took 14-40 s CPU each (minutes of wall time on a shared machine), so the rows
are written as they finish.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

from chain_model import chain_steady_rms  # noqa: E402

from rotbeam.model.params import Beam, Dimensionless, Drive  # noqa: E402

TRUTH = {"E": 1.0e6, "gamma": 0.05}
OMEGA0, AMPLITUDE, N_LINKS = 5.0, 1.0, 20
F_D = [4.0, 5.0, 5.6, 5.9, 6.1, 6.3, 6.6, 7.5]
OUT = HERE / "data" / "chain_resonance.csv"


def main() -> None:
    beam = Beam(**TRUTH)
    OUT.parent.mkdir(exist_ok=True)
    part = OUT.with_suffix(".part")
    with part.open("w") as fh:
        fh.write(f"# chain model (tests/chain_model.py), n_links = {N_LINKS}; beam: Table 1 with "
                 f"E = {TRUTH['E']:g} Pa, gamma = {TRUTH['gamma']:g} N s/m^2, R = {beam.R:g} m; "
                 f"Omega_0 = {OMEGA0:g} rad/s, a = {AMPLITUDE:g} rad/s; made by "
                 f"tests/make_chain_resonance.py\n")  # fmt: skip
        fh.write("f_d,rms\n")
        for f_d in F_D:
            t0 = time.process_time()
            dl = Dimensionless.from_physical(beam, Drive(OMEGA0, AMPLITUDE, f_d))
            res = chain_steady_rms(dl.lam0, dl.alpha, dl.omega, beam.delta, dl.eta,
                                   n_links=N_LINKS, samples_per_period=64, rtol=1e-6,
                                   atol=1e-8)  # fmt: skip
            fh.write(f"{f_d:.6g},{res['rms']:.10g}\n")
            fh.flush()
            print(f"f_d = {f_d:g} Hz: rms {res['rms']:.6g} ({time.process_time() - t0:.0f} s CPU)",
                  flush=True)  # fmt: skip
    part.replace(OUT)


if __name__ == "__main__":
    main()
