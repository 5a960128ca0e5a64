"""The effect budget of a scene: what each effect of the model contributes to RMS(y_m) and to
Delta RMS, and what it costs to simulate (`rotbeam effects`, `--effects auto`).

Each effect is switched off (or on, where the scene leaves it out) one at a time; damping, which
cannot be switched off, is measured by its first-order sensitivity; and sequential shares, the
effects switched off in the order `SEQUENCE`, add up to 1.  How each share is defined and why:
docs/model.md, "The effect budget".
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, fields, replace
from typing import Any

from ..config.errors import RotbeamInputError
from ..config.scenefile import AUTO_TOL as _AUTO_TOL
from ..config.threads import one_blas_thread
from ..model.params import Effects
from ..runs.scene import Scene, SceneResult, simulate
from ..solve.timebudget import TimeBudget

#: relative step of gamma for the damping's first-order share
GAMMA_STEP = 0.01

#: the order in which the sequential shares switch the effects off (damping is never switched)
SEQUENCE = ("extension", "coriolis", "softening", "centrifugal", "euler")


@dataclass(frozen=True)
class EffectShare:
    """One effect's row of the budget: how it was measured, its shares and what it cost.

    Shares are dimensionless: ``share_rms`` relative to the scene's RMS(y_m), ``share_delta`` a
    difference of Delta RMS (docs/model.md, "The effect budget").
    """

    effect: str
    on_in_scene: bool
    method: str  #: "switched off", "switched on" or "first order in gamma"
    rms: float  #: RMS(y_m) / L of the variant (NaN for the first-order row)
    delta_rms: float  #: Delta RMS of the variant
    share_rms: float
    share_delta: float
    seconds: float
    converged: bool
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        """The row as JSON-ready fields.

        Returns
        -------
        dict
            Every field of the row by name.
        """
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass
class EffectBudget:
    """The scene's own result, one `EffectShare` per effect and the sequential shares.

    What `effect_budget` returns; RMS values are RMS(y_m) / L, times are wall seconds.
    """

    scene: Scene
    rms: float
    delta_rms: float
    seconds: float  #: the scene's own simulation
    shares: list[EffectShare] = field(default_factory=list)
    sequential: dict[str, float] = field(default_factory=dict)  #: effect -> sequential share
    rms_last: float = float("nan")  #: RMS with every effect of `sequential` switched off
    sequential_seconds: float = 0.0

    @property
    def total_seconds(self) -> float:
        """Wall time of every run of the budget [s]: the scene's, the rows' and the sequence's."""
        return self.seconds + sum(s.seconds for s in self.shares) + self.sequential_seconds

    def as_dict(self) -> dict[str, Any]:
        """The budget as JSON-ready fields (`rotbeam effects --json`).

        Returns
        -------
        dict
            ``rms_dynamic``, ``delta_rms``, ``seconds``, ``total_seconds``, ``effects`` (one
            `EffectShare.as_dict` per row) and ``sequential`` (``order``, ``shares``,
            ``rms_last``).
        """
        return {
            "rms_dynamic": self.rms,
            "delta_rms": self.delta_rms,
            "seconds": self.seconds,
            "total_seconds": self.total_seconds,
            "effects": [s.as_dict() for s in self.shares],
            "sequential": {
                "order": list(self.sequential),
                "shares": self.sequential,
                "rms_last": self.rms_last,
            },  # fmt: skip
        }


def _toggled(effects: Effects, name: str) -> tuple[Effects, str]:
    """Effects with `name` flipped; switching centrifugal off takes softening with it."""
    values = {f.name: getattr(effects, f.name) for f in fields(effects)}
    values[name] = not values[name]
    note = ""
    if name == "centrifugal" and not values[name] and values.get("softening"):
        values["softening"] = False
        note = "softening switched off with it"
    if name == "softening" and values[name] and not values.get("centrifugal"):
        values["centrifugal"] = True
        note = "centrifugal switched on with it"
    return Effects(**values), note


class _Runs:
    """The budget's simulations, each timed, with `progress()` after each, all within one
    wall-time budget (a run once it is spent stops at its first period of time stepping)."""

    def __init__(self, progress: Callable[[], None] | None, time_budget: TimeBudget) -> None:
        self.progress, self.time_budget = progress, time_budget

    def __call__(self, scene: Scene) -> tuple[SceneResult, float]:
        t0 = time.perf_counter()
        res = simulate(scene, time_budget=self.time_budget)
        if self.progress is not None:
            self.progress()
        return res, time.perf_counter() - t0


def _switched(scene: Scene, base: SceneResult, name: str, _run: _Runs) -> EffectShare:
    on = getattr(scene.effects, name)
    effects, note = _toggled(scene.effects, name)
    res, seconds = _run(replace(scene, effects=effects))
    if on:  # what the effect contributes
        share = (base.rms_dynamic - res.rms_dynamic) / base.rms_dynamic
        share_delta = base.delta_rms - res.delta_rms
    else:  # what leaving it out costs
        share = (res.rms_dynamic - base.rms_dynamic) / base.rms_dynamic
        share_delta = res.delta_rms - base.delta_rms
    method = "switched off" if on else "switched on"
    if not res.converged:  # e.g. the time budget cut it: the share rests on no steady state
        note = "; ".join(filter(None, (note, res.dynamic.message)))
    return EffectShare(name, on, method, res.rms_dynamic, res.delta_rms, share, share_delta,
                       seconds, res.converged, note)  # fmt: skip


def _damping_first_order(scene: Scene, base: SceneResult, _run: _Runs) -> EffectShare:
    runs = []
    for sign in (+1.0, -1.0):
        beam = replace(scene.beam, gamma=scene.beam.gamma * (1.0 + sign * GAMMA_STEP))
        runs.append(_run(replace(scene, beam=beam)))
    (hi, t_hi), (lo, t_lo) = runs
    d_rms = (hi.rms_dynamic - lo.rms_dynamic) / (2.0 * GAMMA_STEP)  # gamma dRMS/dgamma
    d_delta = (hi.delta_rms - lo.delta_rms) / (2.0 * GAMMA_STEP)
    note = f"central differences at gamma (1 +- {GAMMA_STEP:g})"
    failed = [r.dynamic.message for r in (hi, lo) if not r.converged]
    return EffectShare("damping", True, "first order in gamma", float("nan"), float("nan"),
                       d_rms / base.rms_dynamic, d_delta, t_hi + t_lo, not failed,
                       "; ".join([note, *failed]))  # fmt: skip


def _sequential(scene: Scene, base: SceneResult, budget: EffectBudget, _run: _Runs) -> None:
    """Switch the effects that are on off in the order SEQUENCE; record each step's share."""
    effects, previous = scene.effects, base.rms_dynamic
    for name in SEQUENCE:
        if not getattr(effects, name):
            continue
        effects = replace(effects, **{name: False})
        res, seconds = _run(replace(scene, effects=effects))
        budget.sequential_seconds += seconds
        budget.sequential[name] = (previous - res.rms_dynamic) / base.rms_dynamic
        previous = res.rms_dynamic
    budget.rms_last = previous


@one_blas_thread
def effect_budget(
    scene: Scene,
    progress: Callable[[], None] | None = None,
    time_budget: TimeBudget | None = None,
) -> EffectBudget:
    """Every effect's share of RMS(y_m) and of Delta RMS at this scene.

    Each effect is switched off (or on) one at a time, damping by its first-order sensitivity,
    and the effects that are on are switched off in turn for the sequential shares
    (docs/model.md, "The effect budget").  Costs one simulation of the scene, one per effect
    (two for damping) and one per effect of the sequence.

    Parameters
    ----------
    scene : Scene
        The scene to budget (beam, drive, effects, numerics).
    progress : callable or None
        Called after every simulation.
    time_budget : TimeBudget or None
        The wall-time budget of all its simulations; None: the scene's numerics.max_seconds.
        A share whose run the budget cut says so in its note.

    Returns
    -------
    EffectBudget
        The scene's RMS and Delta RMS, one row per effect and the sequential shares; without
        rows where the scene has no steady state or no deflection (nothing to share out).
    """
    _run = _Runs(progress, time_budget or TimeBudget(scene.numerics.max_seconds))
    base, seconds = _run(scene)
    budget = EffectBudget(scene, base.rms_dynamic, base.delta_rms, seconds)
    if base.rms_dynamic == 0.0 or not base.converged:
        return budget  # nothing to share out: the caller reports the scene's own message
    for f in fields(scene.effects):
        if f.name == "damping" and scene.effects.damping:
            budget.shares.append(_damping_first_order(scene, base, _run))
        elif f.name == "damping":  # switching damping on changes the scene's nature
            continue
        elif f.name == "softening" and not scene.effects.centrifugal:
            continue  # softening is part of the centrifugal load
        else:
            budget.shares.append(_switched(scene, base, f.name, _run))
    _sequential(scene, base, budget, _run)
    return budget


#: `--effects auto` keeps the effects whose |share of RMS| is at least this (0.1 %; defined with
#: the scene files' `effects: auto`)
AUTO_TOL = _AUTO_TOL


@dataclass(frozen=True)
class AutoEffects:
    """What `auto_effects` chose: the effects, and what the dropped ones were worth.

    ``dropped_share`` is the accuracy given up, a dimensionless fraction of RMS(y_m).
    """

    effects: Effects
    kept: list[str]
    dropped: list[str]
    dropped_share: float  #: sum of the dropped effects' |share of RMS|: the accuracy given up
    tol: float
    notes: list[str]

    def as_dict(self) -> dict[str, Any]:
        """The choice as JSON-ready fields (``effects_auto`` of `rotbeam simulate --json`).

        Returns
        -------
        dict
            ``kept``, ``dropped``, ``dropped_share``, ``tol`` and ``notes``.
        """
        return {"kept": self.kept, "dropped": self.dropped, "dropped_share": self.dropped_share,
                "tol": self.tol, "notes": self.notes}  # fmt: skip


def auto_effects(budget: EffectBudget, tol: float = AUTO_TOL) -> AutoEffects:
    """The effects whose one-at-a-time |share of RMS| is at least `tol` (an effect the scene
    leaves out is switched on when its share is).  Damping stays on (without it there is no
    steady state); softening keeps centrifugal on (it is part of that load).  tol = 0 keeps
    every effect, and switches on every one the scene leaves out (damping included).

    Parameters
    ----------
    budget : EffectBudget
        The scene's budget (`effect_budget`).
    tol : float
        Keep the effects whose |share of RMS(y_m)| is at least this, dimensionless, >= 0.

    Returns
    -------
    AutoEffects
        The chosen effects, the kept and dropped names, and what the dropped ones were worth.

    Raises
    ------
    ValueError
        If `tol` is not a number >= 0.
    """
    if not tol >= 0.0:
        raise ValueError(f"tol must be >= 0, got {tol!r}")
    share = {s.effect: abs(s.share_rms) for s in budget.shares}
    values = {f.name: share.get(f.name, 0.0) >= tol for f in fields(budget.scene.effects)}
    notes = []
    if budget.scene.effects.damping and not values["damping"]:
        values["damping"] = True
        notes.append("damping kept: without it there is no steady state")
    if values.get("softening") and not values.get("centrifugal"):
        values["centrifugal"] = True
        notes.append("centrifugal kept: softening is part of the centrifugal load")
    kept = [k for k, v in values.items() if v]
    dropped = [k for k, v in values.items() if not v and k in share]
    return AutoEffects(Effects(**values), kept, dropped, sum(share[k] for k in dropped), tol,
                       notes)  # fmt: skip


@one_blas_thread
def auto_scene(
    scene: Scene, tol: float = AUTO_TOL, time_budget: TimeBudget | None = None
) -> tuple[Scene, AutoEffects, EffectBudget]:
    """The scene with the effects its budget calls for (`auto_effects` at `tol`).

    Parameters
    ----------
    scene : Scene
        The scene whose effects are budgeted (at its own drive frequency).
    tol : float
        Keep the effects whose |share of RMS(y_m)| is at least this, dimensionless, >= 0.
    time_budget : TimeBudget or None
        The wall-time budget of the effect budget's runs (`effect_budget`).

    Returns
    -------
    scene : Scene
        The scene with the chosen effects.
    auto : AutoEffects
        What was kept and dropped, and what the dropped effects were worth.
    budget : EffectBudget
        The budget it rests on (its cost: `total_seconds`).

    Raises
    ------
    RotbeamInputError
        If the scene has no steady state to share out.
    """
    budget = effect_budget(scene, time_budget=time_budget)
    if not budget.shares:
        raise RotbeamInputError("effects auto: the scene has no steady state to share out")
    auto = auto_effects(budget, tol)
    return replace(scene, effects=auto.effects), auto, budget
