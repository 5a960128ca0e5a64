"""A single move: the beam time-stepped through it and a settling window after it.

The beam starts at rest (or, with `drive.move_start: quasistatic`, in the quasi-static state of
the move's first sample) and runs beside its quasi-static twin.  The answers: peaks, RMS and
Delta RMS over the move, the residual vibration after it and how long that takes to settle
(definitions: docs/model.md, "Drives").
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..config.errors import RotbeamInputError
from ..config.threads import one_blas_thread
from ..model.criterion import delta_rms, rms
from ..model.modes import resonance_frequency_hz
from ..solve.ivp import CUT, FAILED, IvpInterval
from ..solve.quasistatic import QuasiStaticError, quasistatic_series, solve_static
from ..solve.stepping import EXPLICIT_TOL, NONSTIFF, CompiledStepper, stiffest_rate
from ..solve.system import FirstOrderSystem
from .observables import OBSERVABLES, States, compare, observable_names, still
from .scene import Scene, folded, model_name

#: without `settle`: integrate first-mode periods after the move until |y_m| over one of them
#: stays below this share of the peak, at most SETTLE_PERIODS of them
CALM = 0.01
SETTLE_PERIODS = 20
#: settling time: from the end of the move until |y_m| stays below this share of the peak
SETTLED = 0.05
#: samples of y_m per first-mode period (and at least MOVE_SAMPLES over the move)
PER_PERIOD = 32
MOVE_SAMPLES = 512
#: the move is integrated in this many windows, each reported to `progress`
MOVE_WINDOWS = 20
#: the angles' absolute tolerance: this share of numerics.rtol times the quasi-static
#: response's largest angle (docs/model.md, "Drives": its error in y_m is within 1.5e-6 L on
#: the reference beam's designed moves; a share of 1e-3 costs 2-6x the time)
ATOL_SHARE = 1.0


@dataclass
class MoveResult:
    """The beam through a single move, dynamic beside quasi-static.

    What `simulate_move` returns: the samples (SI time, y_m in units of L) and the move's
    numbers.  NaN marks a number the run did not reach (no samples, or a settling time beyond
    the window).
    """

    scene: Scene
    t_s: np.ndarray  #: sample instants from the start of the move [s]
    y_dynamic: np.ndarray  #: y_m / L at the samples
    y_quasistatic: np.ndarray  #: y_m / L of the quasi-static twin at the samples
    omega: np.ndarray  #: the drive's Omega at the samples [rad/s]
    move_s: float  #: the move's duration [s]
    peak_ym: float  #: largest |y_m| / L during the move, dynamic
    peak_ym_quasistatic: float  #: the same, quasi-static
    rms_dynamic: float  #: RMS of y_m / L over the move
    rms_quasistatic: float
    delta_rms: float
    residual_ym: float  #: largest |y_m| / L after the move ends
    settling_time_s: float  #: from the move's end until |y_m| stays below SETTLED peak_ym
    settle_s: float  #: the window integrated after the move [s]
    converged: bool  #: the whole window was integrated
    message: str
    nfev: int
    seconds: float
    theta: np.ndarray | None = None  #: (m, n) angles [rad] at the samples
    theta_t: np.ndarray | None = None  #: (m, n) their rates (units of 1/T)
    theta_quasistatic: np.ndarray | None = None  #: (m, n) the quasi-static twin's angles

    def observables(self, names: str | Iterable[str] = ("y_m",)) -> dict[str, dict[str, Any]]:
        """Observables of the move, dynamic beside quasi-static (docs/model.md, "Observables").

        RMS and peaks over the move, as for y_m; ``residual``: the largest |value| of the
        dynamic run after the move.  The dynamic accelerations are the equation of motion's at
        the stepper's states; the quasi-static twin's rates are zero (it balances the loads
        with the beam at rest in the turning frame; after the move it is the straight beam).

        Parameters
        ----------
        names : str or iterable of str
            Names of `rotbeam.runs.observables.OBSERVABLES`, or one comma-separated string.

        Returns
        -------
        dict
            name -> {``unit``, ``rms_dynamic``, ``rms_quasistatic``, ``delta_rms``,
            ``peak_dynamic``, ``peak_quasistatic``, ``residual``}.

        Raises
        ------
        RotbeamInputError
            For a name the registry does not hold.
        ValueError
            If the result carries no angles (a MoveResult built without them).
        """
        names = observable_names(names)
        model, beam = self.scene.model(), self.scene.beam
        tau = self.t_s / beam.T
        in_move = tau < model.dl.law.duration
        dyn, qs = self._states(model, any(OBSERVABLES[name].rates for name in names))
        out = {}
        for name in names:
            obs = OBSERVABLES[name]
            values, twin = obs(model, beam, dyn), obs(model, beam, qs)
            out[name] = compare(values[in_move], twin[in_move], obs.unit)
            after = np.abs(values[~in_move])
            out[name]["residual"] = float(np.max(after)) if after.size else math.nan
        return out

    def series(self, name: str) -> np.ndarray:
        """One observable of the dynamic run at every sample (`t_s`), in its unit.

        Parameters
        ----------
        name : str
            A name of `rotbeam.runs.observables.OBSERVABLES`.

        Returns
        -------
        numpy.ndarray
            Shape of `t_s`.

        Raises
        ------
        RotbeamInputError
            For a name the registry does not hold.
        ValueError
            If the result carries no angles (a MoveResult built without them).
        """
        (name,) = observable_names(name)
        model = self.scene.model()
        dyn, _ = self._states(model, OBSERVABLES[name].rates)
        return OBSERVABLES[name](model, self.scene.beam, dyn)

    def _states(self, model, rates: bool) -> tuple[States, States]:
        """The dynamic run's states (with accelerations where `rates`) and the twin's."""
        if self.theta is None or self.theta_quasistatic is None:
            raise ValueError("this MoveResult carries no angles (theta) to observe")
        tau = self.t_s / self.scene.beam.T
        qs = States(tau, self.theta_quasistatic, still(self.theta_quasistatic),
                    still(self.theta_quasistatic))  # fmt: skip
        dyn = States(tau, self.theta, self.theta_t)
        if rates:
            dyn = States(tau, self.theta, self.theta_t, _accelerations(model, dyn))
        return dyn, qs

    def summary(self) -> dict[str, Any]:
        """The move's numbers for tables and JSON (scalars only).

        Returns
        -------
        dict
            ``peak_ym``, ``peak_ym_quasistatic``, ``rms_dynamic``, ``rms_quasistatic``,
            ``residual_ym`` (units of L), ``delta_rms`` (dimensionless), ``settling_time_s``,
            ``settle_s``, ``move_s``, ``seconds`` [s], ``converged``, ``message``, ``nfev``,
            and ``N``, ``drive`` ("move") and ``effects`` (comma-separated).
        """
        keys = ("peak_ym", "peak_ym_quasistatic", "rms_dynamic", "rms_quasistatic",
                "delta_rms", "residual_ym", "settling_time_s", "settle_s", "move_s",
                "converged", "message", "nfev", "seconds")  # fmt: skip
        out = {k: getattr(self, k) for k in keys}
        out.update({"N": self.scene.numerics.N, "model": model_name(self.scene.numerics),
                    "drive": "move",
                    "effects": ",".join(self.scene.effects.active())})  # fmt: skip
        return out

    def time_series(self) -> dict[str, np.ndarray]:
        """The samples, for a CSV file or a figure.

        Returns
        -------
        dict
            ``t_s`` [s] from the start of the move, ``omega`` [rad/s], ``y_m_dynamic`` and
            ``y_m_quasistatic`` (units of L); arrays of one length.
        """
        return {"t_s": self.t_s, "omega": self.omega, "y_m_dynamic": self.y_dynamic,
                "y_m_quasistatic": self.y_quasistatic}  # fmt: skip


def _accelerations(model, states: States) -> np.ndarray:
    """Theta_tt at each sample from the equation of motion (`DiscreteModel.acceleration`)."""
    lam, lam_dot = model.drive_rows(states.tau)
    rows = [model.acceleration(states.theta[k], states.theta_t[k], lam[k], lam_dot[k])
            for k in range(states.tau.size)]  # fmt: skip
    return np.array(rows) if rows else np.zeros_like(states.theta)


@one_blas_thread
def simulate_move(
    scene: Scene, progress: Callable[[float, float], None] | None = None
) -> MoveResult:
    """Time-step a scene whose drive is a `move` through it and a settling window after it.

    A move has no periodic steady state, so this replaces `rotbeam.runs.scene.simulate` for
    it.  The beam starts at rest before the move: in the static state of the first sample's
    speed (the centrifugal load alone; the straight beam for a radial clamp) with zero rates,
    the move's dOmega/dt acting from t = 0 (`drive.move_start: quasistatic` starts it instead in
    the quasi-static state of the first sample, its rate from the quasi-static series: a move
    that continues a motion the beam followed quasi-statically).  Radau with the exact Jacobian
    at numerics.rtol (its right-hand side compiled where the model offers a kernel; where the
    explicit method's stability allows, the compiled DOP853 march instead, `_compiled_suits`),
    in MOVE_WINDOWS windows, samples y_m PER_PERIOD times per first-mode period (at least
    MOVE_SAMPLES over the move); after the move the disk
    turns at its last speed for `drive.settle` seconds or, without it, first-mode periods until
    |y_m| over one stays below CALM of the peak (at most SETTLE_PERIODS).  The wall time is
    bounded by numerics.max_seconds; a run cut short says so in `converged` and `message`.

    Parameters
    ----------
    scene : Scene
        Beam, a drive with a `move`, effects, numerics.
    progress : callable or None
        progress(done_s, planned_s) after every window integrated: seconds of the move and of
        the settling window done, and planned (the settling window's longest).

    Returns
    -------
    MoveResult
        The samples and the move's numbers: peaks, RMS, Delta RMS, residual vibration and
        settling time (docs/model.md, "Drives").

    Raises
    ------
    RotbeamInputError
        If the scene's drive is not a move.
    """
    if scene.drive.periodic:
        raise RotbeamInputError(
            f"simulate_move needs a drive with a move, got a {scene.drive.kind} drive"
        )
    t0 = time.perf_counter()
    T = scene.beam.T
    model = scene.model()
    law = model.dl.law
    f1_end = resonance_frequency_hz(scene.beam, abs(scene.drive.as_kind.final_speed()))
    f1_max = resonance_frequency_hz(scene.beam, scene.drive.omega_max)
    dt = 1.0 / (PER_PERIOD * f1_max) / T  # sample step [units of T]
    steps = max(MOVE_SAMPLES, math.ceil(law.duration / dt))
    taus = np.arange(steps) * (law.duration / steps)
    try:
        theta_qs = quasistatic_series(model, taus)
    except QuasiStaticError as exc:
        raise folded(scene, exc) from None
    if scene.drive.move_start == "quasistatic":
        z = _moving_state(taus, theta_qs)
    else:
        z = _resting_state(model, law.lam(0.0))
    system = FirstOrderSystem(model, t0 + scene.numerics.max_seconds, compiled=True)
    w1 = 2.0 * math.pi * f1_max * T
    scale = float(np.max(np.abs(theta_qs))) or 1e-6
    run = _Stepper(system, scene.numerics.rtol, scale, w1, _reporter(progress, scene, law, f1_end),
                   _compiled_suits(model, dt))  # fmt: skip
    ok, message = True, "through the move"
    for end in law.duration * np.arange(1, MOVE_WINDOWS + 1) / MOVE_WINDOWS:
        ok, message = run.through(run.z if run.z is not None else z, taus, float(end))
        if not ok:
            break
    y_qs = np.atleast_1d(model.midspan(theta_qs))
    peak = float(np.max(np.abs(run.y(model)))) if run.samples else math.nan
    settle_s = 0.0
    if ok:
        chunk = 1.0 / f1_end / T
        settle, message = _settle(run, model, scene, peak, chunk, dt)
        settle_s = settle * T
    tau_all = np.asarray(run.times)
    y = run.y(model)
    in_move = tau_all < law.duration
    y_move, qs_move = y[in_move], y_qs[: int(in_move.sum())]
    after = np.abs(y[~in_move])
    lam_all = np.array([law.lam(t) for t in tau_all])
    y_qs_all = np.concatenate([qs_move, np.zeros(after.size)])  # the straight beam after it
    n_move, n = int(in_move.sum()), model.n
    theta_qs_all = np.concatenate([theta_qs[:n_move], np.zeros((after.size, n))])
    return MoveResult(
        scene=scene,
        t_s=tau_all * T,
        y_dynamic=y,
        y_quasistatic=y_qs_all,
        omega=lam_all / T,
        move_s=law.duration * T,
        peak_ym=peak,
        peak_ym_quasistatic=float(np.max(np.abs(qs_move))) if qs_move.size else math.nan,
        rms_dynamic=rms(y_move) if y_move.size else math.nan,
        rms_quasistatic=rms(qs_move) if qs_move.size else math.nan,
        delta_rms=delta_rms(rms(y_move), rms(qs_move)) if y_move.size else math.nan,
        residual_ym=float(np.max(after)) if after.size else math.nan,
        settling_time_s=_settling_time(tau_all[~in_move], after, peak, law.duration) * T,
        settle_s=settle_s,
        converged=run.ok,
        message=message,
        nfev=run.nfev,
        seconds=time.perf_counter() - t0,
        theta=np.array(run.samples).reshape(-1, n),
        theta_t=np.array(run.rates).reshape(-1, n),
        theta_quasistatic=theta_qs_all,
    )


def _resting_state(model, lam: float) -> np.ndarray:
    """(Theta, 0): the static state under the centrifugal load of a steady speed lam, at rest."""
    res = solve_static(model, lam, 0.0)
    if not res.converged:
        raise RotbeamInputError(
            f"drive.move: no static state of the beam at the move's first speed "
            f"(Omega T = {lam:.4g}): {res.message}"
        )
    return np.concatenate([res.theta, np.zeros(model.n)])


def _moving_state(taus: np.ndarray, theta_qs: np.ndarray) -> np.ndarray:
    """(Theta, Theta_t) of the quasi-static state at the first sample (its rate by a one-sided
    difference of the quasi-static series): `move_start: quasistatic`."""
    rate = (theta_qs[1] - theta_qs[0]) / (taus[1] - taus[0])
    return np.concatenate([theta_qs[0], rate])


def _reporter(progress, scene: Scene, law, f1_end: float) -> Callable[[float], None] | None:
    """progress(done_s, planned_s) from the stepper's time reached [units of T]."""
    if progress is None:
        return None
    T = scene.beam.T
    after = scene.drive.settle if scene.drive.settle is not None else SETTLE_PERIODS / f1_end
    planned = law.duration * T + after
    return lambda tau: progress(tau * T, planned)


def _compiled_suits(model, dt: float) -> bool:
    """Whether the compiled DOP853 march steps the move: the model offers one without a
    tangent (`DiscreteModel.kernel`) and stability bounds its step less than the samples do,
    the stiffest rate times the sample step below `NONSTIFF` (a few modes of the modal model;
    the full model's top grid mode is far stiffer)."""
    return model.kernel(tangent=False)[0] is not None and stiffest_rate(model) * dt <= NONSTIFF


class _Stepper:
    """Radau over consecutive windows (`rotbeam.solve.ivp.IvpInterval`), or the compiled DOP853
    march where `_compiled_suits` says so, keeping the samples and the state at each window's
    end."""

    def __init__(
        self,
        system: FirstOrderSystem,
        rtol: float,
        scale: float,
        rate: float,
        report: Callable[[float], None] | None = None,
        compiled: bool = False,
    ) -> None:
        self.system, self.report = system, report
        n = system.n
        a = ATOL_SHARE * rtol * scale  # the angles' scale: the quasi-static response's
        atol = np.concatenate([np.full(n, a), np.full(n, a * rate)])  # the rates': times w1
        self.ivp = self.march = None
        if compiled:  # DOP853's error estimate is looser than Radau's at one rtol
            self.march = CompiledStepper(
                system.model, EXPLICIT_TOL * rtol, EXPLICIT_TOL * atol, tangent=False
            )
        else:
            self.ivp = IvpInterval(system.rhs, "Radau", rtol, atol, system.jac)
        self.times: list[float] = []
        self.samples: list[np.ndarray] = []
        self.rates: list[np.ndarray] = []
        self.z: np.ndarray | None = None
        self.tau = 0.0
        self.ok = True

    @property
    def nfev(self) -> int:
        """Right-hand-side evaluations of every window so far."""
        return self.ivp.nfev if self.ivp is not None else int(self.march.counts[0])

    def through(self, z: np.ndarray, t_eval: np.ndarray, t_end: float) -> tuple[bool, str]:
        """From state z at self.tau to t_end, sampled at t_eval (those before t_end)."""
        n = self.system.n
        t_eval = t_eval[(t_eval >= self.tau) & (t_eval < t_end)]
        step = self._radau if self.march is None else self._compiled
        why, times, states, end = step(z, t_eval, t_end)
        if why:
            self.ok = False
            return False, why
        self.times += list(times)
        self.samples += list(states[:, :n])
        self.rates += list(states[:, n:])
        self.z, self.tau = end, t_end
        if self.report is not None:
            self.report(t_end)
        return True, "through the move"

    def _radau(self, z: np.ndarray, t_eval: np.ndarray, t_end: float):
        """(why not, or ''; the sample instants; the states there; the state at t_end) by
        Radau."""
        sol = self.ivp.run(self.tau, t_end, z, np.append(t_eval, t_end))
        if sol.status == CUT:
            return f"cut by the time budget at t = {self.tau:.4g} T", None, None, None
        if sol.status == FAILED:
            return f"integrator failed at t = {self.tau:.4g} T: {sol.message}", None, None, None
        return "", sol.t[:-1], sol.y[:-1], sol.y[-1]

    def _compiled(self, z: np.ndarray, t_eval: np.ndarray, t_end: float):
        """`_radau`'s answer by the compiled march: a step never crosses a sample; the deadline
        is checked between windows."""
        if time.perf_counter() > self.system.deadline:
            return f"cut by the time budget at t = {self.tau:.4g} T", None, None, None
        saved, why = self.march.states(np.concatenate([[self.tau], t_eval, [t_end]]), z)
        if why:
            return f"integrator failed at t = {self.tau:.4g} T: {why}", None, None, None
        return "", t_eval, saved[:-1], saved[-1]

    def y(self, model) -> np.ndarray:
        """y_m / L at every sample so far."""
        if not self.samples:
            return np.zeros(0)
        return np.atleast_1d(model.midspan(np.array(self.samples)))


def _settle(run: _Stepper, model, scene: Scene, peak: float, chunk: float, dt: float):
    """Integrate after the move: `settle` seconds, or first-mode periods until calm."""
    T = scene.beam.T
    start = run.tau
    given = scene.drive.settle
    limit = given / T if given is not None else SETTLE_PERIODS * chunk
    while run.tau < start + limit - 1e-12:
        end = min(run.tau + chunk, start + limit)
        grid = run.tau + np.arange(math.ceil((end - run.tau) / dt)) * dt
        first = len(run.samples)
        ok, message = run.through(run.z, grid, end)
        if not ok:
            return run.tau - start, message
        window = run.y(model)[first:]
        if given is None and window.size and np.max(np.abs(window)) < CALM * peak:
            return run.tau - start, f"settled below {CALM:g} of the peak in {run.tau - start:.4g} T"
    what = "settle window" if given is not None else f"{SETTLE_PERIODS} first-mode periods"
    return run.tau - start, f"through the move and the {what}"


def _settling_time(tau: np.ndarray, after: np.ndarray, peak: float, end: float) -> float:
    """From the move's end until |y_m| stays below SETTLED peak (units of T; NaN if it does
    not within the window)."""
    if not after.size or not math.isfinite(peak):
        return math.nan
    above = np.flatnonzero(after >= SETTLED * peak)
    if not above.size:
        return 0.0
    if above[-1] == after.size - 1:
        return math.nan
    return float(tau[above[-1] + 1] - end)
