"""Command line: `rotbeam simulate` (one scene, with the verdict), `rotbeam critical` (f_d* at one
speed), `rotbeam modes` (linearised frequencies), `rotbeam bench` (work-precision benchmark),
`rotbeam damping` (gamma from a ring-down) and `rotbeam identify` (E, gamma from a resonance
curve); `--uncertainty` carries the inputs' spread into simulate's and critical's answers.

Bad input gives one line on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from .config.errors import RotbeamInputError
from .config.parameters import check_value, help_text, param
from .model.params import BETA1, C_MAX_LIMIT, Beam

EXIT_USAGE = 2
#: grid of the classification run without a stable periodic state (`rotbeam simulate`)
RESPONSE_N = 6


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        # values like -2.5e1, -1e-5, -inf are values, not flags (argparse only knows -2, -2.5)
        self._negative_number_matcher = re.compile(
            r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE
        )

    def error(self, message: str) -> None:  # one line, exit 2
        if message.startswith("unrecognized arguments"):
            message += f"; allowed: see `{self.prog} --help`"
        self.exit(EXIT_USAGE, f"rotbeam: error: {message}\n")


def _finite(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(v):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return v


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="rotbeam", description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    s = sub.add_parser("simulate", help="dynamic and quasi-static response of one scene")
    _scene_flags(s, drive_frequency=True)
    s.add_argument("--out", help="write the time series to this CSV or Parquet file")
    s.add_argument("--progress", action="store_true", help="report progress on stderr")
    s.add_argument("--threshold", type=_finite, default=0.10,
                   help="Delta RMS below which quasi-static is good enough, in (0, 1) "
                        "(default 0.10, the paper's)")  # fmt: skip
    s.add_argument("--plot", help="draw y_m, dynamic against quasi-static, with the verdict and "
                   "the cost, to this .png, .pdf or .svg file (without a stable periodic state: "
                   "the Poincare section and the spectrum)")  # fmt: skip
    s.add_argument("--response-periods", type=_int, default=40,
                   help="without a stable periodic state: periods of transient, then as many "
                   "classified (Poincare section, Lyapunov exponent); default 40")  # fmt: skip
    s.add_argument("--response-N", type=_int, default=RESPONSE_N,
                   help="grid intervals of that classification run, in [4, 80] (default "
                   f"{RESPONSE_N}: at large drive the top bending modes ring and set the step; "
                   "a period costs ~9 s at N = 6)")  # fmt: skip

    c = sub.add_parser("critical", help="f_d*: the drive frequency where Delta RMS reaches the "
                       "threshold at one speed (root finding on the full model)")  # fmt: skip
    _scene_flags(c, drive_frequency=False)
    c.add_argument("--threshold", type=_finite, default=0.10,
                   help="Delta RMS at the boundary, in (0, 1) (default 0.10)")  # fmt: skip
    c.add_argument("--ftol", type=_finite, default=1e-3,
                   help="relative tolerance on f_d*, in [1e-8, 0.1] (default 1e-3)")  # fmt: skip

    e = sub.add_parser("effects", help="each effect's share of RMS(y_m) and of Delta RMS at one "
                       "scene, by switching it off (or on), and what each costs")  # fmt: skip
    _scene_flags(e, drive_frequency=True)

    _uncertainty_flags(s)
    _uncertainty_flags(c)
    _calibration_parsers(sub)

    b = sub.add_parser("bench", help="work-precision benchmark (error against wall time)")
    b.add_argument("--quick", action="store_true", help="the small plan (2 scenes, 2 tolerances)")
    b.add_argument("--config", help="YAML mapping of BenchPlan fields (see rotbeam/bench/plan.py)")
    b.add_argument("--out", default="results/performance/work_precision",
                   help="output stem: writes STEM.csv, .md, .pdf, .png")  # fmt: skip
    b.add_argument("--max-seconds", type=_finite, help="budget per run [s]")

    m = sub.add_parser("modes", help="natural frequencies under steady rotation")
    m.add_argument("--omega", type=_finite, default=0.0, help="angular velocity [rad/s]")
    m.add_argument("--k", type=_int, default=3, help="number of modes")
    m.add_argument("--N", type=_int, default=80, help="grid intervals")
    m.add_argument("--R", type=_finite, help="axis to undeformed tip [m]")
    m.add_argument("--no-softening", action="store_true", help="flapwise (no in-plane softening)")
    m.add_argument("--dimensionless", action="store_true", help="answer for the unit beam")
    m.add_argument("--hub-ratio", type=_finite, default=0.0, help="R_o / L (with --dimensionless)")
    m.add_argument(
        "--lambda", dest="lam", type=_finite, default=0.0, help="Omega T (dimensionless)"
    )
    m.add_argument("--json", action="store_true")
    return p


def _scene_flags(p: argparse.ArgumentParser, drive_frequency: bool) -> None:
    """The flags that set a scene (shared by `simulate` and `critical`)."""
    p.add_argument("--scene", help="YAML scene file (sections beam, drive, effects, numerics)")
    p.add_argument("--omega0", type=_finite, help="mean angular velocity Omega_0 [rad/s]")
    if drive_frequency:
        p.add_argument("--fd", type=_finite, help="drive frequency f_d [Hz]")
    p.add_argument("--amplitude", type=_finite, help=help_text("drive", "amplitude"))
    p.add_argument("--N", type=_int, help=help_text("numerics", "N"))
    p.add_argument("--R", type=_finite, help=help_text("beam", "R"))
    p.add_argument("--method", help=f"{help_text('numerics', 'method')}: "
                   f"{', '.join(param('numerics', 'method').choices)}")  # fmt: skip
    p.add_argument("--rtol", type=_finite, help=help_text("numerics", "rtol"))
    p.add_argument("--effects", help="comma list of effects switched on, e.g. centrifugal,euler"
                   + "; or auto[:TOL]: those whose share of RMS is >= TOL (default 0.001), "
                   "from `rotbeam effects`" + ("" if drive_frequency else
                   " at the linear estimate of f_d*"))  # fmt: skip
    p.add_argument("--json", action="store_true", help="print one JSON object")


def _scene_from_args(args: argparse.Namespace):
    from .config.scenefile import scene_sections
    from .model.params import Effects
    from .simulate.scene import build_scene

    spec = scene_sections(_scene_file_sections(args.scene))
    flags = {}  # scene key -> the flag that set it, named in an error about that key
    for section, key, value, flag in (
        ("drive", "omega0", args.omega0, "--omega0"),
        ("drive", "f_d", args.fd, "--fd"),
        ("drive", "amplitude", args.amplitude, "--amplitude"),
        ("numerics", "N", args.N, "--N"),
        ("numerics", "method", args.method, "--method"),
        ("numerics", "rtol", args.rtol, "--rtol"),
        ("beam", "R", args.R, "--R"),
    ):
        if value is not None:
            spec.setdefault(section, {})[key] = value
            flags[f"{section}.{key}"] = flag
    try:
        if args.effects is not None:
            flags["effects"] = "--effects"
            spec["effects"] = vars(Effects.from_list(args.effects)).copy()
        for key, flag, what in (
            ("omega0", "--omega0", "a finite number, rad/s"),
            ("f_d", "--fd", "a number > 0, Hz"),
        ):
            if key not in spec.get("drive", {}):
                raise RotbeamInputError(
                    f"drive.{key} is missing: give {flag} ({what}) or drive.{key} in the "
                    f"--scene file"
                )
        return build_scene(spec)
    except RotbeamInputError as exc:
        msg = str(exc)
        for key, flag in flags.items():
            if msg.startswith(key) and not msg[len(key) : len(key) + 1].isalnum():
                raise RotbeamInputError(f"argument {flag}: {msg}") from None
        raise


def _write_series(path: str, series: dict[str, np.ndarray]) -> None:
    import pandas as pd

    from .report.io import atomic_write

    df = pd.DataFrame(series)

    def write(tmp: Path) -> None:
        if Path(path).suffix == ".parquet":  # suffix checked in cmd_simulate before the run
            try:
                df.to_parquet(tmp)
            except ImportError:
                raise RotbeamInputError(
                    "--out .parquet needs pyarrow or fastparquet (pip install pyarrow); use .csv"
                ) from None
        else:
            df.to_csv(tmp, index=False)

    atomic_write(path, write)


def _check_threshold_flag(value: float) -> None:
    from .config.checks import check_threshold

    try:
        check_threshold(value)
    except RotbeamInputError as exc:
        raise RotbeamInputError(f"argument --threshold: {exc}") from None


def _auto_tol(args: argparse.Namespace) -> float | None:
    """TOL of `--effects auto[:TOL]`, or else of the scene file's `effects: auto` (AUTO_TOL by
    default), else None; clears args.effects of the flag's auto."""
    from .config.scenefile import auto_tol, split_auto

    text = args.effects or ""
    if text == "auto" or text.startswith("auto:"):
        args.effects = None
        return auto_tol(text, "argument --effects")
    if args.effects is None and args.scene:  # an explicit --effects list wins over the file
        return split_auto(_scene_file_sections(args.scene, keep_auto=True))[1]
    return None


def _auto_scene(scene, tol: float):
    """The scene with the effects its budget calls for, and what was chosen."""
    from .analysis.effect_budget import auto_effects, effect_budget

    budget = effect_budget(scene)
    if not budget.shares:
        raise RotbeamInputError("--effects auto: the scene has no steady state to share out")
    auto = auto_effects(budget, tol)
    return replace(scene, effects=auto.effects), auto.as_dict() | {
        "budget_seconds": budget.total_seconds, "budget_f_d": scene.drive.f_d}  # fmt: skip


def _print_auto(auto: dict[str, Any]) -> None:
    print(f"{'effects auto':16s} kept {','.join(auto['kept'])}; dropped "
          f"{','.join(auto['dropped']) or 'none'} (worth {auto['dropped_share']:.2g} of "
          f"RMS at f_d = {auto['budget_f_d']:.4g} Hz; the budget took "
          f"{auto['budget_seconds']:.3g} s)")  # fmt: skip


def cmd_simulate(args: argparse.Namespace) -> int:
    from .analysis.verdict import judge
    from .report.verdict_plot import plot_verdict
    from .simulate.scene import simulate

    tol = _auto_tol(args)
    scene = _scene_from_args(args)
    auto = None
    if tol is not None:
        scene, auto = _auto_scene(scene, tol)
    inputs, scene = _uncertainty_inputs(args, scene)
    if args.out and Path(args.out).suffix not in (".csv", ".parquet"):
        raise RotbeamInputError(f"--out must end in .csv or .parquet, got {args.out!r}")
    _check_plot_flag(args.plot)
    _check_threshold_flag(args.threshold)
    if args.response_periods < 1:
        raise RotbeamInputError(
            f"argument --response-periods: must be >= 1, got {args.response_periods}"
        )
    if not 4 <= args.response_N <= 80:
        raise RotbeamInputError(f"argument --response-N: must be in [4, 80], got {args.response_N}")

    def progress(k: int, bound: float) -> None:
        print(f"\rperiod {k}: transient bound {bound:.2e}", end="", file=sys.stderr, flush=True)

    res = simulate(scene, progress=progress if args.progress else None)
    if args.progress:
        print(file=sys.stderr)
    verdict = judge(res, args.threshold)
    summary = res.summary() | verdict.as_dict() | _response(res, args)
    if auto is not None:
        summary["effects_auto"] = auto
    prop = _simulate_uncertainty(args, scene, res, inputs) if inputs else None
    if prop is not None:
        summary["uncertainty"] = prop.as_dict()
    if args.out:
        _write_series(args.out, res.time_series())
    if args.plot and summary.get("_response") is not None:
        from .report.response_figures import plot_response

        plot_response(summary["_response"], scene, args.plot)
    elif args.plot:
        plot_verdict(res, verdict, args.plot)
    summary.pop("_response", None)
    if args.json:
        print(json.dumps(summary, default=float))
    else:
        for key in ("rms_dynamic", "rms_quasistatic", "delta_rms", "f_n_hz", "f0_hz", "C_max",
                    "E_max"):  # fmt: skip
            print(f"{key:16s} {summary[key]:.6g}")
        print(f"{'converged':16s} {summary['converged']} ({summary['message']})")
        print(f"{'verdict':16s} {verdict.text}")
        if auto is not None:
            _print_auto(auto)
        print(f"{'seconds':16s} {summary['seconds']:.3g}")
        if prop is not None:
            _print_uncertainty(prop)
    return 0 if res.converged else 1


def _response(res, args: argparse.Namespace) -> dict[str, Any]:
    """`response` and `lyapunov_max`: from the multipliers for a stable periodic state
    (ln |mu|max / (P T)), else from classifying the time-stepped response."""
    fl = res.dynamic.floquet
    if res.converged and fl is not None:
        P = 1.0 / res.scene.drive.f_d
        lyap = math.log(fl.max_abs) / P if fl.max_abs > 0 else -math.inf
        return {"response": "periodic", "lyapunov_max": lyap}
    from .simulate.response import response_of

    def progress(done: int, total: int) -> None:
        print(f"\rresponse (N = {args.response_N}): period {done} of {total}", end="",
              file=sys.stderr, flush=True)  # fmt: skip

    r = response_of(res.scene.model(args.response_N), res.scene.beam.T, args.response_periods,
                    args.response_periods,
                    progress=progress if args.progress else None)  # fmt: skip
    return r.as_dict() | {"_response": r}


def cmd_critical(args: argparse.Namespace) -> int:
    from .analysis.verdict import critical_frequency, critical_start_hz

    _check_threshold_flag(args.threshold)
    if not 1e-8 <= args.ftol <= 0.1:
        raise RotbeamInputError(f"argument --ftol: must be in [1e-8, 0.1], got {args.ftol!r}")
    tol = _auto_tol(args)
    args.fd = (
        1.0  # a placeholder the scene needs (a scene file's f_d is ignored): the search sets f_d
    )
    scene = _scene_from_args(args)
    auto = None
    if tol is not None:  # the budget at the search's first guess, the linear estimate
        drive = scene.drive
        f_start = critical_start_hz(scene.beam, drive.omega0, args.threshold, drive.amplitude)
        scene, auto = _auto_scene(replace(scene, drive=replace(drive, f_d=f_start)), tol)
    inputs, scene = _uncertainty_inputs(args, scene)
    res = critical_frequency(scene.beam, scene.drive.omega0, args.threshold, scene.drive.amplitude,
                             scene.effects, scene.numerics, args.ftol)  # fmt: skip
    out = res.as_dict() | {"omega0": scene.drive.omega0, "amplitude": scene.drive.amplitude,
                           "N": scene.numerics.N,
                           "effects": ",".join(scene.effects.active())}  # fmt: skip
    if auto is not None:
        out["effects_auto"] = auto
    prop = _critical_uncertainty(args, scene, res, inputs) if inputs else None
    if prop is not None:
        out["uncertainty"] = prop.as_dict()
    if args.json:
        print(json.dumps(out, default=float))
    else:
        print(f"{'f_d_star_hz':16s} {res.f_d_star:.6g}")
        print(f"{'c = f_d*/f_0':16s} {res.f_d_star / res.f0_hz:.4g}")
        print(f"{'f0_hz':16s} {res.f0_hz:.6g}")
        print(f"{'estimate_hz':16s} {res.estimate_hz:.6g} (linear, where the search started)")
        print(f"{'found':16s} {res.found} ({res.message})")
        print(f"{'evaluations':16s} {len(res.visited)}")
        if auto is not None:
            _print_auto(auto)
        print(f"{'seconds':16s} {res.seconds:.3g}")
        if prop is not None:
            _print_uncertainty(prop)
    return 0 if res.found else 1


def cmd_effects(args: argparse.Namespace) -> int:
    from .analysis.effect_budget import effect_budget

    budget = effect_budget(_scene_from_args(args))
    if args.json:
        print(json.dumps(budget.as_dict(), default=float))
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


def _check_rotation(flag: str, value: float, c: float, formula: str) -> None:
    """The centrifugal number C = G Omega^2 = lambda^2 (R_o/L + 1) within the model's range."""
    if not c <= C_MAX_LIMIT:
        raise RotbeamInputError(
            f"argument {flag}: {value!r} gives C = {formula} = {c:.3g}; allowed: C <= "
            f"{C_MAX_LIMIT:g}"
        )


def cmd_modes(args: argparse.Namespace) -> int:
    from .model.modes import dimensionless_frequencies, natural_frequencies_hz

    try:
        check_value("numerics", "N", args.N)
    except RotbeamInputError as exc:
        raise RotbeamInputError(f"argument --N: {exc}") from None
    if not 1 <= args.k < args.N:
        raise RotbeamInputError(f"--k must be in [1, N-1={args.N - 1}], got {args.k}")
    soft = not args.no_softening
    if args.dimensionless:
        if args.hub_ratio < 0:
            raise RotbeamInputError(f"--hub-ratio must be >= 0, got {args.hub_ratio}")
        c = args.lam * args.lam * (args.hub_ratio + 1.0)
        _check_rotation("--lambda", args.lam, c, "lambda^2 (hub ratio + 1)")
        w = dimensionless_frequencies(args.lam, args.hub_ratio, args.k, args.N, soft)
        out = {"frequencies_dimensionless": w.tolist(), "lambda": args.lam,
               "hub_ratio": args.hub_ratio, "beta1_squared": BETA1**2}  # fmt: skip
    else:
        try:
            beam = Beam(R=args.R) if args.R is not None else Beam()
        except RotbeamInputError as exc:
            raise RotbeamInputError(f"argument --R: {exc}") from None
        _check_rotation("--omega", args.omega, beam.G * args.omega * args.omega, "G Omega^2")
        f = natural_frequencies_hz(beam, args.omega, args.k, args.N, soft)
        out = {"frequencies_hz": f.tolist(), "omega": args.omega, "f_n_hz": beam.f_n}
    if args.json:
        print(json.dumps(out))
    else:
        for key, val in out.items():
            print(f"{key}: {val}")
    return 0


def cmd_bench(args: argparse.Namespace) -> int:
    from .bench.plan import plan_from_dict
    from .bench.report import write_outputs
    from .bench.run import run_benchmark
    from .config.scenefile import load_yaml

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

    def say(msg: str) -> None:
        print(msg, file=sys.stderr, flush=True)

    runs, refs = run_benchmark(plan, progress=say)
    write_outputs(runs, refs, plan, args.out)
    say(f"wrote {args.out}.csv, .md, .pdf, .png")
    return 0


# --- calibration from measurements, and uncertainty (rotbeam damping, identify; --uncertainty) ---

#: Exit status of a fit that ran but cannot be trusted (the message says why).
EXIT_REJECTED = 1


class FitRejected(Exception):
    """A calibration fit the data do not support (one line, exit EXIT_REJECTED)."""


def _uncertainty_flags(p: argparse.ArgumentParser) -> None:
    p.add_argument("--uncertainty", help="inputs' normal spreads, e.g. "
                   "\"gamma=0.039+-0.008,E=1.22e6+-0.05e6\" (beam fields, omega0, amplitude; "
                   "adds to a scene file's uncertainty section)")  # fmt: skip
    p.add_argument("--uq-method", default="linear", help="linear (1 + k runs, default) or "
                   "sobol (--uq-samples runs at a Sobol design)")  # fmt: skip
    p.add_argument("--uq-samples", type=_int, default=32, help="Sobol runs, a power of two "
                   "(default 32)")  # fmt: skip


def _calibration_parsers(sub: Any) -> None:
    d = sub.add_parser("damping", help="gamma from a ring-down (columns t [s], y): fit of a "
                       "damped oscillation, gamma = 2 rho A / t_decay")  # fmt: skip
    d.add_argument("file", help="CSV with columns t and y")
    d.add_argument("--scene", help="YAML scene file whose beam section gives rho A")
    d.add_argument("--json", action="store_true", help="print one JSON object")
    d.add_argument("--plot", help="draw the record and the fit to this .png, .pdf or .svg")
    i = sub.add_parser("identify", help="beam parameters (default E, gamma) from a measured "
                       "resonance curve (columns f_d [Hz], rms[, rms_std])")  # fmt: skip
    i.add_argument("--measured", required=True, help="CSV with columns f_d, rms[, rms_std]")
    i.add_argument("--omega0", type=_finite, required=True, help="Omega_0 of the measurement")
    i.add_argument("--amplitude", type=_finite, help="velocity amplitude a [rad/s] (default 1)")
    i.add_argument("--fit", default="E,gamma", help="comma list of beam fields to fit "
                   "(L, h, b, E, rho, R, gamma; default E,gamma)")  # fmt: skip
    i.add_argument("--scene", help="YAML scene file: the beam to start from, effects, numerics")
    i.add_argument("--N", type=_int, help="grid intervals of the fit (default 20)")
    i.add_argument("--json", action="store_true", help="print one JSON object")
    i.add_argument("--plot", help="draw data, fitted and scene-beam curves (.png, .pdf, .svg)")


def _scene_file_sections(path: str | None, keep_auto: bool = False) -> dict[str, Any]:
    """A scene file's sections without its `uncertainty` section (read by _uncertainty_inputs)
    and, unless keep_auto, without `effects: auto` (read by _auto_tol)."""
    from .config.scenefile import load_scene_file, split_auto

    raw = dict(load_scene_file(path)) if path else {}
    raw.pop("uncertainty", None)
    return raw if keep_auto else split_auto(raw)[0]


def _uncertainty_inputs(args: argparse.Namespace, scene):
    """{name: (mean, sd)} from the scene file's section and --uncertainty (which wins), and the
    scene with the means set (the plain run is the run at the means)."""
    from .analysis.uncertainty import METHODS, apply, parse_spec
    from .config.scenefile import load_scene_file
    from .simulate.scene import Scene

    section = load_scene_file(args.scene).get("uncertainty") if args.scene else None
    if section is not None and not isinstance(section, dict):
        raise RotbeamInputError(
            f"scene file {args.scene!r}: uncertainty must be a mapping, e.g. "
            f'uncertainty: {{gamma: "0.039 +- 0.008"}}'
        )
    inputs = parse_spec(section) | parse_spec(args.uncertainty)
    if args.uq_method not in METHODS:
        raise RotbeamInputError(f"argument --uq-method: {args.uq_method!r}; allowed: "
                                f"{', '.join(METHODS)}")  # fmt: skip
    if not inputs:
        return {}, scene
    beam, drive = apply(scene.beam, scene.drive, {k: m for k, (m, _) in inputs.items()})
    return inputs, Scene(beam, drive, scene.effects, scene.numerics)


def _simulate_uncertainty(args: argparse.Namespace, scene, plain, inputs):
    """RMS, Delta RMS and P(quasi-static) over the inputs' spread (the plain run reused)."""
    from .analysis.uncertainty import apply, propagate
    from .simulate.scene import Scene, simulate

    orbit = plain.dynamic.periodic
    guess = orbit.theta.T if orbit is not None and orbit.converged else None

    def run(values: dict[str, float]) -> dict[str, float]:
        beam, drive = apply(scene.beam, scene.drive, values)
        res = plain if (beam, drive) == (scene.beam, scene.drive) else simulate(
            Scene(beam, drive, scene.effects, scene.numerics), guess=guess)  # fmt: skip
        ok = res.converged
        return {k: (getattr(res, k) if ok else float("nan"))
                for k in ("rms_dynamic", "rms_quasistatic", "delta_rms")}  # fmt: skip

    return propagate(inputs, run, args.uq_method, args.uq_samples, args.threshold)


def _critical_uncertainty(args: argparse.Namespace, scene, plain, inputs):
    """f_d* and c = f_d*/f_0 over the inputs' spread (the plain search reused)."""
    from .analysis.uncertainty import apply, propagate
    from .analysis.verdict import critical_frequency

    def run(values: dict[str, float]) -> dict[str, float]:
        beam, drive = apply(scene.beam, scene.drive, values)
        res = plain if (beam, drive) == (scene.beam, scene.drive) else critical_frequency(
            beam, drive.omega0, args.threshold, drive.amplitude, scene.effects, scene.numerics,
            args.ftol)  # fmt: skip
        return {"f_d_star": res.f_d_star, "c": res.f_d_star / res.f0_hz, "f0_hz": res.f0_hz}

    return propagate(inputs, run, args.uq_method, args.uq_samples, None)


def _print_uncertainty(prop) -> None:
    spread = ", ".join(f"{k} = {m:g} +- {s:g}" for k, (m, s) in prop.inputs.items())
    print(f"{'uncertainty':16s} {spread} (normal; {prop.method}, {prop.runs} runs, "
          f"{prop.seconds:.3g} s{f', {prop.failed} failed' if prop.failed else ''})")  # fmt: skip
    for k in prop.mean:
        print(f"{'  ' + k:16s} {prop.mean[k]:.6g} +- {prop.sd[k]:.3g}  "
              f"95 %: [{prop.low[k]:.6g}, {prop.high[k]:.6g}]")  # fmt: skip
    if prop.p_quasistatic is not None:
        print(f"{'  verdict':16s} quasi-static with probability {prop.p_quasistatic:.3g}")


def _check_plot_flag(path: str | None) -> None:
    from .report.verdict_plot import check_plot_path

    if path:
        check_plot_path(path)


def _beam_from_scene(path: str | None):
    from .config.scenefile import scene_sections
    from .simulate.scene import build_scene

    return build_scene(scene_sections(_scene_file_sections(path)))


def cmd_damping(args: argparse.Namespace) -> int:
    from .analysis.measurements import load_ringdown

    _check_plot_flag(args.plot)
    beam = _beam_from_scene(args.scene).beam
    data = load_ringdown(args.file)  # a bad file fails here, before scipy.signal is loaded
    from .analysis.ringdown import RingdownRejected, fit_ringdown

    try:
        fit = fit_ringdown(data, beam)
    except RingdownRejected as exc:
        raise FitRejected(f"{args.file}: {exc}") from None
    if args.plot:
        from .report.calibration_plots import plot_ringdown

        plot_ringdown(data, fit, args.plot)
    out = fit.as_dict()
    if args.json:
        print(json.dumps(out, default=float))
    else:
        for k in ("f_hz", "t_decay", "gamma", "amplitude", "offset"):
            print(f"{k:16s} {out[k]:.6g} +- {out[k + '_stderr']:.2g}")
        print(f"{'zeta':16s} {fit.zeta:.4g}")
        print(f"{'rhoA':16s} {fit.rhoA:.6g} kg/m (beam of the scene)")
        print(f"{'snr':16s} {fit.snr:.3g} ({fit.cycles:.3g} cycles, {fit.points} samples)")
    return 0


def cmd_identify(args: argparse.Namespace) -> int:
    from dataclasses import replace

    from .analysis.identify import FIT_NUMERICS, IdentifyFailed, identify, parse_names
    from .analysis.measurements import load_resonance

    _check_plot_flag(args.plot)
    names = parse_names(args.fit)
    scene = _beam_from_scene(args.scene)
    numerics = FIT_NUMERICS
    if args.scene and "numerics" in _scene_file_sections(args.scene):
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
        res = identify(curve, args.omega0, amplitude, names, scene.beam, scene.effects, numerics)
    except IdentifyFailed as exc:
        raise FitRejected(str(exc)) from None
    out = res.as_dict() | {"omega0": args.omega0, "amplitude": amplitude, "N": numerics.N,
                           "extrapolate": numerics.extrapolate}  # fmt: skip
    if args.plot:
        _plot_identify(args, curve, res, scene, amplitude, numerics)
    if args.json:
        print(json.dumps(out, default=float))
    else:
        for n in names:
            print(f"{n:16s} {res.values[n]:.6g} +- {res.stderr[n]:.2g}  95 %: "
                  f"[{res.low[n]:.6g}, {res.high[n]:.6g}]  (start {res.start[n]:.4g})")  # fmt: skip
        print(f"{'residual':16s} RSS {res.rss:.3g}, {res.dof} dof, scale {res.scale:.3g}")
        print(f"{'evaluations':16s} {res.evaluations} ({res.runs} steady states, N = "
              f"{numerics.N}{' + Richardson' if numerics.extrapolate else ''})")  # fmt: skip
        print(f"{'seconds':16s} {res.seconds:.3g}")
        print(f"{'converged':16s} {res.success} ({res.message})")
    return 0 if res.success else 1


def _plot_identify(args, curve, res, scene, amplitude, numerics) -> None:
    from .model.params import Beam
    from .report.calibration_plots import plot_identification
    from .simulate.sweeps import scan_line

    lo, hi = float(curve.f_d[0]), float(curve.f_d[-1])
    grid = np.linspace(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo), 41)
    fitted = scan_line(res.beam, args.omega0, grid, amplitude, scene.effects, numerics)
    ref = scan_line(scene.beam, args.omega0, grid, amplitude, scene.effects, numerics)
    label = "Table 1 beam" if scene.beam == Beam() else "scene beam"
    label += f" (E = {scene.beam.E:.4g} Pa, gamma = {scene.beam.gamma:.4g})"
    plot_identification(curve, res, fitted, ref, label, args.plot)


CALIBRATION_COMMANDS = {"damping": cmd_damping, "identify": cmd_identify}


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "simulate":
            return cmd_simulate(args)
        if args.command == "bench":
            return cmd_bench(args)
        if args.command == "critical":
            return cmd_critical(args)
        if args.command == "effects":
            return cmd_effects(args)
        if args.command in CALIBRATION_COMMANDS:
            return CALIBRATION_COMMANDS[args.command](args)
        return cmd_modes(args)
    except RotbeamInputError as exc:
        print(f"rotbeam: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except FitRejected as exc:
        print(f"rotbeam: fit rejected: {exc}", file=sys.stderr)
        return EXIT_REJECTED
    except KeyboardInterrupt:
        print("rotbeam: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
