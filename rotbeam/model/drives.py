"""The registry of drive kinds: which fields each kind of drive reads and how the disk turns.

A kind is a class registered by name (`register`): the `Drive` fields it reads, the field whose
value selects it, whether it repeats, its law in the model's units, its mean speed and swing for
tables and the words its refusals use.  `Drive.kind` is the registered kind whose field is
given; scene files, the CLI's flags and the workflow's scenes learn a kind's own fields when it
is registered.  The built-in kinds are the sine, harmonics, a sampled profile and a single
move; a new one is one class (docs/model.md, "Drives").
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, replace
from typing import Any, ClassVar

import numpy as np

from ..config.errors import RotbeamInputError
from ..config.parameters import SECTIONS, Param, add_fields, check_value, remove_fields
from .drive import DriveLaw, HarmonicLaw, MoveLaw, harmonics_of_samples, kept_harmonics

#: why a kind of drive does not read a field, for the one-line refusal (`DriveKind.why_unused`)
UNUSED_WHY = {
    "omega0": "its speeds are its own; tables report its mean speed as omega0",
    "amplitude": "its swing is its own",
    "f_d": "a single move has no repetition rate",
    "move_start": "only a move starts from rest",
    "harmonics": "the harmonics replace the amplitude",
}


class DriveKind:
    """One kind of drive, bound to a drive: what it reads and how the disk turns.

    A subclass is registered with `register`.  The class attributes say what the kind reads;
    a new kind gives Omega(t) and dOmega/dt(t) in SI units (`omega`, `omega_dot`) and, if it
    does not repeat at drive.f_d, its `period` (a single run: its duration); `law` turns them
    into the model's units.  The built-in kinds give `law` directly (exact harmonics, a
    spline), and the sine its numbers in closed form.

    Attributes
    ----------
    name : str
        The kind's name, as `Drive.kind` and tables give it.
    fields : tuple of str
        The `Drive` fields it reads; any other field set away from its default is refused in
        one line (`unused_drive_field`).
    own : dict of str to Param
        Fields of its own beside `Drive`'s (registry entries: type, default, unit, range);
        registering adds them to the drive section of scene files and to the CLI's flags, and
        a `Drive` keeps their values in `extra`.
    key : str or None
        The field whose value selects the kind (default: the first of `own`); None for the
        one default kind, the sine.
    periodic : bool
        Whether Omega repeats at drive.f_d.
    description : str
        One line saying what Omega(t) is.
    unused_why : dict of str to str
        Why it does not read a field, where `UNUSED_WHY` does not say.

    Parameters
    ----------
    drive : Drive
        The drive (rotbeam.model.params.Drive) this kind reads.
    """

    name: ClassVar[str] = ""
    fields: ClassVar[tuple[str, ...]] = ()
    own: ClassVar[dict[str, Param]] = {}
    key: ClassVar[str | None] = None
    periodic: ClassVar[bool] = True
    description: ClassVar[str] = ""
    unused_why: ClassVar[dict[str, str]] = {}

    def __init__(self, drive: Any) -> None:
        self.drive = drive

    def omega(self, t: float) -> float:
        """Omega at one instant: what a new kind gives (the built-in kinds give `law`).

        Parameters
        ----------
        t : float
            Time [s] from the start of a period (or of the run).

        Returns
        -------
        float
            Omega(t) [rad/s].

        Raises
        ------
        NotImplementedError
            For a kind that gives neither `omega` nor `law`.
        """
        raise NotImplementedError(f"the {self.name} drive gives neither omega(t) nor law(T)")

    def omega_dot(self, t: float) -> float:
        """dOmega/dt at one instant: what a new kind gives beside `omega`.

        Parameters
        ----------
        t : float
            Time [s] from the start of a period (or of the run).

        Returns
        -------
        float
            dOmega/dt (t) [rad/s^2].

        Raises
        ------
        NotImplementedError
            For a kind that gives neither `omega_dot` nor `law`.
        """
        raise NotImplementedError(f"the {self.name} drive gives neither omega_dot(t) nor law(T)")

    def period(self) -> float:
        """The period of a periodic kind, 1 / drive.f_d; a single run gives its duration.

        Returns
        -------
        float
            Seconds.
        """
        return 1.0 / self.drive.f_d

    def law(self, T: float) -> DriveLaw:
        """The drive in the model's units: lam(tau) = Omega(tau T) T.

        Parameters
        ----------
        T : float
            Time scale [s]; 1.0 gives the drive in SI units.

        Returns
        -------
        DriveLaw
            `ClosedFormLaw` of `omega` and `omega_dot` (the built-in kinds: their own laws).
        """
        return ClosedFormLaw(self, T)

    def mean_speed(self) -> float:
        """The mean angular velocity over a period (or the run) [rad/s]: tables' omega0.

        Returns
        -------
        float
        """
        return self.law(1.0).mean

    def swing(self) -> float:
        """The largest |Omega - mean_speed| [rad/s]: tables' amplitude.

        Returns
        -------
        float
        """
        law = self.law(1.0)
        return float(np.max(np.abs(law.dense()[1] - law.mean)))

    def omega_max(self) -> float:
        """The largest |Omega| [rad/s].

        Returns
        -------
        float
        """
        return self.law(1.0).lam_max

    def omega_dot_max(self) -> float:
        """The largest |dOmega/dt| [rad/s^2].

        Returns
        -------
        float
        """
        return self.law(1.0).lam_dot_max

    def final_speed(self) -> float:
        """The speed at the end of a single run, at which the disk turns after it [rad/s].

        Returns
        -------
        float
        """
        law = self.law(1.0)
        return law.lam(law.duration)

    def scales(self, law: DriveLaw, T: float) -> tuple[float, float]:
        """The mean rotation and the swing of the dimensionless problem (lam0, alpha).

        Parameters
        ----------
        law : DriveLaw
            This drive's law in the model's units (`law(T)`).
        T : float
            Time scale [s].

        Returns
        -------
        lam0, alpha : float
            The period mean of lam and its largest distance from it, dimensionless.
        """
        lam0 = law.mean
        return lam0, max(abs(law.lam_max - lam0), abs(lam0 - law.lam_min))

    def euler_numbers(self, G: float, f_n: float) -> tuple[float, float]:
        """E_max = G max |dOmega/dt| and E_n, E_max at f_d = f_n (NaN for a single run).

        Parameters
        ----------
        G : float
            rho A L^3 / (E I) [s^2] (the beam's).
        f_n : float
            The beam's first frequency [Hz].

        Returns
        -------
        E_max, E_n : float
            Dimensionless.
        """
        e_max = G * self.drive.omega_dot_max
        return e_max, (e_max * f_n / self.drive.f_d if self.periodic else math.nan)

    def speed_source(self) -> str:
        """What sets the largest speed, in a refusal's words.

        Returns
        -------
        str
        """
        return f"the {self.name} drive's largest speed {self.drive.omega_max:.4g} rad/s"

    def acceleration_source(self) -> str:
        """What sets the largest |dOmega/dt|, in a refusal's words.

        Returns
        -------
        str
        """
        return (f"the {self.name} drive's largest |dOmega/dt| "
                f"{self.drive.omega_dot_max:.4g} rad/s^2")  # fmt: skip

    def largest_speed(self) -> str:
        """The largest speed as a figure's title gives it.

        Returns
        -------
        str
            "largest speed W rad/s".
        """
        return f"largest speed {self.drive.omega_max:.4g} rad/s"

    def title(self) -> str:
        """The drive as a figure's title names it.

        Returns
        -------
        str
            "KIND drive, largest speed W rad/s".
        """
        return f"{self.name} drive, {self.largest_speed()}"

    @classmethod
    def why_unused(cls, name: str) -> str:
        """Why the kind does not read a field, for the one-line refusal.

        Parameters
        ----------
        name : str
            The field.

        Returns
        -------
        str
        """
        if name in cls.unused_why:
            return cls.unused_why[name]
        if name in UNUSED_WHY:
            return UNUSED_WHY[name]
        owner = next((k.name for k in KINDS.values() if name in k.own), None)
        return f"a field of the {owner} drive" if owner else "no drive reads it"


@dataclass(frozen=True)
class ClosedFormLaw(DriveLaw):
    """lam(tau) = Omega(tau T) T of a kind that gives Omega and dOmega/dt in SI units.

    lam_dot = (dOmega/dt) T^2; the extremes, means and spectra come from DENSE samples.
    `scaled` scales the swing about `centre`.

    Parameters
    ----------
    kind : DriveKind
        The kind, bound to its drive.
    T : float
        Time scale [s].
    factor : float
        Scale of the swing about `centre` (1: the drive itself).
    centre : float
        The lam the swing is scaled about, dimensionless.
    """

    kind: DriveKind
    T: float
    factor: float = 1.0
    centre: float = 0.0

    @property
    def periodic(self) -> bool:  # type: ignore[override]
        """Whether the kind repeats."""
        return self.kind.periodic

    @property
    def omega(self) -> float:  # type: ignore[override]
        """2 pi over the period (or the run's duration) in units of T."""
        return 2.0 * math.pi * self.T / self.kind.period()

    def lam(self, tau: float) -> float:
        """The rotation rate at one instant.

        Parameters
        ----------
        tau : float
            Time in units of T.

        Returns
        -------
        float
            lam = Omega T, dimensionless.
        """
        raw = self.kind.omega(tau * self.T) * self.T
        return raw if self.factor == 1.0 else self.centre + self.factor * (raw - self.centre)

    def lam_dot(self, tau: float) -> float:
        """The rate of change of lam at one instant.

        Parameters
        ----------
        tau : float
            Time in units of T.

        Returns
        -------
        float
            d lam / d tau = (dOmega/dt) T^2, dimensionless.
        """
        return self.factor * self.kind.omega_dot(tau * self.T) * self.T * self.T

    def with_omega(self, omega: float) -> ClosedFormLaw:
        """The same kind at another repetition rate: drive.f_d = omega / (2 pi T).

        Parameters
        ----------
        omega : float
            2 pi f_d T, dimensionless.

        Returns
        -------
        ClosedFormLaw

        Raises
        ------
        ValueError
            For a kind that does not repeat.
        """
        if not self.kind.periodic:
            raise ValueError(f"a single {self.kind.name} run has no repetition rate")
        drive = replace(self.kind.drive, f_d=omega / (2.0 * math.pi * self.T))
        return replace(self, kind=type(self.kind)(drive))

    def scaled(self, factor: float) -> ClosedFormLaw:
        """The swing about the mean times `factor`.

        Parameters
        ----------
        factor : float
            Scale of the swing, dimensionless.

        Returns
        -------
        ClosedFormLaw
        """
        return replace(self, factor=self.factor * factor, centre=self.mean)


#: the registered kinds by name, in the order they were registered
KINDS: dict[str, type[DriveKind]] = {}


def register(cls: type[DriveKind]) -> type[DriveKind]:
    """Register a kind of drive (a class decorator): `Drive`, scene files and the CLI learn it.

    Its `own` fields join the drive section of the registry (rotbeam.config.parameters), so
    that scene files accept them and every command that takes a scene gets a flag for each.

    Parameters
    ----------
    cls : type
        A `DriveKind` subclass with a new `name`.

    Returns
    -------
    type
        `cls`, its `key` set (the first of `own` unless given).

    Raises
    ------
    ValueError
        For a name already registered or empty, a second kind without a key, a key whose
        default is not None (a key given selects the kind), or a field it reads that the drive
        section does not have.
    """
    if not cls.name or cls.name in KINDS:
        raise ValueError(f"drive kind {cls.name!r}: allowed: a new name (not {', '.join(KINDS)})")
    key = cls.key if cls.key is not None else next(iter(cls.own), None)
    if key is None and any(k.key is None for k in KINDS.values()):
        raise ValueError(f"drive kind {cls.name!r} has no key field; allowed: one own field")
    if key in cls.own and cls.own[key].default is not None:
        raise ValueError(f"drive kind {cls.name!r}: its key {key} must default to None")
    add_fields("drive", dict(cls.own))
    missing = [f for f in cls.fields if f not in SECTIONS["drive"]]
    if missing or (key is not None and key not in cls.fields):
        remove_fields("drive", tuple(cls.own))
        raise ValueError(f"drive kind {cls.name!r} reads {missing or [key]}: not drive fields")
    cls.key = key
    KINDS[cls.name] = cls
    return cls


def unregister(name: str) -> None:
    """Remove a registered kind and its own fields (what a test that registers one does after).

    Parameters
    ----------
    name : str
        The kind's name.

    Raises
    ------
    RotbeamInputError
        For a name that is not registered.
    """
    cls = kind_class(name)
    remove_fields("drive", tuple(cls.own))
    del KINDS[name]


def kind_class(name: str) -> type[DriveKind]:
    """The registered class of a kind of drive.

    Parameters
    ----------
    name : str
        The kind's name.

    Returns
    -------
    type
        Its `DriveKind` subclass.

    Raises
    ------
    RotbeamInputError
        One line naming the unknown kind and the registered ones.
    """
    if name not in KINDS:
        raise RotbeamInputError(f"drive kind {name!r} is unknown; allowed: {', '.join(KINDS)}")
    return KINDS[name]


def key_fields() -> tuple[str, ...]:
    """The fields that select a kind, in the order the kinds were registered.

    Returns
    -------
    tuple of str
        E.g. ("harmonics", "profile", "move").
    """
    return tuple(k.key for k in KINDS.values() if k.key is not None)


def own_fields() -> tuple[str, ...]:
    """The fields registered kinds add to `Drive` (kept in `Drive.extra`).

    Returns
    -------
    tuple of str
    """
    return tuple(name for k in KINDS.values() for name in k.own)


def refusable_fields() -> tuple[str, ...]:
    """The drive fields a kind refuses in one line where it does not read them and they differ
    from their defaults: the scalar fields but the keys (given together, they are refused as
    such) and `settle` (`Drive` says "only a move settles").

    Returns
    -------
    tuple of str
        In the registry's order: omega0, amplitude, f_d, move_start, then registered ones.
    """
    keys = key_fields()
    return tuple(name for name, entry in SECTIONS["drive"].items()
                 if entry.kind != "data" and name != "settle" and name not in keys)  # fmt: skip


def given(value: Any) -> bool:
    """Whether a drive field holds a value: not None and not empty.

    Parameters
    ----------
    value : object
        The field's value.

    Returns
    -------
    bool
    """
    return value is not None and not (hasattr(value, "__len__") and len(value) == 0)


def kind_of(values: Mapping[str, Any]) -> str:
    """The kind a drive's fields ask for: the last registered kind whose key holds a value.

    Parameters
    ----------
    values : mapping
        Drive field -> value (a scene's drive section, unchecked, or a drive's fields).

    Returns
    -------
    str
        The kind's name; the kind without a key (the sine) where no key holds a value.
    """
    for cls in reversed(KINDS.values()):
        if cls.key is not None and given(values.get(cls.key)):
            return cls.name
    return next(k.name for k in KINDS.values() if k.key is None)


def unused_drive_field(kind: str, name: str, value: object) -> RotbeamInputError:
    """The one-line error for a drive field that the drive's kind does not read.

    Parameters
    ----------
    kind : str
        The drive's kind, a registered name: "sine", "harmonics", "profile", "move", ...
    name : str
        The field given.
    value : object
        Its value, shown in the message.

    Returns
    -------
    RotbeamInputError
        "drive.NAME = VALUE: a KIND drive does not read it (why); allowed: ...".
    """
    cls = kind_class(kind)
    return RotbeamInputError(
        f"drive.{name} = {value!r}: a {kind} drive does not read it ({cls.why_unused(name)}); "
        f"allowed with a {kind}: {', '.join(cls.fields)}"
    )


def checked_extra(values: Any) -> tuple[tuple[str, Any], ...]:
    """A drive's `extra`: the values of registered kinds' own fields, checked and sorted.

    Parameters
    ----------
    values : mapping or tuple of (str, object)
        Field -> value.

    Returns
    -------
    tuple of (str, object)
        Sorted by name, each value checked against its registry entry.

    Raises
    ------
    RotbeamInputError
        For a name that no registered kind owns, or a value outside its range.
    """
    pairs = dict(values)
    known = own_fields()
    for name in sorted(pairs):
        if name not in known:
            raise RotbeamInputError(
                f"drive.{name}: no registered drive kind reads it; allowed: "
                f"{', '.join(known) or 'none (register a drive kind first)'}"
            )
    return tuple((name, check_value("drive", name, pairs[name])) for name in sorted(pairs))


class _FieldsOfKinds(Mapping):
    """Kind name -> the fields it reads, read from the registry as it stands."""

    def __getitem__(self, kind: str) -> tuple[str, ...]:
        return kind_class(kind).fields

    def __iter__(self) -> Iterator[str]:
        return iter(KINDS)

    def __len__(self) -> int:
        return len(KINDS)


#: the drive fields each kind of drive reads (the others are refused: `unused_drive_field`)
DRIVE_FIELDS: Mapping[str, tuple[str, ...]] = _FieldsOfKinds()


@register
class Sine(DriveKind):
    """Omega_0 + a sin(2 pi f_d t), the paper's; its numbers in closed form."""

    name = "sine"
    fields = ("omega0", "amplitude", "f_d")
    description = "Omega_0 + a sin(2 pi f_d t)"

    def law(self, T: float) -> DriveLaw:
        """A `HarmonicLaw` of one term, k = 1."""
        d = self.drive
        return HarmonicLaw(d.omega0 * T, ((1, d.amplitude * T, 0.0),), 2.0 * math.pi * d.f_d * T)

    def mean_speed(self) -> float:
        """Omega_0."""
        return self.drive.omega0

    def swing(self) -> float:
        """a."""
        return self.drive.amplitude

    def omega_max(self) -> float:
        """|Omega_0| + a."""
        return abs(self.drive.omega0) + self.drive.amplitude

    def omega_dot_max(self) -> float:
        """a 2 pi f_d."""
        return self.drive.amplitude * 2.0 * math.pi * self.drive.f_d

    def scales(self, law: DriveLaw, T: float) -> tuple[float, float]:
        """Omega_0 T and a T."""
        return self.drive.omega0 * T, self.drive.amplitude * T

    def euler_numbers(self, G: float, f_n: float) -> tuple[float, float]:
        """G a 2 pi f_d and G a 2 pi f_n."""
        d = self.drive
        return G * d.amplitude * 2.0 * math.pi * d.f_d, G * d.amplitude * 2.0 * math.pi * f_n

    def speed_source(self) -> str:
        """Its mean speed and amplitude, as given."""
        return f"drive.omega0 = {self.drive.omega0!r}, drive.amplitude = {self.drive.amplitude!r}"

    def acceleration_source(self) -> str:
        """Its amplitude and frequency, as given."""
        return f"drive.amplitude = {self.drive.amplitude!r}, drive.f_d = {self.drive.f_d!r}"

    def title(self) -> str:
        """Omega_0 and a."""
        return rf"$\Omega_0$ = {self.drive.omega0:g} rad/s, a = {self.drive.amplitude:g} rad/s"


@register
class Harmonics(DriveKind):
    """Omega_0 + sum_k a_k sin(2 pi k f_d t + phase_k)."""

    name = "harmonics"
    fields = ("omega0", "f_d", "harmonics")
    key = "harmonics"
    description = "Omega_0 + sum_k a_k sin(2 pi k f_d t + phase_k)"

    def law(self, T: float) -> DriveLaw:
        """A `HarmonicLaw` of its harmonics."""
        d = self.drive
        terms = tuple((h.k, h.amplitude * T, h.phase) for h in d.harmonics)
        return HarmonicLaw(d.omega0 * T, terms, 2.0 * math.pi * d.f_d * T)

    def mean_speed(self) -> float:
        """Omega_0 (the harmonics have zero mean)."""
        return self.drive.omega0


@register
class Profile(DriveKind):
    """One sampled period, repeated at f_d: the trigonometric interpolant of its samples."""

    name = "profile"
    fields = ("f_d", "profile")
    key = "profile"
    description = "one sampled period (phase, Omega) repeated at f_d"

    def law(self, T: float) -> DriveLaw:
        """The `HarmonicLaw` of the samples' trigonometric interpolant."""
        p = self.drive.profile
        mean, terms = harmonics_of_samples(p.x, p.omega, p.keep)
        w = 2.0 * math.pi * self.drive.f_d * T
        return HarmonicLaw(mean * T, tuple((k, a * T, ph) for k, a, ph in terms), w)

    def largest_speed(self) -> str:
        """The profile's own largest |Omega| sample, and its trigonometric interpolant's beside
        it where the two differ at four digits (the Gibbs overshoot at a trapezoid's corners:
        6.018 rad/s for a 6 rad/s trapezoid of 32 harmonics).

        Returns
        -------
        str
            "largest speed W rad/s", with "(W' after the K-harmonic interpolant)" where it
            differs.
        """
        p, law = self.drive.profile, self.drive.omega_max
        own = max(abs(w) for w in p.omega)
        text = f"largest speed {own:.4g} rad/s"
        if f"{own:.4g}" != f"{law:.4g}":
            text += f" ({law:.4g} after the {kept_harmonics(len(p.omega), p.keep)}-harmonic " \
                    f"interpolant)"  # fmt: skip
        return text


@register
class Move(DriveKind):
    """A single run through sampled (t, Omega), then `settle` seconds at its last speed."""

    name = "move"
    fields = ("move", "settle", "move_start")
    key = "move"
    periodic = False
    description = "a single move through sampled (t, Omega)"

    def law(self, T: float) -> DriveLaw:
        """A `MoveLaw` through the samples, its time from the first sample."""
        m = self.drive.move
        t0 = m.x[0]
        return MoveLaw(tuple((t - t0) / T for t in m.x), tuple(w * T for w in m.omega))

    def period(self) -> float:
        """The move's duration [s], first sample to last."""
        return self.drive.move.x[-1] - self.drive.move.x[0]

    def final_speed(self) -> float:
        """The last sample's speed."""
        return self.drive.move.omega[-1]
