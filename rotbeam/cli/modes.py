"""`rotbeam modes`: natural frequencies of the beam turning steadily, a table of the modes at
the requested speed (or one JSON object)."""

from __future__ import annotations

import argparse
import math
from typing import Any

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
    """Parse, solve the eigenproblem, print the first frequencies at the requested speed: a
    table, one row a mode, in Hz (or, with --dimensionless, in units of 1/T), or one JSON
    object.

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
    N = options.option(args, "numerics", "N")
    count = options.option(args, "modes", "count")
    if not count < N:
        raise RotbeamInputError(f"argument --k: must be in [1, N-1={N - 1}], got {count}")
    soft = not args.no_softening
    out = _dimensionless(args, count, N, soft) if args.dimensionless else _physical(
        args, count, N, soft)  # fmt: skip
    if args.json:
        show.as_json(out)
    elif args.dimensionless:
        _print_dimensionless(out)
    else:
        _print_physical(out)
    return 0


def _physical(args: argparse.Namespace, count: int, N: int, soft: bool) -> dict[str, Any]:
    """The modes of the beam (--scene, beam flags) at --omega [rad/s]: frequencies_hz and f_1_hz
    at that speed, f_n_hz and zeta of the first mode at rest."""
    from ..model.modes import modes
    from ..model.params import C_MAX_LIMIT

    beam = _beam(args)
    omega = options.option(args, "modes", "omega")
    _check_rotation("--omega", omega, beam.G * omega * omega, "G Omega^2", C_MAX_LIMIT)
    f = modes(beam, omega, count, N, soft)
    return {"frequencies_hz": f.tolist(), "f_1_hz": float(f[0]), "omega": omega,
            "f_n_hz": beam.f_n, "zeta": beam.zeta, "plane": _plane(soft), "N": N}  # fmt: skip


def _dimensionless(args: argparse.Namespace, count: int, N: int, soft: bool) -> dict[str, Any]:
    """The modes of the unit beam at --lambda = Omega T and --hub-ratio, in units of 1/T."""
    from ..model.modes import dimensionless_frequencies
    from ..model.params import BETA1, C_MAX_LIMIT

    if args.hub_ratio < 0:
        raise RotbeamInputError(f"argument --hub-ratio: must be >= 0, got {args.hub_ratio}")
    c = args.lam * args.lam * (args.hub_ratio + 1.0)
    _check_rotation("--lambda", args.lam, c, "lambda^2 (hub ratio + 1)", C_MAX_LIMIT)
    w = dimensionless_frequencies(args.lam, args.hub_ratio, count, N, soft)
    return {"frequencies_dimensionless": w.tolist(), "lambda": args.lam,
            "hub_ratio": args.hub_ratio, "beta1_squared": BETA1**2, "plane": _plane(soft),
            "N": N}  # fmt: skip


def _plane(softening: bool) -> str:
    """Which motion the modes are of: in-plane (with the softening) or flapwise."""
    return "in-plane" if softening else "flapwise"


def _print_physical(out: dict[str, Any]) -> None:
    """The table of `_physical`'s modes at the speed, then the first mode at rest."""
    print(f"{out['plane']} modes at Omega = {out['omega']:g} rad/s (N = {out['N']})")
    print(f"{'mode':>4}  {'f [Hz]':>12}  {'2 pi f [rad/s]':>14}  {'f / f_n':>9}")
    for k, f in enumerate(out["frequencies_hz"], start=1):
        print(f"{k:>4d}  {f:>12.6g}  {2.0 * math.pi * f:>14.6g}  {f / out['f_n_hz']:>9.4g}")
    show.line("f_n [Hz]", f"{out['f_n_hz']:.6g} (first mode at rest, continuum)")
    show.line("zeta", f"{out['zeta']:.4g} (first mode at rest; damping on the beam only)")


def _print_dimensionless(out: dict[str, Any]) -> None:
    """The table of `_dimensionless`'s modes, w = omega T and w / beta_1^2."""
    print(f"{out['plane']} modes of the unit beam at lambda = Omega T = {out['lambda']:g}, "
          f"R_o / L = {out['hub_ratio']:g} (N = {out['N']})")  # fmt: skip
    print(f"{'mode':>4}  {'w = omega T [-]':>15}  {'w / beta_1^2':>12}")
    for k, w in enumerate(out["frequencies_dimensionless"], start=1):
        print(f"{k:>4d}  {w:>15.6g}  {w / out['beta1_squared']:>12.4g}")


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
