"""Command line: `rotbeam simulate` (one scene, with the verdict), `rotbeam critical` (f_d* at one
speed), `rotbeam modes` (linearised frequencies) and `rotbeam bench` (work-precision benchmark).

Bad input gives one line on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
from pathlib import Path
from typing import Any

import numpy as np

from .config.errors import RotbeamInputError
from .config.parameters import help_text, param
from .model.params import BETA1, C_MAX_LIMIT, Beam

EXIT_USAGE = 2


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
    s.add_argument("--response-periods", type=_int, default=100,
                   help="without a stable periodic state: periods of transient, then as many "
                   "classified (Poincare section, Lyapunov exponent); default 100")  # fmt: skip

    c = sub.add_parser("critical", help="f_d*: the drive frequency where Delta RMS reaches the "
                       "threshold at one speed (root finding on the full model)")  # fmt: skip
    _scene_flags(c, drive_frequency=False)
    c.add_argument("--threshold", type=_finite, default=0.10,
                   help="Delta RMS at the boundary, in (0, 1) (default 0.10)")  # fmt: skip
    c.add_argument("--ftol", type=_finite, default=1e-3,
                   help="relative tolerance on f_d*, in [1e-8, 0.1] (default 1e-3)")  # fmt: skip

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
    p.add_argument("--effects", help="comma list of effects switched on, e.g. centrifugal,euler")
    p.add_argument("--json", action="store_true", help="print one JSON object")


def _scene_from_args(args: argparse.Namespace):
    from .config.scenefile import load_scene_file, scene_sections
    from .model.params import Effects
    from .simulate.scene import build_scene

    spec = scene_sections(load_scene_file(args.scene) if args.scene else {})
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


def cmd_simulate(args: argparse.Namespace) -> int:
    from .analysis.verdict import judge
    from .report.verdict_plot import check_plot_path, plot_verdict
    from .simulate.scene import simulate

    scene = _scene_from_args(args)
    if args.out and Path(args.out).suffix not in (".csv", ".parquet"):
        raise RotbeamInputError(f"--out must end in .csv or .parquet, got {args.out!r}")
    if args.plot:
        check_plot_path(args.plot)
    _check_threshold_flag(args.threshold)
    if args.response_periods < 1:
        raise RotbeamInputError(
            f"argument --response-periods: must be >= 1, got {args.response_periods}"
        )

    def progress(k: int, bound: float) -> None:
        print(f"\rperiod {k}: transient bound {bound:.2e}", end="", file=sys.stderr, flush=True)

    res = simulate(scene, progress=progress if args.progress else None)
    if args.progress:
        print(file=sys.stderr)
    verdict = judge(res, args.threshold)
    summary = res.summary() | verdict.as_dict() | _response(res, args)
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
        print(f"{'seconds':16s} {summary['seconds']:.3g}")
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

    r = response_of(res.scene, args.response_periods, args.response_periods)
    return r.as_dict() | {"_response": r}


def cmd_critical(args: argparse.Namespace) -> int:
    from .analysis.verdict import critical_frequency

    _check_threshold_flag(args.threshold)
    if not 1e-8 <= args.ftol <= 0.1:
        raise RotbeamInputError(f"argument --ftol: must be in [1e-8, 0.1], got {args.ftol!r}")
    args.fd = (
        1.0  # a placeholder the scene needs (a scene file's f_d is ignored): the search sets f_d
    )
    scene = _scene_from_args(args)
    res = critical_frequency(scene.beam, scene.drive.omega0, args.threshold, scene.drive.amplitude,
                             scene.effects, scene.numerics, args.ftol)  # fmt: skip
    out = res.as_dict() | {"omega0": scene.drive.omega0, "amplitude": scene.drive.amplitude,
                           "N": scene.numerics.N}  # fmt: skip
    if args.json:
        print(json.dumps(out, default=float))
    else:
        print(f"{'f_d_star_hz':16s} {res.f_d_star:.6g}")
        print(f"{'c = f_d*/f_0':16s} {res.f_d_star / res.f0_hz:.4g}")
        print(f"{'f0_hz':16s} {res.f0_hz:.6g}")
        print(f"{'estimate_hz':16s} {res.estimate_hz:.6g} (linear, where the search started)")
        print(f"{'found':16s} {res.found} ({res.message})")
        print(f"{'evaluations':16s} {len(res.visited)}")
        print(f"{'seconds':16s} {res.seconds:.3g}")
    return 0 if res.found else 1


def _check_rotation(flag: str, value: float, c: float, formula: str) -> None:
    """The centrifugal number C = G Omega^2 = lambda^2 (R_o/L + 1) within the model's range."""
    if not c <= C_MAX_LIMIT:
        raise RotbeamInputError(
            f"argument {flag}: {value!r} gives C = {formula} = {c:.3g}; allowed: C <= "
            f"{C_MAX_LIMIT:g}"
        )


def cmd_modes(args: argparse.Namespace) -> int:
    from .model.modes import dimensionless_frequencies, natural_frequencies_hz

    if not 3 <= args.N <= 2000:
        raise RotbeamInputError(f"--N must be in [3, 2000], got {args.N}")
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
        return cmd_modes(args)
    except RotbeamInputError as exc:
        print(f"rotbeam: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print("rotbeam: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
