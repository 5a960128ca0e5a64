"""`rotbeam bench`: the work-precision benchmark (error against wall time)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..config.errors import RotbeamInputError
from . import options
from .progress import bar

HELP = "work-precision benchmark (error against wall time)"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam bench`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    p.add_argument("--quick", action="store_true", help="the small plan (2 scenes, 2 tolerances)")
    p.add_argument("--config", help="YAML mapping of BenchPlan fields (see rotbeam/bench/plan.py)")
    p.add_argument("--out", default="results/performance/work_precision",
                   help="output stem: writes STEM.csv, .md, .pdf, .png")  # fmt: skip
    p.add_argument("--max-seconds", type=options.finite, help="budget per run [s], > 0")


def run(args: argparse.Namespace) -> int:
    """Parse the plan, run it, write the outputs (progress on stderr).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (`add_arguments`).

    Returns
    -------
    int
        Exit status 0.

    Raises
    ------
    RotbeamInputError
        If --config cannot be read or holds no mapping, --max-seconds is not > 0, or the plan is
        out of range.
    """
    from ..bench.plan import plan_from_dict
    from ..bench.report import write_outputs
    from ..bench.run import run_benchmark
    from ..config.scenefile import load_yaml

    spec: dict[str, Any] = {}
    if args.config:
        try:
            spec = load_yaml(Path(args.config).read_text()) or {}
        except OSError as exc:
            raise RotbeamInputError(f"--config {args.config!r}: {exc.strerror}") from None
        if not isinstance(spec, dict):
            raise RotbeamInputError(f"--config {args.config!r} must hold a mapping")
    if args.quick:
        spec["quick"] = True
    if args.max_seconds is not None:
        if args.max_seconds <= 0:
            raise RotbeamInputError(f"--max-seconds must be > 0, got {args.max_seconds}")
        spec["max_seconds"] = args.max_seconds
    plan = plan_from_dict(spec)

    with bar(args, "benchmark", "run") as b:

        def say(msg: str) -> None:
            b.write(msg)
            b.update(1)

        runs, refs = run_benchmark(plan, progress=say)
        write_outputs(runs, refs, plan, args.out)
    print(f"wrote {args.out}.csv, .md, .pdf, .png", file=sys.stderr, flush=True)
    return 0
