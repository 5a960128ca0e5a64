"""Small vibrations about the straight beam turning steadily: natural frequencies and the
harmonic response of the linearised model.

The exact counterpart of the Southwell line, for any speed, hub ratio and payload; f_0 of the
verdict and the periodic solver's linear start come from here (docs/model.md, "Linear modes").
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla

from ..config.errors import RotbeamInputError
from ..config.threads import one_blas_thread
from .base import DiscreteModel
from .elastica import DiscreteElastica
from .params import Beam, Dimensionless, Effects


def steady_model(
    lam: float,
    hub_ratio: float,
    N: int,
    softening: bool,
    slenderness: float | None = None,
    tip_mass: float = 0.0,
    tip_inertia: float = 0.0,
) -> DiscreteElastica:
    """The elastica turning steadily at `lam` (no Euler load, no damping), for its modes.

    Parameters
    ----------
    lam : float
        Omega T, dimensionless.
    hub_ratio : float
        R_o / L, dimensionless.
    N : int
        Grid intervals.
    softening : bool
        In-plane (True) or flapwise (False) motion.
    slenderness : float or None
        h / L: the beam stretched by its centrifugal tension (`extension`), None: inextensible.
    tip_mass, tip_inertia : float
        A payload, m / (rho A L) and J / (rho A L^3), dimensionless.

    Returns
    -------
    DiscreteElastica
        With centrifugal loads (and softening if asked), the extension if `slenderness` is
        given.
    """
    effects = Effects(centrifugal=True, softening=softening, euler=False, coriolis=False,
                      damping=False, extension=slenderness is not None)  # fmt: skip
    dl = Dimensionless(hub_ratio, 0.0, lam, 0.0, 1.0, effects, slenderness, None, tip_mass,
                       tip_inertia)  # fmt: skip
    return DiscreteElastica(dl, N)


def linear_frequencies(model: DiscreteModel, lam: float, n_modes: int = 1) -> np.ndarray:
    """Lowest `n_modes` natural frequencies w = omega T of `model` linearised about the straight
    beam turning steadily at `lam`, ascending.

    The generalised eigenvalues of (K + dL/dTheta, M) at Theta = 0 (`linear_operators`).

    Parameters
    ----------
    model : DiscreteModel
        The model (its loads at lam_dot = 0 give the stiffness).
    lam : float
        Omega T, dimensionless.
    n_modes : int
        How many, in [1, n].

    Returns
    -------
    numpy.ndarray
        Angular frequencies in units of 1/T, shape (n_modes,).

    Raises
    ------
    RotbeamInputError
        For `n_modes` out of range, or a negative squared frequency (the straight beam is
        unstable at this speed).
    """
    if not (isinstance(n_modes, int) and 1 <= n_modes <= model.n):
        raise RotbeamInputError(f"number of modes must be in [1, N-1={model.n}], got {n_modes!r}")
    mass, stiffness, _ = model.linear_operators(lam)
    w2 = np.sort(sla.eigvals(stiffness, mass).real)[:n_modes]
    if w2[0] < 0:
        raise RotbeamInputError(f"negative squared frequency {w2[0]:.3g}: the state is unstable")
    return np.sqrt(w2)


def dimensionless_frequencies(
    lam: float,
    hub_ratio: float,
    n_modes: int = 1,
    N: int = 40,
    softening: bool = False,
    slenderness: float | None = None,
    tip_mass: float = 0.0,
    tip_inertia: float = 0.0,
) -> np.ndarray:
    """Lowest `n_modes` natural frequencies w = omega T (ascending) at rotation lam = Omega T.

    The convergence checks of the payload and the extension call this directly.

    Parameters
    ----------
    lam : float
        Omega T, dimensionless.
    hub_ratio : float
        R_o / L, dimensionless, >= 0.
    n_modes : int
        How many, in [1, N - 1].
    N : int
        Grid intervals.
    softening : bool
        False: flapwise (out-of-plane); True: in-plane (the rotating elastica's own plane).
    slenderness : float or None
        h / L: about the beam stretched by its centrifugal tension (extension); None:
        inextensible.
    tip_mass, tip_inertia : float
        A payload, m / (rho A L) and J / (rho A L^3), dimensionless.

    Returns
    -------
    numpy.ndarray
        Angular frequencies in units of 1/T, shape (n_modes,).

    Raises
    ------
    RotbeamInputError
        For a lam that is not finite, a negative hub ratio, `n_modes` out of range, or an
        unstable straight beam.
    """
    if not math.isfinite(lam):
        raise RotbeamInputError(f"lambda must be finite, got {lam!r}")
    if not (hub_ratio >= 0 and math.isfinite(hub_ratio)):
        raise RotbeamInputError(f"hub ratio R_o/L must be >= 0, got {hub_ratio!r}")
    if not (isinstance(n_modes, int) and 1 <= n_modes <= N - 1):
        raise RotbeamInputError(f"number of modes must be in [1, N-1={N - 1}], got {n_modes!r}")
    model = steady_model(lam, hub_ratio, N, softening, slenderness, tip_mass, tip_inertia)
    return linear_frequencies(model, lam, n_modes)


@one_blas_thread
def modes(
    beam: Beam, omega: float = 0.0, n_modes: int = 1, N: int = 40, softening: bool = True
) -> np.ndarray:
    """Natural frequencies [Hz] of `beam` spinning steadily at `omega` rad/s.

    Parameters
    ----------
    beam : Beam
        The beam, with its payload if it has one.
    omega : float
        Angular velocity [rad/s].
    n_modes : int
        How many.
    N : int
        Grid intervals.
    softening : bool
        In-plane (default) or flapwise.

    Returns
    -------
    numpy.ndarray
        Frequencies [Hz], ascending.
    """
    mu = beam.tip_mass / (beam.rhoA * beam.L)
    j = beam.tip_inertia / (beam.rhoA * beam.L**3)
    w = dimensionless_frequencies(omega * beam.T, beam.hub_ratio, n_modes, N, softening, None,
                                  mu, j)  # fmt: skip
    return w / (2.0 * math.pi * beam.T)


def linear_forced_response(model: DiscreteModel, K: int = 8) -> dict[int, np.ndarray]:
    """Steady response of the model linearised at its mean rotation to the drive's harmonics.

    lam_dot = Re sum_k d_k exp(i k omega tau) forces the linearised model with -d_k q (q the
    Euler load per unit lam_dot): Theta_k = -(S - (k w)^2 M + i k w eta Md)^-1 d_k q, S the
    linearised stiffness.  The periodic solver's linear start.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    K : int
        Highest harmonic of the drive kept.

    Returns
    -------
    dict
        k -> complex amplitude Theta_k [rad], shape (n,):
        Theta(tau) = Re sum_k Theta_k exp(i k omega tau).
    """
    dl = model.dl
    lam = dl.lam0  # without the centrifugal load the stiffness does not depend on it
    stiffness, damping, mass = model.straight_blocks(lam)
    q = model.euler_load_vector()
    w = dl.omega
    c = dl.law.coefficients(K)
    out = {}
    for k in range(1, c.size):
        if c[k] == 0:
            continue
        kw = k * w
        d = (1j * kw) * c[k]  # the harmonic of lam_dot
        # the gyroscopic (Coriolis) matrix vanishes on the straight beam: no term here
        A = stiffness - kw * kw * mass + 1j * kw * damping
        out[k] = np.linalg.solve(A, -(d * q))
    return out


def resonance_frequency_hz(beam: Beam, omega_max: float, N: int = 80) -> float:
    """f_0 [Hz]: the first in-plane frequency of the linearised model at the drive's largest
    speed (the premise of Eq. Southwell), exact rather than the Southwell line.

    Parameters
    ----------
    beam : Beam
        The beam (with its payload).
    omega_max : float
        The largest |Omega| of the drive [rad/s]: |Omega_0| + a for the sine.
    N : int
        Grid intervals (80: 1e-4 from the continuum).

    Returns
    -------
    float
    """
    return float(modes(beam, omega_max, 1, N, softening=True)[0])


def damping_ratio(beam: Beam) -> float:
    """The first mode's damping ratio at rest, a payload included: `Beam.zeta`.

    What the verdict's linear estimate of f_d* reads (App. E's c_0(zeta)); at rest the in-plane
    and flapwise modes coincide.

    Parameters
    ----------
    beam : Beam
        The beam and its payload.

    Returns
    -------
    float
        zeta, dimensionless.
    """
    return beam.zeta
