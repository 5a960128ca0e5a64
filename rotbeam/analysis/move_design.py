"""The fastest move within limits that leaves the beam still: motion design with input-shaping
baselines.

A rest-to-rest slew through an angle, or a change from one steady speed to another, is sought
in families of moves (`rotbeam.analysis.move_families`): the rigid-body time-optimal move
convolved with a ZV- or ZVD-pattern train (with a box of beams, two ZV trains), its
acceleration raised as far as the limits allow where the shaped pulses do not overlap; for a
change of speed also two pulses and a coast; each optionally convolved with a train at the
second mode.  The unknowns are found on the modal reduced model (two modes) and the move is
then run on the full model at the scene's grid, whose residual is the one reported.  Why these
families and this search, and what they cost: docs/design.md.
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
from .move_families import SHARE_MIN, Family, family_motion, pulses_start
from .shapers import KINDS, decay_ratio, for_mode, residual_factor, shape

#: modes of the inner model (the modal reduced model; 2 modes: within 1e-4 L of the full
#: model's residual on the reference beam, docs/design.md)
INNER_MODES = 2
#: first-mode periods run after each candidate on the inner model, and after the design's and
#: the baselines' full-model runs (the residual decays: its largest value comes in the first)
INNER_SETTLE_PERIODS = 1.5
CHECK_SETTLE_PERIODS = 2.0
#: the inner model's stepper tolerance (at most; the scene's if looser): its residual within
#: 3e-7 L of Radau's at rtol = 1e-8 (docs/design.md)
INNER_RTOL = 1e-5
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
#: zv2 starts with its trains' log K split by +-this: (K_1, K_2) -> (K_1 + K_2, K_1 K_2), the
#: train's amplitudes, is singular at K_1 = K_2, where the roots of single trains lie, and the
#: secant steps stall there (docs/design.md)
SPLIT_LOG_RATIO = 0.3
#: finite-difference steps of the first Jacobian: a share of the spacing, and of log K
STEP_SPACING = 0.02
STEP_RATIO = 0.03
#: secant (Broyden) steps on the first mode's amplitude, at most, and the shortening steps: the
#: spacing (or coast) tried SHORTEN of the first mode's half period shorter than the root,
#: the second-mode train's spacing SHORTEN_SECOND of its own, where the residual has slack
MAX_NEWTON = 8
#: with more equations than unknowns, two steps in a row that lower the amplitudes' norm by
#: less than 1 - STALL (or raise it) end the secant steps
STALL = 0.8
SHORTEN = 0.03
SHORTEN_SECOND = 0.5
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


@dataclass(frozen=True)
class Evaluation:
    """One candidate of the search: its family and unknowns, the acceleration's factor, its
    duration, its inner residual (the largest at the family's targets) and the first mode's
    amplitude there (`ringing`), and its wall time."""

    family: Family
    params: tuple[float, ...]
    kappa: float
    duration_s: float
    residual: float
    amplitudes: tuple[complex, ...]
    seconds: float

    @property
    def kind(self) -> str:
        """The family's name ("zv", "zvd", "zv2", "pulses", "+m2" with a second-mode train)."""
        return self.family.name

    @property
    def ramp_s(self) -> float:
        """The family's ramp [s]."""
        return self.family.ramp

    @property
    def spacing_s(self) -> float:
        """The first unknown: the (first) train's spacing, or the coast between two pulses [s]."""
        return self.params[0]

    @property
    def ratio(self) -> float:
        """The (first) train's amplitude ratio K, or the first pulse's share of the change."""
        return self.params[1] if self.family.kind == "pulses" else math.exp(self.params[1])


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
        The design's family: "zv", "zvd" (a train of that pattern), "zv2" (two ZV trains, one
        at each end of a box's frequencies), "pulses" (a change of speed as two pulses and a
        coast); "+m2" where a ZV train at the second mode is convolved too.
    ratio : float
        Its (first) train's amplitude ratio K (searched with the spacing; the textbook shaper's
        is exp(-zeta pi / sqrt(1 - zeta^2))), or for two pulses the first one's share of the
        change of speed.
    params : tuple of float
        The family's unknowns as searched (`rotbeam.analysis.move_families`).
    ramp_s : float
        How long its acceleration takes to ramp to the limit [s].
    spacing_s : float
        Its (first) train's spacing, or for two pulses the coast between them [s].
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
    params: tuple[float, ...] = ()
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
            ``kappa``, ``params`` (the family's unknowns), ``f_hz``, ``zeta``, ``evaluations``,
            ``baseline_seconds``, ``settle_s``
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
            "params": list(self.params),
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
    """The search of one request: each family's unknowns on the inner model, the full-model
    checks, and the baselines."""

    def __init__(self, scene: Scene, limits: Limits, request: dict, boxed: list,
                 progress: Callable[[str], None] | None, budget: TimeBudget) -> None:  # fmt: skip
        self.scene, self.limits, self.request = scene, limits, request
        self.boxed, self.progress, self.budget = boxed, progress, budget
        self.tol = request["residual"]
        self.observable = request["observable"]
        slew = request["angle"] is not None
        base = 0.0 if slew else request["omega_end"]
        self.ends = (0.0, limits.max_speed) if slew else (request["omega_start"],
                                                           request["omega_end"])  # fmt: skip
        self.speeds = None if slew else (request["omega_start"], request["omega_end"])
        self.f_hz, self.zeta = first_mode(scene, base)
        scenes = [scene] + [s for _, s in boxed]
        # the first frequency at each end of the move, on the nominal beam and at each corner
        firsts = [[first_mode(s, w)[0] for w in self.ends] for s in scenes]
        freqs = [f for ends in firsts for f in ends]
        self.f_lo, self.f_hi = min(freqs), max(freqs)
        self.settle_s = CHECK_SETTLE_PERIODS / self.f_lo
        self.modes_hz = _two_modes(scene, base)
        self.decay = self.zeta * 2 * math.pi * self.modes_hz[0]
        # the half period met along the move, on the nominal beam and at each corner
        self.halves = [sum(0.25 / f for f in ends) for ends in firsts]
        self._one_train: float | None = None
        self.f2 = tuple(_two_modes(scene, w)[1] for w in self.ends)
        self.second_s = 0.25 / self.f2[0] + 0.25 / self.f2[1]
        self.inner_scenes = [self._inner_scene(s) for s in scenes]
        self.runs: dict[tuple, tuple[float, tuple[complex, complex]]] = {}
        self.cache: dict[tuple, Evaluation] = {}
        self.evaluations: list[Evaluation] = []
        self.motions: dict[tuple, tuple[Motion, float]] = {}
        #: the last root's spacing over the linear half period: where the next family starts
        self.shift = 1.0
        #: family -> what a second-mode train could bring it down to (`_floor`)
        self.floors: dict[Family, float] = {}
        self.families = self._families()

    def _families(self) -> list[Family]:
        """The families, shortest first by their move at the linear starting unknowns: ZV and
        ZVD patterns (with a box, two ZV trains at the box's ends instead of ZVD, which they
        hold at equal spacings; for a change of speed, also two pulses), each with ramps of
        RAMP_SHARE of the shortest first-mode period (without a jerk limit) or the limit's, and
        ramps of one second-mode period (if longer), each with and without a ZV train at the
        second mode."""
        a, j = self.limits.max_accel, self.limits.max_jerk
        short = RAMP_SHARE / self.f_hi if j is None else a / j
        ramps = sorted({short, max(short, 1.0 / self.modes_hz[1])})
        kinds = ["zv", "zv2" if self.boxed else "zvd"] + (["pulses"] if self.speeds else [])
        # zv2's zeros start at the box's ends
        spread = (max(self.halves) - min(self.halves)) / (2 * self.halves[0])
        second = {"second_s": self.second_s, "second_ratio": math.exp(-self.decay * self.second_s)}
        fams = [Family(kind, ramp, spread=spread if kind == "zv2" else 0.0, **extra)
                for kind in kinds for ramp in ramps for extra in ({}, second)]  # fmt: skip
        return sorted(fams, key=lambda f: self.candidate(f, self.start(f, True))[0].duration)

    # --- the family ------------------------------------------------------------------------
    def rigid(self, limits: Limits) -> Motion:
        """The rigid-body time-optimal move under `limits`."""
        r = self.request
        if r["angle"] is not None:
            return rigid_slew(r["angle"], limits)
        return rigid_speed_change(r["omega_start"], r["omega_end"], limits)

    def candidate(self, fam: Family, params: tuple[float, ...]) -> tuple[Motion, float]:
        """The family's move at these unknowns and its acceleration's factor kappa."""
        key = (fam, params)
        if key not in self.motions:
            self.motions[key] = family_motion(fam, params, self.rigid, self.limits, self.speeds)
        return self.motions[key]

    def motion_of(self, ev: Evaluation) -> Motion:
        """The move of one evaluation."""
        return self.candidate(ev.family, ev.params)[0]

    def targets(self, fam: Family) -> list[int]:
        """The inner scenes whose first-mode amplitude the family cancels: the nominal beam's,
        or (zv2) the box's corners of the longest and of the shortest half period (four
        equations, four unknowns: zero there and, between, to first order).  A second-mode
        train cancels the second mode's amplitude at the first of them."""
        if fam.kind != "zv2":
            return [fam.at]
        corner = self.halves[1:]
        return [1 + int(np.argmax(corner)), 1 + int(np.argmin(corner))]

    def start(self, fam: Family, linear: bool = False) -> tuple[float, ...]:
        """The unknowns the search starts from: the half period met along the move, times the
        shift of the last train's root from it, and the model's zeta's K (of the beam the
        family cancels, `Family.at`); with a second-mode train, the root of the family without
        it where that was searched.  zv2: the roots of one ZV train alone at each of its two
        target corners (for a linear oscillator the convolved trains cancel each corner's
        amplitude where each train alone does), their log K split by +-SPLIT_LOG_RATIO, or
        with `linear` the linear start without a run, the ZVD start's spacing split into
        s (1 +- spread).  For two pulses, the coast and share that leave a linear oscillator
        of the middle frequency still (docs/design.md)."""
        half, logk = self.shift * self.halves[fam.at], math.log(decay_ratio(self.zeta))
        second = (fam.second_s, math.log(fam.second_ratio)) if fam.second_s > 0 else ()
        base = fam.without_second
        if second and not linear and base in self.floors:  # the family without the train's root
            return (*self._least(base).params, *second)
        if fam.kind == "zv2" and linear:  # the linear ZVD start (zv2 at equal spacings), split
            root = self.start(replace(fam, kind="zvd", spread=0.0), True)
            s1, s2 = root[0] * (1 + fam.spread), root[0] * (1 - fam.spread)
            return (s1, root[1], s2, root[1], *root[2:])
        if fam.kind == "zv2":  # one ZV train's root at each target corner, alone
            one = replace(fam.without_second, kind="zv", spread=0.0)
            (s1, k1), (s2, k2) = (self._root(replace(one, at=k))[0].params
                                  for k in self.targets(fam))  # fmt: skip
            return (s1, k1 + SPLIT_LOG_RATIO, s2, k2 - SPLIT_LOG_RATIO, *second)
        if fam.kind != "pulses":
            return (half, logk, *second)
        T = abs(self.speeds[1] - self.speeds[0]) / self.limits.max_accel
        return (*pulses_start(T, 2.0 * half, fam.ramp), *second)

    def _least(self, fam: Family) -> Evaluation:
        """The family's evaluation of least inner residual so far."""
        return min((e for e in self.evaluations if e.family == fam), key=lambda e: e.residual)

    def _scales(self, fam: Family) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The unknowns' finite-difference steps, trust region and bounds."""
        half, s2 = self.halves[0], self.second_s
        lo_s, hi_s = (1 - BRACKET) * 0.5 / self.f_hi, (1 + BRACKET) * 0.5 / self.f_lo
        trains = {"pulses": 0, "zv2": 2}.get(fam.kind, 1)  # first-mode trains (s, log K)
        pairs = [(half, lo_s, hi_s)] * trains
        if fam.second_s > 0:
            lo2, hi2 = (1 - BRACKET) * 0.5 / max(self.f2), (1 + BRACKET) * 0.5 / min(self.f2)
            pairs.append((s2, lo2, hi2))
        step = [v for h, _, _ in pairs for v in (STEP_SPACING * h, STEP_RATIO)]
        trust = [v for h, _, _ in pairs for v in (TRUST_SPACING * h, TRUST_RATIO)]
        lo = [v for _, a, _ in pairs for v in (a, -LOG_RATIO_MAX)]
        hi = [v for _, _, b in pairs for v in (b, LOG_RATIO_MAX)]
        if fam.kind == "pulses":  # the coast and the first pulse's share
            step = [STEP_SPACING * half, STEP_RATIO, *step]
            trust = [TRUST_SPACING * half, TRUST_RATIO, *trust]
            lo, hi = [0.0, SHARE_MIN, *lo], [2.0 / self.f_lo, 1 - SHARE_MIN, *hi]
        return np.array(step), np.array(trust), np.array(lo), np.array(hi)

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

    def _inner_run(self, index: int, fam: Family,
                   params: tuple[float, ...]) -> tuple[float, complex]:  # fmt: skip
        """The inner residual and first-mode amplitude of a candidate on inner scene `index`
        (0: the nominal beam; then the box's corners)."""
        key = (index, fam, params)
        if key not in self.runs:
            c = self._run(self.inner_scenes[index], self.candidate(fam, params)[0])
            if not c.converged:
                self.runs[key] = (math.inf, (complex(math.inf, 0), complex(math.inf, 0)))
            else:
                if index == 0:
                    self._resolves(c.peak)
                self.runs[key] = (c.residual, ringing(c, self.modes_hz, self.decay))
        return self.runs[key]

    def inner(self, fam: Family, params: tuple[float, ...]) -> Evaluation:
        """A candidate on the inner model at the family's targets: the largest residual there
        and the first mode's amplitudes."""
        params = tuple(float(p) for p in params)
        key = (fam, params)
        if key in self.cache:
            return self.cache[key]
        motion, kappa = self.candidate(fam, params)
        t0 = time.perf_counter()
        got = [self._inner_run(i, fam, params) for i in self.targets(fam)]
        amps = [a[0] for _, a in got] + ([got[0][1][1]] if fam.second_s > 0 else [])
        ev = Evaluation(fam, params, kappa, motion.duration, max(r for r, _ in got),
                        tuple(amps), time.perf_counter() - t0)  # fmt: skip
        self.cache[key] = ev
        self.evaluations.append(ev)
        if self.progress is not None:
            shown = ", ".join(f"{p:.4g}" for p in params)
            where = f" at {self.boxed[fam.at - 1][0]}" if fam.at else ""
            self.progress(f"{fam.name}{where} ({shown}), ramp {fam.ramp * 1e3:.3g} ms: T "
                          f"{motion.duration:.4g} s, residual {ev.residual:.3g}")  # fmt: skip
        return ev

    def worst(self, ev: Evaluation) -> float:
        """The candidate's inner residual, the worst over the nominal beam and the box's corners
        with one (stopping at the first above the tolerance)."""
        worst = ev.residual
        for index in range(len(self.inner_scenes)):
            if worst > self.tol:
                break
            worst = max(worst, self._inner_run(index, ev.family, ev.params)[0])
        return worst

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
        """Each family in turn, shortest first: the unknowns that cancel the first mode on the
        inner model, shortened where the tolerance leaves slack, checked on the full model."""
        out = MoveDesign(False, "", self.scene, self.request, f_hz=self.f_hz, zeta=self.zeta,
                         settle_s=self.settle_s)  # fmt: skip
        best: float | None = None  # the least full-model residual so far
        try:
            for fam in self.families:
                if out.found:
                    break
                for ev in self._search(fam):
                    motion = self.motion_of(ev)
                    if out.found and motion.duration >= out.duration_s:
                        continue
                    check = self.full(motion)
                    corner = self._corners(ev) if check.residual <= self.tol else {}
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
                out.message = (f"{out.kind} family ({self._describe(out)}), ramps "
                               f"{out.ramp_s * 1e3:.3g} ms: residual {out.check.residual:.3g}"
                               f"{box} <= {self.tol:g}")  # fmt: skip
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

    @staticmethod
    def _describe(out: MoveDesign) -> str:
        """The design's unknowns in words."""
        if out.kind.startswith("pulses"):
            return f"coast {out.spacing_s * 1e3:.4g} ms, first pulse {out.ratio:.3g} of the change"
        return f"spacing {out.spacing_s * 1e3:.4g} ms"

    def _adopt(self, out: MoveDesign, ev: Evaluation, check: MoveCheck | None) -> None:
        out.motion, out.check = self.motion_of(ev), check
        out.kind, out.ramp_s, out.spacing_s, out.kappa = ev.kind, ev.ramp_s, ev.spacing_s, ev.kappa
        out.ratio, out.params = ev.ratio, ev.params

    def _corners(self, ev: Evaluation) -> dict[str, float]:
        """The full model's residual at the box's corners, in turn until one misses: the
        corners of larger inner residual first (those not run on the inner model last)."""
        motion = self.motion_of(ev)

        def inner_residual(k: int) -> float:
            run = self.runs.get((k + 1, ev.family, ev.params))
            return -math.inf if run is None else run[0]

        order = sorted(range(len(self.boxed)), key=inner_residual, reverse=True)
        corner: dict[str, float] = {}
        for label, sc in (self.boxed[k] for k in order):
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

    def _search(self, fam: Family) -> list[Evaluation]:
        """The family's candidates worth a full-model check, shortest first: its root
        (`_root`), and where the least residual leaves slack (below INNER_MARGIN of the
        tolerance, at every corner of a box) the shortest first unknown (a spacing or the coast)
        at that level, down to SHORTEN of a half period shorter.  A family with a second-mode
        train is not searched where the same family without it misses by more than what its
        second mode leaves (the train cannot help there).  With a box, one ZV train is not
        searched where it misses the box even in linear theory (`one_train_misses`)."""
        if fam.kind == "zv" and self.boxed and self.one_train_misses():
            return []
        if fam.second_s > 0:
            base = fam.without_second
            if base in self.floors and self.floors[base] > INNER_SLACK * self.tol:
                return []
        _, lo, _ = self._root(fam)
        target = INNER_MARGIN * self.tol
        least = self._least(fam)
        if fam.kind in ("zv", "zvd") and least.residual <= target:
            self.shift = least.params[0] / self.halves[0]
        self.floors[fam] = self._floor(fam)
        worst = self.worst(least)
        if worst > INNER_SLACK * self.tol:
            return []
        if worst > target:
            return [least]
        short = self._shorten(fam, least, target, lo)
        return [short, least] if short is not least else [least]

    def _floor(self, fam: Family) -> float:
        """What a second-mode train could bring the family down to: the least over its
        candidates of the inner residual less the second mode's amplitude, the largest over the
        family's targets (the least over all candidates, not the least-residual one's: where
        the secant steps stall before the first mode is cancelled, another candidate may hold
        less of it)."""

        def part(ev: Evaluation) -> float:
            runs = [self.runs[(k, fam, ev.params)] for k in self.targets(fam)]
            return max(r - abs(amps[1]) if math.isfinite(r) else math.inf for r, amps in runs)

        return min(part(e) for e in self.evaluations if e.family == fam)

    def one_train_misses(self) -> bool:
        """Whether one ZV train tuned to the nominal beam misses the box in linear theory: at
        each corner it leaves `residual_factor` of the unshaped move's residual (about
        pi eps / 2 at a relative error eps of the half period; the unshaped residual the rigid
        move's on the inner model; the beam leaves three times that, docs/design.md)."""
        if self._one_train is None:
            rigid = self._run(self.inner_scenes[0], self.rigid(self.limits)).residual
            zv = for_mode("zv", 0.5 / self.halves[0], self.zeta)
            share = max(residual_factor(zv, 0.5 / h, self.zeta) for h in self.halves)
            self._one_train = share * rigid
            if self.progress is not None and self._one_train > self.tol:
                self.progress(f"zv: not searched, one train misses the box even in linear "
                              f"theory ({self._one_train:.3g} > {self.tol:g})")  # fmt: skip
        return self._one_train > self.tol

    def _root(self, fam: Family) -> tuple[Evaluation, np.ndarray, np.ndarray]:
        """The family's least-residual candidate, and its unknowns' bounds.

        Secant (Broyden) steps in the family's unknowns drive the first mode's complex
        amplitudes after the move (at its targets; with a second-mode train, the second mode's
        too) to zero on the inner model, by least squares where there are more equations than
        unknowns, from `start`, the first Jacobian by finite differences; each step within a
        trust region and taken back half way once if the residual grows; a secant step that
        does not lower the amplitudes' norm is not taken, and the Jacobian is taken again by
        finite differences where it stands (once per point); with more equations
        than unknowns, until two steps in a row lower their norm by less than 1 - STALL.  Runs
        are cached: a second call costs nothing."""
        x = np.array(self.start(fam))
        scale, trust, lo, hi = self._scales(fam)
        x = np.clip(x, lo, hi)

        def f(ev: Evaluation) -> np.ndarray:
            return np.array([v for a in ev.amplitudes for v in (a.real, a.imag)])

        def run(x: np.ndarray) -> Evaluation:
            return self.inner(fam, tuple(x))

        def jacobian(x: np.ndarray, ev: Evaluation) -> np.ndarray:
            cols = []
            for k in range(x.size):
                d = np.zeros(x.size)
                d[k] = scale[k] if x[k] + scale[k] <= hi[k] else -scale[k]
                cols.append((f(run(x + d)) - f(ev)) / d[k])
            return np.column_stack(cols)

        ev = run(x)
        jac, fresh = jacobian(x, ev), True
        target = INNER_MARGIN * self.tol
        stalls = 0
        for _ in range(MAX_NEWTON):
            if not np.all(np.isfinite(f(ev))) or ev.residual <= 0.2 * target:
                break
            if np.max(np.abs(f(ev))) <= 0.2 * target:  # solved: the rest is the family's floor
                break
            step = np.linalg.lstsq(jac, -f(ev), rcond=None)[0]
            step *= min(1.0, float(np.min(trust / np.maximum(np.abs(step), 1e-300))))
            new = np.clip(x + step, lo, hi)
            if np.all(np.abs(new - x) < XTOL * scale / STEP_SPACING):
                break
            nxt = run(new)
            if nxt.residual > ev.residual:  # a step too far: back half way once
                half = run(x + 0.5 * (new - x))
                nxt, new = (
                    (half, x + 0.5 * (new - x)) if half.residual < nxt.residual else (nxt, new)
                )
            dx, df = new - x, f(nxt) - f(ev)
            if np.all(np.isfinite(df)) and float(dx @ dx) > 0:
                jac = jac + np.outer(df - jac @ dx, dx) / float(dx @ dx)
            if np.linalg.norm(f(nxt)) >= np.linalg.norm(f(ev)) and not fresh:
                jac, fresh = jacobian(x, ev), True  # the secant went astray: differences again
                continue
            slow = np.linalg.norm(f(nxt)) > STALL * np.linalg.norm(f(ev))
            stalls = stalls + 1 if slow and jac.shape[0] > jac.shape[1] else 0
            x, ev, fresh = new, nxt, False
            if stalls >= 2:  # least squares (more equations than unknowns) at its floor
                break
        return self._least(fam), lo, hi

    def _shorten(self, fam: Family, least: Evaluation, target: float,
                 lowest: np.ndarray) -> Evaluation:  # fmt: skip
        """The shortest move whose worst residual is within target along one of the family's
        spacings (the first unknown, a spacing or the coast; the second-mode train's spacing),
        the other unknowns kept at the root's: the first down to SHORTEN of the first mode's
        half period shorter, the second-mode train's to SHORTEN_SECOND of its own (a train
        shorter than the second mode's half period cancels a share of it), by a root finder;
        the shortest of them."""
        from scipy.optimize import brentq

        knobs = [0] + ([len(least.params) - 2] if fam.second_s > 0 else [])
        found = [least]
        for k in knobs:
            x = list(least.params)
            half = self.halves[0] if k == 0 else self.second_s
            s1 = x[k]
            s0 = max(float(lowest[k]), s1 - (SHORTEN if k == 0 else SHORTEN_SECOND) * half)

            def at(v: float, k: int = k, x: list = x) -> Evaluation:
                return self.inner(fam, tuple(x[:k] + [v] + x[k + 1 :]))

            if s0 < s1 and self.worst(at(s0)) > target:
                try:
                    brentq(lambda v: self.worst(at(v)) - target, s0, s1,
                           xtol=XTOL * half, maxiter=MAX_ROOT)  # fmt: skip
                except RuntimeError:  # not converged in MAX_ROOT: the evaluations so far stand
                    pass
            others = least.params[:k] + least.params[k + 1 :]
            found += [e for e in self.evaluations if e.family == fam
                      and e.params[:k] + e.params[k + 1 :] == others
                      and self.worst(e) <= target]  # fmt: skip
        return min(found, key=lambda e: e.duration_s)

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


def _two_modes(scene: Scene, omega: float) -> tuple[float, float]:
    """The first two linear frequencies of the beam turning steadily at omega [Hz]."""
    from ..model.modes import linear_frequencies

    T = scene.beam.T
    w = linear_frequencies(scene.model(), omega * T, 2) / T
    return float(w[0]) / (2 * math.pi), float(w[1]) / (2 * math.pi)
