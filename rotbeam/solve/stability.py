"""Stability of the steady state `steady_state` reports: the hooks it calls.

* `orbit_stability`: the Floquet multipliers of a converged collocated orbit, before any time
  stepping.  An unstable orbit is never the reported steady state.
* `leave_orbit`: the state time stepping starts from when the orbit is unstable: the orbit
  pushed along its most unstable Floquet direction, so that the stepper does not sit on the
  unstable orbit for as long as its slow growth would let it pass the transient check.
* `window_stability`: the multipliers of the orbit time stepping settled on (its samples).
* `stability_note`: the words the message gains.
"""

from __future__ import annotations

import numpy as np

from ..model.elastica import DiscreteElastica
from ..model.params import Dimensionless
from .floquet import FloquetResult, beam_floquet, sampled_beam_floquet
from .periodic import PeriodicResult

#: size of the push off an unstable orbit, relative to the response (max |Theta|)
LEAVE_FRACTION = 0.05

#: status of a SteadyState whose only periodic orbit found is unstable (no time stepping to
#: decide, numerics.integrate = False, or time stepping stayed on it)
STATUS_UNSTABLE = 2


def orbit_stability(
    model: DiscreteElastica, dl: Dimensionless, periodic: PeriodicResult | None
) -> FloquetResult | None:
    """Multipliers of the collocated orbit, None when there is no converged one."""
    if periodic is None or not periodic.converged:
        return None
    return beam_floquet(model, dl, periodic.theta, periodic.theta_t)


def leave_orbit(z: np.ndarray, fl: FloquetResult, size: float) -> np.ndarray:
    """z pushed by LEAVE_FRACTION * size along the leading Floquet vector (its real part)."""
    w, V = np.linalg.eig(fl.monodromy)
    v = np.real(V[:, int(np.argmax(np.abs(w)))])
    if not np.any(v):
        v = np.imag(V[:, int(np.argmax(np.abs(w)))])
    n = z.size // 2
    v = v / max(float(np.max(np.abs(v[:n]))), 1e-300)
    return z + LEAVE_FRACTION * max(size, 1e-12) * v


def window_stability(
    model: DiscreteElastica, dl: Dimensionless, theta_one_period: np.ndarray
) -> FloquetResult | None:
    """Multipliers of a time-stepped steady orbit from one period of its samples (n, m)."""
    if theta_one_period.ndim != 2 or theta_one_period.shape[1] < 8:
        return None
    return sampled_beam_floquet(model, dl, theta_one_period)


def stability_note(fl: FloquetResult | None) -> str:
    """'; Floquet |mu|max = ...' for the message, '' without multipliers."""
    if fl is None:
        return ""
    what = "" if fl.stable else f", {fl.crossing()} instability"
    return f"; Floquet {fl.describe()}{what}"
