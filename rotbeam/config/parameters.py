"""The parameter registry: type, default, range, unit and help of every scene field, in one place.

`Beam`, `Drive`, `Effects` (rotbeam.model.params) and `Numerics` (rotbeam.solve.numerics) take
their defaults from here and check their fields with `check_fields`; scene files and CLI flags
are checked against the same entries, and `tests/test_parameters.py` holds the workflow's JSON
schema (workflow/schemas/config.schema.yaml) to them.  Cross-field rules (h < L, R > L, N >= 6
with extrapolation) stay with the class that owns both fields.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from .errors import RotbeamInputError
from .schema import g


@dataclass(frozen=True)
class Param:
    """One field of the registry: its type, default, help, unit and range.

    `kind` is "real", "int", "bool", "choice" or "data" (a structure its class checks:
    harmonics, sampled speeds); bounds are inclusive unless `lo_open` / `hi_open` (None:
    unbounded); `optional` fields may be None.  `unit` is the SI unit shown in help and
    messages ("" for dimensionless values).
    """

    kind: str
    default: Any
    help: str
    unit: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    choices: tuple[str, ...] = ()
    hi_open: bool = False
    optional: bool = False


def _real(default, help, unit="", lo=None, hi=None, lo_open=False, hi_open=False) -> Param:
    return Param("real", default, help, unit, lo, hi, lo_open, hi_open=hi_open)


def _int(default, help, lo=None, hi=None) -> Param:
    return Param("int", default, help, "", lo, hi)


def _bool(default, help) -> Param:
    return Param("bool", default, help)


def _choice(default, help, *choices) -> Param:
    return Param("choice", default, help, choices=choices)


def _data(default, help) -> Param:
    return Param("data", default, help)


#: Every section of a scene and its fields, in the order of the dataclasses.
SECTIONS: dict[str, dict[str, Param]] = {
    "beam": {
        "L": _real(0.040, "length", "m", 0, lo_open=True),
        "h": _real(0.002, "thickness (bending direction), < L", "m", 0, lo_open=True),
        "b": _real(0.010, "width", "m", 0, lo_open=True),
        "E": _real(1.22e6, "Young's modulus", "Pa", 0, lo_open=True),
        "rho": _real(1170.2, "density", "kg/m^3", 0, lo_open=True),
        # R is not printed in the paper; 0.155 m follows from the C and E ranges of Sec. 5
        "R": _real(0.155, "axis to undeformed tip, > L (clamp at R - L)", "m", 0, lo_open=True),
        "gamma": _real(0.039, "viscous damping per unit length (App. B)", "N s/m^2", 0),
        "tip_mass": _real(0.0, "point mass at the free end (a payload)", "kg", 0),
        "tip_inertia": _real(0.0, "its rotary inertia about its own centre", "kg m^2", 0),
    },
    "drive": {
        "omega0": _real(5.0, "mean angular velocity Omega_0", "rad/s"),
        "amplitude": _real(1.0, "velocity amplitude a", "rad/s", 0),
        "f_d": _real(7.0, "drive (repetition) frequency", "Hz", 0, lo_open=True),
        "harmonics": _data((), "harmonics {k, amplitude [rad/s], phase [rad]} replacing amplitude"),
        "profile": _data(None, "one period of sampled speed: CSV (phase, omega) or a named shape"),
        "move": _data(None, "a single move: CSV with columns t [s], omega [rad/s]"),
        "settle": Param(
            "real",
            None,
            "time after a move (default: until calm, at most 20 first-mode periods)",
            "s",
            0,
            lo_open=True,
            optional=True,
        ),  # fmt: skip
        "move_start": _choice(
            "rest",
            "how the beam starts a move: at rest in the static state of the first speed, or "
            "(quasistatic) in the quasi-static state and rate of the first sample, a move that "
            "continues a motion",
            "rest",
            "quasistatic",
        ),  # fmt: skip
        "extra": _data((), "the fields of drive kinds registered beside these: name -> value"),
    },
    "effects": {
        "centrifugal": _bool(True, "centrifugal load C (1 - delta + delta x)"),
        "softening": _bool(True, "in-plane centrifugal softening delta C y (needs centrifugal)"),
        "euler": _bool(True, "Euler load of the angular acceleration"),
        "coriolis": _bool(False, "Coriolis load (negligible, Sec. 2; off in the paper)"),
        "damping": _bool(True, "viscous damping gamma"),
        "extension": _bool(
            False, "axial stretch by the centrifugal tension, strain N/(EA) (off in the paper)"
        ),  # fmt: skip
    },
    "numerics": {
        "N": _int(40, "grid intervals", 3, 2000),
        "method": _choice("Radau", "time stepper", "Radau", "BDF", "LSODA", "TRBDF2"),
        "rtol": _real(1e-5, "time stepper's relative tolerance (transients)", "", 1e-13, 0.1),
        "ss_tol": _real(
            1e-3, "steady-state tolerance (relative remaining transient)", "", 1e-10, 0.5
        ),  # fmt: skip
        "rms_periods": _int(1, "whole drive periods in the RMS window", 1),
        "samples_per_period": _int(
            64,
            "samples of y_m per drive period, at least: where 4 K exceeds it, K the highest "
            "harmonic of the drive or of the collocated orbit, 4 K rounded up to a power of two",
            8,
        ),  # fmt: skip
        "max_periods": _int(2000, "give up after this many periods", 2),
        "max_tau": _real(2000.0, "... or after this much dimensionless time", "", 0, lo_open=True),
        "max_seconds": _real(
            900.0, "wall-time budget of a whole command (all its phases)", "s", 0, lo_open=True
        ),  # fmt: skip
        "start": _choice("periodic", "initial state", "periodic", "linear", "quasistatic", "rest"),
        "tail_tol": _real(1e-3, "harmonic tail of the collocated orbit", "", 1e-12, 0.1),
        "floquet_tol": _real(
            1e-5, "how closely the reported Floquet |mu|max is resolved", "", 1e-9, 1.0
        ),  # fmt: skip
        "integrate": _bool(True, "verify the collocated orbit by time stepping"),
        "certify": _choice(
            "monodromy", "what accepts an attracting collocated orbit", "monodromy", "time"
        ),  # fmt: skip
        "jacobian": _choice("exact", "Jacobian of the stepper", "exact", "fd"),
        "extrapolate": _bool(False, "Richardson-extrapolate RMS from N and N // 2"),
        "model": _choice(
            "elastica", "the discrete model: the full elastica or its modes", "elastica", "modal"
        ),  # fmt: skip
        "modes": _int(3, "modes of the modal model (numerics.model: modal)", 1, 1999),
    },
}


#: What a command asks beside its scene: the verdict's threshold, the f_d* search's tolerance,
#: the classification run without a stable periodic state, the modes, a sweep's line.  Not
#: scene-file sections.
OPTIONS: dict[str, dict[str, Param]] = {
    "verdict": {
        "threshold": _real(
            0.10,
            "Delta RMS below which quasi-static is good enough (the paper's)",
            "",
            0,
            1,
            lo_open=True,
            hi_open=True,
        ),  # fmt: skip
    },
    "critical": {
        "ftol": _real(1e-3, "relative tolerance on f_d*", "", 1e-8, 0.1),
    },
    "response": {
        "periods": _int(
            100,
            "without a stable periodic state: periods of transient, then as many "
            "classified (Poincare section, Lyapunov exponent)",
            1,
        ),  # fmt: skip
        "N": _int(
            6,
            "grid intervals of that classification run (at large drive the top bending "
            "modes ring and set the step)",
            4,
            80,
        ),  # fmt: skip
    },
    "modes": {
        "omega": _real(0.0, "steady angular velocity", "rad/s"),
        "count": _int(3, "number of modes", 1),
    },
    "sweep": {
        "fd_min": Param(
            "real",
            None,
            "first drive frequency of the line (required)",
            "Hz",
            0,
            lo_open=True,
            optional=True,
        ),
        "fd_max": Param(
            "real",
            None,
            "last drive frequency of the line (required)",
            "Hz",
            0,
            lo_open=True,
            optional=True,
        ),
        "points": _int(40, "drive frequencies, equally spaced from --fd-min to --fd-max", 2),
    },
}


def param(section: str, name: str) -> Param:
    """The registry entry of one field: a scene section's or a command option's.

    Parameters
    ----------
    section : str
        A scene section (`SECTIONS`: beam, drive, effects, numerics) or a command's options
        (`OPTIONS`).
    name : str
        The field.

    Returns
    -------
    Param

    Raises
    ------
    KeyError
        For an unknown section or field.
    """
    table = SECTIONS.get(section)
    return table[name] if table is not None else OPTIONS[section][name]


def default(section: str, name: str) -> Any:
    """The default of one field (what the dataclasses use).

    Parameters
    ----------
    section, name : str
        The section and the field (`param`).

    Returns
    -------
    object
        The default, in the field's unit.
    """
    return param(section, name).default


def allowed(p: Param) -> str:
    """What a field accepts, in words (for error messages and help).

    Parameters
    ----------
    p : Param
        The field.

    Returns
    -------
    str
        E.g. "a finite number > 0", "an integer in [3, 2000]", "true or false".
    """
    if p.kind == "data":
        return "see the docs"
    if p.kind == "bool":
        return "true or false"
    if p.kind == "choice":
        return f"one of {p.choices}"
    what = "an integer" if p.kind == "int" else "a finite number"
    bounds = _bounds(p)
    return f"{what} {bounds}" if bounds else what


def _bounds(p: Param) -> str:
    """ "in [lo, hi]", "> lo" or "<= hi": the words the schema messages use too."""
    if p.lo is not None and p.hi is not None:
        return f"in {'(' if p.lo_open else '['}{g(p.lo)}, {g(p.hi)}{')' if p.hi_open else ']'}"
    if p.lo is not None:
        return f"{'>' if p.lo_open else '>='} {g(p.lo)}"
    if p.hi is not None:
        return f"{'<' if p.hi_open else '<='} {g(p.hi)}"
    return ""


def check_value(section: str, name: str, value: Any) -> Any:
    """A value checked against the registry, returned as the field's type.

    The one check behind the dataclasses, scene files and CLI flags, so that a bad value fails
    with the same one line wherever it comes from.  "data" fields are returned as they are
    (their class checks them).

    Parameters
    ----------
    section, name : str
        The section and the field (`param`).
    value : object
        The value, in the field's unit.

    Returns
    -------
    object
        `value` as a bool, a choice, an int or a float.

    Raises
    ------
    RotbeamInputError
        One line naming `section.name`, the value and what is allowed: the wrong type, a value
        that is not finite, out of range, or not one of the choices.
    """
    p = param(section, name)
    key = f"{section}.{name}"
    if p.kind == "data" or (p.optional and value is None):
        return value
    if p.kind == "bool":
        if not isinstance(value, (bool, np.bool_)):
            raise RotbeamInputError(f"{key} must be true or false, got {value!r}")
        return bool(value)
    if p.kind == "choice":
        if value not in p.choices:
            raise RotbeamInputError(f"{key} must be one of {p.choices}, got {value!r}")
        return value
    if p.kind == "int":
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
            raise RotbeamInputError(f"{key} must be an integer, got {value!r}")
        value = int(value)
    else:
        if isinstance(value, (bool, np.bool_)) or not isinstance(
            value, (int, float, np.integer, np.floating)
        ):
            raise RotbeamInputError(
                f"{key} must be a number, got {value!r} ({type(value).__name__})"
            )
        value = float(value)
        if not math.isfinite(value):
            raise RotbeamInputError(f"{key} must be finite, got {value!r}")
    too_low = p.lo is not None and (value <= p.lo if p.lo_open else value < p.lo)
    too_high = p.hi is not None and (value >= p.hi if p.hi_open else value > p.hi)
    if too_low or too_high:
        raise RotbeamInputError(f"{key} must be {_bounds(p)}, got {value!r}")
    return value


def check_fields(obj: object, section: str) -> None:
    """Check every registry field of a frozen dataclass instance in place.

    Each field is replaced by its checked value (an int given for a real becomes a float).  The
    fields of registered drive kinds are not the class's own: `Drive` checks them in its `extra`.

    Parameters
    ----------
    obj : object
        The instance (`Beam`, `Drive`, `Effects` or `Numerics`).
    section : str
        Its registry section.

    Raises
    ------
    RotbeamInputError
        For the first field that fails `check_value`.
    """
    own = {f.name for f in fields(obj)}  # a registered drive kind's fields live in Drive.extra
    for name in SECTIONS[section]:
        if name in own:
            object.__setattr__(obj, name, check_value(section, name, getattr(obj, name)))


def add_fields(section: str, entries: dict[str, Param]) -> None:
    """Add fields to a scene section: what registering a drive kind with fields of its own does.

    Scene files, CLI flags and `check_value` read the section, so they learn the fields here.

    Parameters
    ----------
    section : str
        The scene section (`SECTIONS`).
    entries : dict
        Field name -> its registry entry.

    Raises
    ------
    ValueError
        If a name is already a field of the section (registered twice or by another kind).
    """
    clash = sorted(set(entries) & set(SECTIONS[section]))
    if clash:
        raise ValueError(f"{section}.{clash[0]} is already a field; allowed: a new name")
    SECTIONS[section].update(entries)


def remove_fields(section: str, names: tuple[str, ...]) -> None:
    """Remove fields that `add_fields` added (unregistering a drive kind).

    Parameters
    ----------
    section : str
        The scene section.
    names : tuple of str
        The fields; names that are not in the section are passed over.
    """
    for name in names:
        SECTIONS[section].pop(name, None)


def help_text(section: str, name: str) -> str:
    """The help of a CLI flag, from the registry: ``help [unit] (default ...; allowed ...)``.

    Parameters
    ----------
    section, name : str
        The section and the field (`param`).

    Returns
    -------
    str
        One line.
    """
    p = param(section, name)
    unit = f" [{p.unit}]" if p.unit else ""
    if p.default is None:  # no default to show: the help says what happens without a value
        return f"{p.help}{unit} ({allowed(p)})"
    shown = f"{p.default:g}" if p.kind in ("real", "int") else str(p.default)
    return f"{p.help}{unit} (default {shown}; {allowed(p)})"
