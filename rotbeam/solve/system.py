"""A model as a first-order ODE for scipy's solve_ivp: the right-hand side and its exact
Jacobian, within a wall-time deadline."""

from __future__ import annotations

import math
import time

import numpy as np

from ..model.base import DiscreteModel
from .timebudget import OutOfTime

__all__ = ["FirstOrderSystem", "OutOfTime"]


class FirstOrderSystem:
    """z' = f(tau, z) with z = (Theta, Theta_t), and df/dz, of one model and its drive.

    Parameters
    ----------
    model : DiscreteModel
        The model.
    deadline : float
        A `time.perf_counter` value after which `rhs` raises `OutOfTime`, so that solve_ivp
        stops inside a step (default: never).
    compiled : bool
        `rhs` by the compiled right-hand side where the model offers one
        (`DiscreteModel.kernel`, without a tangent; equal to the numpy model's to round-off).

    Attributes
    ----------
    kernel : Kernel or None
        The compiled kernel `rhs` calls, None for the numpy model's.
    """

    def __init__(
        self, model: DiscreteModel, deadline: float = math.inf, compiled: bool = False
    ) -> None:
        self.model, self.deadline = model, deadline
        self.n = model.n
        self.kernel = model.kernel(tangent=False)[0] if compiled else None

    def rhs(self, tau: float, z: np.ndarray) -> np.ndarray:
        """(Theta_t, Theta_tt) at tau."""
        if time.perf_counter() > self.deadline:
            raise OutOfTime
        if self.kernel is not None:
            out = np.empty(2 * self.n)
            self.kernel.rates(tau, z, out, False, *self.kernel.arguments)
            return out
        n, dl = self.n, self.model.dl
        acc = self.model.acceleration(z[:n], z[n:], dl.lam(tau), dl.lam_dot(tau))
        return np.concatenate([z[n:], acc])

    def tangent(self, tau: float, y: np.ndarray) -> np.ndarray:
        """The rates of the state and of a tangent vector (`DiscreteModel.first_order_jvp`:
        J v without forming J).

        Parameters
        ----------
        tau : float
            The instant.
        y : numpy.ndarray
            (z, v), shape (4 n,).

        Returns
        -------
        numpy.ndarray
            (f(tau, z), J(tau, z) v), shape (4 n,).
        """
        if time.perf_counter() > self.deadline:
            raise OutOfTime
        n, dl = self.n, self.model.dl
        d = 2 * n
        f, jv = self.model.first_order_jvp(y[:n], y[n:d], dl.lam(tau), dl.lam_dot(tau),
                                           y[d : d + n], y[d + n :])  # fmt: skip
        return np.concatenate([f, jv])

    def jac(self, tau: float, z: np.ndarray) -> np.ndarray:
        """The exact Jacobian of `rhs`, shape (2 n, 2 n)."""
        n, dl = self.n, self.model.dl
        return self.model.first_order_jacobian(z[:n], z[n:], dl.lam(tau), dl.lam_dot(tau))
