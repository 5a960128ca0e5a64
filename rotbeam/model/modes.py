"""Small vibrations about the centrifugally stretched straight beam under steady rotation.

Linearising Eq. (discretizedEq) about Theta = 0 at constant lam = Omega T gives

    W Theta_tt + eta W Theta_t + (K + diag(n0) - sigma lam^2 W) Theta = -lam_t Q (r_o + s),

with n0(s) = lam^2 [r_o (1 - s) + (1 - s^2)/2] the straight beam's centrifugal tension and
sigma = 1 for in-plane (chordwise) motion, 0 for flapwise.  Its eigenvalues are the exact
counterpart of the Southwell line (Eq. centrifugal_stiffening): (2 pi f_0)^2 = (2 pi f_n)^2 +
S_1 Omega^2 holds only approximately, these frequencies hold for any Omega and hub ratio.
Because the softening term is -sigma lam^2 times the mass matrix, w_inplane^2 = w_flap^2 - lam^2
exactly, in the discrete model as in the continuum.

With `kappa` = (h/L)^2 / 12 > 0 (effect `extension`) the straight beam is first stretched by its
own centrifugal tension (`rotbeam.model.elastica`): W, K and the hub lever arm r_o + x are those
of the stretched grid, and the strain is the one of the rotation `lam_stretch` (the steady `lam`
itself for the natural frequencies).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla

from ..config.errors import RotbeamInputError
from .elastica import DiscreteElastica
from .params import Beam, Dimensionless, Effects


def _model(
    N: int, hub_ratio: float, softening: bool, kappa: float = 0.0, lam_stretch: float = 0.0
) -> DiscreteElastica:
    eff = Effects(
        centrifugal=True,
        softening=softening,
        euler=False,
        coriolis=False,
        damping=False,
        extension=kappa > 0,
    )
    return DiscreteElastica(N, hub_ratio, 0.0, eff, kappa, lam_stretch)


def linear_operators(
    N: int,
    hub_ratio: float,
    lam: float,
    softening: bool = True,
    kappa: float = 0.0,
    lam_stretch: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Mass W and stiffness K + diag(n0) - sigma lam^2 W of the linearised model (stretched by
    the tension of `lam_stretch`, default `lam`, when kappa > 0)."""
    model = _model(N, hub_ratio, softening, kappa, lam if lam_stretch is None else lam_stretch)
    stiff = model.static_jacobian(np.zeros(model.n), lam, 0.0)
    return model.grid.W, stiff


def dimensionless_frequencies(
    lam: float,
    hub_ratio: float,
    n_modes: int = 1,
    N: int = 40,
    softening: bool = False,
    kappa: float = 0.0,
) -> np.ndarray:
    """Lowest `n_modes` natural frequencies w = omega T (ascending) at rotation lam = Omega T.

    softening=False: flapwise (out-of-plane); True: in-plane (the rotating elastica's own plane).
    kappa = (h/L)^2 / 12 > 0: about the beam stretched by its centrifugal tension (extension).
    """
    if not math.isfinite(lam):
        raise RotbeamInputError(f"lambda must be finite, got {lam!r}")
    if not (hub_ratio >= 0 and math.isfinite(hub_ratio)):
        raise RotbeamInputError(f"hub ratio R_o/L must be >= 0, got {hub_ratio!r}")
    if not (isinstance(n_modes, int) and 1 <= n_modes <= N - 1):
        raise RotbeamInputError(f"number of modes must be in [1, N-1={N - 1}], got {n_modes!r}")
    W, S = linear_operators(N, hub_ratio, lam, softening, kappa)
    w2 = np.sort(sla.eigvals(S, W).real)[:n_modes]
    if w2[0] < 0:
        # in-plane with a hub below zero stiffness cannot happen for a tensile beam; be explicit
        raise RotbeamInputError(f"negative squared frequency {w2[0]:.3g}: the state is unstable")
    return np.sqrt(w2)


def natural_frequencies_hz(
    beam: Beam, omega: float, n_modes: int = 1, N: int = 40, softening: bool = True
) -> np.ndarray:
    """Natural frequencies [Hz] of `beam` spinning steadily at `omega` rad/s (in-plane default)."""
    w = dimensionless_frequencies(omega * beam.T, beam.hub_ratio, n_modes, N, softening)
    return w / (2.0 * math.pi * beam.T)


def linear_forced_response(dl: Dimensionless, N: int) -> tuple[np.ndarray, np.ndarray]:
    """Steady harmonic response of the linearised model at the mean rotation lam0.

    Returns the complex amplitude Theta_hat with Theta(tau) = Re(Theta_hat e^{i omega tau}),
    and the (N-1,) load vector; used as a starting state close to the steady state.
    """
    ef = dl.effects
    lam = dl.lam0 if ef.centrifugal else 0.0
    W, stiff = linear_operators(N, dl.hub_ratio, lam, ef.softening, dl.kappa, dl.lam_stretch)
    grid = DiscreteElastica.from_dimensionless(dl, N).grid
    x = grid.s if grid.strain is None else grid.positions(np.zeros(grid.N - 1))[0]
    q = grid.Q @ (dl.hub_ratio + x) if ef.euler else np.zeros(grid.N - 1)
    eta = dl.eta if ef.damping else 0.0
    w = dl.omega
    # the gyroscopic (Coriolis) matrix vanishes on the straight beam: no term here
    A = stiff - w * w * W + 1j * w * eta * W
    return np.linalg.solve(A, (-dl.alpha * w * q).astype(complex)), q
