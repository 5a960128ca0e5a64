"""`rotbeam identify`: beam parameters (default E, gamma) from a measured resonance curve."""

from __future__ import annotations

import argparse
from dataclasses import replace

from ..config.errors import RotbeamInputError
from . import options, show
from .damping import FitRejected, scene_beam
from .progress import bar

HELP = ("beam parameters (default E, gamma) from a measured resonance curve (columns f_d [Hz], "
        "rms[, rms_std])")  # fmt: skip


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam identify`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    p.add_argument("--measured", required=True, help="CSV with columns f_d, rms[, rms_std]")
    p.add_argument("--omega0", type=options.finite, required=True,
                   help="Omega_0 of the measurement [rad/s]")  # fmt: skip
    p.add_argument("--amplitude", type=options.finite,
                   help="velocity amplitude a [rad/s] (default the scene's, 1)")  # fmt: skip
    p.add_argument("--fit", default="E,gamma", help="comma list of beam fields to fit "
                   "(L, h, b, E, rho, R, gamma; default E,gamma)")  # fmt: skip
    p.add_argument("--scene", help="YAML scene file: the beam to start from, effects, numerics")
    p.add_argument("--N", type=options.integer, help="grid intervals of the fit (default 20)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", help="draw data, fitted and scene-beam curves (.png, .pdf, .svg)")


def run(args: argparse.Namespace) -> int:
    """Parse, fit, print: each fitted value with its standard error, 95 % interval and start,
    the residual, the cost; the figure with --plot.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (`add_arguments`).

    Returns
    -------
    int
        Exit status: 0 where the least squares converged, 1 where not.

    Raises
    ------
    RotbeamInputError
        If the file, the scene, --fit, --N, --amplitude or --plot's suffix is not allowed.
    FitRejected
        If the fit cannot be carried out (a run without a steady state, a beam out of range).
    """
    from ..analysis.identify import FIT_NUMERICS, IdentifyFailed, identify, parse_names
    from ..analysis.measurements import load_resonance
    from ..config.scenefile import load_scene_file

    options.check_plot_path(args.plot)
    names = parse_names(args.fit)
    scene = scene_beam(args.scene)
    numerics = FIT_NUMERICS
    if args.scene and "numerics" in load_scene_file(args.scene):
        numerics = scene.numerics
    if args.N is not None:
        try:
            numerics = replace(numerics, N=args.N)
        except RotbeamInputError as exc:
            raise RotbeamInputError(f"argument --N: {exc}") from None
    amplitude = scene.drive.amplitude if args.amplitude is None else args.amplitude
    if args.amplitude is not None and not args.amplitude > 0:
        raise RotbeamInputError(f"argument --amplitude: must be > 0, got {args.amplitude!r}")
    curve = load_resonance(args.measured, len(names))
    try:
        with bar(args, "fit", "steady state") as b:
            res = identify(curve, args.omega0, amplitude, names, scene.beam, scene.effects,
                           numerics, progress=b.update)  # fmt: skip
    except IdentifyFailed as exc:
        raise FitRejected(str(exc)) from None
    out = res.as_dict() | {"omega0": args.omega0, "amplitude": amplitude, "N": numerics.N,
                           "extrapolate": numerics.extrapolate}  # fmt: skip
    if args.plot:
        from ..report.calibration_plots import plot_identification_run

        plot_identification_run(curve, res, scene, args.omega0, amplitude, numerics, args.plot)
    if args.json:
        show.as_json(out)
        return 0 if res.success else 1
    for n in names:
        show.line(n, f"{res.values[n]:.6g} +- {res.stderr[n]:.2g}  95 %: "
                  f"[{res.low[n]:.6g}, {res.high[n]:.6g}]  (start {res.start[n]:.4g})")  # fmt: skip
    show.line("residual", f"RSS {res.rss:.3g}, {res.dof} dof, scale {res.scale:.3g}")
    show.line("evaluations", f"{res.evaluations} ({res.runs} steady states, N = "
              f"{numerics.N}{' + Richardson' if numerics.extrapolate else ''})")  # fmt: skip
    show.line("seconds", f"{res.seconds:.3g}")
    show.line("converged", f"{res.success} ({res.message})")
    return 0 if res.success else 1
