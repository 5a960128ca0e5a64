"""One time stepper: a scipy ODE solver driven over an interval, sampled at given instants.

`IvpInterval` is what every time-stepped run of `rotbeam.solve` and `rotbeam.runs` calls: the
steady-state march (`rotbeam.solve.steady`), the classification's Radau and scipy DOP853
steppers (`rotbeam.solve.stepping`, `rotbeam.solve.lyapunov`) and a single move
(`rotbeam.runs.move`).  It steps a `scipy.integrate.OdeSolver` from ta to tb, samples the state
at the instants asked for by the interpolant of the step that ends at or after each (the rule of
`solve_ivp`'s t_eval), counts the right-hand side and Jacobian evaluations and the steps, and
says why it stopped short: the solver's failure, a state that is not finite, or the wall-time
deadline (`OutOfTime` from the right-hand side).  The samples are returned instants first,
shape (m, dim), the package's one convention (docs/numerics.md, "Array shapes"): the solver's
dense output, states in columns, is turned here and nowhere else.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .timebudget import OutOfTime

REACHED = 0  #: `Stepped.status`: the solver reached tb
FAILED = -1  #: the solver failed, or the state is not finite
CUT = 1  #: the wall-time deadline stopped it (`OutOfTime`)


@dataclass
class Stepped:
    """What one `IvpInterval.run` stepped."""

    t: np.ndarray  #: the instants sampled (those the solver reached), shape (m,)
    y: np.ndarray  #: the state at them, shape (m, dim)
    end: np.ndarray  #: the solver's state where it stopped (at tb when `status` is REACHED)
    status: int  #: REACHED, FAILED or CUT
    message: str  #: '' when it reached tb, else why not
    nfev: int  #: right-hand-side evaluations
    njev: int  #: Jacobian evaluations
    steps: int  #: accepted steps


class IvpInterval:
    """An initial-value problem y' = fun(t, y), stepped over one interval a call by a scipy
    `OdeSolver`; counts its evaluations and steps over all calls.

    Parameters
    ----------
    fun : callable
        fun(t, y) -> y', shape (dim,); it may raise `OutOfTime` past a deadline.
    method : str or type
        The name of a scipy solver ("Radau", "BDF", "LSODA", "DOP853", "RK45", "RK23") or an
        `OdeSolver` class (`rotbeam.solve.trbdf2.TRBDF2`).
    rtol : float
        Relative tolerance.
    atol : float or numpy.ndarray
        Absolute tolerances, scalar or shape (dim,).
    jac : callable or None
        The Jacobian of `fun` (implicit methods); None: the solver's own.

    Attributes
    ----------
    nfev, njev, steps : int
        Right-hand-side and Jacobian evaluations and accepted steps over every call.
    last : Stepped or None
        What the last call stepped.
    """

    def __init__(
        self,
        fun: Callable[[float, np.ndarray], np.ndarray],
        method: str | type,
        rtol: float,
        atol: float | np.ndarray,
        jac: Callable[[float, np.ndarray], np.ndarray] | None = None,
    ) -> None:
        self.fun, self.method, self.rtol, self.atol = fun, method, rtol, atol
        self.options = {} if jac is None else {"jac": jac}
        self.nfev = self.njev = self.steps = 0
        self.last: Stepped | None = None

    def run(
        self,
        ta: float,
        tb: float,
        y: np.ndarray,
        t_eval: np.ndarray | None = None,
        rtol: float | None = None,
        atol: float | np.ndarray | None = None,
    ) -> Stepped:
        """Step from y at ta to tb (ta < tb), sampling the state at t_eval.

        Never raises for a solver failure or the deadline: the result's status and message say
        where it stopped.  A sample is the interpolant of the step that ends at or after its
        instant (a sample at tb is the interpolant's value there, `Stepped.end` the solver's).

        Parameters
        ----------
        ta, tb : float
            The interval.
        y : numpy.ndarray
            The state at ta, shape (dim,).
        t_eval : numpy.ndarray or None
            Increasing instants in [ta, tb] to sample; None: none.
        rtol : float or None
            Relative tolerance of this call; None: the interval's.
        atol : float or numpy.ndarray or None
            Absolute tolerances of this call; None: the interval's.

        Returns
        -------
        Stepped
            The samples, the state where it stopped, the status and message, and what the call
            cost.
        """
        instants = np.zeros(0) if t_eval is None else np.asarray(t_eval, dtype=float)
        ts, ys, done, steps = [], [], 0, 0
        solver, status, message = None, REACHED, ""
        try:
            solver = self._solver(ta, tb, y, rtol, atol)
            while solver.status == "running":
                why = solver.step()
                if solver.status == "failed":
                    status, message = FAILED, why
                    break
                steps += 1
                done = _sample(solver, instants, done, ts, ys)
        except OutOfTime:
            at = ta if solver is None else solver.t
            status, message = CUT, f"the wall-time deadline passed at t = {at:.6g}"
        out = _stepped(solver, y, ts, ys, status, message, steps)
        self.nfev += out.nfev
        self.njev += out.njev
        self.steps += out.steps
        self.last = out
        return out

    def __call__(
        self, ta: float, tb: float, y: np.ndarray, t_eval: np.ndarray | None
    ) -> tuple[np.ndarray, np.ndarray | None, str]:
        """One interval as a `rotbeam.solve.lyapunov.IntervalStep`.

        Parameters
        ----------
        ta, tb : float
            The interval.
        y : numpy.ndarray
            The state (z, v) at ta, shape (dim,).
        t_eval : numpy.ndarray or None
            Instants from ta to tb (the last is tb) at which the first half of y is wanted.

        Returns
        -------
        y : numpy.ndarray
            The solver's state at tb (where it stopped on a failure).
        samples : numpy.ndarray or None
            y[:dim // 2] at t_eval[:-1], shape (t_eval.size - 1, dim // 2); None without
            t_eval or on a failure.
        message : str
            '' on success, else why the step failed.
        """
        out = self.run(ta, tb, y, None if t_eval is None else t_eval[:-1])
        if out.status != REACHED or t_eval is None:
            return out.end, None, out.message
        return out.end, out.y[:, : y.size // 2], ""

    def _solver(self, ta, tb, y, rtol, atol):
        """The scipy solver of this call, at its first instant."""
        import scipy.integrate  # here: only a time-stepped run needs it (0.2 s of start-up)

        method = (
            getattr(scipy.integrate, self.method) if isinstance(self.method, str) else self.method
        )
        return method(self.fun, float(ta), y, float(tb),
                      rtol=self.rtol if rtol is None else rtol,
                      atol=self.atol if atol is None else atol, **self.options)  # fmt: skip


def _sample(solver, instants: np.ndarray, done: int, ts: list, ys: list) -> int:
    """Sample the instants the solver's last step reached (those up to its end, after the
    `done` already sampled) by its interpolant; the count sampled so far."""
    reach = int(np.searchsorted(instants, solver.t, side="right"))
    if reach > done:
        ts.append(instants[done:reach])
        ys.append(solver.dense_output()(instants[done:reach]).T)  # (dim, k) -> (k, dim)
    return reach


def _stepped(solver, y, ts: list, ys: list, status: int, message: str, steps: int) -> Stepped:
    """A call's result from its solver (None: the deadline passed before its first step)."""
    t = np.hstack(ts) if ts else np.zeros(0)
    samples = np.vstack(ys) if ys else np.zeros((0, np.size(y)))
    if solver is None:
        return Stepped(t, samples, np.asarray(y, dtype=float), status, message, 0, 0, 0)
    end = solver.y
    if status == REACHED and not (np.all(np.isfinite(end)) and np.all(np.isfinite(samples))):
        status, message = FAILED, "the state is not finite"
    return Stepped(t, samples, end, status, message, solver.nfev, solver.njev, steps)
