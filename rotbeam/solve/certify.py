"""Certification: the one place that decides whether an orbit is the steady state.

`rotbeam.solve.steady` searches; it asks `certify_orbit` (-> `OrbitVerdict`: is the collocated
orbit the steady state without time stepping?  the candidate check `orbit_stability`, the
monodromy certificate `accept_certified`, the refinement `certify_refining`, the verdict with
integrate = False `collocation_verdict`; where time stepping starts: `OrbitVerdict.march_start`,
`leave_orbit`) and `certify_window` (-> `WindowVerdict`: the verdict on a time-stepped window,
`window_stability`).  Each answer carries the status, the message (`stability_note`), the
certificate and the multipliers reported (`reported_multipliers`), which come from
`rotbeam.solve.floquet`.  What it decides and why: docs/stability.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model.base import DiscreteModel
from ..model.params import Dimensionless
from .collocated_floquet import (
    above_cluster,
    collocated_multipliers,
    resolved_multipliers,
    uniform_decay,
)
from .floquet import (
    FIRST_TRY_MAX_INSTANTS,
    SPREAD_TOL,
    STEP_LADDER,
    VERDICT_ONLY,
    FloquetResult,
    beam_floquet,
    first_try_stands,
    sampled_orbit,
)
from .numerics import Numerics
from .periodic import PeriodicResult, refined

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

#: the finest collocation `certify_refining` goes to (solve_periodic_adaptive's M_max)
REFINE_M_MAX = 129


@dataclass(frozen=True)
class OrbitVerdict:
    """`certify_orbit`'s answer: whether the collocated orbit is the steady state, and what
    time stepping starts from when it is not."""

    #: the orbit decided on (refined while its certificate asked for it), or None
    periodic: PeriodicResult | None
    #: its multipliers: the reported ones when the orbit is the state, else the candidate's
    floquet: FloquetResult | None
    #: the status of the orbit as the reported state (0 certified; with integrate = False also
    #: 1 not verified, STATUS_UNSTABLE unstable); None: time stepping decides
    status: int | None = None
    #: the message of the reported orbit; when time stepping decides, why the orbit is not
    #: certified ('' without a certificate), the start of the time-stepped state's message
    message: str = ""
    certificate: Certificate | None = None  #: the monodromy certificate decided by, if any
    #: the reported orbit's remaining transient: the certificate's offset estimate, or the
    #: harmonic tail of a collocation reported as it is (inf while time stepping decides)
    transient: float = math.inf

    @property
    def decided(self) -> bool:
        """The orbit is the reported state: no time stepping."""
        return self.status is not None

    @property
    def unstable(self) -> bool:
        """The orbit's multipliers say it is unstable."""
        return self.floquet is not None and self.floquet.unstable

    @property
    def on_orbit(self) -> bool:
        """Time stepping starts on the orbit: it converged and is not unstable."""
        return self.periodic is not None and self.periodic.converged and not self.unstable

    def march_start(self, z: np.ndarray, size: float) -> np.ndarray:
        """The state time stepping starts from: z, pushed off an unstable orbit along its most
        unstable Floquet direction (`leave_orbit`).

        Parameters
        ----------
        z : numpy.ndarray
            The starting state (Theta, Theta_t), shape (2 n,).
        size : float
            The response's size, max |Theta| [rad].

        Returns
        -------
        numpy.ndarray
            z itself unless the orbit is unstable, shape (2 n,).
        """
        return leave_orbit(z, self.floquet, size) if self.unstable else z


@dataclass(frozen=True)
class WindowVerdict:
    """`certify_window`'s answer: the status, message and multipliers of a time-stepped state."""

    status: int  #: the window's, or STATUS_UNSTABLE when the orbit reached is unstable
    message: str  #: the whole message: why the orbit was not certified, the window's, the note
    floquet: FloquetResult | None  #: multipliers of the reported orbit (else of the collocated)


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
    """The multipliers of a collocated orbit that is reported: `fl` (a candidate's), resolved
    until |mu|max stands to `mu_tol`.

    An orbit of more than FIRST_TRY_MAX_INSTANTS instants takes them from a Radau collocation
    of its variational equation (`collocated_multipliers`: 16 to 1024 intervals, where the step
    ladder would climb to 337 or 1012 exponentials), checked against `fl`, which the candidate
    check resolved to a tenth of its distance from 1: where the two differ by more than that,
    `fl`'s spread and `mu_tol` together, no two interval counts agree or the collocation's
    |mu|max lies in the cluster of moduli it cannot tell apart, the ladder goes on instead
    (docs/stability.md, "Multipliers from a collocation").  Where `fl`'s |mu|max and spread
    together stay inside that cluster, the collocation is not tried.  A step count stands only
    where its |mu|max also stands apart from the next modulus or lies at the cluster
    (`rotbeam.solve.floquet.top_stands_apart`): two counts can agree on |mu|max and both miss
    it where the order of two moduli above the cluster swaps between them.

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
        `fl` when it already stands to `mu_tol` (or it has no comparison: a fixed count), else
        the finer pass: Radau's, or the ladder's next counts (`fl` itself where the candidate
        check already climbed to the ladder's last count and Radau does not answer).
    """
    if fl is None or fl.coarse is None or mu_tol >= VERDICT_ONLY:
        return fl
    cluster = uniform_decay(model)
    if first_try_stands(fl, 0.0, math.inf, mu_tol, cluster):
        return fl
    if periodic.M > FIRST_TRY_MAX_INSTANTS and above_cluster(cluster, fl.max_abs + fl.spread):
        collocated = collocated_multipliers(model, periodic.theta, periodic.theta_t, mu_tol)
        resolved = 0.1 * abs(1.0 - fl.max_abs) + fl.spread + mu_tol
        if collocated is not None and abs(collocated.max_abs - fl.max_abs) <= resolved:
            return collocated
    if fl.steps >= STEP_LADDER[-1]:  # the ladder ends here
        return fl
    return beam_floquet(model, periodic.theta, periodic.theta_t, after=fl, offset_atol=math.inf,
                        mu_tol=mu_tol, cluster=cluster)  # fmt: skip


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


def window_stability(
    model: DiscreteModel, theta_one_period: np.ndarray, mu_tol: float = SPREAD_TOL
) -> FloquetResult | None:
    """Floquet multipliers of the orbit time stepping settled on, from one period of samples.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    theta_one_period : numpy.ndarray
        Angles [rad] at m equispaced instants of the last drive period, shape (m, n).
    mu_tol : float
        How closely |mu|max is resolved (`Numerics.floquet_tol`).

    Returns
    -------
    FloquetResult or None
        The multipliers of the samples and their spectral derivative
        (`rotbeam.solve.floquet.sampled_orbit`, `resolved_multipliers`: no fixed-point offset
        is asked for); None with fewer than 8 samples.
    """
    if theta_one_period.ndim != 2 or theta_one_period.shape[0] < 8:
        return None
    return resolved_multipliers(model, *sampled_orbit(model, theta_one_period), mu_tol)


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
        The orbit's angles [rad], shape (M, n): their largest |value| is the response's size.
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


def _certificate(
    fl: FloquetResult | None, periodic: PeriodicResult, num: Numerics, dl: Dimensionless
) -> Certificate | None:
    """`monodromy_certificate` with the run's ss_tol and velocity scale max(omega, 1)."""
    return monodromy_certificate(fl, periodic.theta, num.ss_tol, max(dl.omega, 1.0))


def certify_orbit(
    model: DiscreteModel, num: Numerics, periodic: PeriodicResult | None
) -> OrbitVerdict:
    """Whether the collocated orbit is the steady state without time stepping.

    With numerics.integrate = False the collocation is reported as it is
    (`collocation_verdict`).  Else a converged orbit whose candidate check finds it stable is
    certified by its monodromy, refined while the certificate fails on the offset estimate
    (`certify_refining`); an orbit not certified is left to time stepping, with its multipliers
    (an unstable one's too: time stepping leaves it, `OrbitVerdict.march_start`).

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    num : Numerics
        integrate, certify, tail_tol, ss_tol and floquet_tol.
    periodic : PeriodicResult or None
        The collocated orbit, if one was made.

    Returns
    -------
    OrbitVerdict
        Decided (a status and the message of the reported orbit), or left to time stepping.
    """
    if not num.integrate and periodic is not None:
        return collocation_verdict(model, num, periodic)
    fl = orbit_stability(model, periodic, candidate=True)
    if periodic is None or not periodic.converged or (fl is not None and fl.unstable):
        return OrbitVerdict(periodic, fl)
    return certify_refining(model, num, periodic, fl)


def collocation_verdict(model: DiscreteModel, num: Numerics, res: PeriodicResult) -> OrbitVerdict:
    """The collocated orbit reported as it is, without time stepping (numerics.integrate =
    False): steady when it met its tolerance on a damped model and is not unstable.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    num : Numerics
        tail_tol, ss_tol and floquet_tol.
    res : PeriodicResult
        The collocated orbit.

    Returns
    -------
    OrbitVerdict
        Status 0, 1 (not verified, or undamped) or STATUS_UNSTABLE, the message with the
        certificate it would have had and the multipliers.
    """
    fl = orbit_stability(model, res, candidate=True)
    ok = res.converged and res.harmonic_tail <= num.tail_tol and model.damped
    msg = f"collocation M={res.M}: {res.message}, harmonic tail {res.harmonic_tail:.2g}"
    cert = _certificate(fl, res, num, model.dl)
    if cert is not None:
        msg += f"; {cert.describe()}"
    fl = reported_multipliers(model, res, fl, num.floquet_tol)
    msg += stability_note(fl)
    unstable = ok and fl is not None and fl.unstable
    if unstable:
        ok = False
        msg += " (not a steady state: the orbit is unstable)"
    elif not model.damped:
        msg += "; undamped model has no steady state (a periodic orbit, not an attractor)"
    elif not ok:
        msg += " (not verified: collocation did not meet its tolerance)"
    status = 0 if ok else (STATUS_UNSTABLE if unstable else 1)
    return OrbitVerdict(res, fl, status, msg, cert, res.harmonic_tail)


def accept_certified(
    model: DiscreteModel, num: Numerics, periodic: PeriodicResult, fl: FloquetResult | None
) -> OrbitVerdict:
    """The collocated orbit as the steady state when its monodromy certificate holds.

    An ambiguous certificate (the Floquet steps taken cannot tell) is decided again with the
    next step counts of the ladder (`rotbeam.solve.floquet.STEP_LADDER`).

    Parameters
    ----------
    model : DiscreteModel
        The model.
    num : Numerics
        certify, tail_tol, ss_tol and floquet_tol.
    periodic : PeriodicResult
        The collocated orbit.
    fl : FloquetResult or None
        Its multipliers and defect (the candidate check's).

    Returns
    -------
    OrbitVerdict
        Status 0 with the reported multipliers when certified; else undecided, with `fl`, the
        certificate and why it failed ('' when there was no certificate).
    """
    undecided = OrbitVerdict(periodic, fl)
    if num.certify != "monodromy" or periodic.harmonic_tail > num.tail_tol:
        return undecided
    candidate = fl
    cert = _certificate(fl, periodic, num, model.dl)
    while cert is not None and cert.ambiguous and fl.steps < STEP_LADDER[-1]:
        fl = orbit_stability(model, periodic, after=fl, candidate=True)  # more steps decide
        cert = _certificate(fl, periodic, num, model.dl)
    if cert is None:
        return undecided
    if not cert.certified:
        why_not = f"not certified by the monodromy ({cert.describe()}); "
        return OrbitVerdict(periodic, candidate, message=why_not, certificate=cert)
    fl = reported_multipliers(model, periodic, fl, num.floquet_tol)
    message = (
        f"collocation orbit (M={periodic.M}, harmonic tail {periodic.harmonic_tail:.2g}) "
        f"certified by the monodromy ({cert.describe()})" + stability_note(fl)
    )
    return OrbitVerdict(periodic, fl, 0, message, cert, cert.offset)


def certify_refining(
    model: DiscreteModel, num: Numerics, periodic: PeriodicResult, fl: FloquetResult | None
) -> OrbitVerdict:
    """`accept_certified`, with the orbit refined (`rotbeam.solve.periodic.refined`, up to
    REFINE_M_MAX) while its certificate fails on the offset estimate.

    The offset falls with the interpolant's defect, and a finer orbit costs less than the
    periods of time stepping that would verify the coarse one (docs/stability.md); the
    refinement stops where the offset does not halve, or where the finer orbit is not stable.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    num : Numerics
        certify, tail_tol, ss_tol and floquet_tol.
    periodic : PeriodicResult
        The collocated orbit, stable by its candidate check.
    fl : FloquetResult or None
        Its multipliers and defect.

    Returns
    -------
    OrbitVerdict
        The last orbit's: certified, or left to time stepping with why not.
    """
    verdict = accept_certified(model, num, periodic, fl)
    while not verdict.decided and verdict.message and 2 * periodic.M - 1 <= REFINE_M_MAX:
        finer = refined(model, periodic)
        finer_fl = orbit_stability(model, finer, candidate=True)
        if finer_fl is None or not finer_fl.stable:
            break
        previous = verdict.certificate.offset
        periodic = finer
        verdict = accept_certified(model, num, periodic, finer_fl)
        cert = verdict.certificate
        if cert is None or not cert.offset <= previous / 2:  # the defect does not fall with M
            break
    return verdict


def certify_window(
    model: DiscreteModel,
    num: Numerics,
    orbit: OrbitVerdict,
    status: int,
    message: str,
    periods: int,
    last_period: np.ndarray,
) -> WindowVerdict:
    """The verdict on a time-stepped window: the collocated orbit's multipliers when one period
    verified it, else those of the orbit time stepping settled on (an unstable one is a slow
    transient, not a steady state).

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    num : Numerics
        floquet_tol.
    orbit : OrbitVerdict
        `certify_orbit`'s answer on the collocated orbit (undecided).
    status : int
        The window's status (0 steady, 1 no steady state within budget, -1 failure).
    message : str
        The window's message.
    periods : int
        Drive periods integrated in all.
    last_period : numpy.ndarray
        Angles [rad] at the window's instants of its last drive period, shape (m, n).

    Returns
    -------
    WindowVerdict
        The status (STATUS_UNSTABLE when the orbit reached is unstable), the whole message
        (why the orbit was not certified, the window's, the stability note) and the
        multipliers of the reported orbit (else the collocated one's, resolved to
        num.floquet_tol: `reported_multipliers`).
    """
    orbit_fl = orbit.floquet
    fl = orbit_fl if status == 0 and periods == 1 and orbit.on_orbit else None
    if status == 0 and fl is None:
        fl = window_stability(model, last_period, num.floquet_tol)
        if fl is not None and fl.unstable:
            status = STATUS_UNSTABLE
            message += "; but the orbit reached is unstable (a slow transient, not a steady state)"
    if orbit_fl is not None and orbit_fl.unstable:
        message = f"collocated orbit unstable ({orbit_fl.crossing()}); {message}"
    if (fl is None or fl is orbit_fl) and orbit.periodic is not None:
        fl = reported_multipliers(model, orbit.periodic, orbit_fl, num.floquet_tol)
    message += stability_note(fl if fl is not None else orbit_fl)
    return WindowVerdict(status, orbit.message + message, fl if fl is not None else orbit_fl)
