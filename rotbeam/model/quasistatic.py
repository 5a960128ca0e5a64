"""Quasi-static response: static equilibrium under the instantaneous loads (time derivatives zero).

Two independent solvers of the same problem:

* `solve_static` / `quasistatic_series`: the discrete static equations K Theta + L(Theta) = 0 of
  `rotbeam.elastica`, solved by Newton with the exact Jacobian, with continuation in time (each
  instant starts from the previous one) and, if Newton stalls, bisection of the load step.
* `solve_static_bvp`: the continuum boundary value problem (Eqs. EOM1-3 with time derivatives
  set to zero, BC of Eq. BC) with scipy's `solve_bvp`, the counterpart of the paper's bvp4c.
  Angles, y and n_y are scaled by the load so that the tolerance is relative to the deflection.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..config.errors import RotbeamInputError
from .elastica import DiscreteElastica
from .params import Dimensionless, Effects


class QuasiStaticError(RuntimeError):
    """Newton did not converge, even with load bisection; the message says where."""


@dataclass
class StaticResult:
    theta: np.ndarray
    converged: bool
    iterations: int
    residual: float
    message: str


def _newton(model: DiscreteElastica, lam, lam_dot, theta, rtol, maxiter) -> StaticResult:
    r = model.static_residual(theta, lam, lam_dot)
    rnorm0 = float(np.max(np.abs(r)))
    if rnorm0 == 0.0:
        return StaticResult(theta, True, 0, 0.0, "exact")
    for it in range(1, maxiter + 1):
        J = model.static_jacobian(theta, lam, lam_dot)
        try:
            step = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError:
            return StaticResult(theta, False, it, float(np.max(np.abs(r))), "singular Jacobian")
        # backtracking on the residual max-norm
        t = 1.0
        rnorm = float(np.max(np.abs(r)))
        while True:
            trial = theta + t * step
            r_trial = model.static_residual(trial, lam, lam_dot)
            rn = float(np.max(np.abs(r_trial)))
            if np.isfinite(rn) and (rn < rnorm or t < 1e-3):
                break
            t *= 0.5
        theta, r = trial, r_trial
        scale = max(float(np.max(np.abs(theta))), 1e-300)
        if float(np.max(np.abs(t * step))) <= rtol * scale:
            return StaticResult(theta, True, it, rn, "converged")
        if not np.isfinite(rn):
            break
    return StaticResult(theta, False, maxiter, float(np.max(np.abs(r))), "no convergence")


def solve_static(
    model: DiscreteElastica,
    lam: float,
    lam_dot: float,
    theta0: np.ndarray | None = None,
    rtol: float = 1e-11,
    maxiter: int = 30,
) -> StaticResult:
    """Static equilibrium at constant (lam, lam_dot); load continuation if Newton stalls."""
    guess = np.zeros(model.n) if theta0 is None else np.array(theta0, dtype=float)
    res = _newton(model, lam, lam_dot, guess, rtol, maxiter)
    if res.converged:
        return res
    # continuation from the previous guess' loads is unknown here: ramp the loads from zero
    theta = np.zeros(model.n)
    steps = 4
    while steps <= 4096:
        ok = True
        theta = np.zeros(model.n)
        for k in range(1, steps + 1):
            t = k / steps
            sub = _newton(model, lam * np.sqrt(t), lam_dot * t, theta, rtol, maxiter)
            if not sub.converged:
                ok = False
                break
            theta = sub.theta
        if ok:
            return StaticResult(theta, True, sub.iterations, sub.residual, f"ramped in {steps}")
        steps *= 4
    return StaticResult(theta, False, maxiter, res.residual, "no convergence after load ramp")


#: chord Newton (one Jacobian) in `batched_static` while all angles stay below this (rad)
CHORD_MAX_ANGLE = 0.1


def batched_static(
    model: DiscreteElastica,
    lam: np.ndarray,
    lam_dot: np.ndarray,
    rtol: float = 1e-11,
    maxiter: int = 12,
) -> np.ndarray | None:
    """Static equilibria at many (lam, lam_dot) at once: Newton from the straight beam, all
    instants in one batched solve.  The same residual and Jacobian as `solve_static`
    (vectorised); None unless every instant converges (callers then use the robust path).

    While every angle stays below CHORD_MAX_ANGLE the Jacobian built at the straight beam is
    kept (chord Newton): it changes only at second order in Theta (1 % at 0.1 rad), so the
    iterations contract almost as fast as Newton's and skip most of the cost, the assembly and
    inversion of the m Jacobians.  Larger angles get plain Newton.
    """
    K = model.grid.K
    theta = np.zeros((lam.size, model.n))
    inverse = None
    for _ in range(maxiter):
        if inverse is None:
            torque, J = model.load_torque_rows(theta, lam, lam_dot, jacobian=True)
            J += K[None]
            try:
                inverse = np.linalg.inv(J)
            except np.linalg.LinAlgError:
                return None
        else:
            torque = model.load_torque_rows(theta, lam, lam_dot)
        r = theta @ K.T + torque
        step = -np.einsum("jik,jk->ji", inverse, r)
        theta = theta + step
        if not np.all(np.isfinite(theta)):
            return None
        scale = np.maximum(np.max(np.abs(theta), axis=1), 1e-300)
        if np.all(np.max(np.abs(step), axis=1) <= rtol * scale):
            return theta
        if float(np.max(np.abs(theta))) > CHORD_MAX_ANGLE:
            inverse = None  # large angles: a fresh Jacobian at every iteration (plain Newton)
    return None


def quasistatic_series(
    model: DiscreteElastica, dl: Dimensionless, taus: np.ndarray, rtol: float = 1e-11
) -> np.ndarray:
    """Theta(tau) of the quasi-static response at the given instants, shape (N-1, len(taus)).

    First all instants at once (`batched_static`); if any instant does not converge, the
    robust path: continuation in time, each instant starting Newton from the previous solution,
    a failed instant approached by bisecting the time step.  Raises QuasiStaticError on failure.
    """
    taus = np.asarray(taus, dtype=float)
    lam = np.array([dl.lam(t) for t in taus])
    lam_dot = np.array([dl.lam_dot(t) for t in taus])
    if taus.size:
        fast = batched_static(model, lam, lam_dot, rtol)
        if fast is not None:
            return fast.T.copy()
    out = np.empty((model.n, taus.size))
    theta = None
    tau_prev = None
    for j, tau in enumerate(taus):
        res = solve_static(model, dl.lam(tau), dl.lam_dot(tau), theta, rtol)
        if not res.converged and tau_prev is not None:
            # bisect from the last converged instant
            sub_theta, ok = theta, True
            for k in range(1, 65):
                tk = tau_prev + (tau - tau_prev) * k / 64
                sub = solve_static(model, dl.lam(tk), dl.lam_dot(tk), sub_theta, rtol)
                if not sub.converged:
                    ok = False
                    break
                sub_theta = sub.theta
            if ok:
                res = StaticResult(sub_theta, True, 0, 0.0, "bisected")
        if not res.converged:
            raise QuasiStaticError(
                f"quasi-static Newton did not converge at tau={tau:.6g} "
                f"(lam={dl.lam(tau):.6g}, lam_dot={dl.lam_dot(tau):.6g}): {res.message}"
            )
        theta, tau_prev = res.theta, tau
        out[:, j] = theta
    return out


@dataclass
class BVPSolution:
    s: np.ndarray
    theta: np.ndarray
    x: np.ndarray
    y: np.ndarray
    nx: np.ndarray
    ny: np.ndarray
    success: bool
    message: str
    sol: object  #: scipy's result (callable `sol` on [0, 1])

    def y_at(self, s: float) -> float:
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
    # Over 60 lines as one named step: the equations, boundary conditions and first guess of the
    # BVP share the load scale eps and exist only for this one solve_bvp call.
    """The continuum static elastica under constant (lam, lam_dot), by scipy.integrate.solve_bvp.

    Unknowns (theta, theta_s, x, y, n_x, n_y); theta, theta_s, y, n_y are divided by a load scale
    eps (the linear tip angle under the Euler load) so that `tol` is relative to the deflection.
    """
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
