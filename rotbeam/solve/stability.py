"""Stability of the steady state `steady_state` reports: the hooks it calls.

* `orbit_stability`: the Floquet multipliers of a converged collocated orbit, before any time
  stepping.  An unstable orbit is never the reported steady state.
* `leave_orbit`: the state time stepping starts from when the orbit is unstable: the orbit
  pushed along its most unstable Floquet direction, so that the stepper does not sit on the
  unstable orbit for as long as its slow growth would let it pass the transient check.
* `window_stability`: the multipliers of the orbit time stepping settled on (its samples).
* `monodromy_certificate`: whether an attracting collocated orbit is accepted without time
  stepping: its distance to the true periodic state, from its one-period defect and the
  monodromy, is below the steady-state tolerance with a safety factor.
* `stability_note`: the words the message gains.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model.base import DiscreteModel
from .floquet import (
    SPREAD_TOL,
    STEP_LADDER,
    FloquetResult,
    beam_floquet,
    sampled_beam_floquet,
)
from .periodic import PeriodicResult

#: the monodromy certificate asks the estimated offset to be this many times below ss_tol: the
#: estimate is first order in the defect and its quadrature (the monodromy's midpoints) is within
#: a factor 2 of the defect measured by tight time stepping at the benchmark scenes
#: (tests/test_floquet.py)
CERTIFICATE_SAFETY = 10.0

#: size of the push off an unstable orbit, relative to the response (max |Theta|)
LEAVE_FRACTION = 0.05

#: status of a SteadyState whose only periodic orbit found is unstable (no time stepping to
#: decide, numerics.integrate = False, or time stepping stayed on it)
STATUS_UNSTABLE = 2


def orbit_stability(
    model: DiscreteModel,
    periodic: PeriodicResult | None,
    steps: int | None = None,
    after: FloquetResult | None = None,
    candidate: bool = False,
) -> FloquetResult | None:
    """Floquet multipliers and defect of a collocated orbit, before any time stepping.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    periodic : PeriodicResult or None
        The collocated orbit (`rotbeam.solve.periodic`).
    steps : int or None
        A fixed number of Magnus steps; None: the first try, then the ladder
        (`rotbeam.solve.floquet.orbit_floquet`).
    after : FloquetResult or None
        A pass of the same orbit already made, for the ladder to go on from.
    candidate : bool
        Whether the orbit is only a candidate yet: the step count then answers for the
        stability verdict alone (|mu|max to a tenth of its distance from 1), and the
        fixed-point offset is left to `monodromy_certificate`, which weighs it with its
        spread between two counts and asks for more where that is ambiguous.  An orbit that
        is reported gets |mu|max to its `Numerics.floquet_tol` (`reported_multipliers`).

    Returns
    -------
    FloquetResult or None
        The orbit's multipliers; None when there is no orbit or it did not converge.
    """
    if periodic is None or not periodic.converged:
        return None
    loose = math.inf if candidate else None
    return beam_floquet(model, periodic.theta, periodic.theta_t, steps, after, loose,
                        math.inf if candidate else SPREAD_TOL)  # fmt: skip


def reported_multipliers(
    model: DiscreteModel,
    periodic: PeriodicResult,
    fl: FloquetResult | None,
    mu_tol: float = SPREAD_TOL,
) -> FloquetResult | None:
    """The multipliers of a collocated orbit that is reported: `fl` (a candidate's), with the
    step ladder gone on until |mu|max stands to `mu_tol`.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    periodic : PeriodicResult
        The orbit.
    fl : FloquetResult or None
        Its multipliers as the candidate check left them.
    mu_tol : float
        How closely |mu|max is resolved (`Numerics.floquet_tol`): the spread of two step
        counts it must stand within.  1 keeps `fl`: the candidate check already resolved it to
        a tenth of its distance from 1, enough for the stability verdict.

    Returns
    -------
    FloquetResult or None
        `fl` when its spread is already within `mu_tol` (or it has no comparison: a fixed
        count), else the finer pass.
    """
    if fl is None or fl.coarse is None or fl.spread <= mu_tol:
        return fl
    if fl.steps >= STEP_LADDER[-1]:
        return fl
    return beam_floquet(model, periodic.theta, periodic.theta_t, after=fl, offset_atol=math.inf,
                        mu_tol=mu_tol)  # fmt: skip


def leave_orbit(z: np.ndarray, fl: FloquetResult, size: float) -> np.ndarray:
    """The start of time stepping off an unstable orbit: z pushed along its most unstable
    Floquet direction, so that the stepper does not sit on the orbit for as long as its slow
    growth would let it pass the transient check.

    Parameters
    ----------
    z : numpy.ndarray
        The orbit's state (Theta, Theta_t) at tau = 0, shape (2 n,).
    fl : FloquetResult
        Its multipliers and monodromy.
    size : float
        The response's size, max |Theta| [rad].

    Returns
    -------
    numpy.ndarray
        z + LEAVE_FRACTION * size * v, shape (2 n,), v the leading eigenvector of the monodromy
        (its real part, else its imaginary part) scaled to max |v_Theta| = 1.
    """
    w, V = np.linalg.eig(fl.monodromy)
    v = np.real(V[:, int(np.argmax(np.abs(w)))])
    if not np.any(v):
        v = np.imag(V[:, int(np.argmax(np.abs(w)))])
    n = z.size // 2
    v = v / max(float(np.max(np.abs(v[:n]))), 1e-300)
    return z + LEAVE_FRACTION * max(size, 1e-12) * v


def window_stability(model: DiscreteModel, theta_one_period: np.ndarray) -> FloquetResult | None:
    """Floquet multipliers of the orbit time stepping settled on, from one period of samples.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    theta_one_period : numpy.ndarray
        Angles [rad] at m equispaced instants of the last drive period, shape (n, m).

    Returns
    -------
    FloquetResult or None
        The multipliers (`rotbeam.solve.floquet.sampled_beam_floquet`); None with fewer than 8
        samples.
    """
    if theta_one_period.ndim != 2 or theta_one_period.shape[1] < 8:
        return None
    return sampled_beam_floquet(model, theta_one_period)


@dataclass(frozen=True)
class Certificate:
    """Outcome of `monodromy_certificate`: the offset estimate and whether it certifies."""

    offset: float  #: estimated distance to the true periodic state, relative to the response
    limit: float  #: what it had to be below: ss_tol / CERTIFICATE_SAFETY
    certified: bool
    #: how far the coarse monodromy's estimate lies from it (0 without one): the certificate
    #: asks offset + spread to be below the limit
    spread: float = 0.0

    @property
    def ambiguous(self) -> bool:
        """Below the limit, but not with the spread added: more Floquet steps decide."""
        return not self.certified and self.offset <= self.limit

    def describe(self) -> str:
        """The certificate in words, for messages.

        Returns
        -------
        str
            E.g. 'monodromy offset estimate 3.5e-06 <= 1e-05' (with ' + spread' when a coarse
            estimate is beside it; '>' when it fails).
        """
        verdict = "<=" if self.certified else ">"
        spread = f" + {self.spread:.2g}" if self.spread else ""
        return f"monodromy offset estimate {self.offset:.2g}{spread} {verdict} {self.limit:.2g}"


def _relative(w: np.ndarray, size: float, wref: float) -> float:
    """max-norm of a state offset (angles; velocities divided by wref) relative to size."""
    n = w.size // 2
    return max(float(np.max(np.abs(w[:n]))), float(np.max(np.abs(w[n:]))) / wref) / size


def monodromy_certificate(
    fl: FloquetResult | None, theta: np.ndarray, ss_tol: float, wref: float
) -> Certificate | None:
    """Whether an attracting collocated orbit is the steady state without time stepping.

    The fixed point of the period map is the orbit's start plus w, (I - Phi) w = defect (first
    order).  |w| (max-norm, velocities divided by `wref`, as the time-stepped transient bound)
    relative to max |Theta| must be below ss_tol / CERTIFICATE_SAFETY: the same quantity the
    verification period bounds by d rho / (1 - rho), with the margin of an estimate.  With a
    coarse monodromy beside it, the distance between the two estimates is added
    (docs/stability.md, "The monodromy certificate").

    Parameters
    ----------
    fl : FloquetResult or None
        The orbit's multipliers, with the defect they carry.
    theta : numpy.ndarray
        The orbit's angles [rad], shape (n, M): their largest |value| is the response's size.
    ss_tol : float
        The steady-state tolerance (relative remaining transient).
    wref : float
        Rates d Theta / d tau are compared divided by this (max(omega, 1), omega the
        dimensionless drive frequency).

    Returns
    -------
    Certificate or None
        The offset estimate, its limit, the spread and the verdict; None when there is no
        certificate to give (no multipliers, no defect, an orbit that is not stable, or an
        offset that is not finite).
    """
    w = fl.fixed_point_offset() if fl is not None else None
    if w is None or not np.all(np.isfinite(w)):
        return None
    size = max(float(np.max(np.abs(theta))), 1e-300)
    offset = _relative(w, size, wref)
    w_coarse = fl.coarse.fixed_point_offset() if fl.coarse is not None else None
    spread = 0.0
    if w_coarse is not None:
        spread = _relative(w - w_coarse, size, wref) if np.all(np.isfinite(w_coarse)) else np.inf
    limit = ss_tol / CERTIFICATE_SAFETY
    return Certificate(offset, limit, offset + spread <= limit, spread)


def stability_note(fl: FloquetResult | None) -> str:
    """The words a steady-state message gains from the multipliers.

    Parameters
    ----------
    fl : FloquetResult or None
        The multipliers of the reported orbit.

    Returns
    -------
    str
        '; Floquet |mu|max = ... (..., stable)', with ', fold instability' (or period doubling,
        torus) when unstable; '' without multipliers.
    """
    if fl is None:
        return ""
    what = "" if fl.stable else f", {fl.crossing()} instability"
    return f"; Floquet {fl.describe()}{what}"
