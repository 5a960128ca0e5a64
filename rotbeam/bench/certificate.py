"""What the monodromy certificate saves: each benchmark scene solved with numerics.certify
"time" (one period of time stepping verifies the collocated orbit) and "monodromy" side by side,
in one process, with the CPU seconds, the certificate's offset estimate and whether the two RMS
values agree to the last digit.

    python3 -m rotbeam.bench.certificate [N]
"""

from __future__ import annotations

import sys
import time
from dataclasses import replace

import pandas as pd

from ..model.criterion import rms
from ..model.params import Beam, Dimensionless, Drive, Effects
from ..solve.numerics import Numerics
from ..solve.steady import steady_state
from .plan import SCENES


def certificate_costs(N: int = 40, scenes=SCENES) -> pd.DataFrame:
    """One row per scene: CPU seconds with each certificate, the monodromy's message, RMS."""
    rows = []
    for label, omega0, f_d in scenes:
        dl = Dimensionless.from_physical(Beam(), Drive(omega0=omega0, f_d=f_d), Effects())
        row = {"scene": label, "omega0": omega0, "f_d": f_d}
        for certify in ("time", "monodromy"):
            num = replace(Numerics(N=N), certify=certify)
            t0 = time.process_time()
            st = steady_state(dl, num)
            row[f"cpu_{certify}"] = time.process_time() - t0
            row[f"rms_{certify}"] = rms(st.y_m)
            row[f"periods_{certify}"] = st.periods
        row["message"] = st.message
        row["identical"] = row["rms_time"] == row["rms_monodromy"]
        rows.append(row)
    return pd.DataFrame(rows)


if __name__ == "__main__":  # pragma: no cover - a measurement, not a test
    N = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    df = certificate_costs(N)
    pd.set_option("display.width", 200, "display.max_colwidth", 120)
    print(df.drop(columns="message").to_string(index=False))
    for m in df["message"]:
        print(m)
