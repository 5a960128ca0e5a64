"""A wall-time budget that every phase of one command shares, and the deadline a phase's
solvers check while a budget watches them."""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field


class OutOfTime(Exception):
    """Raised inside a solver when the wall-time budget is spent."""


#: the deadline (`time.perf_counter` value) of the budget watching the current phase, if any
_WATCHED: ContextVar[float | None] = ContextVar("rotbeam_deadline", default=None)


def check_deadline() -> None:
    """Raise `OutOfTime` when a budget watches this phase (`TimeBudget.watch`) and is spent.

    The solvers without a time stepper of their own (the collocation's Newton steps, the
    Floquet pass) call it between their steps; outside a watch it does nothing.

    Raises
    ------
    OutOfTime
        When the watching budget's deadline has passed.
    """
    deadline = _WATCHED.get()
    if deadline is not None and time.perf_counter() >= deadline:
        raise OutOfTime


@dataclass(frozen=True)
class TimeBudget:
    """`seconds` of wall time from `start` (a `time.perf_counter` value).

    One budget bounds a whole command: the steady state, Richardson's second grid, the
    response classification, the effect budget's runs, the critical search and a sweep all draw
    on it, so that a command ends near its `numerics.max_seconds` whatever its phases.

    Parameters
    ----------
    seconds : float
        The budget [s], > 0.
    start : float
        When it began (`time.perf_counter`; default: now).
    whole : float or None
        The budget [s] of the command this one is a part of (`part`), for the messages.
    """

    seconds: float
    start: float = field(default_factory=time.perf_counter)
    whole: float | None = None

    @property
    def deadline(self) -> float:
        """The `time.perf_counter` value at which the budget is spent."""
        return self.start + self.seconds

    def elapsed(self) -> float:
        """Seconds since the budget began."""
        return time.perf_counter() - self.start

    def remaining(self) -> float:
        """Seconds left (0 once spent)."""
        return max(0.0, self.deadline - time.perf_counter())

    def spent(self) -> bool:
        """Whether the deadline has passed."""
        return time.perf_counter() >= self.deadline

    def part(self, share: float) -> TimeBudget:
        """A budget of its own for one phase: `share` (0 to 1) of what remains.

        Parameters
        ----------
        share : float
            The phase's share of the remaining time.

        Returns
        -------
        TimeBudget
            Starting now, `share` times the remaining seconds long.
        """
        return TimeBudget(share * self.remaining(), whole=self.whole or self.seconds)

    def cut(self, phase: str) -> str:
        """The words for a phase the budget cut short.

        Parameters
        ----------
        phase : str
            What was cut, e.g. "the time stepping at N = 40".

        Returns
        -------
        str
            "the time budget of S s cut <phase> after E s" (for a part: "the time budget (S s of
            the command's W s) cut ...").
        """
        size = f"of {self.seconds:.3g} s"
        if self.whole is not None:
            size = f"({self.seconds:.3g} s of the command's {self.whole:.3g} s)"
        return f"the time budget {size} cut {phase} after {self.elapsed():.3g} s"

    @contextmanager
    def watch(self) -> Iterator[TimeBudget]:
        """Within the block, `check_deadline` raises `OutOfTime` once this budget is spent.

        Yields
        ------
        TimeBudget
            This budget.
        """
        token = _WATCHED.set(self.deadline)
        try:
            yield self
        finally:
            _WATCHED.reset(token)
