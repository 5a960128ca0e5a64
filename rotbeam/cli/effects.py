"""`rotbeam effects`: each effect's share of RMS(y_m) and of Delta RMS at one scene."""

from __future__ import annotations

import argparse

from ..config.errors import RotbeamInputError
from . import options, show
from .progress import bar

HELP = ("each effect's share of RMS(y_m) and of Delta RMS at one scene, by switching it off "
        "(or on), and what each costs")  # fmt: skip


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam effects`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    options.add_scene_flags(p, drive_frequency=True)


def run(args: argparse.Namespace) -> int:
    """Parse, budget, print: each effect's share of RMS(y_m) and of Delta RMS, how it was
    measured and its cost, and the sequential shares.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (`add_arguments`).

    Returns
    -------
    int
        Exit status: 0, or 1 where the scene has no steady state (or no deflection) to share.

    Raises
    ------
    RotbeamInputError
        If a flag or the scene file is not allowed, or omega0 or f_d is missing.
    """
    scene, tol, _ = options.scene_request(args)
    if tol is not None:
        raise RotbeamInputError(
            "effects: auto: rotbeam effects computes the budget that auto reads; allowed: a "
            "list of effects the budget starts from (--effects centrifugal,euler or the scene "
            "file's effects section)"
        )

    from ..analysis.effect_budget import effect_budget

    with bar(args, "effect budget", "run") as b:
        budget = effect_budget(scene, progress=b.update)
    if args.json:
        show.as_json(budget.as_dict())
        return 0 if budget.shares else 1
    print(f"RMS(y_m)/L {budget.rms:.6g}, Delta RMS {budget.delta_rms:.4g} "
          f"({budget.seconds:.3g} s)")  # fmt: skip
    if not budget.shares:
        print("no steady state (or no deflection) to share out")
        return 1
    print(f"{'effect':12s} {'in scene':8s} {'measured by':22s} {'share RMS':>10s} "
          f"{'share Delta':>11s} {'seconds':>8s}")  # fmt: skip
    for r in budget.shares:
        print(f"{r.effect:12s} {'on' if r.on_in_scene else 'off':8s} {r.method:22s} "
              f"{r.share_rms:+10.4f} {r.share_delta:+11.4f} {r.seconds:8.3g}"
              + (f"  ({r.note})" if r.note else ""))  # fmt: skip
    order = " -> ".join(f"{k} {v:+.4f}" for k, v in budget.sequential.items())
    print(f"sequential shares (switched off in turn; they add to 1): {order}")
    print(f"total {budget.total_seconds:.3g} s")
    return 0
