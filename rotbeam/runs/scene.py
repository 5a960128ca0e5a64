"""One scene: a beam, a drive, the effects and the numerics; dynamic and quasi-static responses.

`build_scene` turns a scene spec (the sections of a scene file, rotbeam.config.scenefile) into a
`Scene`; omitted keys take the registry's defaults (the paper's values), but for the drive's
omega0 and f_d, which `rotbeam simulate` needs from the file or its flags.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..config.checks import check_finite
from ..config.errors import RotbeamInputError
from ..config.scenefile import read_columns, scene_sections
from ..config.threads import one_blas_thread
from ..model.base import DiscreteModel
from ..model.criterion import delta_rms, rms
from ..model.drive import PROFILE_SHAPES, profile_samples
from ..model.drives import (
    DRIVE_FIELDS,
    kind_of,
    own_fields,
    refusable_fields,
    unused_drive_field,
)
from ..model.elastica import DiscreteElastica
from ..model.modal import ModalModel
from ..model.params import (
    Beam,
    Dimensionless,
    Drive,
    Effects,
    Harmonic,
    Samples,
    check_model_range,
    drive_groups,
    unit_hint,
)
from ..solve.extrapolation import richardson
from ..solve.floquet import VERDICT_ONLY
from ..solve.numerics import Numerics
from ..solve.periodic import Neighbour
from ..solve.quasistatic import QuasiStaticError, quasistatic_series
from ..solve.spectral import trig_interpolate
from ..solve.steady import SteadyState, steady_state, window_samples
from ..solve.timebudget import TimeBudget
from .observables import OBSERVABLES, States, compare, observable_names, still, window_rates

CLASSES = {"beam": Beam, "drive": Drive, "effects": Effects, "numerics": Numerics}
#: the drive keys that name a CSV file, and its columns
DRIVE_FILES = {"profile": ("phase", "omega"), "move": ("t", "omega")}


@dataclass(frozen=True)
class Scene:
    """One scene: a beam, a drive, the effects and the numerics, all in SI units.

    What every command runs; `dimensionless` is the problem the model solves and `model` the
    discrete model on the scene's grid.  Build it from a scene spec with `build_scene`.

    Parameters
    ----------
    beam : Beam
        The beam and its payload (default: the paper's reference beam).
    drive : Drive
        How the disk turns.
    effects : Effects
        The loads (default: the paper's).
    numerics : Numerics
        Grid, solver tolerances and budgets.

    Raises
    ------
    RotbeamInputError
        For a scene outside the model's range (`check_model_range`): a drive too fast for the
        beam, or a centrifugal tension that would stretch it past twice its length.
    """

    beam: Beam = Beam()
    drive: Drive = Drive()
    effects: Effects = Effects()
    numerics: Numerics = Numerics()

    def __post_init__(self) -> None:
        check_model_range(self.beam, self.drive)

    @property
    def dimensionless(self) -> Dimensionless:
        """The scene's dimensionless problem (groups, effects, drive)."""
        return Dimensionless.from_physical(self.beam, self.drive, self.effects)

    def model(self, N: int | None = None) -> DiscreteModel:
        """The discrete model of the scene.

        Parameters
        ----------
        N : int or None
            Grid intervals (default numerics.N).

        Returns
        -------
        DiscreteModel
            The `DiscreteElastica` of the scene's dimensionless problem, or with numerics.model
            modal its `ModalModel` of numerics.modes modes.
        """
        return discrete_model(self.dimensionless, self.numerics, N)


def model_name(num: Numerics) -> str:
    """'elastica', or 'modal n' for the modal model of n modes: the model a result comes from.

    Parameters
    ----------
    num : Numerics
        model and modes.

    Returns
    -------
    str
    """
    return "elastica" if num.model == "elastica" else f"modal {num.modes}"


def discrete_model(dl: Dimensionless, num: Numerics, N: int | None = None) -> DiscreteModel:
    """The discrete model numerics ask for: the elastica on N intervals, or its modal model.

    Parameters
    ----------
    dl : Dimensionless
        The scene's dimensionless problem.
    num : Numerics
        model ("elastica" or "modal"), modes and N.
    N : int or None
        Grid intervals (default numerics.N).

    Returns
    -------
    DiscreteModel
        A `DiscreteElastica`, or the `ModalModel` of numerics.modes of its modes.
    """
    full = DiscreteElastica(dl, num.N if N is None else N)
    return full if num.model == "elastica" else ModalModel(full, num.modes)


def build_scene(spec: dict[str, Any] | None = None, base: str | Path = ".") -> Scene:
    """The scene of a nested dict like a scene file's: its sections checked by
    rotbeam.config.scenefile, its values by the classes; an error names the offending key.

    Parameters
    ----------
    spec : dict or None
        Sections beam, drive, effects, numerics; omitted keys take the registry's defaults.
    base : str or Path
        The folder relative paths of drive.profile and drive.move start from (the scene
        file's).

    Returns
    -------
    Scene

    Raises
    ------
    RotbeamInputError
        One line naming the offending key: an unknown section or key, a bad value, a bad drive
        file, or a scene outside the model's range (`check_model_range`).
    """
    sections = scene_sections(spec)
    parts = {
        name: cls(**sections.get(name, {})) for name, cls in CLASSES.items() if name != "drive"
    }
    return Scene(drive=drive_of(sections.get("drive", {}), Path(base)), **parts)


def scene_files(spec: dict[str, Any]) -> list[str]:
    """The CSV files a scene spec reads (a sampled profile, a move), as written in it: relative
    to the scene's folder.

    Parameters
    ----------
    spec : dict
        A scene spec (sections beam, drive, effects, numerics), unchecked.

    Returns
    -------
    list of str
        The file paths, in the order of `DRIVE_FILES`.
    """
    drive = spec.get("drive") if isinstance(spec, dict) else None
    out = []
    for key in DRIVE_FILES:
        value = drive.get(key) if isinstance(drive, dict) else None
        if isinstance(value, dict):
            value = value.get("file")
        if isinstance(value, str):
            out.append(value)
    return out


def drive_of(values: dict[str, Any], base: Path) -> Drive:
    """The Drive of a scene's drive section: harmonics as mappings {k, amplitude, phase}, a
    profile as a CSV file (columns phase, omega) or a named shape {shape, omega_min,
    omega_max, ramp}, a move as a CSV file (columns t, omega).

    Parameters
    ----------
    values : dict
        The drive section.
    base : Path
        Folder of relative file paths.

    Returns
    -------
    Drive

    Raises
    ------
    RotbeamInputError
        For amplitude and harmonics together, a harmonic that is not {k, amplitude, phase}, a
        profile or move that is neither a CSV file nor (a profile) {file, harmonics} or a named
        shape, a bad named shape, or a bad file (`rotbeam.config.scenefile.read_columns`).
    """
    values = dict(values)
    kind = drive_kind(values)
    if "harmonics" in values and "amplitude" in values:
        raise RotbeamInputError(
            "drive: amplitude and harmonics given together; allowed: one of them (harmonics "
            "replace the amplitude: {k: 1, amplitude: a} is the sine)"
        )
    for name in refusable_fields():
        if name in values and name not in DRIVE_FIELDS[kind]:
            raise unused_drive_field(kind, name, values[name])
    if values.get("harmonics") is not None:
        values["harmonics"] = _harmonics(values["harmonics"])
    for key, columns in DRIVE_FILES.items():
        value = values.get(key)
        if value is None:
            continue
        keep = None
        if key == "profile" and isinstance(value, dict) and "shape" in value:
            values[key] = _named_profile(value)
            continue
        if key == "profile" and isinstance(value, dict):
            extra = sorted(set(value) - {"file", "harmonics"})
            if extra or "file" not in value:
                raise RotbeamInputError(
                    f"drive.profile = {value!r}: allowed: a CSV file, {{file: F, harmonics: K}} "
                    f"or a named shape {{shape: trapezoid, ...}}"
                )
            value, keep = value["file"], value.get("harmonics")
        if not isinstance(value, (str, Path)):
            raise RotbeamInputError(
                f"drive.{key} = {value!r}: allowed: a CSV file with columns {', '.join(columns)}"
                + (" or a named shape {shape: trapezoid, ...}" if key == "profile" else "")
            )
        data = read_columns(base / value, columns, f"drive.{key}")
        values[key] = Samples(data[columns[0]], data["omega"], key, str(value), keep)
    extra = dict(values.pop("extra", None) or {})
    extra.update({name: values.pop(name) for name in own_fields() if name in values})
    return Drive(**values, extra=extra)


def drive_kind(values: dict[str, Any]) -> str:
    """The kind of drive a drive section asks for, from its keys.

    Parameters
    ----------
    values : dict
        A drive section (unchecked).

    Returns
    -------
    str
        The registered kind whose key holds a value: "move", "profile", "harmonics" or a kind
        registered beside them, else "sine" (rotbeam.model.drives.kind_of).
    """
    return kind_of(values)


def _harmonics(items: Any) -> tuple[Harmonic, ...]:
    """Harmonic objects from a list of mappings {k, amplitude, phase}."""
    if not isinstance(items, (list, tuple)):
        raise RotbeamInputError(
            f"drive.harmonics = {items!r}: allowed: a list of {{k, amplitude, phase}}"
        )
    out = []
    for i, h in enumerate(items):
        if isinstance(h, Harmonic):
            out.append(h)
            continue
        if (
            not isinstance(h, dict)
            or set(h) - {"k", "amplitude", "phase"}
            or not {"k", "amplitude"} <= set(h)
        ):
            raise RotbeamInputError(
                f"drive.harmonics[{i}] = {h!r}: allowed: a mapping with k, amplitude [rad/s] "
                f"and optionally phase [rad]"
            )
        try:
            out.append(Harmonic(h["k"], h["amplitude"], h.get("phase", 0.0)))
        except RotbeamInputError as exc:  # name the entry: drive.harmonics[i].amplitude
            raise RotbeamInputError(
                str(exc).replace("drive.harmonics.", f"drive.harmonics[{i}].", 1)
            ) from None
    return tuple(out)


def _named_profile(spec: dict[str, Any]) -> Samples:
    """Samples of a named profile {shape, omega_min, omega_max, ramp} (model.drive)."""
    shape = spec.get("shape")
    if shape not in PROFILE_SHAPES:
        raise RotbeamInputError(
            f"drive.profile.shape = {shape!r}; allowed: {', '.join(PROFILE_SHAPES)} (or a CSV "
            f"file with columns phase, omega)"
        )
    keys = PROFILE_SHAPES[shape]
    wrong = sorted(set(spec) - {"shape", *keys}) + sorted(set(keys) - set(spec))
    if wrong:
        raise RotbeamInputError(
            f"drive.profile ({shape}): keys {', '.join(wrong)}; allowed: shape, {', '.join(keys)}"
        )
    nums = {k: check_finite(f"drive.profile.{k}", spec[k]) for k in keys}
    if not 0.0 < nums["ramp"] <= 0.5:
        raise RotbeamInputError(
            f"drive.profile.ramp = {nums['ramp']!r}; allowed: in (0, 0.5] (a share of the period)"
        )
    phase, omega = profile_samples(shape, **nums)
    return Samples(phase, omega, "profile", shape)


def load_scene(path: str | Path) -> Scene:
    """The scene of a YAML scene file (sections beam, drive, effects, numerics; omitted keys
    take the registry's defaults; its `uncertainty` section and `effects: auto` are the command
    line's and are not read here).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    Scene

    Raises
    ------
    RotbeamInputError
        For a file that cannot be read or parsed, or a scene `build_scene` refuses.
    """
    from ..config.scenefile import load_scene_file, split_auto

    raw = dict(load_scene_file(path))
    raw.pop("uncertainty", None)
    return build_scene(split_auto(raw)[0], Path(path).parent)


@dataclass
class SceneResult:
    """Dynamic and quasi-static responses of one scene over the same RMS window.

    What `simulate` returns.  `tau` is in units of T and the deflections y_m in units of L;
    `delta_rms` is the paper's criterion (dimensionless).  With numerics.extrapolate the RMS
    values are Richardson's and `extrapolation` says from what.
    """

    scene: Scene
    dynamic: SteadyState
    tau: np.ndarray
    y_dynamic: np.ndarray
    y_quasistatic: np.ndarray
    theta_quasistatic: np.ndarray  #: (m, n) the quasi-static twin at the window's instants
    rms_dynamic: float
    rms_quasistatic: float
    delta_rms: float
    seconds: float
    extrapolation: dict[str, Any] | None = None  #: Richardson from N and N // 2, if asked

    @property
    def converged(self) -> bool:
        """Whether the dynamic run reached a verified, stable steady state."""
        return self.dynamic.converged

    def summary(self) -> dict[str, Any]:
        """The scene's numbers for tables and JSON (scalars only).

        Returns
        -------
        dict
            RMS values (units of L) and Delta RMS, how the steady state was reached
            (``converged``, ``status``, ``message``, ``periods``, ``transient_bound``,
            ``nfev``), the Floquet columns (`stability_columns`), the drive's groups
            (`rotbeam.model.params.drive_groups`: C_max, E_max, E_n, I_max, f_d / f_n), f_n [Hz],
            the drive and numerics settings, G [s^2], delta, eta, zeta, the wall time [s] and,
            when asked, the extrapolation's fields.
        """
        beam, drive = self.scene.beam, self.scene.drive
        out: dict[str, Any] = {
            "rms_dynamic": self.rms_dynamic,
            "rms_quasistatic": self.rms_quasistatic,
            "delta_rms": self.delta_rms,
            "converged": self.converged,
            "status": self.dynamic.status,
            "message": self.dynamic.message,
            "periods": self.dynamic.periods,
            "transient_bound": self.dynamic.transient,
            "nfev": self.dynamic.nfev,
            "f_n_hz": beam.f_n,
            "omega0": drive.mean_speed,
            "amplitude": drive.swing,
            "f_d": drive.f_d,
            "N": self.scene.numerics.N,
            "model": model_name(self.scene.numerics),
            "method": self.scene.numerics.method,
            "effects": ",".join(self.scene.effects.active()),
            "seconds": self.seconds,
        }
        out.update(stability_columns(self.dynamic))
        out.update(drive_groups(beam, drive))
        out.update({k: v for k, v in beam.derived().items() if k in ("G", "delta", "eta", "zeta")})
        if self.extrapolation is not None:
            out.update(self.extrapolation)
        return out

    def observables(self, names: str | Iterable[str] = ("y_m",)) -> dict[str, dict[str, Any]]:
        """Observables of both responses over the RMS window (docs/model.md, "Observables").

        The dynamic steady state's rates and accelerations are the spectral derivatives of
        each period's samples (the orbit repeats with the drive); the quasi-static twin's are
        zero (it balances the loads with the beam at rest in the turning frame).  The values
        are those of grid N (`numerics.extrapolate` extrapolates y_m's RMS only).

        Parameters
        ----------
        names : str or iterable of str
            Names of `rotbeam.runs.observables.OBSERVABLES`, or one comma-separated string.

        Returns
        -------
        dict
            name -> {``unit``, ``rms_dynamic``, ``rms_quasistatic``, ``delta_rms``,
            ``peak_dynamic``, ``peak_quasistatic``}; the dynamic numbers are NaN where no
            period was sampled, and those that read rates where the window holds no steady
            state.

        Raises
        ------
        RotbeamInputError
            For a name the registry does not hold.
        """
        names = observable_names(names)
        model, beam = self.scene.model(), self.scene.beam
        theta = self.dynamic.theta
        rates = None
        if self.converged:
            rates = window_rates(theta, self.dynamic.samples_per_period, model.dl.period)
        dyn = States(self.tau, theta, *(rates or (None, None)))
        qs = States(self.tau, self.theta_quasistatic, still(self.theta_quasistatic),
                    still(self.theta_quasistatic))  # fmt: skip
        out = {}
        for name in names:
            obs = OBSERVABLES[name]
            values = np.full(self.tau.size, math.nan)
            if self.tau.size > 1 and (rates is not None or not obs.rates):
                values = obs(model, beam, dyn)
            out[name] = compare(values, obs(model, beam, qs), obs.unit)
        return out

    def time_series(self) -> dict[str, np.ndarray]:
        """The samples of the RMS window, for a CSV file or a figure.

        Returns
        -------
        dict
            ``tau`` (units of T), ``t_s`` [s], ``y_m_dynamic`` and ``y_m_quasistatic`` (units
            of L); arrays of one length.
        """
        T = self.scene.beam.T
        return {
            "tau": self.tau,
            "t_s": self.tau * T,
            "y_m_dynamic": self.y_dynamic,
            "y_m_quasistatic": self.y_quasistatic,
        }

    def dense_series(self, samples: int) -> dict[str, np.ndarray]:
        """The window's curves at `samples` instants per drive period, for a figure.

        The dynamic curve is the trigonometric interpolant of each period's samples (a steady
        state repeats with the drive, and the window resolves its harmonics:
        `rotbeam.solve.steady.window_samples`); the quasi-static one is solved again at the
        new instants.  Without a steady state, or with no more instants than the window's, it
        is `time_series` itself.

        Parameters
        ----------
        samples : int
            Instants per drive period.

        Returns
        -------
        dict
            ``tau`` (units of T), ``t_s`` [s], ``y_m_dynamic`` and ``y_m_quasistatic`` (units
            of L) over the window's periods; arrays of one length.
        """
        m, size = self.dynamic.samples_per_period, self.tau.size
        if not self.converged or m == 0 or size % m or samples <= m:
            return self.time_series()
        periods = size // m
        model = self.scene.model()
        P = model.dl.period
        theta = self.dynamic.theta.reshape(periods, m, model.n)
        dense = [trig_interpolate(theta[q], samples) for q in range(periods)]
        tau = self.tau[0] + np.arange(periods * samples) * (P / samples)
        y_qs = quasistatic_midspan(model, tau[:samples])[1]
        T = self.scene.beam.T
        return {
            "tau": tau,
            "t_s": tau * T,
            "y_m_dynamic": np.atleast_1d(model.midspan(np.concatenate(dense))),
            "y_m_quasistatic": np.tile(y_qs, periods),
        }


def folded(scene: Scene, exc: QuasiStaticError) -> QuasiStaticError:
    """The quasi-static solver's failure restated for the scene: the beam folds under its loads,
    with the drive's C_max and E_max and a likely unit slip (`unit_hint`).

    Parameters
    ----------
    scene : Scene
        The scene whose quasi-static response has no equilibrium Newton reaches.
    exc : QuasiStaticError
        The solver's error (where, in the model's units).

    Returns
    -------
    QuasiStaticError
        One line for a reader.
    """
    g = drive_groups(scene.beam, scene.drive)
    return QuasiStaticError(
        f"no quasi-static state: the beam folds under the scene's loads (C_max = "
        f"{g['C_max']:.3g}, E_max = {g['E_max']:.3g}; {exc}){unit_hint(scene.beam)}"
    )


def stability_columns(dyn: SteadyState) -> dict[str, Any]:
    """The Floquet columns of a dynamic run, for the summary.

    Parameters
    ----------
    dyn : SteadyState
        The dynamic run.

    Returns
    -------
    dict
        ``floquet_max``: the largest |mu| of the reported orbit, or of the collocated one when
        no steady state was reached (NaN without multipliers); ``stable``: bool, or None
        without multipliers.
    """
    fl = dyn.floquet
    return {"floquet_max": fl.max_abs if fl is not None else math.nan,
            "stable": bool(fl.stable) if fl is not None else None}  # fmt: skip


def quasistatic_midspan(model: DiscreteModel, taus: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The quasi-static response of the model at given instants.

    Parameters
    ----------
    model : DiscreteModel
        The model and its drive.
    taus : numpy.ndarray
        Instants in units of T, shape (m,).

    Returns
    -------
    theta : numpy.ndarray
        Angles [rad], shape (m, n).
    y_m : numpy.ndarray
        Midspan deflection in units of L, shape (m,).
    """
    theta = quasistatic_series(model, taus)
    return theta, np.atleast_1d(model.midspan(theta))


#: Richardson extrapolation is skipped when the two grids differ by more than this (relative):
#: then the pair is not in the asymptotic range (e.g. a different branch near resonance).
EXTRAPOLATION_MAX_CHANGE = 0.1


@one_blas_thread
def simulate(
    scene: Scene,
    progress: Callable[[int, float], None] | None = None,
    guess: np.ndarray | Neighbour | None = None,
    time_budget: TimeBudget | None = None,
) -> SceneResult:
    """Dynamic steady state and quasi-static response sampled at the same instants.

    The dynamic run is `rotbeam.solve.steady.steady_state` (collocation, certificate or time
    stepping; it never raises for a solver failure: the result says), the quasi-static one the
    static equilibrium at every sample.  With numerics.extrapolate the RMS values are
    Richardson-extrapolated from N and N // 2 (the discretisation is second order in 1/N),
    unless the two grids differ by more than EXTRAPOLATION_MAX_CHANGE; the time series stay
    those of grid N.  Both grids draw on one wall-time budget.

    Parameters
    ----------
    scene : Scene
        Beam, a periodic drive, effects, numerics.
    progress : callable or None
        Called as progress(period, transient bound) by the time stepping on grid N.
    guess : numpy.ndarray, Neighbour or None
        Seeds the periodic collocation: an orbit on grid N (angles [rad] at M equispaced
        instants of a period, shape (M, n)), or the previous point's along a sweep
        (`rotbeam.solve.periodic.Neighbour`, whose state also starts time stepping where no
        orbit continues it).
    time_budget : TimeBudget or None
        The wall-time budget of the whole call, shared with a caller's other phases; None:
        numerics.max_seconds from the call.

    Returns
    -------
    SceneResult
        Both responses over one RMS window, their RMS and Delta RMS, the steady state's status,
        message and multipliers, the wall time [s], and Richardson's account when asked for.

    Raises
    ------
    RotbeamInputError
        If the drive is a single move (`rotbeam.runs.move.simulate_move` runs it).
    """
    if not scene.drive.periodic:
        raise RotbeamInputError(
            "a single move has no periodic steady state: simulate it with "
            "rotbeam.runs.move.simulate_move (rotbeam simulate --move)"
        )
    time_budget = time_budget or TimeBudget(scene.numerics.max_seconds)
    try:
        fine = _simulate_grid(scene, progress, guess, time_budget)
    except QuasiStaticError as exc:
        raise folded(scene, exc) from None
    num = scene.numerics
    if not num.extrapolate:
        return fine
    Nc = num.N // 2
    if not fine.converged:  # nothing to extrapolate: the coarse run would only cost time
        note = f"not extrapolated: no steady state at N = {num.N} (N = {Nc} not run)"
        return replace(fine, extrapolation={"N_coarse": Nc, "extrapolated": False, "note": note})
    coarse_guess = None
    if guess is not None and num.N % 2 == 0:  # the coarse grid's nodes are every second one
        coarse_guess = guess.coarse() if isinstance(guess, Neighbour) else guess[:, 1::2]
    # the coarse grid's multipliers are not reported (docs/stability.md)
    coarse_num = replace(num, N=Nc, extrapolate=False, floquet_tol=VERDICT_ONLY)
    coarse = _simulate_grid(
        Scene(scene.beam, scene.drive, scene.effects, coarse_num),
        None,
        coarse_guess,
        time_budget,
    )
    info = {"N_coarse": Nc, "rms_dynamic_N": fine.rms_dynamic,
            "rms_dynamic_coarse": coarse.rms_dynamic, "rms_quasistatic_N": fine.rms_quasistatic,
            "rms_quasistatic_coarse": coarse.rms_quasistatic,
            "coarse_seconds": coarse.seconds}  # fmt: skip
    pairs = [(fine.rms_dynamic, coarse.rms_dynamic), (fine.rms_quasistatic, coarse.rms_quasistatic)]
    change = max(abs(f - c) / abs(f) if f else abs(c) for f, c in pairs)
    ok = fine.converged and coarse.converged and math.isfinite(change)
    if ok and change <= EXTRAPOLATION_MAX_CHANGE:
        r_dyn, r_qs = (richardson(f, c, num.N / Nc) for f, c in pairs)
        info["extrapolated"] = True
    else:
        r_dyn, r_qs = fine.rms_dynamic, fine.rms_quasistatic
        info["extrapolated"] = False
        why = (f"grids differ by {change:.2g}" if coarse.converged
               else f"N = {Nc}: {coarse.dynamic.message}")  # fmt: skip
        info["note"] = f"not extrapolated: {why}"
    return replace(
        fine,
        rms_dynamic=r_dyn,
        rms_quasistatic=r_qs,
        delta_rms=delta_rms(r_dyn, r_qs),
        seconds=fine.seconds + coarse.seconds,
        extrapolation=info,
    )


def _simulate_grid(
    scene: Scene,
    progress: Callable[[int, float], None] | None,
    guess: np.ndarray | Neighbour | None,
    time_budget: TimeBudget,
) -> SceneResult:
    t0 = time.perf_counter()
    num = scene.numerics
    model = scene.model()
    dl = model.dl
    # quasi-static first: it is cheap, sets the response scale and the tolerances' size; at the
    # drive's window samples (the collocated orbit's harmonics may ask the window for more)
    m = window_samples(dl, num)
    th_qs1, y_qs1 = quasistatic_midspan(model, np.arange(m) / m * dl.period)
    scale = float(np.max(np.abs(th_qs1))) if th_qs1.size else 0.0
    dyn = steady_state(model, num, progress=progress, response_scale=scale or None, guess=guess,
                       time_budget=time_budget)  # fmt: skip
    if dyn.samples_per_period > m:  # the same instants as the dynamic window
        m = dyn.samples_per_period
        th_qs1, y_qs1 = quasistatic_midspan(model, np.arange(m) / m * dl.period)
    # the quasi-static response has the drive's period: reuse the one-period solve when the
    # window's instants fall on its phases (they do, but for a failed run's last sample)
    phase = (dyn.tau / dl.period) % 1.0 * m
    idx = np.rint(phase).astype(int) % m
    if np.allclose(phase, np.rint(phase), atol=1e-6):
        theta_qs, y_qs = th_qs1[idx], np.atleast_1d(y_qs1)[idx]
    else:
        theta_qs, y_qs = quasistatic_midspan(model, dyn.tau)
    y_dyn = OBSERVABLES["y_m"](model, scene.beam, States(dyn.tau, dyn.theta))
    r_dyn = rms(y_dyn)
    r_qs = rms(y_qs)
    if not math.isfinite(r_dyn) or y_dyn.size <= 1:
        r_dyn = float("nan")  # no period stepped: the one sample is the initial state
    return SceneResult(
        scene=scene,
        dynamic=dyn,
        tau=dyn.tau,
        y_dynamic=y_dyn,
        y_quasistatic=y_qs,
        theta_quasistatic=theta_qs,
        rms_dynamic=r_dyn,
        rms_quasistatic=r_qs,
        delta_rms=delta_rms(r_dyn, r_qs),
        seconds=time.perf_counter() - t0,
    )
