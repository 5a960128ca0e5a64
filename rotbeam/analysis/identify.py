"""Beam parameters (E and gamma by default) from a measured resonance curve RMS(y_m)(f_d).

Least squares with the full model in log parameters, one periodic steady state per measured f_d
and evaluation, with standard errors and 95 % intervals from the Jacobian at the optimum
(`rotbeam identify`).  The start, the steps, the penalty for runs without a steady state and the
intervals: docs/calibration.md, "E and gamma from a resonance curve".
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, replace

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import t as student_t

from ..config.errors import RotbeamInputError
from ..config.threads import one_blas_thread
from ..model.modes import resonance_frequency_hz
from ..model.params import Beam, Drive, Effects
from ..runs.scene import Scene, simulate
from ..solve.numerics import Numerics
from ..solve.timebudget import TimeBudget
from .measurements import ResonanceCurve

FITTABLE = ("L", "h", "b", "E", "rho", "R", "gamma")
STEP = 0.01  #: forward-difference step in log(X): 1 %
BOUND = 3.0  #: |log(X / X_start)| <= BOUND (a factor e^3 = 20 either way)
#: Default numerics of the fit: N = 20, no Richardson (N = 10 fails near a lightly damped
#: resonance), and a budget in periods rather than wall time, so that a run that finds no steady
#: state fails after the same work on any machine (docs/calibration.md gives the accuracy cost).
FIT_NUMERICS = Numerics(N=20, max_periods=100)
#: A trial point whose runs find no steady state gets residuals of this size (times the data's
#: largest value): the trust region shrinks back towards the last good point.
PENALTY = 10.0


class IdentifyFailed(Exception):
    """The fit could not be carried out (a model run without steady state, a beam out of
    range); the message says where."""


class FitOutOfTime(IdentifyFailed):
    """The time budget ran out before the fit converged; the message says after how many runs."""


def parse_names(text: str) -> tuple[str, ...]:
    """The names of the parameters to fit, from the text of `--fit`: 'E,gamma' -> ('E', 'gamma').

    Parameters
    ----------
    text : str
        A comma list of beam fields (FITTABLE: L, h, b, E, rho, R, gamma).

    Returns
    -------
    tuple of str
        The names in the order given.

    Raises
    ------
    RotbeamInputError
        If the text names nothing, an unknown field, or a field twice.
    """
    names = tuple(n.strip() for n in text.split(",") if n.strip())
    bad = [n for n in names if n not in FITTABLE]
    if not names or bad:
        raise RotbeamInputError(
            f"--fit {text!r}: {'unknown ' + ', '.join(bad) if bad else 'names nothing'}; "
            f"allowed: comma list of {', '.join(FITTABLE)}"
        )
    if len(set(names)) != len(names):
        raise RotbeamInputError(f"--fit {text!r} names a parameter twice")
    return names


@dataclass
class ResonanceModel:
    """RMS(y_m) at fixed drive frequencies for a beam; orbits reused, results cached.

    Called with a `Beam`, it runs one periodic steady state per frequency of `f_d` [Hz] at the
    speed `omega0` and velocity amplitude `amplitude` [rad/s] and returns RMS(y_m) / L
    (dimensionless) per frequency; each run is seeded with the last orbit at its frequency, and a
    beam seen before costs nothing.  `runs` counts steady states, `evaluations` beams.  A run
    without a steady state raises `IdentifyFailed`.
    """

    f_d: np.ndarray
    omega0: float
    amplitude: float = 1.0
    effects: Effects = field(default_factory=Effects)
    numerics: Numerics = FIT_NUMERICS
    runs: int = 0
    evaluations: int = 0
    progress: Callable[[], None] | None = None  #: called after every steady state
    time_budget: TimeBudget | None = None  #: the whole fit's; None: numerics.max_seconds a run
    _guess: list = field(default_factory=list)
    _cache: dict = field(default_factory=dict)

    def __call__(self, beam: Beam) -> np.ndarray:
        key = tuple(asdict(beam).values())
        if key in self._cache:
            return self._cache[key]
        if not self._guess:
            self._guess = [None] * len(self.f_d)
        out = np.empty(len(self.f_d))
        self.evaluations += 1
        for k, f in enumerate(self.f_d):
            scene = Scene(beam, Drive(self.omega0, self.amplitude, float(f)), self.effects,
                          self.numerics)  # fmt: skip
            if self.time_budget is not None and self.time_budget.spent():
                raise FitOutOfTime(
                    self.time_budget.cut(f"the fit after {self.runs} steady states")
                    + f" (last trial {_describe(beam)})"
                )
            res = simulate(scene, guess=self._guess[k], time_budget=self.time_budget)
            self.runs += 1
            if self.progress is not None:
                self.progress()
            if not res.converged or not math.isfinite(res.rms_dynamic):
                raise IdentifyFailed(
                    f"no steady state at f_d = {f:.4g} Hz for {_describe(beam)}: "
                    f"{res.dynamic.message}"
                )
            orbit = res.dynamic.periodic
            if orbit is not None and orbit.converged:
                self._guess[k] = orbit.theta
            out[k] = res.rms_dynamic
        self._cache[key] = out
        return out


def _describe(beam: Beam) -> str:
    return f"E = {beam.E:.4g} Pa, gamma = {beam.gamma:.4g} N s/m^2"


@dataclass(frozen=True)
class Identification:
    """The result of `identify`: fitted values, standard errors, 95 % intervals and the cost.

    Values are in the beam fields' SI units (E in Pa, gamma in N s/m^2, lengths in m, rho in
    kg/m^3); the intervals come from log parameters, so they are not symmetric about the value
    (docs/calibration.md, "E and gamma from a resonance curve").
    """

    names: tuple[str, ...]
    values: dict[str, float]
    stderr: dict[str, float]
    low: dict[str, float]  #: 95 % interval
    high: dict[str, float]
    start: dict[str, float]
    beam: Beam  #: the scene's beam with the fitted values
    model_rms: np.ndarray  #: the fitted model at the measured f_d
    rss: float  #: sum of squared (weighted) residuals
    dof: int
    scale: float  #: s^2 of the covariance (see the module docstring)
    evaluations: int  #: residual evaluations (one model run per f_d each)
    runs: int  #: steady states computed
    seconds: float
    success: bool
    message: str

    def as_dict(self) -> dict[str, object]:
        """The fit as JSON-ready fields (`rotbeam identify --json`).

        Returns
        -------
        dict
            For each fitted X: ``X``, ``X_stderr``, ``X_ci95`` ([low, high]) and ``X_start``;
            then ``rss``, ``dof``, ``residual_scale``, ``model_rms``, ``evaluations``, ``runs``,
            ``seconds``, ``success`` and ``message``.
        """
        out: dict[str, object] = {}
        for n in self.names:
            out[n] = self.values[n]
            out[f"{n}_stderr"] = self.stderr[n]
            out[f"{n}_ci95"] = [self.low[n], self.high[n]]
            out[f"{n}_start"] = self.start[n]
        out.update(rss=self.rss, dof=self.dof, residual_scale=self.scale,
                   model_rms=self.model_rms.tolist(), evaluations=self.evaluations,
                   runs=self.runs, seconds=self.seconds, success=self.success,
                   message=self.message)  # fmt: skip
        return out


def _with(beam: Beam, names: tuple[str, ...], values: np.ndarray) -> Beam:
    try:
        return replace(beam, **{n: float(v) for n, v in zip(names, values, strict=True)})
    except RotbeamInputError as exc:
        raise IdentifyFailed(f"the fit left the beam's range: {exc}") from None


def _peak_frequency(curve: ResonanceCurve) -> float:
    f, r = curve.f_d, curve.rms
    k = int(np.argmax(r))
    if 0 < k < f.size - 1:
        a, b, c = np.polyfit(f[k - 1 : k + 2], r[k - 1 : k + 2], 2)
        if a < 0 and f[k - 1] < -b / (2 * a) < f[k + 1]:
            return float(-b / (2 * a))
    return float(f[k])


def start_values(curve: ResonanceCurve, names: tuple[str, ...], beam: Beam,
                 model: ResonanceModel) -> Beam:  # fmt: skip
    """The fit's start: E from the peak's f_d, then gamma from its height.

    E is set so that the model's linear f_0 at Omega_0 + a equals the f_d of the data's peak;
    gamma is scaled by the ratio of the model's largest RMS to the data's (docs/calibration.md,
    "E and gamma from a resonance curve").  Other fields keep the beam's values.

    Parameters
    ----------
    curve : ResonanceCurve
        The measured resonance curve.
    names : tuple of str
        The fields to fit; only E and gamma get a start of their own.
    beam : Beam
        The beam to start from.
    model : ResonanceModel
        The model at the measured frequencies (its runs count towards the fit's cost).

    Returns
    -------
    Beam
        The beam with the start values.

    Raises
    ------
    IdentifyFailed
        If a start value leaves the beam's range.
    """
    if "E" in names:
        target = _peak_frequency(curve)
        for _ in range(6):  # f_0^2 is affine in E at fixed speed: converges in a few steps
            f0 = resonance_frequency_hz(beam, abs(model.omega0) + model.amplitude)
            beam = _with(beam, ("E",), np.array([beam.E * (target / f0) ** 2]))
    if "gamma" in names and beam.gamma > 0:
        for _ in range(3):  # a lightly damped start may find no steady state: more damping
            try:
                ratio = float(np.max(model(beam)) / np.max(curve.rms))
                break
            except IdentifyFailed:
                beam = _with(beam, ("gamma",), np.array([beam.gamma * 1.5]))
        else:
            return beam
        beam = _with(beam, ("gamma",), np.array([beam.gamma * min(max(ratio, 0.2), 5.0)]))
    return beam


@one_blas_thread
def identify(
    curve: ResonanceCurve,
    omega0: float,
    amplitude: float = 1.0,
    names: tuple[str, ...] = ("E", "gamma"),
    beam: Beam | None = None,
    effects: Effects | None = None,
    numerics: Numerics | None = None,
    progress: Callable[[], None] | None = None,
    time_budget: TimeBudget | None = None,
) -> Identification:
    """Least-squares fit of beam parameters to a measured resonance curve, with intervals.

    Every residual evaluation runs the full model's periodic steady state at every measured
    f_d; the parameters are fitted as log(X / X_start) with a trust region, and the standard
    errors and 95 % intervals come from the Jacobian at the optimum (docs/calibration.md, "E and
    gamma from a resonance curve").

    Parameters
    ----------
    curve : ResonanceCurve
        The measurement: f_d [Hz], RMS(y_m) (dimensionless) and optionally its std.
    omega0 : float
        Mean angular velocity of the measurement, Omega_0 [rad/s].
    amplitude : float
        Velocity amplitude a of the drive [rad/s].
    names : tuple of str
        Beam fields to fit (`parse_names`).
    beam : Beam or None
        The beam to start from and to hold the other fields (default: Table 1).
    effects : Effects or None
        Effects of the model (default: `Effects()`).
    numerics : Numerics or None
        Numerics of every run (default: FIT_NUMERICS, N = 20).
    progress : callable or None
        Called after every steady state of the fit.
    time_budget : TimeBudget or None
        The wall-time budget of the whole fit; None: numerics.max_seconds for it.

    Returns
    -------
    Identification
        Fitted values, standard errors, intervals, the fitted beam and its curve, and the cost.

    Raises
    ------
    RotbeamInputError
        If the curve has no more points than there are parameters.
    IdentifyFailed
        If the fit cannot be carried out: no steady state at the start or the optimum, a beam
        out of range, or the time budget spent first (`FitOutOfTime`).
    """
    t0 = time.perf_counter()
    model = ResonanceModel(curve.f_d, omega0, amplitude, effects or Effects(),
                           numerics or FIT_NUMERICS, progress=progress,
                           time_budget=time_budget or TimeBudget(
                               (numerics or FIT_NUMERICS).max_seconds))  # fmt: skip
    n, p = curve.f_d.size, len(names)
    if n <= p:
        raise RotbeamInputError(f"{n} points cannot fit {p} parameters; need >= {p + 1}")
    start = start_values(curve, names, beam or Beam(), model)
    x0 = np.array([getattr(start, k) for k in names])
    resid, jac, failures = _residuals(curve, names, start, x0, model)
    sol = least_squares(resid, np.zeros(p), jac=jac, bounds=(-BOUND, BOUND), method="trf",
                        xtol=1e-4, ftol=1e-8, max_nfev=40)  # fmt: skip
    x = x0 * np.exp(sol.x)
    r = resid(sol.x, strict=True)
    rss, dof = float(r @ r), n - p
    scale = rss / dof if curve.rms_std is None else max(1.0, rss / dof)
    se = _log_stderr(jac(sol.x), scale)  # the Jacobian at the optimum (cached base point)
    q = float(student_t.ppf(0.975, dof))
    fitted = _with(start, names, x)
    return Identification(
        names=names, values=dict(zip(names, x.tolist(), strict=True)),
        stderr={k: float(v * s) for k, v, s in zip(names, x, se, strict=True)},
        low={k: float(v * math.exp(-q * s)) for k, v, s in zip(names, x, se, strict=True)},
        high={k: float(v * math.exp(q * s)) for k, v, s in zip(names, x, se, strict=True)},
        start=dict(zip(names, x0.tolist(), strict=True)), beam=fitted, model_rms=model(fitted),
        rss=rss, dof=dof, scale=scale, evaluations=model.evaluations, runs=model.runs,
        seconds=time.perf_counter() - t0, success=bool(sol.success),
        message=str(sol.message) + (f"; {len(failures)} trial point(s) without steady state"
                                    if failures else ""),
    )  # fmt: skip


def _residuals(curve: ResonanceCurve, names: tuple[str, ...], start: Beam, x0: np.ndarray,
               model: ResonanceModel):  # fmt: skip
    """The weighted residuals r(u) of the fit in log parameters u (x = x0 exp(u)), their
    forward-difference Jacobian, and the list the trial points without a steady state go to
    (a penalty residual, unless `strict`)."""
    n, p = curve.f_d.size, len(names)
    w = curve.rms_std if curve.rms_std is not None else np.ones(n)
    failures: list[str] = []

    def resid(u: np.ndarray, strict: bool = False) -> np.ndarray:
        try:
            return (model(_with(start, names, x0 * np.exp(u))) - curve.rms) / w
        except FitOutOfTime:
            raise
        except IdentifyFailed as exc:
            if strict:
                raise
            failures.append(str(exc))
            return np.full(n, PENALTY * float(np.max(curve.rms))) / w

    def jac(u: np.ndarray) -> np.ndarray:
        r0 = resid(u, strict=True)
        cols = []
        for e in np.eye(p):  # forward, or backward where the forward point has no steady state
            try:
                cols.append((resid(u + STEP * e, strict=True) - r0) / STEP)
            except IdentifyFailed:
                cols.append((r0 - resid(u - STEP * e, strict=True)) / STEP)
        return np.column_stack(cols)

    return resid, jac, failures


def _log_stderr(J: np.ndarray, scale: float) -> np.ndarray:
    """Standard errors of the log parameters from the Jacobian at the optimum (infinite when
    J^T J is singular: a parameter the curve does not determine)."""
    try:
        cov = scale * np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov = np.full((J.shape[1], J.shape[1]), np.inf)
    return np.sqrt(np.clip(np.diag(cov), 0.0, np.inf))
