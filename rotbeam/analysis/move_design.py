"""The fastest move within limits that leaves the beam still: motion design with input-shaping
baselines.

A rest-to-rest slew through an angle, or a change from one steady speed to another, is the
rigid-body time-optimal move (bang-coast-bang, with a jerk limit its S-curve) convolved with a
two- or three-impulse train (`rotbeam.analysis.shapers`) whose spacing is searched on the beam
itself, its acceleration and jerk raised as far as the limits allow where the shaped pulses do
not overlap.  The spacing is found on the modal reduced model (two modes) and the move is then
run on the full model at the scene's grid, whose residual is the one reported.  Why this family
and this search, and what they cost: docs/design.md.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..config.errors import RotbeamInputError
from ..runs.observables import observable_names
from ..runs.scene import Scene, build_scene
from ..solve.timebudget import TimeBudget
from .motion import Limits, Motion, rigid_slew, rigid_speed_change
from .move_box import corners, parse_box
from .move_check import (
    MoveCheck,
    check_move,
    integrated_angle,
    move_samples,
    ringing,
    write_move_csv,
)
from .shapers import KINDS, decay_ratio, for_mode, shape, train

#: modes of the inner model (the modal reduced model; 2 modes: within 1e-4 L of the full
#: model's residual on the reference beam, docs/design.md)
INNER_MODES = 2
#: first-mode periods run after each candidate on the inner model, and after the design's and
#: the baselines' full-model runs (the residual decays: its largest value comes in the first)
INNER_SETTLE_PERIODS = 1.5
CHECK_SETTLE_PERIODS = 2.0
#: the inner model's stepper tolerance (at most; the scene's if looser): its residual moves by
#: 1e-5 L from numerics.rtol = 1e-5 at half the cost (docs/design.md)
INNER_RTOL = 1e-4
#: without a jerk limit the design's acceleration ramps over this share of the shortest
#: first-mode period (a step rings every mode of the beam and costs the stepper 20x more); the
#: longer ramps last one period of the second mode, whose spectrum vanishes there
RAMP_SHARE = 1.0 / 20.0
#: the inner model's target: this share of the tolerance (room for the full model)
INNER_MARGIN = 0.5
#: the spacing searched from (1 - BRACKET) to (1 + BRACKET) times the half periods met, the
#: train's amplitude ratio K within exp(+-LOG_RATIO_MAX)
BRACKET = 0.2
LOG_RATIO_MAX = 1.5
#: finite-difference steps of the first Jacobian: a share of the spacing, and of log K
STEP_SPACING = 0.02
STEP_RATIO = 0.03
#: secant (Broyden) steps on the first mode's amplitude, at most, and the shortening step: the
#: spacing tried SHORTEN shorter than the root, where the residual has slack
MAX_NEWTON = 8
SHORTEN = 0.03
#: the secant steps' trust region: a share of the spacing, and of log K
TRUST_SPACING = 0.1
TRUST_RATIO = 0.3
#: a family whose least inner residual is within INNER_SLACK of the tolerance is checked on
#: the full model (the inner model is within about 1e-4 L of it)
INNER_SLACK = 1.25
#: the root's resolution, a share of the half period
XTOL = 5e-4
MAX_ROOT = 8
#: a tolerance below RESOLVE * numerics.rtol * peak is below what the run resolves
RESOLVE = 100.0
#: acceleration scalings tried, from the largest (1 / the train's largest amplitude) down to 1
KAPPA_STEPS = 32


@dataclass(frozen=True)
class Evaluation:
    """One candidate of the search: its family, the train's spacing and amplitude ratio K, the
    scaling, its duration, its inner residual and first-mode amplitude (`ringing`)."""

    kind: str
    ramp_s: float
    spacing_s: float
    ratio: float
    kappa: float
    duration_s: float
    residual: float
    amplitude: complex
    seconds: float


@dataclass
class MoveDesign:
    """The designed move, its checks on the full model and the baselines beside it.

    Attributes
    ----------
    found : bool
        The design meets the tolerance on the full model (at every corner of a robust box).
    message : str
        What the search found, or why not (the best residual and its duration), or where the
        time budget cut it.
    motion : Motion or None
        The designed move (the best found when none meets the tolerance).
    t, omega : numpy.ndarray
        Its samples, the rows of its move file.
    check : MoveCheck or None
        Its run on the full model at the scene's grid, as `rotbeam simulate --move` runs it.
    robust_residual : float or None
        The largest full-model residual over the corners of the box (None without a box).
    corner_residuals : dict
        Corner label -> full-model residual.
    baselines : dict
        "rigid", "zv", "zvd" -> MoveCheck on the full model (empty when not asked for).
    kind : str
        The design's impulse train ("zv" or "zvd" family).
    ratio : float
        Its train's amplitude ratio K (searched with the spacing; the textbook shaper's is
        exp(-zeta pi / sqrt(1 - zeta^2))).
    ramp_s : float
        How long its acceleration takes to ramp to the limit [s].
    spacing_s : float
        Its impulses' spacing [s].
    kappa : float
        The factor on the acceleration (and jerk) limit of the rigid move it shapes.
    f_hz, zeta : float
        The first mode the baselines are tuned to (at rest; for a speed change, at the final
        speed) and its damping ratio.
    evaluations : list of Evaluation
        Every candidate run on the inner model, in order.
    settle_s : float
        Seconds run after each move on the full model (`rotbeam simulate --move FILE --settle
        settle_s` repeats the design's run).
    seconds : float
        Wall time of the search, the full-model checks of the design included (baselines not).
    baseline_seconds : float
        Wall time of the baselines' runs.
    """

    found: bool
    message: str
    scene: Scene
    request: dict[str, Any]
    motion: Motion | None = None
    t: np.ndarray = field(default_factory=lambda: np.zeros(0))
    omega: np.ndarray = field(default_factory=lambda: np.zeros(0))
    check: MoveCheck | None = None
    robust_residual: float | None = None
    corner_residuals: dict[str, float] = field(default_factory=dict)
    baselines: dict[str, MoveCheck] = field(default_factory=dict)
    baseline_motions: dict[str, Motion] = field(default_factory=dict)
    kind: str = ""
    ratio: float = math.nan
    ramp_s: float = math.nan
    spacing_s: float = math.nan
    kappa: float = math.nan
    f_hz: float = math.nan
    zeta: float = math.nan
    evaluations: list[Evaluation] = field(default_factory=list)
    seconds: float = 0.0
    baseline_seconds: float = 0.0
    profile_csv: str | None = None
    settle_s: float = math.nan

    @property
    def duration_s(self) -> float:
        """The designed move's length [s] (NaN without one)."""
        return self.motion.duration if self.motion is not None else math.nan

    @property
    def angle_rad(self) -> float:
        """The angle turned along the designed move's samples, integrated [rad]."""
        return integrated_angle(self.t, self.omega) if self.t.size else math.nan

    def write_csv(self, path: str | Path) -> None:
        """Write the designed move as a move file (`rotbeam simulate --move` reads it).

        Parameters
        ----------
        path : str or Path

        Raises
        ------
        RotbeamInputError
            Without a designed move, or if the folder does not exist.
        """
        if not self.t.size:
            raise RotbeamInputError("no designed move to write: the search found none")
        write_move_csv(path, self.t, self.omega)
        self.profile_csv = str(path)

    def shorter_than(self) -> dict[str, float | None]:
        """How much shorter the design is than each baseline that meets the tolerance.

        Returns
        -------
        dict
            Baseline name -> 1 - duration / the baseline's duration, or None for a baseline
            that does not meet the tolerance.
        """
        tol = self.request["residual"]
        return {name: (1.0 - self.duration_s / b.duration_s if b.residual <= tol else None)
                for name, b in self.baselines.items()}  # fmt: skip

    def rows(self) -> list[dict[str, Any]]:
        """One row per move, the design first and then each baseline: a table's rows.

        Returns
        -------
        list of dict
            ``move`` (designed, rigid, zv, zvd), ``duration_s``, ``residual``, ``peak`` (full
            model), ``meets`` (the tolerance; the design's at every corner of a box too) and
            ``shorter_by`` (the design's saving over a baseline that meets it; None otherwise
            and on the design's row).
        """
        shorter = self.shorter_than()
        tol = self.request["residual"]
        runs = {"designed": self.check} | self.baselines
        return [{"move": name, "duration_s": self.duration_s if name == "designed"
                 else c.duration_s, "residual": c.residual if c else math.nan,
                 "peak": c.peak if c else math.nan,
                 "meets": self.found if name == "designed"
                 else bool(c is not None and c.residual <= tol),
                 "shorter_by": shorter.get(name)} for name, c in runs.items()]  # fmt: skip

    def summary(self) -> dict[str, Any]:
        """The design's numbers for tables and JSON.

        Returns
        -------
        dict
            ``duration_s``, ``residual``, ``peak`` (full model, the observable's unit),
            ``angle_rad`` (integrated), ``robust_residual`` (worst over the box, or None),
            ``profile_csv``, ``seconds`` (the search's), ``found``, ``message``,
            ``observable``, ``tolerance``, ``family``, ``ramp_s``, ``ratio``, ``spacing_s``,
            ``kappa``, ``f_hz``, ``zeta``, ``evaluations``, ``baseline_seconds``, ``settle_s``
            and ``baselines``: {rigid, zv, zvd} each with ``duration_s``, ``residual``,
            ``peak``, ``meets`` and ``shorter_by`` (the design's saving, None where the baseline
            misses).
        """
        check = self.check
        shorter = self.shorter_than()
        tol = self.request["residual"]
        return {
            "duration_s": self.duration_s,
            "residual": check.residual if check else math.nan,
            "peak": check.peak if check else math.nan,
            "angle_rad": self.angle_rad,
            "robust_residual": self.robust_residual,
            "profile_csv": self.profile_csv,
            "seconds": self.seconds,
            "found": self.found,
            "message": self.message,
            "observable": self.request["observable"],
            "tolerance": tol,
            "family": self.kind,
            "ramp_s": self.ramp_s,
            "ratio": self.ratio,
            "spacing_s": self.spacing_s,
            "kappa": self.kappa,
            "f_hz": self.f_hz,
            "zeta": self.zeta,
            "evaluations": len(self.evaluations),
            "baseline_seconds": self.baseline_seconds,
            "settle_s": self.settle_s,
            "baselines": {
                name: b.as_dict() | {"meets": bool(b.residual <= tol), "shorter_by": shorter[name]}
                for name, b in self.baselines.items()
            },  # fmt: skip
        }


class _Cut(Exception):
    """The time budget is spent."""


def first_mode(scene: Scene, omega: float) -> tuple[float, float]:
    """The first mode of the straight beam turning steadily at omega: f [Hz] and zeta.

    Parameters
    ----------
    scene : Scene
        Beam, effects, numerics (the model that runs the moves).
    omega : float
        rad/s.

    Returns
    -------
    f_hz, zeta : float
    """
    T = scene.beam.T
    w1, c = scene.model().first_mode_decay(omega * T)
    return w1 / (2.0 * math.pi * T), c / (2.0 * w1)


def design_move(
    scene: Scene | None = None,
    *,
    angle: float | None = None,
    omega_start: float | None = None,
    omega_end: float | None = None,
    max_speed: float,
    max_accel: float,
    max_jerk: float | None = None,
    residual: float = 0.005,
    observable: str = "y_m",
    robust: str | None = None,
    baselines: bool = True,
    progress: Callable[[str], None] | None = None,
) -> MoveDesign:
    """The shortest move within the limits whose residual vibration is at most `residual`.

    A rest-to-rest slew through `angle`, or (with omega_start and omega_end) a change from one
    steady speed to another.  The beam starts at rest; the residual is the largest |observable|
    after the move on the full model at the scene's grid (with `robust`, at every corner of the
    box).  Beside it, the baselines: the rigid-body time-optimal move and that move shaped by
    ZV and ZVD at the first mode at rest (a speed change: at the final speed).  The search is
    bounded by numerics.max_seconds; a cut says what it found so far.

    Parameters
    ----------
    scene : Scene or None
        Beam, effects, numerics (its drive is not read); default the reference beam.
    angle : float or None
        The slew's angle [rad], > 0.
    omega_start, omega_end : float or None
        The speed change's steady speeds [rad/s] (instead of an angle).
    max_speed, max_accel : float
        Limits [rad/s, rad/s^2], > 0.
    max_jerk : float or None
        Limit [rad/s^3], > 0, or None.
    residual : float
        The largest |observable| allowed after the move, in the observable's unit (y_m: L).
    observable : str
        A name of `rotbeam.runs.observables.OBSERVABLES`.
    robust : str or None
        A box of beam inputs, "E=+-5%,gamma=+-25%,tip_mass=+-10%" (`parse_box`).
    baselines : bool
        Run the rigid, ZV and ZVD baselines on the full model.
    progress : callable or None
        progress(text) after every run.

    Returns
    -------
    MoveDesign

    Raises
    ------
    RotbeamInputError
        One line for a bad input: a limit that is not > 0, neither or both of an angle and a
        speed change, an angle that is not > 0, a speed beyond the speed limit, equal speeds,
        a tolerance that is not > 0 or below what the run resolves, an unknown observable or
        one that a speed change cannot bring to rest, or a bad box.
    """
    t0 = time.perf_counter()
    scene = scene if scene is not None else build_scene({})
    limits = Limits(max_speed, max_accel, max_jerk)
    request = _request(angle, omega_start, omega_end, limits, residual, observable)
    box = parse_box(robust)
    boxed = corners(scene, box)
    run = _Search(scene, limits, request, boxed, progress, TimeBudget(scene.numerics.max_seconds))
    design = run.design()
    design.seconds = time.perf_counter() - t0
    if baselines:
        t1 = time.perf_counter()
        design.baselines, design.baseline_motions = run.baselines()
        design.baseline_seconds = time.perf_counter() - t1
    return design


#: the keys of one `move_designs` entry of the workflow's config beside name and scene
DESIGN_KEYS = ("angle", "omega_start", "omega_end", "max_speed", "max_accel", "max_jerk",
               "residual", "observable", "robust")  # fmt: skip


def design_spec(spec: dict[str, Any], base: str | Path = ".") -> tuple[str, Scene, dict]:
    """One entry of the workflow's `move_designs` list: its name, scene and request, checked.

    Parameters
    ----------
    spec : dict
        ``name``, ``scene`` (optional: sections beam, effects, numerics as in a scene file) and
        the keys of `design_move` (DESIGN_KEYS).
    base : str or Path
        The folder relative file paths of the scene start from.

    Returns
    -------
    name : str
    scene : Scene
    request : dict
        Keyword arguments of `design_move`.

    Raises
    ------
    RotbeamInputError
        One line naming the key within the entry (``scene.numerics.N = ...``, ``angle = ...``)
        for a missing name, an unknown key, a bad scene or a request `design_move` refuses.
    """
    spec = dict(spec)
    name = spec.pop("name", None)
    if not isinstance(name, str) or not name:
        raise RotbeamInputError(f"name = {name!r}: must be a non-empty string")
    extra = sorted(set(spec) - set(DESIGN_KEYS) - {"scene"})
    if extra:
        raise RotbeamInputError(
            f"{extra[0]} = {spec[extra[0]]!r}: unknown key; allowed: name, scene, "
            f"{', '.join(DESIGN_KEYS)}"
        )
    try:
        scene = build_scene(spec.pop("scene", None) or {}, base)
    except RotbeamInputError as exc:
        raise RotbeamInputError(f"scene.{exc}") from None
    limits = Limits(spec.get("max_speed"), spec.get("max_accel"), spec.get("max_jerk"))
    _request(spec.get("angle"), spec.get("omega_start"), spec.get("omega_end"), limits,
             spec.get("residual", 0.005), spec.get("observable", "y_m"))  # fmt: skip
    parse_box(spec.get("robust"))
    return name, scene, spec


def _request(angle, omega_start, omega_end, limits: Limits, residual, observable) -> dict:
    """The request checked, one line for each bad value."""
    speeds = omega_start is not None or omega_end is not None
    if (angle is None) == (not speeds):
        raise RotbeamInputError(
            "give either --angle (a rest-to-rest slew) or --omega-start and --omega-end (a "
            "change of speed), not both and not neither"
        )
    if angle is not None:
        if not isinstance(angle, (int, float)) or not math.isfinite(angle) or angle <= 0:
            raise RotbeamInputError(
                f"angle = {angle!r}: allowed a finite number > 0 rad (a move the other way is "
                f"its mirror image)"
            )
    else:
        if omega_start is None or omega_end is None:
            raise RotbeamInputError(
                "omega_start and omega_end: a change of speed needs both (rad/s)"
            )
        for name, w in (("omega_start", omega_start), ("omega_end", omega_end)):
            if not math.isfinite(w) or abs(w) > limits.max_speed:
                raise RotbeamInputError(
                    f"{name} = {w!r} rad/s: allowed |{name}| <= max_speed = "
                    f"{limits.max_speed:g} rad/s (the speed limit cannot reach it)"
                )
        if omega_start == omega_end:
            raise RotbeamInputError(
                f"omega_end = {omega_end!r}: allowed a speed other than omega_start (no change "
                f"to design)"
            )
    if not isinstance(residual, (int, float)) or not math.isfinite(residual) or residual <= 0:
        raise RotbeamInputError(f"residual = {residual!r}: allowed a finite number > 0")
    (name,) = observable_names(observable)
    if angle is None and name == "tip_acceleration" and omega_end != 0:
        raise RotbeamInputError(
            "observable = tip_acceleration: after a change to a speed other than 0 the tip "
            "keeps its centripetal acceleration; allowed there: y_m, tip, root_moment, "
            "root_stress"
        )
    return {"angle": angle, "omega_start": omega_start, "omega_end": omega_end,
            "limits": limits, "residual": float(residual), "observable": name}  # fmt: skip


class _Search:
    """The search of one request: each family's train on the inner model, the full-model
    checks, and the baselines."""

    def __init__(self, scene: Scene, limits: Limits, request: dict, boxed: list,
                 progress: Callable[[str], None] | None, budget: TimeBudget) -> None:  # fmt: skip
        from ..model.modes import linear_frequencies

        self.scene, self.limits, self.request = scene, limits, request
        self.boxed, self.progress, self.budget = boxed, progress, budget
        self.tol = request["residual"]
        self.observable = request["observable"]
        slew = request["angle"] is not None
        base = 0.0 if slew else request["omega_end"]
        ends = (0.0, limits.max_speed) if slew else (request["omega_start"], request["omega_end"])
        self.f_hz, self.zeta = first_mode(scene, base)
        scenes = [scene] + [s for _, s in boxed]
        freqs = [first_mode(s, w)[0] for s in scenes for w in ends]
        self.f_lo, self.f_hi = min(freqs), max(freqs)
        self.settle_s = CHECK_SETTLE_PERIODS / self.f_lo
        T = scene.beam.T
        w12 = linear_frequencies(scene.model(), base * T, 2) / T
        self.modes_hz = (float(w12[0]) / (2 * math.pi), float(w12[1]) / (2 * math.pi))
        self.decay = self.zeta * float(w12[0])
        self.nominal = self._inner_scene(scene)
        self.corners = [self._inner_scene(s) for _, s in boxed]
        self.cache: dict[tuple, Evaluation] = {}
        self.worst_cache: dict[tuple, float] = {}
        self.evaluations: list[Evaluation] = []
        self.motions: dict[tuple, tuple[Motion, float]] = {}
        self.families = self._families()

    def _families(self) -> list[tuple[str, float]]:
        """(train, ramp) pairs, shortest first by the move at the half period of the middle
        frequency: ramps of RAMP_SHARE of the shortest first-mode period (without a jerk
        limit) or the limit's, and ramps of one second-mode period (if longer)."""
        a, j = self.limits.max_accel, self.limits.max_jerk
        short = RAMP_SHARE / self.f_hi if j is None else a / j
        ramps = sorted({short, max(short, 1.0 / self.modes_hz[1])})
        mid = 0.25 / self.f_lo + 0.25 / self.f_hi
        fams = [(kind, ramp) for kind in KINDS for ramp in ramps]
        K = decay_ratio(self.zeta)
        return sorted(fams, key=lambda f: self.candidate(f[0], f[1], mid, K)[0].duration)

    # --- the family ------------------------------------------------------------------------
    def rigid(self, limits: Limits) -> Motion:
        """The rigid-body time-optimal move under `limits`."""
        r = self.request
        if r["angle"] is not None:
            return rigid_slew(r["angle"], limits)
        return rigid_speed_change(r["omega_start"], r["omega_end"], limits)

    def candidate(self, kind: str, ramp: float, spacing: float,
                  ratio: float) -> tuple[Motion, float]:  # fmt: skip
        """The rigid move at kappa times the acceleration limit (its ramps `ramp` long), shaped
        by the `kind` train of this spacing and amplitude ratio: the largest kappa whose shaped
        move keeps every limit."""
        key = (kind, ramp, spacing, ratio)
        if key not in self.motions:
            a = self.limits.max_accel
            own = Limits(self.limits.max_speed, a, a / ramp)
            impulses = train(kind, spacing, ratio)
            top = 1.0 / max(impulses.amplitudes)
            found = (shape(self.rigid(own), impulses), 1.0)
            for kappa in np.linspace(top, 1.0, KAPPA_STEPS):
                m = shape(self.rigid(own.scaled(float(kappa))), impulses)
                if m.within(self.limits):
                    found = (m, float(kappa))
                    break
            self.motions[key] = found
        return self.motions[key]

    def motion_of(self, ev: Evaluation) -> Motion:
        """The move of one evaluation."""
        return self.candidate(ev.kind, ev.ramp_s, ev.spacing_s, ev.ratio)[0]

    # --- runs ------------------------------------------------------------------------------
    def _inner_scene(self, scene: Scene) -> Scene:
        """The scene on the inner model: its modal reduced model of INNER_MODES modes."""
        num = replace(scene.numerics, rtol=max(scene.numerics.rtol, INNER_RTOL))
        if num.model != "modal":
            num = replace(num, model="modal", modes=min(INNER_MODES, num.N - 1))
        return replace(scene, numerics=num)

    def _remaining(self) -> float:
        left = self.budget.remaining()
        if left <= 0:
            raise _Cut
        return left

    def _run(self, scene: Scene, motion: Motion) -> MoveCheck:
        """One inner run (cut by the budget)."""
        settle = INNER_SETTLE_PERIODS / self.f_lo
        c = check_move(scene, motion, self.f_hi, self.observable, settle, self._remaining())
        if not c.converged and self.budget.spent():
            raise _Cut
        return c

    def inner(self, kind: str, ramp: float, spacing: float, ratio: float) -> Evaluation:
        """The inner model's residual and first-mode amplitude of one candidate (nominal)."""
        key = (kind, ramp, float(spacing), float(ratio))
        if key in self.cache:
            return self.cache[key]
        motion, kappa = self.candidate(*key)
        t0 = time.perf_counter()
        c = self._run(self.nominal, motion)
        residual = c.residual if c.converged else math.inf
        if c.converged:
            self._resolves(c.peak)
        amp = ringing(c, self.modes_hz, self.decay) if c.converged else complex(math.inf, 0)
        ev = Evaluation(kind, ramp, float(spacing), float(ratio), kappa, motion.duration,
                        residual, amp, time.perf_counter() - t0)  # fmt: skip
        self.cache[key] = ev
        self.evaluations.append(ev)
        if self.progress is not None:
            self.progress(f"{kind} spacing {spacing * 1e3:.3f} ms, K {ratio:.3g}, ramp "
                          f"{ramp * 1e3:.3g} ms: T {motion.duration:.4g} s, residual "
                          f"{residual:.3g}")  # fmt: skip
        return ev

    def worst(self, ev: Evaluation) -> float:
        """The candidate's inner residual, the worst over the box's corners with one."""
        key = (ev.kind, ev.ramp_s, ev.spacing_s, ev.ratio)
        if key not in self.worst_cache:
            worst = ev.residual
            for sc in self.corners:
                if worst > self.tol:
                    break
                c = self._run(sc, self.motion_of(ev))
                worst = max(worst, c.residual if c.converged else math.inf)
            self.worst_cache[key] = worst
        return self.worst_cache[key]

    def _resolves(self, peak: float) -> None:
        """Refuse a tolerance below what the run resolves (RESOLVE * rtol * peak)."""
        floor = RESOLVE * self.scene.numerics.rtol * peak
        if self.tol < floor:
            raise RotbeamInputError(
                f"residual = {self.tol:g}: below what the run resolves, {floor:.3g} "
                f"({RESOLVE:g} x numerics.rtol = {self.scene.numerics.rtol:g} x the move's peak "
                f"{peak:.3g}); allowed >= {floor:.3g}, or a smaller numerics.rtol"
            )

    def full(self, motion: Motion, scene: Scene | None = None) -> MoveCheck:
        """A move on the full model at the scene's grid, CHECK_SETTLE_PERIODS after it."""
        sc = scene if scene is not None else self.scene
        c = check_move(sc, motion, self.f_hi, self.observable, self.settle_s, self._remaining())
        if not c.converged and self.budget.spent():
            raise _Cut
        if self.progress is not None:
            self.progress(f"full model: T {motion.duration:.4g} s, residual {c.residual:.3g}")
        return c

    # --- the search ------------------------------------------------------------------------
    def design(self) -> MoveDesign:
        """Each family in turn, shortest first: the train that cancels the first mode on the
        inner model, shortened where the tolerance leaves slack, checked on the full model."""
        out = MoveDesign(False, "", self.scene, self.request, f_hz=self.f_hz, zeta=self.zeta,
                         settle_s=self.settle_s)  # fmt: skip
        best: float | None = None  # the least full-model residual so far
        try:
            for kind, ramp in self.families:
                for ev in self._search(kind, ramp):
                    motion = self.motion_of(ev)
                    if out.found and motion.duration >= out.duration_s:
                        continue
                    check = self.full(motion)
                    corner = self._corners(motion) if check.residual <= self.tol else {}
                    worst = max([check.residual, *corner.values()])
                    meets = worst <= self.tol and len(corner) == len(self.boxed)
                    if meets or (not out.found and (best is None or worst < best)):
                        best = worst if best is None else min(best, worst)
                        self._adopt(out, ev, check)
                        out.corner_residuals = corner
                        out.robust_residual = max(corner.values()) if corner else None
                        out.found = out.found or meets
                if out.found:
                    box = (
                        ""
                        if out.robust_residual is None
                        else f", {out.robust_residual:.3g} at the worst corner of the box"
                    )
                    out.message = (f"{out.kind} family, spacing {out.spacing_s * 1e3:.4g} ms, "
                                   f"ramps {out.ramp_s * 1e3:.3g} ms: residual "
                                   f"{out.check.residual:.3g}{box} <= {self.tol:g}")  # fmt: skip
                    return self._done(out)
        except _Cut:
            out.message = self._cut_message(out)
            return self._done(out)
        if out.motion is None and self.evaluations:
            ev = min(self.evaluations, key=lambda e: e.residual)
            self._adopt(out, ev, None)
            out.message = (f"no move within the limits meets residual {self.tol:g}: the best "
                           f"found is {ev.residual:.3g} (inner model) at duration "
                           f"{ev.duration_s:.4g} s")  # fmt: skip
        elif out.check is not None:
            worst = max([out.check.residual, *out.corner_residuals.values()])
            out.message = (f"no move within the limits meets residual {self.tol:g}: the best "
                           f"found is {worst:.3g} at duration {out.duration_s:.4g} s "
                           f"({out.kind} family)")  # fmt: skip
        return self._done(out)

    def _adopt(self, out: MoveDesign, ev: Evaluation, check: MoveCheck | None) -> None:
        out.motion, out.check = self.motion_of(ev), check
        out.kind, out.ramp_s, out.spacing_s, out.kappa = ev.kind, ev.ramp_s, ev.spacing_s, ev.kappa
        out.ratio = ev.ratio

    def _corners(self, motion: Motion) -> dict[str, float]:
        """The full model's residual at the box's corners, in turn until one misses."""
        corner: dict[str, float] = {}
        for label, sc in self.boxed:
            corner[label] = self.full(motion, sc).residual
            if corner[label] > self.tol:
                break
        return corner

    def _done(self, out: MoveDesign) -> MoveDesign:
        out.evaluations = list(self.evaluations)
        if out.motion is not None:
            out.t, out.omega = move_samples(out.motion, self.f_hi)
        return out

    def _cut_message(self, out: MoveDesign) -> str:
        done = f"cut by the time budget (numerics.max_seconds = {self.budget.seconds:g} s)"
        if out.found:
            return (f"{done}; found so far: {out.kind} family, residual {out.check.residual:.3g}"
                    f" <= {self.tol:g} at duration {out.duration_s:.4g} s")  # fmt: skip
        if self.evaluations:
            ev = min(self.evaluations, key=lambda e: e.residual)
            if out.motion is None:
                self._adopt(out, ev, None)
            return (f"{done} after {len(self.evaluations)} runs: so far the least residual is "
                    f"{ev.residual:.3g} (inner model) at duration {ev.duration_s:.4g} s "
                    f"({ev.kind} family)")  # fmt: skip
        return f"{done} before the first run"

    def _search(self, kind: str, ramp: float) -> list[Evaluation]:
        """The family's candidates worth a full-model check, shortest first.

        Secant (Broyden) steps in (spacing, log K of the train) drive the first mode's complex
        amplitude after the move to zero on the inner model, from the half period of the middle
        frequency and the model's zeta's K, its first Jacobian by finite differences.  Where the
        least residual leaves slack (below INNER_MARGIN of the tolerance, at every corner of a
        box), the shortest spacing at that level is found between SHORTEN shorter and it."""
        lo, hi = (1 - BRACKET) * 0.5 / self.f_hi, (1 + BRACKET) * 0.5 / self.f_lo
        x = np.array([0.25 / self.f_lo + 0.25 / self.f_hi, math.log(decay_ratio(self.zeta))])
        scale = np.array([STEP_SPACING * x[0], STEP_RATIO])
        trust = np.array([TRUST_SPACING * x[0], TRUST_RATIO])

        def f(ev: Evaluation) -> np.ndarray:
            return np.array([ev.amplitude.real, ev.amplitude.imag])

        def run(x: np.ndarray) -> Evaluation:
            return self.inner(kind, ramp, float(x[0]), math.exp(float(x[1])))

        ev = run(x)
        jac = np.column_stack([(f(run(x + d)) - f(ev)) / h
                               for d, h in ((np.array([scale[0], 0.0]), scale[0]),
                                            (np.array([0.0, scale[1]]), scale[1]))])  # fmt: skip
        target = INNER_MARGIN * self.tol
        for _ in range(MAX_NEWTON):
            if not np.all(np.isfinite(f(ev))) or ev.residual <= 0.2 * target:
                break
            step = np.linalg.lstsq(jac, -f(ev), rcond=None)[0]
            step *= min(1.0, float(np.min(trust / np.maximum(np.abs(step), 1e-300))))
            new = np.clip(x + step, [lo, -LOG_RATIO_MAX], [hi, LOG_RATIO_MAX])
            if np.all(np.abs(new - x) < np.array([XTOL * x[0], 1e-5])):
                break
            nxt = run(new)
            if nxt.residual > ev.residual:  # a step too far: back half way once
                half = run(x + 0.5 * (new - x))
                nxt, new = (
                    (half, x + 0.5 * (new - x)) if half.residual < nxt.residual else (nxt, new)
                )
            dx, df = new - x, f(nxt) - f(ev)
            if np.all(np.isfinite(df)):
                jac = jac + np.outer(df - jac @ dx, dx) / float(dx @ dx)
            x, ev = new, nxt
        mine = [e for e in self.evaluations if (e.kind, e.ramp_s) == (kind, ramp)]
        least = min(mine, key=lambda e: e.residual)
        if self.worst(least) > INNER_SLACK * self.tol:
            return []
        if self.worst(least) > target:
            return [least]
        short = self._shorten(kind, ramp, least, target)
        return [short, least] if short is not least else [least]

    def _shorten(self, kind: str, ramp: float, least: Evaluation, target: float) -> Evaluation:
        """The shortest spacing (the train's K kept) whose residual is within target."""
        from scipy.optimize import brentq

        ratio, s1 = least.ratio, least.spacing_s
        s0 = s1 * (1 - SHORTEN)

        def g(s: float) -> float:
            return self.worst(self.inner(kind, ramp, s, ratio)) - target

        if g(s0) > 0:
            try:
                brentq(g, s0, s1, xtol=XTOL * s1, maxiter=MAX_ROOT)
            except RuntimeError:  # not converged in MAX_ROOT: the evaluations so far stand
                pass
        ok = [
            e
            for e in self.evaluations
            if (e.kind, e.ramp_s, e.ratio) == (kind, ramp, ratio)
            and self.worst_cache.get((kind, ramp, e.spacing_s, ratio), math.inf) <= target
        ]
        ok.append(least)
        return min(ok, key=lambda e: e.duration_s)

    # --- baselines -------------------------------------------------------------------------
    def baselines(self) -> tuple[dict[str, MoveCheck], dict[str, Motion]]:
        """The rigid move and its ZV and ZVD shapings at the first mode, on the full model."""
        rigid = self.rigid(self.limits)
        motions = {"rigid": rigid}
        for kind in KINDS:
            motions[kind] = shape(rigid, for_mode(kind, self.f_hz, self.zeta))
        out = {}
        for name, m in motions.items():
            c = check_move(self.scene, m, self.f_hi, self.observable, self.settle_s)
            if self.progress is not None:
                self.progress(f"baseline {name}: T {m.duration:.4g} s, residual {c.residual:.3g}")
            out[name] = c
        return out, motions
