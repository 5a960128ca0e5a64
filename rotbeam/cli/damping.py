"""`rotbeam damping`: gamma from a ring-down record."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from . import options, show

if TYPE_CHECKING:
    from ..runs.scene import Scene

HELP = ("gamma from a ring-down (columns t [s], y): fit of a damped oscillation, gamma = 2 rho A "
        "/ t_decay")  # fmt: skip


class FitRejected(Exception):
    """A calibration fit the data do not support (one line, exit status 1)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam damping`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    p.add_argument("file", help="CSV with columns t and y")
    p.add_argument("--scene", help="YAML scene file whose beam section gives rho A")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", help="draw the record and the fit to this .png, .pdf or .svg")


def scene_beam(path: str | None) -> Scene:
    """The scene of a --scene file (its drive and effects as given, the rest defaults).

    Parameters
    ----------
    path : str or None
        The YAML scene file; None: the default scene (Table 1 beam).

    Returns
    -------
    Scene
        The scene; its `uncertainty` section and `effects: auto` are not read.

    Raises
    ------
    RotbeamInputError
        If the file cannot be read or a value is not allowed.
    """
    from ..config.scenefile import load_scene_file, scene_sections, split_auto
    from ..runs.scene import build_scene

    raw = dict(load_scene_file(path)) if path else {}
    raw.pop("uncertainty", None)
    return build_scene(scene_sections(split_auto(raw)[0]))


def run(args: argparse.Namespace) -> int:
    """Parse, fit, print: frequency, decay time, gamma, amplitude and offset with standard
    errors, zeta, rho A and the fit's quality; the figure with --plot.

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
        If the file, the scene or --plot's suffix is not allowed.
    FitRejected
        If the record cannot carry the fit (the message says why).
    """
    from ..analysis.measurements import load_ringdown

    options.check_plot_path(args.plot)
    beam = scene_beam(args.scene).beam
    data = load_ringdown(args.file)  # a bad file fails here, before scipy.signal is loaded
    from ..analysis.ringdown import RingdownRejected, fit_ringdown

    try:
        fit = fit_ringdown(data, beam)
    except RingdownRejected as exc:
        raise FitRejected(f"{args.file}: {exc}") from None
    if args.plot:
        from ..report.calibration_plots import plot_ringdown

        plot_ringdown(data, fit, args.plot)
    out = fit.as_dict()
    if args.json:
        show.as_json(out)
        return 0
    for k in ("f_hz", "t_decay", "gamma", "amplitude", "offset"):
        show.line(k, f"{out[k]:.6g} +- {out[k + '_stderr']:.2g}")
    show.line("zeta", f"{fit.zeta:.4g}")
    show.line("rhoA", f"{fit.rhoA:.6g} kg/m (beam of the scene)")
    show.line("snr", f"{fit.snr:.3g} ({fit.cycles:.3g} cycles, {fit.points} samples)")
    return 0
