"""`rotbeam simulate`: one scene, dynamic beside quasi-static, with the verdict and its cost."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..config.errors import RotbeamInputError
from . import options, show
from .progress import bar

HELP = "dynamic and quasi-static response of one scene, and the verdict"
#: the steady state's share of the time budget that remains after `--effects auto`; the rest
#: is kept for the classification that follows when there is no stable steady state
STEADY_SHARE = 0.5


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam simulate`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    options.add_scene_flags(p, drive_frequency=True)
    options.add_field(p, "verdict", "threshold")
    options.add_criterion_flag(p)
    options.add_field(p, "response", "periods")
    options.add_field(p, "response", "N")
    p.add_argument("--out", help="write the time series to this CSV or Parquet file")
    p.add_argument("--plot", help="draw y_m, dynamic against quasi-static, with the verdict and "
                   "the cost, to this .png, .pdf or .svg file (without a stable periodic state: "
                   "the Poincare section and the spectrum)")  # fmt: skip
    p.add_argument("--observe", metavar="NAMES", help="also report these observables, "
                   "comma-separated: y_m, tip, root_moment, root_stress, tip_acceleration "
                   "(RMS, peaks and Delta RMS of each; a move also its residual)")  # fmt: skip
    options.add_uncertainty_flags(p)


def run(args: argparse.Namespace) -> int:
    """Parse, simulate, judge, print: RMS of both models, Delta RMS, the verdict and its cost,
    the response's class, and the time series and figure where asked for.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (`add_arguments`).

    Returns
    -------
    int
        Exit status: 0 where the dynamic run reached a steady state, 1 where not.

    Raises
    ------
    RotbeamInputError
        If a flag, the scene file or the uncertainty is not allowed, omega0 or f_d is missing,
        --criterion names no observable (or meets an uncertainty), or --out or --plot has a
        suffix that is not written.
    """
    threshold = options.option(args, "verdict", "threshold")
    periods, response_N = options.option(args, "response", "periods"), options.option(
        args, "response", "N")  # fmt: skip
    if args.out and Path(args.out).suffix not in (".csv", ".parquet"):
        raise RotbeamInputError(f"--out must end in .csv or .parquet, got {args.out!r}")
    options.check_plot_path(args.plot)
    observe = _observe(args)
    scene, tol, inputs = options.scene_request(args)
    criterion = options.criterion_request(args, inputs)
    if criterion != "y_m" and criterion not in observe:
        observe = (*observe, criterion)  # the criterion's numbers beside the verdict
    if not scene.drive.periodic:
        return _run_move(args, scene, threshold, tol, inputs, observe, criterion)

    from ..analysis.verdict import judge
    from ..runs.response import response_of_result
    from ..runs.scene import simulate
    from ..solve.timebudget import TimeBudget

    time_budget = TimeBudget(scene.numerics.max_seconds)  # the whole command's
    summary = {}
    if tol is not None:
        from ..analysis.effect_budget import auto_scene

        scene, auto, budget = auto_scene(scene, tol, time_budget)
        summary["effects_auto"] = show.auto_dict(auto, budget, scene.drive.f_d)
    with bar(args, "time stepping", "period") as b:

        def period(k: int, bound: float) -> None:
            b.update(1)
            b.set_postfix_str(f"transient bound {bound:.2e}")

        res = simulate(scene, progress=period, time_budget=time_budget.part(STEADY_SHARE))
    verdict = judge(res, threshold, criterion)
    with bar(args, f"response (N = {response_N})", "period", 2 * periods) as b:

        def classified_period(done: int, total: int) -> None:
            b.update(1)

        columns, classified = response_of_result(res, response_N, periods, classified_period,
                                                 time_budget)  # fmt: skip
    summary = res.summary() | verdict.as_dict() | columns | summary
    summary["classification_seconds"] = classified.seconds if classified is not None else 0.0
    prop = None
    if inputs:
        from ..analysis.uncertainty import simulate_spread

        prop = simulate_spread(scene, res, inputs, args.uq_method, args.uq_samples, threshold,
                               time_budget)  # fmt: skip
        summary["uncertainty"] = prop.as_dict()
    if observe:
        summary["observables"] = res.observables(observe)
    if args.out:
        from ..report.io import write_series

        write_series(args.out, res.time_series())
    if args.plot:
        _plot(args.plot, res, verdict, classified)
    if args.json:
        show.as_json(summary)
    else:
        _print(summary, verdict, prop)
        _print_observables(summary.get("observables"))
    return 0 if res.converged else 1


def _observe(args: argparse.Namespace) -> tuple[str, ...]:
    """The observables --observe asks for, checked (none without the flag)."""
    if args.observe is None:
        return ()
    from ..runs.observables import observable_names

    return observable_names(args.observe)


def _print_observables(table: dict | None) -> None:
    """A small table of the observables: one row per name, its unit and numbers."""
    if not table:
        return
    columns = [k for k in next(iter(table.values())) if k != "unit"]
    print(f"{'observable':{show.WIDTH}s} {'unit':6s} " + " ".join(f"{c:>16s}" for c in columns))
    for name, row in table.items():
        cells = " ".join(f"{row[c]:16.6g}" for c in columns)
        print(f"{name:{show.WIDTH}s} {row['unit']:6s} {cells}")


def _print(summary: dict, verdict, prop) -> None:
    show.values(summary, ("rms_dynamic", "rms_quasistatic", "delta_rms", "f_n_hz", "f0_hz",
                          "C_max", "E_max"))  # fmt: skip
    show.line("converged", f"{summary['converged']} ({summary['message']})")
    show.line("verdict", verdict.text)
    if summary["response"] != "periodic" or "response_message" in summary:
        show.line("response", summary.get("response_message", summary["response"]))
    if "effects_auto" in summary:
        show.auto_effects(summary["effects_auto"])
    seconds = f"{summary['seconds']:.3g}"
    if summary["classification_seconds"]:
        seconds += f" (+ {summary['classification_seconds']:.3g} classifying the response)"
    show.line("seconds", seconds)
    if prop is not None:
        show.uncertainty(prop)


def _plot(path: str, res, verdict, classified) -> None:
    """The verdict's figure, or without a stable periodic state the classification's."""
    if classified is not None:
        from ..report.response_figures import plot_response

        plot_response(classified, res.scene, path)
    else:
        from ..report.verdict_plot import plot_verdict

        plot_verdict(res, verdict, path)


def _run_move(args: argparse.Namespace, scene, threshold: float, tol, inputs, observe=(),
              criterion: str = "y_m") -> int:  # fmt: skip
    """`rotbeam simulate --move`: the move, its verdict, its numbers, its figure."""
    if tol is not None or inputs:
        raise RotbeamInputError(
            "a move takes neither --effects auto nor --uncertainty (both rest on steady states)"
        )
    from ..analysis.verdict import judge_move
    from ..runs.move import simulate_move

    with bar(args, "move and settling", "ms") as b:
        reached = [0]

        def advanced(done_s: float, planned_s: float) -> None:
            b.total = round(1e3 * planned_s)  # the settling window ends early once calm
            b.update(round(1e3 * done_s) - reached[0])
            reached[0] = round(1e3 * done_s)

        res = simulate_move(scene, progress=advanced)
    verdict = judge_move(res, threshold, criterion)
    summary = res.summary() | verdict.as_dict()
    if observe:
        summary["observables"] = res.observables(observe)
    if args.out:
        from ..report.io import write_series

        write_series(args.out, res.time_series())
    if args.plot:
        from ..report.verdict_plot import plot_move

        plot_move(res, verdict, args.plot)
    if args.json:
        show.as_json(summary)
        return 0 if res.converged else 1
    show.values(summary, ("peak_ym", "peak_ym_quasistatic", "rms_dynamic", "rms_quasistatic",
                          "delta_rms", "residual_ym", "settling_time_s"))  # fmt: skip
    show.line("converged", f"{res.converged} ({res.message})")
    show.line("verdict", verdict.text)
    show.line("seconds", f"{res.seconds:.3g}")
    _print_observables(summary.get("observables"))
    return 0 if res.converged else 1
