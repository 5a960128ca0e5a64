"""What the stated uncertainty of the inputs does to RMS, Delta RMS, f_d* and the verdict.

Inputs are independent normal distributions of beam fields, omega0 and amplitude (e.g.
"gamma=0.039+-0.008" on the command line, or a scene file's `uncertainty` section), carried
through the model by a secant per input ("linear", 1 + k runs) or by a scrambled Sobol design
("sobol").  The methods and what they report: docs/calibration.md, "Uncertainty into the answer".
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..config.errors import RotbeamInputError
from ..config.threads import one_blas_thread
from ..model.params import Beam, Drive

if TYPE_CHECKING:
    from ..runs.scene import Scene, SceneResult
    from ..solve.timebudget import TimeBudget
    from .verdict import Critical

BEAM_FIELDS = ("L", "h", "b", "E", "rho", "R", "gamma")
DRIVE_FIELDS = ("omega0", "amplitude")
METHODS = ("linear", "sobol")
_PM = re.compile(r"^\s*([^+]+?)\s*(?:\+-|\+/-|±)\s*(\S+)\s*$")


def parse_spread(name: str, text: object) -> tuple[float, float]:
    """One input's normal distribution from its text: '0.039 +- 0.008' -> (0.039, 0.008).

    Parameters
    ----------
    name : str
        The input's name, for the error message.
    text : str or float
        'mean +- sd' ('+/-' and '±' also read), or a number (no spread).

    Returns
    -------
    tuple of float
        (mean, sd), in the input's own unit (SI, as the beam and drive fields).

    Raises
    ------
    RotbeamInputError
        If the text is not 'mean +- sd', or the mean or sd is not finite, or sd < 0.
    """
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        mean, sd = float(text), 0.0
    else:
        m = _PM.match(str(text))
        if not m:
            raise RotbeamInputError(
                f"uncertainty {name} = {text!r}: expected 'mean +- sd', e.g. '0.039 +- 0.008'"
            )
        try:
            mean, sd = float(m.group(1)), float(m.group(2))
        except ValueError:
            raise RotbeamInputError(
                f"uncertainty {name} = {text!r}: mean and sd must be numbers"
            ) from None
    if not (math.isfinite(mean) and math.isfinite(sd)) or sd < 0:
        raise RotbeamInputError(
            f"uncertainty {name} = {text!r}: allowed a finite mean and a finite sd >= 0"
        )
    return mean, sd


def parse_spec(spec: str | dict | None) -> dict[str, tuple[float, float]]:
    """The uncertain inputs of a CLI string 'a=m+-s,b=m+-s' or a scene-file mapping.

    Parameters
    ----------
    spec : str, dict or None
        "gamma=0.039+-0.008,E=1.22e6+-0.05e6", {"gamma": "0.039 +- 0.008"}, or None (none).

    Returns
    -------
    dict
        Input name -> (mean, sd).

    Raises
    ------
    RotbeamInputError
        If a part is not name=mean+-sd, a name is not a beam field, omega0 or amplitude, or a
        spread does not parse (`parse_spread`).
    """
    if spec is None:
        return {}
    items: list[tuple[str, object]]
    if isinstance(spec, dict):
        items = [(str(k), v) for k, v in spec.items()]
    else:
        items = []
        for part in str(spec).split(","):
            if not part.strip():
                continue
            if "=" not in part:
                raise RotbeamInputError(
                    f"uncertainty {part.strip()!r}: expected name=mean+-sd, e.g. gamma=0.039+-0.008"
                )
            k, v = part.split("=", 1)
            items.append((k.strip(), v))
    out = {}
    for name, value in items:
        if name not in BEAM_FIELDS + DRIVE_FIELDS:
            raise RotbeamInputError(
                f"uncertainty {name!r}: unknown input; allowed: "
                f"{', '.join(BEAM_FIELDS + DRIVE_FIELDS)}"
            )
        out[name] = parse_spread(name, value)
    return out


def apply(beam: Beam, drive: Drive, values: dict[str, float]) -> tuple[Beam, Drive]:
    """Beam and drive with the given inputs set; a value out of range names the input.

    Parameters
    ----------
    beam : Beam
        The beam to change.
    drive : Drive
        The drive to change.
    values : dict
        Input name -> value (beam fields and omega0, amplitude; SI units).

    Returns
    -------
    beam : Beam
        The beam with its inputs set.
    drive : Drive
        The drive with its inputs set.

    Raises
    ------
    RotbeamInputError
        If a value lies outside its field's range (a spread too wide for a normal distribution).
    """
    b = {k: v for k, v in values.items() if k in BEAM_FIELDS}
    d = {k: v for k, v in values.items() if k in DRIVE_FIELDS}
    try:
        return replace(beam, **b), replace(drive, **d)
    except RotbeamInputError as exc:
        raise RotbeamInputError(
            f"uncertainty: a sample outside the model's range ({exc}); the stated spread "
            f"is too wide for a normal distribution"
        ) from None


@dataclass(frozen=True)
class Propagated:
    """Mean, sd and 95 % interval of each output; P(quasi-static); the cost.

    What `propagate` returns.  Outputs keep their own units (RMS and Delta RMS dimensionless,
    f_d* and f_0 in Hz); ``p_quasistatic`` is None where no threshold applies.
    """

    method: str
    inputs: dict[str, tuple[float, float]]
    mean: dict[str, float]
    sd: dict[str, float]
    low: dict[str, float]
    high: dict[str, float]
    p_quasistatic: float | None
    runs: int
    seconds: float
    failed: int  #: runs without an answer (left out of the statistics)

    def as_dict(self) -> dict[str, object]:
        """The statistics as JSON-ready fields (``uncertainty`` of the commands' --json).

        Returns
        -------
        dict
            ``method``, ``runs``, ``seconds``, ``failed``, ``inputs`` (name -> mean, sd), one
            entry per output (mean, sd, ci95) and ``p_quasistatic`` where there is one.
        """
        out: dict[str, object] = {"method": self.method, "runs": self.runs,
                                  "seconds": self.seconds, "failed": self.failed,
                                  "inputs": {k: {"mean": m, "sd": s}
                                             for k, (m, s) in self.inputs.items()}}  # fmt: skip
        for k in self.mean:
            out[k] = {"mean": self.mean[k], "sd": self.sd[k], "ci95": [self.low[k], self.high[k]]}
        if self.p_quasistatic is not None:
            out["p_quasistatic"] = self.p_quasistatic
        return out


def _normal_cdf(x: float) -> float:
    """Phi(x), the standard normal distribution function."""
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


def design(inputs: dict[str, tuple[float, float]], method: str, samples: int = 32
           ) -> list[dict[str, float]]:  # fmt: skip
    """The input values of every run: the plain run first, then the method's points.

    Parameters
    ----------
    inputs : dict
        Input name -> (mean, sd).
    method : str
        "linear" (one run per input with sd > 0, moved by +1 sd) or "sobol".
    samples : int
        Sobol runs, a power of two >= 2.

    Returns
    -------
    list of dict
        Input name -> value for each run; only the plain run where every sd is zero.

    Raises
    ------
    RotbeamInputError
        If the method is unknown or, for "sobol", `samples` is not a power of two >= 2.
    """
    if method not in METHODS:
        raise RotbeamInputError(f"uncertainty method {method!r}; allowed: {', '.join(METHODS)}")
    plain = {k: m for k, (m, _) in inputs.items()}
    live = [k for k, (_, s) in inputs.items() if s > 0]
    if not live:
        return [plain]
    if method == "linear":
        return [plain] + [plain | {k: inputs[k][0] + inputs[k][1]} for k in live]
    if samples < 2 or samples & (samples - 1):
        raise RotbeamInputError(f"uncertainty samples must be a power of two >= 2, got {samples}")
    from scipy.stats import norm, qmc  # here: only a Sobol design needs scipy.stats (0.5 s)

    u = qmc.Sobol(len(live), scramble=True, seed=0).random(samples)
    z = norm.ppf(u)
    return [plain] + [
        plain | {k: inputs[k][0] + inputs[k][1] * z[i, j] for j, k in enumerate(live)}
        for i in range(samples)
    ]


def summarise(method: str, inputs: dict[str, tuple[float, float]],
              outputs: list[dict[str, float]], threshold: float | None,
              seconds: float) -> Propagated:  # fmt: skip
    """Statistics of the runs' outputs (first run the plain one) by the method's rule.

    "linear": the plain run's value as mean and sd = sqrt(sum (Y_i - Y_0)^2), interval mean +-
    1.96 sd, P(quasi-static) = Phi((threshold - Delta RMS) / sd).  "sobol": sample mean and sd,
    the 2.5 / 97.5 % quantiles and the fraction of runs below the threshold, over the runs with
    an answer.

    Parameters
    ----------
    method : str
        "linear" or "sobol".
    inputs : dict
        Input name -> (mean, sd), reported with the result.
    outputs : list of dict
        Output name -> value per run, in the order of `design` (NaN: no answer).
    threshold : float or None
        Delta RMS threshold (dimensionless) for P(quasi-static); None: no probability.
    seconds : float
        Wall time of the runs [s], reported with the result.

    Returns
    -------
    Propagated
    """
    keys = list(outputs[0])
    vals = {k: np.array([o.get(k, math.nan) for o in outputs], dtype=float) for k in keys}
    ok = np.all([np.isfinite(v) for v in vals.values()], axis=0)
    failed = int((~ok).sum())
    mean, sd, low, high = {}, {}, {}, {}
    p = None
    live = len(outputs) > 1
    for k, v in vals.items():
        if not live:
            mean[k], sd[k] = float(v[0]), 0.0
        elif method == "linear":
            mean[k] = float(v[0])
            sd[k] = float(np.sqrt(np.sum((v[1:] - v[0]) ** 2)))
        else:
            s = v[1:][ok[1:]]
            mean[k], sd[k] = float(np.mean(s)), float(np.std(s, ddof=1))
        if method == "sobol" and live:
            s = v[1:][ok[1:]]
            low[k], high[k] = (float(x) for x in np.quantile(s, [0.025, 0.975]))
        else:
            low[k], high[k] = mean[k] - 1.96 * sd[k], mean[k] + 1.96 * sd[k]
    if threshold is not None and "delta_rms" in vals:
        d = vals["delta_rms"]
        if not live:
            p = float(d[0] < threshold)
        elif method == "linear":
            p = (
                _normal_cdf((threshold - mean["delta_rms"]) / sd["delta_rms"])
                if sd["delta_rms"] > 0
                else float(mean["delta_rms"] < threshold)
            )
        else:
            s = d[1:][ok[1:]]
            p = float(np.mean(s < threshold)) if s.size else math.nan
    return Propagated(method, inputs, mean, sd, low, high, p, len(outputs), seconds, failed)


def propagate(
    inputs: dict[str, tuple[float, float]],
    run: Callable[[dict[str, float]], dict[str, float]],
    method: str = "linear",
    samples: int = 32,
    threshold: float | None = None,
) -> Propagated:
    """Run `run(values)` at every design point and summarise; `run` returns named outputs
    (NaN where it found no answer; those are counted in `failed`).

    Parameters
    ----------
    inputs : dict
        Input name -> (mean, sd).
    run : callable
        Input name -> value, to output name -> value (e.g. rms_dynamic, delta_rms).
    method : str
        "linear" or "sobol".
    samples : int
        Sobol runs, a power of two >= 2.
    threshold : float or None
        Delta RMS threshold (dimensionless) for P(quasi-static); None: no probability.

    Returns
    -------
    Propagated
        Mean, sd and 95 % interval of each output, P(quasi-static), the runs and their cost.

    Raises
    ------
    RotbeamInputError
        If the method or the number of samples is not allowed (`design`), or a sample lies
        outside a parameter's range.
    """
    t0 = time.perf_counter()
    points = design(inputs, method, samples)
    outputs = [run(v) for v in points]
    return summarise(method, inputs, outputs, threshold, time.perf_counter() - t0)


def read_inputs(section: Any, spec: str | None, where: str = "scene file") -> dict:
    """The uncertain inputs of a scene file's `uncertainty` section and a CLI spec (which wins).

    Parameters
    ----------
    section : mapping or None
        The scene file's section, e.g. {"gamma": "0.039 +- 0.008"}.
    spec : str or None
        "gamma=0.039+-0.008,E=1.22e6+-0.05e6".
    where : str
        Names the section's source in an error.

    Returns
    -------
    dict
        Input name -> (mean, sd).

    Raises
    ------
    RotbeamInputError
        If the section is not a mapping, or an input does not parse (`parse_spec`).
    """
    if section is not None and not isinstance(section, dict):
        raise RotbeamInputError(
            f'{where}: uncertainty must be a mapping, e.g. uncertainty: {{gamma: "0.039 +- 0.008"}}'
        )
    return parse_spec(section) | parse_spec(spec)


def at_means(scene: Scene, inputs: dict[str, tuple[float, float]]) -> Scene:
    """The scene with every uncertain input at its mean (the plain run is the run there).

    Parameters
    ----------
    scene : Scene
        The scene as given.
    inputs : dict
        Input name -> (mean, sd).

    Returns
    -------
    Scene
        The scene with each input's field set to its mean (the scene itself without inputs).

    Raises
    ------
    RotbeamInputError
        If a mean lies outside its field's range.
    """
    if not inputs:
        return scene
    beam, drive = apply(scene.beam, scene.drive, {k: m for k, (m, _) in inputs.items()})
    return replace(scene, beam=beam, drive=drive)


@one_blas_thread
def simulate_spread(
    scene: Scene,
    plain: SceneResult,
    inputs: dict[str, tuple[float, float]],
    method: str = "linear",
    samples: int = 32,
    threshold: float = 0.10,
    time_budget: TimeBudget | None = None,
) -> Propagated:
    """RMS, Delta RMS and P(quasi-static) of a scene over its inputs' spread.

    Parameters
    ----------
    scene : Scene
        The scene at the inputs' means (`at_means`).
    plain : SceneResult
        Its own result, reused for the plain run; its orbit seeds the others.
    inputs : dict
        Input name -> (mean, sd).
    method : str
        "linear" or "sobol".
    samples : int
        Sobol runs (a power of two).
    threshold : float
        Delta RMS below which a run counts as quasi-static, dimensionless, in (0, 1).
    time_budget : TimeBudget or None
        The wall-time budget of all the runs (a run it cuts counts as failed); None: each run
        its numerics.max_seconds.

    Returns
    -------
    Propagated
        Mean, sd and 95 % interval of rms_dynamic, rms_quasistatic and delta_rms, and
        P(quasi-static).

    Raises
    ------
    RotbeamInputError
        If the method or samples are not allowed, or a sample lies outside a field's range.
    """
    from ..runs.scene import simulate

    orbit = plain.dynamic.periodic
    guess = orbit.theta if orbit is not None and orbit.converged else None

    def run(values: dict[str, float]) -> dict[str, float]:
        beam, drive = apply(scene.beam, scene.drive, values)
        res = plain if (beam, drive) == (scene.beam, scene.drive) else simulate(
            replace(scene, beam=beam, drive=drive), guess=guess,
            time_budget=time_budget)  # fmt: skip
        return {k: (getattr(res, k) if res.converged else float("nan"))
                for k in ("rms_dynamic", "rms_quasistatic", "delta_rms")}  # fmt: skip

    return propagate(inputs, run, method, samples, threshold)


@one_blas_thread
def critical_spread(
    scene: Scene,
    plain: Critical,
    inputs: dict[str, tuple[float, float]],
    method: str = "linear",
    samples: int = 32,
    threshold: float = 0.10,
    ftol: float = 1e-3,
    time_budget: TimeBudget | None = None,
) -> Propagated:
    """f_d* and c = f_d* / f_0 over the inputs' spread (`plain`: the search at the means).

    Parameters
    ----------
    scene : Scene
        The scene at the inputs' means (`at_means`).
    plain : Critical
        The search at the means, reused for the plain run.
    inputs : dict
        Input name -> (mean, sd).
    method : str
        "linear" or "sobol".
    samples : int
        Sobol runs (a power of two).
    threshold : float
        The Delta RMS threshold of every search, dimensionless, in (0, 1).
    ftol : float
        Relative tolerance of every search on f_d* (`critical`'s rtol), dimensionless.
    time_budget : TimeBudget or None
        The wall-time budget of all the searches (a search it cuts counts as failed); None:
        each search its numerics.max_seconds.

    Returns
    -------
    Propagated
        Mean, sd and 95 % interval of f_d_star [Hz], c (dimensionless) and f0_hz [Hz]; no
        probability of a verdict.

    Raises
    ------
    RotbeamInputError
        If the method or samples are not allowed, or a sample lies outside a field's range.
    """
    from .verdict import critical

    def run(values: dict[str, float]) -> dict[str, float]:
        beam, drive = apply(scene.beam, scene.drive, values)
        same = (beam, drive) == (scene.beam, scene.drive)
        res = plain if same else critical(replace(scene, beam=beam, drive=drive), threshold, ftol,
                                          time_budget=time_budget)  # fmt: skip
        return {"f_d_star": res.f_d_star, "c": res.f_d_star / res.f0_hz, "f0_hz": res.f0_hz}

    return propagate(inputs, run, method, samples, None)
