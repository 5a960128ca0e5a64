"""`rotbeam modes`: natural frequencies of the beam turning steadily."""

from __future__ import annotations

import argparse

from ..config.errors import RotbeamInputError
from . import options, show

HELP = "natural frequencies under steady rotation"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The flags of `rotbeam modes`.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser; the flags are added to it.
    """
    p.add_argument("--scene", help="YAML scene file whose beam section is the beam")
    options.add_section(p, "beam")
    options.add_field(p, "modes", "omega")
    options.add_field(p, "modes", "count")
    options.add_field(p, "numerics", "N")
    p.add_argument("--no-softening", action="store_true", help="flapwise (no in-plane softening)")
    p.add_argument("--dimensionless", action="store_true", help="answer for the unit beam")
    p.add_argument("--hub-ratio", type=options.finite, default=0.0,
                   help="R_o / L (with --dimensionless; default 0, >= 0)")  # fmt: skip
    p.add_argument("--lambda", dest="lam", type=options.finite, default=0.0,
                   help="Omega T (with --dimensionless; default 0)")  # fmt: skip
    p.add_argument("--json", action="store_true", help="print one JSON object")


def run(args: argparse.Namespace) -> int:
    """Parse, solve the eigenproblem, print the first frequencies [Hz] (or, with
    --dimensionless, in units of 1/T).

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
        If a flag or the scene file is not allowed, --k is not below N, or the rotation is
        beyond the model's range of C.
    """
    from ..model.modes import dimensionless_frequencies, modes
    from ..model.params import BETA1, C_MAX_LIMIT

    N = options.option(args, "numerics", "N")
    count = options.option(args, "modes", "count")
    if not count < N:
        raise RotbeamInputError(f"argument --k: must be in [1, N-1={N - 1}], got {count}")
    soft = not args.no_softening
    if args.dimensionless:
        if args.hub_ratio < 0:
            raise RotbeamInputError(f"argument --hub-ratio: must be >= 0, got {args.hub_ratio}")
        c = args.lam * args.lam * (args.hub_ratio + 1.0)
        _check_rotation("--lambda", args.lam, c, "lambda^2 (hub ratio + 1)", C_MAX_LIMIT)
        w = dimensionless_frequencies(args.lam, args.hub_ratio, count, N, soft)
        out = {"frequencies_dimensionless": w.tolist(), "lambda": args.lam,
               "hub_ratio": args.hub_ratio, "beta1_squared": BETA1**2}  # fmt: skip
    else:
        beam = _beam(args)
        omega = options.option(args, "modes", "omega")
        _check_rotation("--omega", omega, beam.G * omega * omega, "G Omega^2", C_MAX_LIMIT)
        f = modes(beam, omega, count, N, soft)
        out = {"frequencies_hz": f.tolist(), "omega": omega, "f_n_hz": beam.f_n}
    if args.json:
        show.as_json(out)
    else:
        for key, val in out.items():
            print(f"{key}: {val}")
    return 0


def _beam(args: argparse.Namespace):
    """The beam of the --scene file, overridden by the beam flags."""
    from ..config.scenefile import load_scene_file, scene_sections
    from ..model.params import Beam

    raw = dict(load_scene_file(args.scene)) if args.scene else {}
    spec = scene_sections({k: v for k, v in raw.items() if k == "beam"})
    values = spec.get("beam", {}) | options.scene_values(args).get("beam", {})
    return Beam(**values)


def _check_rotation(flag: str, value: float, c: float, formula: str, limit: float) -> None:
    """The centrifugal number C = G Omega^2 = lambda^2 (R_o/L + 1) within the model's range."""
    if not c <= limit:
        raise RotbeamInputError(
            f"argument {flag}: {value!r} gives C = {formula} = {c:.3g}; allowed: C <= {limit:g}"
        )
