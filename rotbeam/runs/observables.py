"""Observables: what a run reports about the beam, evaluated on its states after the solvers.

An `Observable` is a name, a unit and a function of the model, the beam and a batch of
instants (`States`: the angles, and where needed their rates and accelerations).  `OBSERVABLES`
holds the registry: ``y_m`` (the paper's output, the default), ``tip``, ``root_moment``,
``root_stress`` and ``tip_acceleration``.  Definitions, units and how the rates of a steady
state, a move and the quasi-static twin are taken: docs/model.md, "Observables".
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np

from ..config.errors import RotbeamInputError
from ..model.base import DiscreteModel
from ..model.criterion import delta_rms, rms
from ..model.params import Beam
from ..solve.spectral import periodic_rates


@dataclass(frozen=True)
class States:
    """A batch of instants of one response: what an observable reads.

    Parameters
    ----------
    tau : numpy.ndarray
        Instants in units of T, shape (m,).
    theta : numpy.ndarray
        Angles [rad] at the grid's nodes 1..N-1, shape (m, n).
    theta_t : numpy.ndarray or None
        Their rates (units of 1/T), shape (m, n); None where the response has none.
    theta_tt : numpy.ndarray or None
        Their accelerations (units of 1/T^2), shape (m, n); None where the response has none.
    """

    tau: np.ndarray
    theta: np.ndarray
    theta_t: np.ndarray | None = None
    theta_tt: np.ndarray | None = None


@dataclass(frozen=True)
class Observable:
    """One output of a run: a name, its unit and how it is computed from the states.

    Parameters
    ----------
    name : str
        The name `--observe` and JSON use.
    unit : str
        The unit of its values ("L" for lengths in units of the beam's length).
    description : str
        What it is, one line.
    function : callable
        function(model, beam, states) -> values, shape (m,), in `unit`.
    rates : bool
        Whether it reads the rates and accelerations of the states.
    """

    name: str
    unit: str
    description: str
    function: Callable[[DiscreteModel, Beam, States], np.ndarray]
    rates: bool = False

    def __call__(self, model: DiscreteModel, beam: Beam, states: States) -> np.ndarray:
        """The observable's values at the instants of `states`.

        Parameters
        ----------
        model : DiscreteModel
            The discrete model the states belong to (its grid and drive).
        beam : Beam
            The scene's beam: the dimensional scales EI, L, T, h, I, R_o.
        states : States
            The instants.

        Returns
        -------
        numpy.ndarray
            Shape (m,), in `unit`.

        Raises
        ------
        ValueError
            If the observable reads rates and `states` has none.
        """
        if self.rates and (states.theta_t is None or states.theta_tt is None):
            raise ValueError(f"observable {self.name} needs the rates and accelerations")
        values = self.function(model, beam, on_the_beam(model, states))
        return np.atleast_1d(np.asarray(values, dtype=float))


def on_the_beam(model: DiscreteModel, states: States) -> States:
    """The states in the beam's angles on the model's grid (`DiscreteModel.beam_angles`): the
    model's coordinates may be others (a modal model's amplitudes), and the map is linear, so
    rates and accelerations map alike.

    Parameters
    ----------
    model : DiscreteModel
        The model whose coordinates `states` holds.
    states : States
        Coordinates, shape (m, model.n), and their rates.

    Returns
    -------
    States
        Angles [rad] at the grid's nodes 1..N-1, shape (m, N - 1), and their rates.
    """

    def up(x: np.ndarray | None) -> np.ndarray | None:
        if x is None:
            return None
        return model.beam_angles(np.asarray(x, dtype=float).reshape(-1, model.n))

    return States(states.tau, up(states.theta), up(states.theta_t), up(states.theta_tt))


def _midspan(model: DiscreteModel, beam: Beam, states: States) -> np.ndarray:
    """y_m = y(1/2) / L."""
    return model.grid.midspan(states.theta)


def _tip(model: DiscreteModel, beam: Beam, states: States) -> np.ndarray:
    """y(1) / L."""
    return model.grid.tip(states.theta)[1]


def root_curvature(model: DiscreteModel, theta: np.ndarray) -> np.ndarray:
    """d theta / ds at the clamp, by the second-order one-sided difference of the grid's angles.

    theta_0 = 0 at the clamp and the angles at nodes 1, 2 give
    theta_s(0) = (4 theta_1 - theta_2) / (2 ds) + O(ds^2) (node 2 is the free end's angle
    theta_N = theta_{N-1} where N = 2).

    Parameters
    ----------
    model : DiscreteModel
        The model (its grid's ds).
    theta : numpy.ndarray
        Angles [rad] at nodes 1..N-1, shape (m, N - 1).

    Returns
    -------
    numpy.ndarray
        The curvature at s = 0 in units of 1/L (reference arc length), shape (m,).
    """
    theta = np.asarray(theta, dtype=float).reshape(-1, model.grid.N - 1)
    second = theta[:, 1] if theta.shape[1] > 1 else theta[:, 0]
    return (4.0 * theta[:, 0] - second) / (2.0 * model.grid.ds)


def _root_moment(model: DiscreteModel, beam: Beam, states: States) -> np.ndarray:
    """M(0) = EI theta_s(0) / L [N m]."""
    return beam.EI / beam.L * root_curvature(model, states.theta)


def _root_stress(model: DiscreteModel, beam: Beam, states: States) -> np.ndarray:
    """sigma = M(0) h / (2 I) [Pa], the bending stress at the surface of the clamp's section."""
    return _root_moment(model, beam, states) * beam.h / (2.0 * beam.I)


def tip_kinematics(
    model: DiscreteModel, states: States
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The tip's position, velocity and acceleration relative to the clamp, in the rotating
    frame, from the angles and their rates (the tip row of the grid's quadrature P).

    x = x_0 + P_N cos Theta, y = P_N sin Theta, x_t = -P_N (sin Theta Theta_t),
    y_t = P_N (cos Theta Theta_t), x_tt = -P_N (sin Theta Theta_tt + cos Theta Theta_t^2),
    y_tt = P_N (cos Theta Theta_tt - sin Theta Theta_t^2).

    Parameters
    ----------
    model : DiscreteModel
        The model (its grid).
    states : States
        Angles, rates and accelerations at m instants.

    Returns
    -------
    x, y, x_t, y_t, x_tt, y_tt : numpy.ndarray
        In units of L, L/T and L/T^2, shape (m,) each.
    """
    grid = model.grid
    p = grid.P[-1]
    th = np.asarray(states.theta, dtype=float).reshape(-1, model.grid.N - 1)
    c, s = np.cos(th), np.sin(th)
    th_t = np.asarray(states.theta_t, dtype=float).reshape(th.shape)
    th_tt = np.asarray(states.theta_tt, dtype=float).reshape(th.shape)
    x, y = grid.x0 + c @ p, s @ p
    x_t, y_t = -((s * th_t) @ p), (c * th_t) @ p
    x_tt = -((s * th_tt + c * th_t**2) @ p)
    y_tt = (c * th_tt - s * th_t**2) @ p
    return x, y, x_t, y_t, x_tt, y_tt


def tip_acceleration_components(
    model: DiscreteModel, beam: Beam, states: States
) -> tuple[np.ndarray, np.ndarray]:
    """The tip's acceleration in the inertial frame, along and across the clamp's direction.

    With r = (R_o + L x(1), L y(1)) in the frame turning at Omega e_z:
    a = r'' + 2 Omega e_z x r' + Omega' e_z x r + Omega e_z x (Omega e_z x r), so
    a_x = X'' - 2 Omega Y' - Omega' Y - Omega^2 X and
    a_y = Y'' + 2 Omega X' + Omega' X - Omega^2 Y (docs/model.md, "Observables").

    Parameters
    ----------
    model : DiscreteModel
        The model (its grid and drive lam(tau) = Omega T).
    beam : Beam
        The scale L, T and the clamp's distance R_o [m].
    states : States
        Angles, rates and accelerations at m instants.

    Returns
    -------
    a_x, a_y : numpy.ndarray
        [m/s^2], radial and tangential (positive with the rotation), shape (m,) each.
    """
    L, T = beam.L, beam.T
    x, y, x_t, y_t, x_tt, y_tt = tip_kinematics(model, states)
    lam, lam_dot = model.drive_rows(np.atleast_1d(states.tau))
    W, Wd = lam / T, lam_dot / T**2
    X, Y = beam.R_o + L * x, L * y
    Xd, Yd = L * x_t / T, L * y_t / T
    Xdd, Ydd = L * x_tt / T**2, L * y_tt / T**2
    a_x = Xdd - 2.0 * W * Yd - Wd * Y - W**2 * X
    a_y = Ydd + 2.0 * W * Xd + Wd * X - W**2 * Y
    return a_x, a_y


def _tip_acceleration(model: DiscreteModel, beam: Beam, states: States) -> np.ndarray:
    """|a| of the tip in the inertial frame [m/s^2]."""
    a_x, a_y = tip_acceleration_components(model, beam, states)
    return np.hypot(a_x, a_y)


#: the registry: name -> Observable (the first, y_m, is the default)
OBSERVABLES: dict[str, Observable] = {
    o.name: o
    for o in (
        Observable("y_m", "L", "midspan deflection y(1/2) / L (the paper's)", _midspan),
        Observable("tip", "L", "tip deflection y(1) / L", _tip),
        Observable(
            "root_moment", "N m", "bending moment at the clamp, EI theta_s(0)", _root_moment
        ),
        Observable(
            "root_stress", "Pa", "bending stress at the clamp's surface, M h / (2 I)", _root_stress
        ),
        Observable(
            "tip_acceleration",
            "m/s^2",
            "|acceleration| of the tip (the payload) in the inertial frame",
            _tip_acceleration,
            rates=True,
        ),
    )
}


def observable_names(names: str | Iterable[str]) -> tuple[str, ...]:
    """The observables asked for, checked against the registry.

    Parameters
    ----------
    names : str or iterable of str
        Names, or one comma-separated string ("tip,root_moment").

    Returns
    -------
    tuple of str
        The names, in the order given, each once.

    Raises
    ------
    RotbeamInputError
        One line naming an unknown (or empty) name and the allowed ones.
    """
    if isinstance(names, str):
        names = names.split(",")
    out: list[str] = []
    for raw in names:
        name = str(raw).strip()
        if name not in OBSERVABLES:
            raise RotbeamInputError(
                f"observable {name!r} is not known; allowed: {', '.join(OBSERVABLES)}"
            )
        if name not in out:
            out.append(name)
    if not out:
        raise RotbeamInputError(f"no observable given; allowed: {', '.join(OBSERVABLES)}")
    return tuple(out)


def criterion_name(name: str) -> str:
    """The one observable a verdict and the f_d* search are put on, checked against the registry.

    Parameters
    ----------
    name : str
        One name of OBSERVABLES ("y_m", the paper's, or "root_moment", ...).

    Returns
    -------
    str
        The name, stripped.

    Raises
    ------
    RotbeamInputError
        One line naming the value and the allowed names, for anything but one known name.
    """
    key = name.strip() if isinstance(name, str) else None
    if key not in OBSERVABLES:
        raise RotbeamInputError(
            f"criterion {name!r} is not an observable; allowed: {', '.join(OBSERVABLES)}"
        )
    return key


def window_rates(
    theta: np.ndarray, per_period: int, period: float
) -> tuple[np.ndarray, np.ndarray] | None:
    """Rates and accelerations over a window of whole periods, each period differentiated
    spectrally (`periodic_rates`).

    Parameters
    ----------
    theta : numpy.ndarray
        Angles at the window's instants, shape (periods * per_period, n).
    per_period : int
        Instants per period (0: none).
    period : float
        The period, in units of T.

    Returns
    -------
    (theta_t, theta_tt) or None
        Each the shape of `theta`; None where the window is not whole periods.
    """
    size = theta.shape[0]
    if per_period < 4 or size % per_period:
        return None
    q, n = size // per_period, theta.shape[1]
    first, second = periodic_rates(theta.reshape(q, per_period, n), period, axis=1)
    return first.reshape(size, n), second.reshape(size, n)


def still(theta: np.ndarray) -> np.ndarray:
    """Zero rates of the shape of `theta`: the quasi-static twin's (docs/model.md,
    "Observables": it balances the loads with the beam at rest in the turning frame).

    Parameters
    ----------
    theta : numpy.ndarray
        Angles, any shape.

    Returns
    -------
    numpy.ndarray
        Zeros of that shape.
    """
    return np.zeros_like(np.asarray(theta, dtype=float))


def compare(dynamic: np.ndarray, quasistatic: np.ndarray, unit: str) -> dict[str, float | str]:
    """The numbers of one observable over a window, dynamic beside quasi-static.

    Parameters
    ----------
    dynamic, quasistatic : numpy.ndarray
        Its values at the window's instants (NaN where not known).
    unit : str
        Their unit.

    Returns
    -------
    dict
        ``unit``, ``rms_dynamic``, ``rms_quasistatic``, ``delta_rms`` (dimensionless),
        ``peak_dynamic``, ``peak_quasistatic`` (largest |value|); NaN for an empty series.
    """
    r_dyn, r_qs = _rms(dynamic), _rms(quasistatic)
    return {
        "unit": unit,
        "rms_dynamic": r_dyn,
        "rms_quasistatic": r_qs,
        "delta_rms": delta_rms(r_dyn, r_qs) if math.isfinite(r_dyn) else math.nan,
        "peak_dynamic": _peak(dynamic),
        "peak_quasistatic": _peak(quasistatic),
    }


def _rms(values: np.ndarray) -> float:
    """RMS, NaN for an empty series."""
    values = np.asarray(values, dtype=float)
    return rms(values) if values.size else math.nan


def _peak(values: np.ndarray) -> float:
    """Largest |value|, NaN for an empty series."""
    values = np.asarray(values, dtype=float)
    return float(np.max(np.abs(values))) if values.size else math.nan
