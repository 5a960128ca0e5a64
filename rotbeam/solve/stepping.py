"""How a model is stepped from one instant to the next when its response is classified: the
state alone (the transient) or the state with one tangent vector (Benettin's exponent,
`rotbeam.solve.lyapunov`).

Three steppers: Radau with the exact Jacobian (`ImplicitStepper`), and the explicit embedded
Runge-Kutta method DOP853, either scipy's around the model's numpy right-hand side and fused
tangent (`ExplicitStepper`) or the compiled march a model may offer (`CompiledStepper`,
`DiscreteModel.kernel`).  `SwitchingStepper` takes the
explicit one while its steps are set by accuracy and Radau while they are set by stability;
`period_stepper` builds the one a run asks for.  Why, and what each costs: docs/stability.md,
"What a classification period costs".
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np

from ..model.base import DiscreteModel, Kernel
from .ivp import IvpInterval
from .lyapunov import tangent_system
from .system import FirstOrderSystem

METHODS = ("auto", "radau", "dop853")
#: DOP853's tolerances are this times the classification's (the Radau ones they stand in
#: for): at a = 3 rad/s, 7 Hz its error over a sixteenth of a period is then 20 times below
#: Radau's at N = 6 and 8 (docs/stability.md, "What a classification period costs")
EXPLICIT_TOL = 1e-2
TANGENT_ATOL = 1e-10  #: absolute tolerance of the tangent vector (normalised to 1 each period)
#: the edge of DOP853's stability region: |R(h lambda)| <= 1 for h |lambda| up to 5.96 on the
#: imaginary axis and 6.39 on the negative real one
STABILITY_EDGE = 6.0
#: an explicit interval whose mean step times the stiffest rate `rho` reaches this is set by
#: stability (measured: 4.1-4.7 where it is, <= 0.7 where accuracy sets it): Radau takes the
#: next, if it took more steps than the explicit stepper's `stiff_steps`
STIFF = 3.0
#: a Radau interval whose mean step times `rho` is below this is set by accuracy, with the
#: explicit method's stability a factor 3 away: the explicit method takes the next
NONSTIFF = 2.0


class PeriodStepper(ABC):
    """Steps the state, or the state and a tangent vector, of one model over an interval.

    Attributes
    ----------
    name : str
        The method, for messages.
    steps : int
        Accepted steps of the last call.
    """

    name: str
    steps: int = 0
    #: an explicit interval bound by stability hands over to Radau only beyond this many steps:
    #: below it, it costs less than Radau's interval would (docs/stability.md)
    stiff_steps: int = 0

    @abstractmethod
    def state(self, ta: float, tb: float, z: np.ndarray) -> tuple[np.ndarray, str]:
        """z at tb from z at ta.

        Parameters
        ----------
        ta, tb : float
            The interval.
        z : numpy.ndarray
            The state at ta, shape (2 n,).

        Returns
        -------
        z : numpy.ndarray
            The state at tb.
        message : str
            '' on success, else why the step failed.
        """

    @abstractmethod
    def tangent(
        self, ta: float, tb: float, y: np.ndarray, t_eval: np.ndarray | None
    ) -> tuple[np.ndarray, np.ndarray | None, str]:
        """The state and one tangent vector at tb from those at ta
        (`rotbeam.solve.lyapunov.IntervalStep`).

        Parameters
        ----------
        ta, tb : float
            The interval.
        y : numpy.ndarray
            (z, v) at ta, shape (4 n,).
        t_eval : numpy.ndarray or None
            Instants from ta to tb (the last is tb) at which the state is wanted.

        Returns
        -------
        y : numpy.ndarray
            (z, v) at tb.
        samples : numpy.ndarray or None
            The state at t_eval[:-1], shape (t_eval.size - 1, 2 n); None without t_eval.
        message : str
            '' on success, else why the step failed.
        """


class _IvpStepper(PeriodStepper):
    """A stepper of two `IvpInterval`s, one for the state and one for state and tangent."""

    def __init__(self, state: IvpInterval, tangent: IvpInterval) -> None:
        self._state, self._tangent = state, tangent

    def state(self, ta: float, tb: float, z: np.ndarray) -> tuple[np.ndarray, str]:
        """z at tb from z at ta (`PeriodStepper.state`)."""
        y, _, msg = self._state(ta, tb, z, None)
        self.steps = self._state.last.steps
        return y, msg

    def tangent(self, ta, tb, y, t_eval):
        """(z, v) at tb and the samples (`PeriodStepper.tangent`)."""
        out = self._tangent(ta, tb, y, t_eval)
        self.steps = self._tangent.last.steps
        return out


class ImplicitStepper(_IvpStepper):
    """Radau with the exact Jacobian; the tangent as z' = f, v' = J v with J formed at every
    right-hand side (`tangent_system`).

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances of the state, shape (2 n,).
    """

    name = "Radau"

    def __init__(self, model: DiscreteModel, rtol: float, atol: np.ndarray) -> None:
        system = FirstOrderSystem(model, compiled=True)
        aug, aug_jac = tangent_system(system.rhs, system.jac, 2 * model.n)
        tangent = IvpInterval(aug, "Radau", rtol, _tangent_atol(atol), aug_jac)
        super().__init__(IvpInterval(system.rhs, "Radau", rtol, atol, system.jac), tangent)


class ExplicitStepper(_IvpStepper):
    """scipy's DOP853 around the model's numpy right-hand side; the tangent fused with it
    (`DiscreteModel.first_order_jvp`, `FirstOrderSystem.tangent`).

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances of the state, shape (2 n,).
    """

    name = "DOP853"
    stiff_steps = 200

    def __init__(self, model: DiscreteModel, rtol: float, atol: np.ndarray) -> None:
        system = FirstOrderSystem(model)
        tangent = IvpInterval(system.tangent, "DOP853", rtol, _tangent_atol(atol))
        super().__init__(IvpInterval(system.rhs, "DOP853", rtol, atol), tangent)


class CompiledStepper(PeriodStepper):
    """The compiled DOP853 march a model offers (`DiscreteModel.kernel`): scipy's tableau, error
    estimate and step control without Python in the loop.  The step size carries over from one
    call to the next; a step never crosses an instant of t_eval.

    Parameters
    ----------
    model : DiscreteModel
        A model the kernel covers (`compiled_cover` says '').
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances of the state, shape (2 n,).
    tangent : bool
        Whether `tangent` will be asked for (without, the kernel may cover more models).

    Attributes
    ----------
    counts : numpy.ndarray
        Right-hand-side evaluations, accepted and rejected steps, over every call.
    """

    name = "DOP853 (compiled)"
    stiff_steps = 2000

    def __init__(
        self, model: DiscreteModel, rtol: float, atol: np.ndarray, tangent: bool = True
    ) -> None:
        kernel = model_kernel(model, tangent)
        self._advance_kernel, self._args = kernel.advance, kernel.arguments
        self._carries_tangent = tangent
        self._rtol = float(rtol)
        self._atol = {False: np.ascontiguousarray(atol, dtype=float)}
        self._atol[True] = _tangent_atol(self._atol[False])
        self._h = {False: 0.0, True: 0.0}
        self.counts = np.zeros(3, dtype=np.int64)

    def _advance(self, stops: np.ndarray, y: np.ndarray, tangent: bool):
        """y at every stop after the first: (y at the last, (stops - 1, dim), message)."""
        y = np.array(y, dtype=float)
        saved = np.empty((stops.size - 1, y.size))
        before = int(self.counts[1])
        status, h = self._advance_kernel(y, stops, self._h[tangent], self._rtol,
                                         self._atol[tangent], tangent, self._args, saved,
                                         self.counts)  # fmt: skip
        self._h[tangent] = h
        self.steps = int(self.counts[1]) - before
        if status:
            return y, saved, f"step size too small before t = {stops[status]:.6g}"
        if not np.all(np.isfinite(y)):
            return y, saved, "the state is not finite"
        return y, saved, ""

    def state(self, ta: float, tb: float, z: np.ndarray) -> tuple[np.ndarray, str]:
        """z at tb from z at ta (`PeriodStepper.state`)."""
        y, _, msg = self._advance(np.array([ta, tb], dtype=float), z, False)
        return y, msg

    def states(self, stops: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, str]:
        """The state at every stop after the first, from z at the first.

        Parameters
        ----------
        stops : numpy.ndarray
            Non-decreasing instants; no step crosses one.
        z : numpy.ndarray
            The state at stops[0].

        Returns
        -------
        saved : numpy.ndarray
            Shape (stops.size - 1, z.size); rows past a failure are not filled.
        message : str
            '' when every stop was reached, else why not.
        """
        _, saved, msg = self._advance(np.asarray(stops, dtype=float), z, False)
        return saved, msg

    def tangent(self, ta, tb, y, t_eval):
        """(z, v) at tb and the samples (`PeriodStepper.tangent`)."""
        if not self._carries_tangent:
            raise ValueError("this march was built without a tangent")
        if t_eval is None:
            y_end, _, msg = self._advance(np.array([ta, tb], dtype=float), y, True)
            return y_end, None, msg
        stops = np.asarray(t_eval, dtype=float)
        lead = bool(stops[0] > ta)
        if lead:
            stops = np.concatenate([[ta], stops])
        y_end, saved, msg = self._advance(stops, y, True)
        rows = saved if lead else np.vstack([np.asarray(y, dtype=float)[None], saved])
        return y_end, rows[:-1, : y_end.size // 2], msg  # the state at t_eval[:-1]


class SwitchingStepper(PeriodStepper):
    """The explicit stepper while its steps are set by accuracy, Radau while the explicit
    method's stability sets them; decided after every interval from its mean step h and the
    stiffest rate `rho` of the model: h rho >= STIFF after an explicit interval of more than
    its `stiff_steps` steps moves the next to Radau, h rho < NONSTIFF after a Radau interval
    moves it back.

    Parameters
    ----------
    explicit, implicit : PeriodStepper
        The two steppers.
    rho : float
        The largest |eigenvalue| of the first-order Jacobian (`stiffest_rate`).

    Attributes
    ----------
    stiff : bool
        Whether the next interval goes to Radau.
    intervals : dict
        Intervals stepped by each, by name.
    """

    def __init__(self, explicit: PeriodStepper, implicit: PeriodStepper, rho: float) -> None:
        self.explicit, self.implicit, self.rho = explicit, implicit, rho
        self.stiff = False
        self.intervals = {explicit.name: 0, implicit.name: 0}

    @property
    def name(self) -> str:  # type: ignore[override]
        """The steppers used so far, with their intervals when both were."""
        used = {k: v for k, v in self.intervals.items() if v}
        if len(used) < 2:
            return next(iter(used), self.explicit.name)
        return " and ".join(f"{k} for {v}" for k, v in used.items()) + " intervals"

    def _stepped(self, which: PeriodStepper, length: float) -> None:
        """Count the interval and decide the next one's stepper from this one's steps."""
        self.steps = which.steps
        self.intervals[which.name] += 1
        h_rho = length / max(which.steps, 1) * self.rho
        if which is self.explicit:
            self.stiff = h_rho >= STIFF and which.steps > which.stiff_steps
        else:
            self.stiff = h_rho >= NONSTIFF

    def state(self, ta: float, tb: float, z: np.ndarray) -> tuple[np.ndarray, str]:
        """z at tb from z at ta (`PeriodStepper.state`), by the stepper `stiff` chooses."""
        which = self.implicit if self.stiff else self.explicit
        out = which.state(ta, tb, z)
        self._stepped(which, tb - ta)
        return out

    def tangent(self, ta, tb, y, t_eval):
        """(z, v) at tb and the samples (`PeriodStepper.tangent`), by the stepper chosen."""
        which = self.implicit if self.stiff else self.explicit
        out = which.tangent(ta, tb, y, t_eval)
        self._stepped(which, tb - ta)
        return out


def _tangent_atol(atol: np.ndarray) -> np.ndarray:
    """Absolute tolerances of the state and of the tangent vector."""
    return np.concatenate([atol, np.full(atol.size, TANGENT_ATOL)])


def stiffest_rate(model: DiscreteModel) -> float:
    """The largest |eigenvalue| of the first-order Jacobian on the straight beam at rest, at
    the drive's largest |lam|: the top bending mode's frequency on the grid, which sets the
    explicit method's stability limit (h <= STABILITY_EDGE / rho).

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.

    Returns
    -------
    float
        rho, per unit tau.
    """
    zero = np.zeros(model.n)
    J = model.first_order_jacobian(zero, zero, model.dl.law.lam_max, 0.0)
    return float(np.max(np.abs(np.linalg.eigvals(J))))


def compiled_cover(model: DiscreteModel) -> str:
    """Whether the model offers a compiled kernel for its scene: '' if it does, else why not
    (`DiscreteModel.kernel`).

    Parameters
    ----------
    model : DiscreteModel
        The model.

    Returns
    -------
    str
        '' or the reason.
    """
    return model.kernel()[1]


def model_kernel(model: DiscreteModel, tangent: bool = True) -> Kernel:
    """The compiled march the model offers (`DiscreteModel.kernel`).

    Parameters
    ----------
    model : DiscreteModel
        A model that offers one (`compiled_cover`).
    tangent : bool
        Whether the march will carry a tangent.

    Returns
    -------
    Kernel
        Its march, right-hand side and the arrays they read.

    Raises
    ------
    ValueError
        For a model that offers no kernel for its scene (the reason in the message).
    """
    kernel, why_not = model.kernel(tangent)
    if kernel is None:
        raise ValueError(why_not)
    return kernel


def explicit_stepper(model: DiscreteModel, rtol: float, atol: np.ndarray) -> PeriodStepper:
    """DOP853, compiled where `compiled_cover` allows, else scipy's on the numpy model.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerances of the state, shape (2 n,).

    Returns
    -------
    PeriodStepper
    """
    if compiled_cover(model) == "":
        return CompiledStepper(model, rtol, atol)
    return ExplicitStepper(model, rtol, atol)


def period_stepper(
    model: DiscreteModel, rtol: float, atol: np.ndarray, method: str = "auto"
) -> PeriodStepper:
    """The stepper of a classification run.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    rtol : float
        The classification's relative tolerance (Radau's; DOP853 runs at `EXPLICIT_TOL` times
        it and its absolute tolerances).
    atol : numpy.ndarray
        Absolute tolerances of the state, shape (2 n,).
    method : str
        "radau", "dop853" (`explicit_stepper`) or "auto" (`SwitchingStepper` of the two).

    Returns
    -------
    PeriodStepper

    Raises
    ------
    ValueError
        For another method.
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    atol = np.asarray(atol, dtype=float)
    if method == "radau":
        return ImplicitStepper(model, rtol, atol)
    explicit = explicit_stepper(model, EXPLICIT_TOL * rtol, EXPLICIT_TOL * atol)
    if method == "dop853":
        return explicit
    return SwitchingStepper(explicit, ImplicitStepper(model, rtol, atol), stiffest_rate(model))
