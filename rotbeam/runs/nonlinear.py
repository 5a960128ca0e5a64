r"""Large drive around the first resonance: the branch of periodic orbits in f_d beside
time-stepped sweeps that follow the beam (the workflow target ``nonlinear``).

For one drive amplitude: two arms of the branch (`rotbeam.solve.beam_branch`), the orbit at f_lo
continued up and the one at f_hi continued down; two sweeps by time stepping, each point started
from the state the previous one ended in; and the check that an arm's first loss of stability
lies where the sweep in the same direction leaves that arm (`fold_row`).  What it writes and
what it found: docs/stability.md, "The workflow target `nonlinear`".
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..model.criterion import rms
from ..model.elastica import DiscreteElastica
from ..model.params import Beam, Dimensionless, Drive, Effects
from ..solve.beam_branch import BeamBranch, beam_branch
from ..solve.continuation import Branch
from ..solve.numerics import Numerics
from ..solve.periodic import harmonic_tail
from ..solve.steady import steady_state
from .observables import OBSERVABLES, States
from .scene import discrete_model

#: the arms of the branch and their direction in f_d
ARMS = {"from_below": 1.0, "from_above": -1.0}
#: the time-stepped sweeps and their direction in f_d
SWEEPS = {"up": 1.0, "down": -1.0}
#: the sweep that leaves the branch an arm follows: up leaves the arm from below, down the other
SWEEP_OF_ARM = {"from_below": "up", "from_above": "down"}


@dataclass(frozen=True)
class NonlinearSpec:
    """One amplitude's branch and sweeps (the config section ``nonlinear`` with one a)."""

    omega0: float  #: Omega_0 [rad/s]
    amplitude: float  #: a [rad/s]
    f_lo: float  #: [Hz]
    f_hi: float  #: [Hz]
    N: int = 8  #: grid intervals (branch and sweeps)
    tail_tol: float = 1e-4  #: harmonic tail an arm's orbits are to reach (what sets its M)
    #: most collocation instants of an arm: it is followed again on 2 M - 1 while its orbit at
    #: the first loss of stability has a harmonic tail above tail_tol (`resolved_arm`)
    M_max: int = 129
    ds: float = 0.02  #: first arclength step
    ds_max: float = 0.1  #: largest arclength step
    max_points: int = 300  #: per arm
    beyond: int = 15  #: points an arm keeps after its first unstable one
    sweep_step: float = 0.05  #: [Hz]
    rtol: float = 1e-5  #: time stepper of the sweeps
    ss_tol: float = 1e-3  #: steady-state tolerance of the sweeps
    max_periods: int = 400  #: per sweep point
    #: [Hz] each sweep only within this distance of its arm's first loss of stability (started on
    #: the arm's orbit there); None: over all of f_lo .. f_hi, the first point from collocation
    sweep_window: float | None = None

    def frequencies(self, direction: float) -> np.ndarray:
        """The sweep's drive frequencies, in the order it visits them.

        Parameters
        ----------
        direction : float
            > 0: up from f_lo; < 0: down from f_hi.

        Returns
        -------
        numpy.ndarray
            f_lo, f_lo + sweep_step, ... up to f_hi [Hz], reversed for a sweep down.
        """
        k = int(math.floor((self.f_hi - self.f_lo) / self.sweep_step + 1e-9))
        f = self.f_lo + self.sweep_step * np.arange(k + 1)
        return f if direction > 0 else f[::-1]


def _stop_after_unstable(beyond: int):
    """Stop an arm `beyond` points after its first unstable point."""

    def stop(branch: Branch) -> bool:
        first = branch.first_unstable()
        return first is not None and len(branch.points) - 1 - first >= beyond

    return stop


def branch_model(
    beam: Beam, omega0: float, amplitude: float, f_d: float, effects: Effects, N: int
) -> DiscreteElastica:
    """The discrete elastica of the sine drive a branch in f_d follows
    (`rotbeam.solve.beam_branch.beam_branch` replaces its drive frequency point by point).

    Parameters
    ----------
    beam : Beam
        The beam (SI units).
    omega0, amplitude : float
        Omega_0 and a [rad/s].
    f_d : float
        A drive frequency [Hz] (the branch's start).
    effects : Effects
        Effects of the model.
    N : int
        Grid intervals.

    Returns
    -------
    DiscreteElastica
    """
    drive = Drive(omega0=omega0, f_d=f_d, amplitude=amplitude)
    return DiscreteElastica(Dimensionless.from_physical(beam, drive, effects), N)


def branch_arm(
    beam: Beam, spec: NonlinearSpec, arm: str, effects: Effects, M: int | None = None
) -> BeamBranch:
    """One arm of the branch, stopped `spec.beyond` points past its first unstable point.

    Where collocation finds no orbit at the arm's end of the range, the start moves inwards by
    sweep steps (up to 5).

    Parameters
    ----------
    beam : Beam
        The beam (SI units).
    spec : NonlinearSpec
        The amplitude, range, grid and continuation steps.
    arm : str
        "from_below" (the orbit at f_lo continued up) or "from_above" (`ARMS`).
    effects : Effects
        Effects of the model.
    M : int or None
        Collocation instants of the arm; None: from its first orbit's harmonic tail
        (`spec.tail_tol`, at most 65).

    Returns
    -------
    BeamBranch
        The continued arm.

    Raises
    ------
    RuntimeError
        When no start is found within 5 sweep steps of the arm's end.
    """
    lo, hi = spec.f_lo, spec.f_hi
    for k in range(6):
        shift = k * spec.sweep_step
        f_range = (lo + shift, hi) if ARMS[arm] > 0 else (lo, hi - shift)
        try:
            model = branch_model(beam, spec.omega0, spec.amplitude, f_range[0], effects, spec.N)
            return beam_branch(model, beam.T, f_range,
                               tail_tol=spec.tail_tol, ds=spec.ds, ds_max=spec.ds_max,
                               max_points=spec.max_points, direction=ARMS[arm],
                               stop=_stop_after_unstable(spec.beyond), M=M)  # fmt: skip
        except RuntimeError:
            if k == 5:
                raise
    raise AssertionError("unreachable")


def loss_tail(bb: BeamBranch) -> float:
    """The harmonic tail of the arm's orbit at its first unstable point (at its last point when
    it does not lose stability): how well M resolves the orbits the loss is read from.

    Parameters
    ----------
    bb : BeamBranch
        The arm.

    Returns
    -------
    float
        max |c_k| over the top harmonics relative to the largest (`harmonic_tail`).
    """
    pts = bb.branch.points
    i = bb.branch.first_unstable()
    at = pts[i] if i is not None else pts[-1]
    return harmonic_tail(at.x.reshape(bb.problem.M, bb.problem.model.n))


def resolved_arm(
    beam: Beam, spec: NonlinearSpec, arm: str, effects: Effects
) -> tuple[BeamBranch, BeamBranch | None]:
    """An arm whose orbit at the first loss of stability M resolves: followed again on 2 M - 1
    instants while that orbit's harmonic tail stays above `spec.tail_tol` and 2 M - 1 <=
    `spec.M_max`.

    The arm's M comes from its first orbit, far from the resonance; the orbits grow along the
    arm and at M = 33 or 65 can read a loss of stability tens of mHz off (docs/stability.md,
    "The workflow target `nonlinear`", "An arm's M").

    Parameters
    ----------
    beam : Beam
        The beam (SI units).
    spec : NonlinearSpec
        The amplitude, range, grid, continuation steps, tail_tol and M_max.
    arm : str
        "from_below" or "from_above" (`ARMS`).
    effects : Effects
        Effects of the model.

    Returns
    -------
    arm : BeamBranch
        The arm on the last M.
    coarse : BeamBranch or None
        The same arm on the M before (None when the first M resolved it).
    """
    bb, coarse = branch_arm(beam, spec, arm, effects), None
    while loss_tail(bb) > spec.tail_tol and 2 * bb.problem.M - 1 <= spec.M_max:
        bb, coarse = branch_arm(beam, spec, arm, effects, M=2 * bb.problem.M - 1), bb
    return bb, coarse


def first_instability(bb: BeamBranch) -> dict:
    """Where an arm first loses stability, and how.

    Parameters
    ----------
    bb : BeamBranch
        The arm.

    Returns
    -------
    dict
        kind: "fold", "period doubling", "torus", "branch point" (a real multiplier through +1
        where f_d does not turn) or "none" (no loss, or the first point already unstable);
        f_loss [Hz]: the bifurcation's estimate at that step, else the mean of the two points'
        f_d; f_stable and f_unstable [Hz]: the points on either side; f_fold [Hz]: the first
        fold on the arm (nan: none).
    """
    pts = bb.branch.points
    i = bb.branch.first_unstable()
    folds = bb.branch.folds()
    out = {"kind": "none", "f_loss": math.nan, "f_stable": math.nan, "f_unstable": math.nan,
           "f_fold": folds[0] if folds else math.nan}  # fmt: skip
    if i is None or i == 0:
        return out
    at = [b for b in bb.branch.bifurcations if b.index == i]
    kinds = [b.kind for b in at]
    kind = next((k for k in ("fold", "period doubling", "torus") if k in kinds), "")
    f = next((b.p for b in at if b.kind == kind), 0.5 * (pts[i - 1].p + pts[i].p))
    if not kind:  # no turn in f_d nor a change of counts: what the leading multiplier does
        kind = pts[i].floquet.crossing()
        kind = "branch point" if kind == "fold" else kind  # mu through +1 without a fold
    out.update(kind=kind, f_loss=f, f_stable=pts[i - 1].p, f_unstable=pts[i].p)
    return out


def arm_rows(bb: BeamBranch, arm: str, amplitude: float) -> list[dict]:
    """The arm's points as rows of `branches.csv`.

    Parameters
    ----------
    bb : BeamBranch
        The arm.
    arm : str
        Its name (`ARMS`).
    amplitude : float
        Drive amplitude a [rad/s].

    Returns
    -------
    list of dict
        `BeamBranch.rows` with amplitude, kind ("branch"), arm, N, M, and bifurcation: the
        kinds the continuation detected between the point and the one before, joined by "+".
    """
    found: dict[int, list[str]] = {}
    for b in bb.branch.bifurcations:
        found.setdefault(b.index, []).append(b.kind)
    return [
        {"amplitude": amplitude, "kind": "branch", "arm": arm, "N": bb.problem.model.grid.N,
         "M": bb.problem.M, **row, "bifurcation": "+".join(found.get(row["index"], []))}
        for row in bb.rows()
    ]  # fmt: skip


def sweep_numerics(spec: NonlinearSpec) -> Numerics:
    """The numerics of a sweep point: the spec's grid, tolerances and period budget, from a
    collocated start, without limits in tau or wall time.

    Parameters
    ----------
    spec : NonlinearSpec
        N, rtol, ss_tol and max_periods.

    Returns
    -------
    Numerics
        The settings of `steady_state` along the sweep.
    """
    return Numerics(N=spec.N, rtol=spec.rtol, ss_tol=spec.ss_tol, max_periods=spec.max_periods,
                    max_tau=1e9, max_seconds=1e9, start="periodic")  # fmt: skip


def _window(spec: NonlinearSpec, sweep: str, bb: BeamBranch | None) -> tuple[np.ndarray, object]:
    """The sweep's frequencies and the collocation guess of its first point: all of them and
    None, or (with `spec.sweep_window` and the arm) those within the window of the arm's first
    loss of stability, and the arm's stable orbit nearest the first of them."""
    f = spec.frequencies(SWEEPS[sweep])
    if spec.sweep_window is None or bb is None:
        return f, None
    f_loss = first_instability(bb)["f_loss"]
    if not math.isfinite(f_loss):
        return f, None
    f = f[np.abs(f - f_loss) <= spec.sweep_window + 1e-9]
    stable = bb.branch.stable_start()
    if not stable or f.size == 0:
        return f, None
    near = min(stable, key=lambda pt: abs(pt.p - f[0]))
    return f, near.x.reshape(bb.problem.M, bb.problem.model.n)


def follow_sweep(
    beam: Beam,
    spec: NonlinearSpec,
    sweep: str,
    effects: Effects,
    log=None,
    arm: BeamBranch | None = None,
) -> list[dict]:
    """Time stepping along the sweep's frequencies, following the beam.

    The first point starts from its collocated orbit (seeded by the arm's orbit if given), every
    next one from the state the previous one ended in (`steady_state(state0=...)`).  With
    `spec.sweep_window` and an arm, only the frequencies within the window of the arm's first
    loss of stability are visited.

    Parameters
    ----------
    beam : Beam
        The beam (SI units).
    spec : NonlinearSpec
        Amplitude, range, step, grid and tolerances.
    sweep : str
        "up" or "down" (`SWEEPS`).
    effects : Effects
        Effects of the model.
    log : logging.Logger or None
        Gets one line per point.
    arm : BeamBranch or None
        The arm whose orbit seeds the first point and whose loss of stability sets the window.

    Returns
    -------
    list of dict
        One row per point in the order visited: amplitude, kind ("sweep"), arm (the sweep's
        name), N, f_d [Hz], rms_ym and max_ym (y_m / L over the reported samples), max_theta
        [rad], status, periods, floquet_max and stable (of the orbit reached), seconds (CPU).
    """
    num = sweep_numerics(spec)
    rows, state = [], None
    freqs, guess = _window(spec, sweep, arm)
    for f in freqs:
        cpu = time.process_time()
        dl = Dimensionless.from_physical(
            beam, Drive(omega0=spec.omega0, f_d=float(f), amplitude=spec.amplitude), effects
        )
        model = discrete_model(dl, num)
        ss = steady_state(model, num, state0=state, guess=guess if state is None else None)
        state = ss.state if ss.state is not None else state
        y_m = OBSERVABLES["y_m"](model, beam, States(ss.tau, ss.theta))
        rows.append(
            {"amplitude": spec.amplitude, "kind": "sweep", "arm": sweep, "N": spec.N,
             "f_d": float(f), "rms_ym": rms(y_m), "max_ym": float(np.max(np.abs(y_m))),
             "max_theta": float(np.max(np.abs(ss.theta))), "status": ss.status,
             "periods": ss.periods,
             "floquet_max": ss.floquet.max_abs if ss.floquet is not None else math.nan,
             "stable": bool(ss.floquet.stable) if ss.floquet is not None else False,
             "seconds": time.process_time() - cpu}
        )  # fmt: skip
        if log is not None:
            log.info("  %s f_d = %.4g Hz: RMS %.4g, status %d after %d periods (CPU %.1f s)",
                     sweep, f, rows[-1]["rms_ym"], ss.status, ss.periods,
                     rows[-1]["seconds"])  # fmt: skip
    return rows


def largest_jump(rows: list[dict]) -> dict:
    """The largest jump of a sweep: the consecutive pair of points whose RMS changes most.

    Parameters
    ----------
    rows : list of dict
        The sweep's rows (f_d, rms_ym) in the order visited.

    Returns
    -------
    dict
        f_before and f_after [Hz] (in the sweep's order), jump (the change of RMS y_m / L) and
        share (|jump| over the sweep's RMS range); nan, nan, 0, 0 with fewer than two points.
    """
    y = np.array([r["rms_ym"] for r in rows])
    f = np.array([r["f_d"] for r in rows])
    if y.size < 2:
        return {"f_before": math.nan, "f_after": math.nan, "jump": 0.0, "share": 0.0}
    d = np.diff(y)
    k = int(np.argmax(np.abs(d)))
    span = float(np.ptp(y)) or 1.0
    return {"f_before": float(f[k]), "f_after": float(f[k + 1]), "jump": float(d[k]),
            "share": float(abs(d[k]) / span)}  # fmt: skip


def hysteresis(up: list[dict], down: list[dict], tol: float = 0.1) -> list[float]:
    """Where the up and down sweeps are on different attractors.

    Parameters
    ----------
    up, down : list of dict
        The two sweeps' rows (f_d, rms_ym).
    tol : float
        Relative difference, of the largest RMS of both sweeps, that counts.

    Returns
    -------
    list of float
        The up sweep's drive frequencies [Hz] where the down sweep, at the same f_d, differs
        by more than tol times the largest RMS (frequencies the down sweep did not visit do
        not count).
    """
    down_at = {round(r["f_d"], 9): r["rms_ym"] for r in down}
    top = max(r["rms_ym"] for r in up + down)
    out = []
    for r in up:
        other = down_at.get(round(r["f_d"], 9), r["rms_ym"])
        if abs(r["rms_ym"] - other) > tol * top:
            out.append(r["f_d"])
    return out


def departure(bb: BeamBranch, sweep_rows: list[dict], tol: float = 0.02) -> tuple[float, float]:
    """Where the sweep leaves the arm's stable part (the points before its first unstable one).

    A sweep point is on it when its f_d lies in the stable part's range and its RMS is within
    `tol` (relative) of the stable part's RMS interpolated there.

    Parameters
    ----------
    bb : BeamBranch
        The arm.
    sweep_rows : list of dict
        The sweep in the same direction (f_d, rms_ym), in the order visited.
    tol : float
        Relative RMS difference of a point still on the arm.

    Returns
    -------
    last_on : float
        f_d [Hz] of the last sweep point on the arm (nan when the first is already off).
    first_off : float
        f_d [Hz] of the first one off it.  (nan, nan) when the sweep never leaves.
    """
    stable = bb.branch.stable_start()
    f = np.array([pt.p for pt in stable])
    y = np.array([rms(bb.problem.midspan(pt.x, pt.p)) for pt in stable])
    order = np.argsort(f)
    f, y = f[order], y[order]
    last = math.nan
    for r in sweep_rows:
        on = f.size > 0 and f[0] - 1e-9 <= r["f_d"] <= f[-1] + 1e-9
        if on:
            ref = float(np.interp(r["f_d"], f, y))
            on = abs(r["rms_ym"] - ref) <= tol * ref
        if not on:
            return last, float(r["f_d"])
        last = float(r["f_d"])
    return math.nan, math.nan


def fold_row(
    bb: BeamBranch,
    arm: str,
    sweep_rows: list[dict],
    spec: NonlinearSpec,
    coarse: BeamBranch | None = None,
) -> dict:
    """One row of the folds table: where the arm first loses stability against where the sweep
    in the same direction leaves the arm.

    Parameters
    ----------
    bb : BeamBranch
        The arm.
    arm : str
        Its name (`ARMS`).
    sweep_rows : list of dict
        The sweep in the same direction (`SWEEP_OF_ARM`).
    spec : NonlinearSpec
        The amplitude and grid.
    coarse : BeamBranch or None
        The same arm on fewer instants (`resolved_arm`).

    Returns
    -------
    dict
        The loss (`first_instability`: loss_kind, f_loss, f_fold, f_stable, f_unstable), the
        sweep's departure (`departure`: sweep_last_on, sweep_first_off), distance [Hz] (how far
        the loss lies outside that interval, 0 inside, nan when either is unknown), agrees
        (distance 0), the sweep's largest jump (`largest_jump`: jump_from, jump_to, jump_rms,
        jump_share), N and M, tail (`loss_tail`), and the coarse arm's loss_kind_coarse,
        f_loss_coarse and M_coarse (empty, nan and 0 without one).
    """
    loss = first_instability(bb)
    on, off = departure(bb, sweep_rows)
    jump = largest_jump(sweep_rows)
    f = loss["f_loss"]
    lo, hi = sorted((on, off))
    dist = max(lo - f, f - hi, 0.0) if math.isfinite(f) and math.isfinite(lo) else math.nan
    return {
        "amplitude": spec.amplitude, "arm": arm, "sweep": SWEEP_OF_ARM[arm],
        "loss_kind": loss["kind"], "f_loss": f, "f_fold": loss["f_fold"],
        "f_stable": loss["f_stable"], "f_unstable": loss["f_unstable"],
        "sweep_last_on": on, "sweep_first_off": off, "distance": dist,
        "agrees": bool(math.isfinite(dist) and dist == 0.0),
        "jump_from": jump["f_before"], "jump_to": jump["f_after"], "jump_rms": jump["jump"],
        "jump_share": jump["share"], "N": spec.N, "M": bb.problem.M, "tail": loss_tail(bb),
        **_coarse_loss(coarse),
    }  # fmt: skip


def _coarse_loss(coarse: BeamBranch | None) -> dict:
    """loss_kind_coarse, f_loss_coarse [Hz] and M_coarse of the arm on fewer instants."""
    if coarse is None:
        return {"loss_kind_coarse": "", "f_loss_coarse": math.nan, "M_coarse": 0}
    loss = first_instability(coarse)
    return {"loss_kind_coarse": loss["kind"], "f_loss_coarse": loss["f_loss"],
            "M_coarse": coarse.problem.M}  # fmt: skip


def run_amplitude(
    beam: Beam, spec: NonlinearSpec, effects: Effects | None = None, log=None
) -> tuple[list[dict], list[dict]]:
    """Both arms and both sweeps of one amplitude, and their comparison: one job of the
    workflow target ``nonlinear``.

    Parameters
    ----------
    beam : Beam
        The beam (SI units).
    spec : NonlinearSpec
        The amplitude and everything numerical.
    effects : Effects or None
        Effects of the model; None: the defaults.
    log : logging.Logger or None
        Gets a line per arm, sweep and sweep point.

    Returns
    -------
    rows : list of dict
        The arms' points (`arm_rows`) and the sweeps' points (`follow_sweep`).
    folds : list of dict
        One `fold_row` per arm, with hysteresis_from and hysteresis_to [Hz]: the range where
        the two sweeps differ (`hysteresis`; nan when they do not).
    """
    effects = effects if effects is not None else Effects()
    rows, folds, arms, coarse = [], [], {}, {}
    for arm in ARMS:
        cpu = time.process_time()
        bb, coarse[arm] = resolved_arm(beam, spec, arm, effects)
        arms[arm] = bb
        rows += arm_rows(bb, arm, spec.amplitude)
        if log is not None:
            log.info("a = %g, arm %s: %d points, M = %d (tail %.1e at the loss), %s (CPU %.1f s)",
                     spec.amplitude, arm, len(bb.branch.points), bb.problem.M, loss_tail(bb),
                     bb.branch.message, time.process_time() - cpu)  # fmt: skip
    sweeps = {}
    for sweep in SWEEPS:
        cpu = time.process_time()
        arm = next(arms[a] for a, s in SWEEP_OF_ARM.items() if s == sweep)
        sweeps[sweep] = follow_sweep(beam, spec, sweep, effects, log, arm)
        rows += sweeps[sweep]
        if log is not None:
            log.info("a = %g, sweep %s: %d points (CPU %.1f s)", spec.amplitude, sweep,
                     len(sweeps[sweep]), time.process_time() - cpu)  # fmt: skip
    hyst = hysteresis(sweeps["up"], sweeps["down"])
    for arm, bb in arms.items():
        row = fold_row(bb, arm, sweeps[SWEEP_OF_ARM[arm]], spec, coarse[arm])
        row["hysteresis_from"] = min(hyst) if hyst else math.nan
        row["hysteresis_to"] = max(hyst) if hyst else math.nan
        folds.append(row)
    return rows, folds
