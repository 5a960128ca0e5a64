"""`rotbeam <command>`: the parser of every command and the dispatch; bad input gives one line
on stderr and exit status 2, never a traceback."""

from __future__ import annotations

import os

#: BLAS and OpenMP thread counts a command runs with unless its caller set them: the matrices
#: are small (n <= 2 N), and a second thread only adds overhead (a sweep is 8.6x slower with
#: OpenBLAS' default threads on a busy 2-core machine).  Set before numpy loads OpenBLAS.
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS",
                    "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")  # fmt: skip
for _name in THREAD_VARIABLES:
    os.environ.setdefault(_name, "1")

import argparse  # noqa: E402
import importlib  # noqa: E402
import sys  # noqa: E402

from ..config.errors import RotbeamInputError  # noqa: E402
from . import options  # noqa: E402
from .progress import add_quiet_flag  # noqa: E402

#: command -> module of rotbeam.cli that parses and runs it
COMMANDS = {
    "simulate": "simulate",
    "sweep": "sweep",
    "critical": "critical",
    "effects": "effects",
    "modes": "modes",
    "bench": "bench",
    "damping": "damping",
    "identify": "identify",
    "atlas": "atlas",
    "design-move": "design",
}

#: exit status of a fit that ran but cannot be trusted (the message says why)
EXIT_REJECTED = 1


def version() -> str:
    """The installed package's version."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("rotbeam")
    except PackageNotFoundError:  # pragma: no cover - a source tree that was never installed
        return "0+unknown"


def build_parser() -> argparse.ArgumentParser:
    """The `rotbeam` parser with every command's flags."""
    p = options.Parser(prog="rotbeam", description="Dynamic versus quasi-static response of a "
                       "cantilevered beam on a rotating disk.")  # fmt: skip
    p.add_argument("--version", action="version", version=f"rotbeam {version()}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=options.Parser)
    for name, module in COMMANDS.items():
        mod = importlib.import_module(f".{module}", __package__)
        command = sub.add_parser(name, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(command)
        add_quiet_flag(command)
    return p


def main(argv: list[str] | None = None) -> int:
    """Run one command; its exit status (0 done, 1 no answer or a rejected fit, 2 bad input).

    Bad input gives one line on stderr naming the flag, never a traceback.

    Parameters
    ----------
    argv : list of str or None
        The arguments after `rotbeam`; None: ``sys.argv[1:]``.

    Returns
    -------
    int
        0 done, 1 no answer (a scene whose loads fold the beam) or a rejected fit, 2 bad input,
        130 interrupted.

    Raises
    ------
    SystemExit
        With status 2 for a flag argparse rejects (one line on stderr), 0 after --help or
        --version.
    """
    args = build_parser().parse_args(argv)
    run = importlib.import_module(f".{COMMANDS[args.command]}", __package__).run
    from ..solve.quasistatic import QuasiStaticError
    from .damping import FitRejected

    try:
        return run(args)
    except RotbeamInputError as exc:
        print(f"rotbeam: error: {options.named_flag(str(exc), args)}", file=sys.stderr)
        return options.EXIT_USAGE
    except QuasiStaticError as exc:  # no equilibrium: the scene's loads fold the beam
        print(f"rotbeam: no answer: {exc}", file=sys.stderr)
        return EXIT_REJECTED
    except FitRejected as exc:
        print(f"rotbeam: fit rejected: {exc}", file=sys.stderr)
        return EXIT_REJECTED
    except KeyboardInterrupt:
        print("rotbeam: interrupted", file=sys.stderr)
        return 130
