"""Writes tests/data/elastica_inextensible.npz: the inextensible model's outputs on fixed random
states, computed by the code before the `extension` effect existed (run once with
PYTHONPATH at that commit, 642035f; tests/test_extension.py holds today's code to it bit for bit).
"""

from pathlib import Path

import numpy as np
from conftest import elastica

from rotbeam.model.params import Effects


def reference() -> dict[str, np.ndarray]:
    rng = np.random.default_rng(15)
    out = {}
    for tag, eff in (("paper", Effects()), ("coriolis", Effects(coriolis=True))):
        m = elastica(9, 2.875, 0.143, eff)
        th, tt = 0.6 * rng.normal(size=m.n), rng.normal(size=m.n)
        lam, ld = 1.7, -0.4
        out[f"{tag}_state"] = np.concatenate([th, tt])
        out[f"{tag}_acc"] = m.acceleration(th, tt, lam, ld)
        out[f"{tag}_jac"] = m.first_order_jacobian(th, tt, lam, ld)
        out[f"{tag}_static_jac"] = m.static_rows(th[None], [lam], [ld], jacobian=True)[1][0]
        out[f"{tag}_ym"] = np.atleast_1d(m.grid.midspan(th))
        out[f"{tag}_x"], out[f"{tag}_y"] = m.grid.positions(th)
    return out


if __name__ == "__main__":
    path = Path(__file__).parent / "data" / "elastica_inextensible.npz"
    np.savez(path, **reference())
    print(path)
