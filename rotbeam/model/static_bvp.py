"""The continuum static elastica under constant loads, by scipy's solve_bvp: the counterpart of
the paper's bvp4c and an independent reference for the discrete quasi-static solver."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..config.errors import RotbeamInputError
from .params import Effects


@dataclass
class BVPSolution:
    """The continuum static elastica at the nodes s: angle, shape and internal force, all
    dimensionless (lengths in units of L, forces in units of EI / L^2)."""

    s: np.ndarray  #: arclength nodes on [0, 1]
    theta: np.ndarray  #: angle [rad]
    x: np.ndarray  #: radial position from the clamp
    y: np.ndarray  #: deflection
    nx: np.ndarray  #: internal force, x component
    ny: np.ndarray  #: internal force, y component
    success: bool  #: scipy's solve_bvp converged
    message: str
    sol: object  #: scipy's result (callable `sol` on [0, 1])

    def y_at(self, s: float) -> float:
        """The deflection y / L at any arclength, from scipy's continuous solution.

        Parameters
        ----------
        s : float
            Arclength in [0, 1] (units of L).

        Returns
        -------
        float
            y / L at s.
        """
        return float(self.sol.sol(s)[3] * self._eps)

    _eps: float = 1.0


def solve_static_bvp(
    hub_ratio: float,
    lam: float,
    lam_dot: float,
    effects: Effects | None = None,
    tol: float = 1e-9,
    nodes: int = 101,
    guess: BVPSolution | None = None,
) -> BVPSolution:
    """The continuum static elastica under constant (lam, lam_dot), by scipy.integrate.solve_bvp:
    the counterpart of the paper's bvp4c and the tests' reference for the discrete quasi-static
    solver.

    Unknowns (theta, theta_s, x, y, n_x, n_y); theta, theta_s, y, n_y are divided by a load scale
    eps (the linear tip angle under the Euler load) so that `tol` is relative to the deflection.

    Parameters
    ----------
    hub_ratio : float
        Hub radius over beam length, R / L.
    lam : float
        Dimensionless angular velocity Omega T.
    lam_dot : float
        Its rate d lam / d tau (the Euler load).
    effects : Effects or None
        Which loads act (centrifugal, softening, Euler); None: the defaults.  `extension` is
        not supported.
    tol : float
        solve_bvp's tolerance (relative to the deflection, see above).
    nodes : int
        Nodes of the first mesh and of the returned samples.
    guess : BVPSolution or None
        A solution under nearby loads to start from (continuation); None: the straight beam.

    Returns
    -------
    BVPSolution
        The solution at `nodes` equispaced s, and scipy's result.

    Raises
    ------
    RotbeamInputError
        With effects.extension.
    """
    # Over 60 lines as one named step: the equations, boundary conditions and first guess of the
    # BVP share the load scale eps and exist only for this one solve_bvp call.
    ef = effects if effects is not None else Effects()
    if ef.extension:
        raise RotbeamInputError("solve_static_bvp is the inextensible elastica: no `extension`")
    lam2 = lam * lam if ef.centrifugal else 0.0
    soft = lam2 if (ef.centrifugal and ef.softening) else 0.0
    ld = lam_dot if ef.euler else 0.0
    r_o = hub_ratio
    eps = abs(ld) * (r_o + 1.0) / 2.0
    if eps == 0.0:
        eps = 1.0

    def f(s, u):
        th = eps * u[0]
        sn, cs = np.sin(th), np.cos(th)
        x = u[2]
        nx = u[4]
        return np.vstack(
            [
                u[1],
                nx * sn / eps - u[5] * cs,
                cs,
                sn / eps,
                -(lam2 * (r_o + x) + ld * eps * u[3]),
                -(-ld * (r_o + x) + soft * eps * u[3]) / eps,
            ]
        )

    def bc(ua, ub):
        return np.array([ua[0], ua[2], ua[3], ub[1], ub[4], ub[5]])

    s = np.linspace(0.0, 1.0, nodes)
    if guess is not None:
        u0 = guess.sol.sol(s)
        scale_old = guess._eps
        u0[[0, 1, 3, 5]] *= scale_old / eps
    else:
        u0 = np.zeros((6, nodes))
        u0[2] = s
        u0[4] = lam2 * (r_o * (1 - s) + (1 - s**2) / 2)
    from scipy.integrate import solve_bvp  # imported here: the sweeps never need it

    sol = solve_bvp(f, bc, s, u0, tol=tol, max_nodes=100000)
    u = sol.sol(s)
    out = BVPSolution(
        s=s,
        theta=eps * u[0],
        x=u[2],
        y=eps * u[3],
        nx=u[4],
        ny=eps * u[5],
        success=bool(sol.success),
        message=str(sol.message),
        sol=sol,
    )
    out._eps = eps
    return out
