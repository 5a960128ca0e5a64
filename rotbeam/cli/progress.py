"""Progress a person sees: a tqdm bar on stderr for work that can take more than a couple of
seconds, off with --quiet and when stderr is not a terminal (stdout and its JSON stay clean)."""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any


def add_quiet_flag(p: argparse.ArgumentParser) -> None:
    """--quiet: no progress bar.

    Parameters
    ----------
    p : argparse.ArgumentParser
        A command's parser.
    """
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")


def shown(args: argparse.Namespace) -> bool:
    """Whether progress is drawn: not --quiet, and stderr is a terminal.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags.

    Returns
    -------
    bool
    """
    return not getattr(args, "quiet", False) and sys.stderr.isatty()


def bar(args: argparse.Namespace, desc: str, unit: str, total: int | None = None) -> Any:
    """A progress bar on stderr (tqdm), or a stand-in that draws nothing.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (--quiet).
    desc : str
        What the bar counts.
    unit : str
        Its unit ("run", "period").
    total : int or None
        How many there are (None: a counter).

    Returns
    -------
    object
        A context manager with update(n), set_postfix_str(text) and write(text).
    """
    if not shown(args):
        return _Silent()
    from tqdm import tqdm  # here: a run without a terminal never loads it

    columns, lines = _size()
    # every update is drawn (mininterval 0): a step can take less than tqdm's default 0.1 s
    # between draws (a compiled classification period: 0.05 s), and the last count must show
    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, leave=False, ncols=columns,
                nrows=lines, mininterval=0)  # fmt: skip


def _size() -> tuple[int, int]:
    """The terminal's columns and lines, 80 x 24 where it reports none (a bare pseudo-terminal:
    tqdm would draw a zero-width bar and hide it below a zero-height screen)."""
    try:
        size = os.get_terminal_size(sys.stderr.fileno())
        columns, lines = size.columns, size.lines
    except OSError:
        columns = lines = 0
    return (columns if columns > 0 else 80), (lines if lines > 0 else 24)


class _Silent:
    """A progress bar that draws nothing (--quiet, or stderr not a terminal)."""

    def __enter__(self) -> _Silent:
        return self

    def __exit__(self, *exc: object) -> None:
        return None

    def update(self, n: int = 1) -> None:
        """Nothing to draw."""

    def set_postfix_str(self, text: str) -> None:
        """Nothing to draw."""

    def write(self, text: str) -> None:
        """A bench line still goes to stderr."""
        print(text, file=sys.stderr, flush=True)
