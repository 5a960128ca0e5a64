"""`rotbeam critical`: f_d*, the drive frequency where Delta RMS reaches the threshold at one
speed, by root finding on the full model."""

from __future__ import annotations

import argparse
from dataclasses import replace

from . import options, show
from .progress import bar

HELP = ("f_d*: the drive frequency where Delta RMS reaches the threshold at one speed (root "
        "finding on the full model)")  # fmt: skip


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam critical`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    options.add_scene_flags(p, drive_frequency=False)
    options.add_field(p, "verdict", "threshold")
    options.add_criterion_flag(p)
    options.add_field(p, "critical", "ftol")
    options.add_uncertainty_flags(p)


def run(args: argparse.Namespace) -> int:
    """Parse, search, print: f_d* of the full model, c = f_d* / f_0, f_0 and the search's cost,
    with the chosen effects and the uncertainty's spread where asked for.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (`add_arguments`).

    Returns
    -------
    int
        Exit status: 0 where f_d* was found, 1 where not (the message says why).

    Raises
    ------
    RotbeamInputError
        If a flag, the scene file or the uncertainty is not allowed, omega0 is missing, or
        --criterion names no observable (or meets an uncertainty).
    """
    threshold = options.option(args, "verdict", "threshold")
    ftol = options.option(args, "critical", "ftol")
    scene, tol, inputs = options.scene_request(args, needs=("omega0",))
    criterion = options.criterion_request(args, inputs)

    from ..analysis.verdict import critical, critical_start_hz
    from ..runs.scene import model_name
    from ..solve.timebudget import TimeBudget

    time_budget = TimeBudget(scene.numerics.max_seconds)  # the whole command's
    out = {}
    if tol is not None:  # the budget at the search's first guess, the linear estimate
        from ..analysis.effect_budget import auto_scene

        f_start = critical_start_hz(scene, threshold)
        scene, auto, budget = auto_scene(replace(scene, drive=replace(scene.drive, f_d=f_start)),
                                         tol, time_budget)  # fmt: skip
        out["effects_auto"] = show.auto_dict(auto, budget, f_start)
    with bar(args, "f_d* search", "run") as b:
        res = critical(scene, threshold, ftol, progress=b.update, time_budget=time_budget,
                       criterion=criterion)  # fmt: skip
    out = res.as_dict() | {"omega0": scene.drive.mean_speed, "amplitude": scene.drive.swing,
                           "N": scene.numerics.N, "model": model_name(scene.numerics),
                           "effects": ",".join(scene.effects.active())} | out  # fmt: skip
    prop = None
    if inputs:
        from ..analysis.uncertainty import critical_spread

        prop = critical_spread(scene, res, inputs, args.uq_method, args.uq_samples, threshold,
                               ftol, time_budget)  # fmt: skip
        out["uncertainty"] = prop.as_dict()
    if args.json:
        show.as_json(out)
        return 0 if res.found else 1
    show.line("f_d_star_hz", f"{res.f_d_star:.6g}")
    show.line("c = f_d*/f_0", f"{res.f_d_star / res.f0_hz:.4g}")
    show.line("f0_hz", f"{res.f0_hz:.6g}")
    show.line("estimate_hz", f"{res.estimate_hz:.6g} (linear, where the search started)")
    show.line("found", f"{res.found} ({res.message})")
    if criterion != "y_m":
        show.line("criterion", f"Delta RMS of {criterion}")
    show.line("evaluations", f"{len(res.visited)}")
    if "effects_auto" in out:
        show.auto_effects(out["effects_auto"])
    show.line("seconds", f"{res.seconds:.3g}")
    if prop is not None:
        show.uncertainty(prop)
    return 0 if res.found else 1
