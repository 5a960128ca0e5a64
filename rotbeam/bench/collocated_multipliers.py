"""Multipliers from a collocation of the variational equation, against the exponential product:
what a monodromy condensed from a piecewise-polynomial collocation (AUTO's and BifurcationKit's
way) gives on the beam's orbits, and what it costs built from scratch.

    python3 -m rotbeam.bench.collocated_multipliers [intervals ...]

Each benchmark scene's orbit (N = 40, collocated at M = 17 instants, 65 at the resonant 5 rad/s,
7 Hz) is taken through one period of y' = J(t) y - r(t) by s = 4 point collocation on equal
intervals, Gauss-Legendre or Radau IIA; the product of the intervals' propagators is the
monodromy that a condensation of that collocation's Jacobian would give.  Its |mu|max and its
fixed-point offset (I - Phi)^-1 defect are compared with the exponential midpoint product at
3037 steps (docs/stability.md, "Multipliers from a collocation").
"""

from __future__ import annotations

import sys
import time

import numpy as np
import pandas as pd

from ..model.base import DiscreteModel
from ..model.elastica import DiscreteElastica
from ..model.params import Beam, Dimensionless, Drive
from ..solve.collocated_floquet import collocated_monodromy
from ..solve.floquet import beam_floquet, spectral_radius
from ..solve.periodic import solve_periodic
from .plan import SCENES

#: the exponential product the collocations are measured against (converged in the step count)
REFERENCE_STEPS = 3037
#: interval counts of the study
INTERVALS = (16, 32, 64, 128)


def _orbit(omega0: float, f_d: float, N: int) -> tuple[DiscreteModel, np.ndarray, np.ndarray]:
    """A benchmark scene's orbit: M = 65 at the resonant 5 rad/s, 7 Hz, else 17."""
    dl = Dimensionless.from_physical(Beam(), Drive(omega0=omega0, f_d=f_d))
    model = DiscreteElastica(dl, N)
    res = solve_periodic(model, 65 if (omega0, f_d) == (5.0, 7.0) else 17)
    if not res.converged:
        raise RuntimeError(f"the orbit at {omega0} rad/s, {f_d} Hz did not converge")
    return model, res.theta, res.theta_t


def collocated_study(intervals: tuple[int, ...] = INTERVALS, N: int = 40) -> pd.DataFrame:
    """One row per scene, kind and interval count: |mu|max, its error and the offset's against
    the exponential product at REFERENCE_STEPS, and the CPU seconds of the collocation.

    Parameters
    ----------
    intervals : tuple of int
        Interval counts.
    N : int
        Grid intervals of the beam.

    Returns
    -------
    pandas.DataFrame
        scene, M, kind, intervals, mu_max, mu_error, offset_error (relative, max-norm),
        seconds (the monodromy and its defect, from scratch).
    """
    rows = []
    for name, omega0, f_d in SCENES:
        model, theta, theta_t = _orbit(omega0, f_d, N)
        ref = beam_floquet(model, theta, theta_t, steps=REFERENCE_STEPS)
        dim = ref.monodromy.shape[0]
        w_ref = np.linalg.solve(np.eye(dim) - ref.monodromy, ref.defect)
        for kind in ("gauss", "radau"):
            for count in intervals:
                t0 = time.process_time()
                Phi, e = collocated_monodromy(model, theta, theta_t, count, kind)
                seconds = time.process_time() - t0
                mu = spectral_radius(Phi)
                w = np.linalg.solve(np.eye(dim) - Phi, e) if mu < 1.0 else np.full(dim, np.nan)
                off = float(np.max(np.abs(w - w_ref)) / np.max(np.abs(w_ref)))
                rows.append({"scene": name, "M": theta.shape[0], "kind": kind,
                             "intervals": count, "mu_max": mu, "mu_error": mu - ref.max_abs,
                             "offset_error": off, "seconds": seconds})  # fmt: skip
    return pd.DataFrame(rows)


def main(argv: list[str]) -> None:
    """Print the study as a Markdown table (interval counts from argv, INTERVALS by default)."""
    counts = tuple(int(a) for a in argv) or INTERVALS
    print(collocated_study(counts).to_markdown(index=False, floatfmt=".3g"))


if __name__ == "__main__":  # pragma: no cover - a command
    main(sys.argv[1:])
