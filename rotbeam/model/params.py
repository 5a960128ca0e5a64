"""Beam, drive, effects and the dimensionless problem of the rotating cantilever.

`Beam`, `Drive` and `Effects` describe a scene in SI units; `Dimensionless` is the problem the
model solves, with lengths in units of L, forces in units of EI/L^2 and time in units of
T = sqrt(rho A L^4 / (E I)).  Five numbers fix it whatever the beam's size: the hub ratio r_o,
the damping eta and the drive lam(tau) = Omega T (lam0, alpha, omega for the paper's sine).
The groups, how the paper's C, E and I map onto them and why two printed factors differ:
docs/model.md, "Dimensionless groups".
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any

import numpy as np

from ..config.checks import check_finite, check_nonnegative, check_positive
from ..config.errors import RotbeamInputError
from ..config.parameters import check_fields, default
from .drive import DriveLaw, HarmonicLaw
from .drives import (
    DriveKind,
    checked_extra,
    given,
    key_fields,
    kind_class,
    kind_of,
    own_fields,
    refusable_fields,
    unused_drive_field,
)

#: Root of 1 + cos(b) cosh(b) = 0 (first cantilever mode).  The paper rounds it to 1.875.
BETA1 = 1.8751040687119611


def tip_loaded_root(mu: float, j: float) -> float:
    """First root b of the cantilever's characteristic equation with a tip mass and inertia.

    The non-rotating beam with a payload at its free end vibrates first at b^2 / T, b the first
    root of::

        1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b)
          - j b^3 (sin b cosh b + cos b sinh b) + mu j b^4 (1 - cos b cosh b) = 0

    (b = 1.4200 at mu = 0.5).  A payload lowers the first frequency, so the root is the first
    sign change on a grid below the bare root beta_1, refined by bisection to round-off.  `Beam.f_n`
    and the checks of the discrete model's payload read it (docs/model.md, "A payload at the
    tip").

    Parameters
    ----------
    mu : float
        Tip mass m_tip / (rho A L), dimensionless, >= 0.
    j : float
        Tip rotary inertia J_tip / (rho A L^3), dimensionless, >= 0.

    Returns
    -------
    float
        b, dimensionless: the first mode's angular frequency is b^2 sqrt(EI / (rho A L^4)).

    Raises
    ------
    RotbeamInputError
        If the grid finds no sign change below beta_1 (a payload with mu, j >= 0 has one).
    """

    def f(b: float) -> float:
        c, ch, s, sh = math.cos(b), math.cosh(b), math.sin(b), math.sinh(b)
        return (1 + c * ch + mu * b * (c * sh - s * ch) - j * b**3 * (s * ch + c * sh)
                + mu * j * b**4 * (1 - c * ch))  # fmt: skip

    if mu == 0.0 and j == 0.0:
        return BETA1
    grid = np.linspace(1e-6, BETA1, 2001)  # f(0) = 2 > 0: the first sign change, then bisection
    values = np.array([f(x) for x in grid])
    first = int(np.argmax(values <= 0.0))
    if values[first] > 0.0:
        raise RotbeamInputError(f"no first mode below beta_1 for mu = {mu!r}, j = {j!r}")
    lo, hi = float(grid[first - 1]), float(grid[first])
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if f(mid) > 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def tip_loaded_mode(b: float, mu: float, j: float) -> tuple[float, float]:
    """The first mode of the cantilever with a payload, as two coefficients of its closed form.

    phi(s) = A (cosh bs - cos bs) + B (sinh bs - sin bs) is clamped at s = 0; (A, B) is the
    null vector of the two tip conditions phi_ss(1) = j b^4 phi_s(1) (the payload's rotary
    inertia balances the bending moment) and phi_sss(1) = -mu b^4 phi(1) (its mass balances the
    shear force), whose determinant is twice the characteristic equation of `tip_loaded_root`
    (docs/model.md, "A payload at the tip").

    Parameters
    ----------
    b : float
        The root, dimensionless (`tip_loaded_root(mu, j)`).
    mu : float
        Tip mass m_tip / (rho A L), dimensionless, >= 0.
    j : float
        Tip rotary inertia J_tip / (rho A L^3), dimensionless, >= 0.

    Returns
    -------
    tuple of float
        (A, B), of unit Euclidean norm (the sign and scale of a mode are arbitrary).
    """
    c, ch, s, sh = math.cos(b), math.cosh(b), math.sin(b), math.sinh(b)
    jb3, mub = j * b**3, mu * b
    conditions = np.array([[ch + c - jb3 * (sh + s), sh + s - jb3 * (ch - c)],
                           [sh - s + mub * (ch - c), ch + c + mub * (sh - s)]])  # fmt: skip
    null = np.linalg.svd(conditions)[2][-1]  # the right singular vector of the zero singular value
    return float(null[0]), float(null[1])


#: Gauss-Legendre nodes and weights on [-1, 1] for the mode's integral (exact to round-off)
_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(32)


def damped_mass_share(mu: float, j: float) -> float:
    """The share of the first mode's modal mass that the beam's damping acts on.

    s = int_0^1 phi^2 ds / (int_0^1 phi^2 ds + mu phi(1)^2 + j phi_s(1)^2), with phi the first
    mode of the cantilever with the payload (`tip_loaded_mode`): the viscous damping acts per
    unit length of the beam and not on the payload, so the first mode's damping ratio is
    eta s / (2 b^2) (`Beam.zeta`; the derivation is in docs/model.md, "A payload at the tip").

    Parameters
    ----------
    mu : float
        Tip mass m_tip / (rho A L), dimensionless, >= 0.
    j : float
        Tip rotary inertia J_tip / (rho A L^3), dimensionless, >= 0.

    Returns
    -------
    float
        s, dimensionless, in (0, 1]; 1 without a payload.

    Raises
    ------
    RotbeamInputError
        If `tip_loaded_root` finds no first mode.
    """
    if mu == 0.0 and j == 0.0:
        return 1.0
    b = tip_loaded_root(mu, j)
    A, B = tip_loaded_mode(b, mu, j)
    x = 0.5 * (_GAUSS_NODES + 1.0) * b  # b s at the nodes mapped to s in [0, 1]
    phi = A * (np.cosh(x) - np.cos(x)) + B * (np.sinh(x) - np.sin(x))
    beam = 0.5 * float(_GAUSS_WEIGHTS @ (phi * phi))
    tip = A * (math.cosh(b) - math.cos(b)) + B * (math.sinh(b) - math.sin(b))
    slope = b * (A * (math.sinh(b) + math.sin(b)) + B * (math.cosh(b) - math.cos(b)))
    return beam / (beam + mu * tip * tip + j * slope * slope)


@dataclass(frozen=True)
class Beam:
    """Rectangular elastic beam clamped on the disk, with an optional payload (SI units).

    Defaults are the paper's reference beam (Table 1) with R = 0.155 m (distance from the axis to
    the undeformed tip; not printed in the paper, inferred from the C and E ranges of Sec. 5) and
    gamma = 0.039 N s/m^2 (App. B).  The properties give the derived scales: T, f_n, G, the hub
    ratio and the damping groups.  Every field's range is the registry's
    (`rotbeam.config.parameters`).

    Raises
    ------
    RotbeamInputError
        For a field outside its range, h >= L or R <= L.
    """

    L: float = default("beam", "L")  #: length [m]
    h: float = default("beam", "h")  #: thickness (bending direction) [m]
    b: float = default("beam", "b")  #: width [m]
    E: float = default("beam", "E")  #: Young's modulus [Pa]
    rho: float = default("beam", "rho")  #: density [kg/m^3]
    R: float = default("beam", "R")  #: axis to undeformed tip [m]; the clamp sits at R_o = R - L
    gamma: float = default("beam", "gamma")  #: viscous damping per unit length [N s / m^2]
    tip_mass: float = default("beam", "tip_mass")  #: point mass at the free end [kg]
    tip_inertia: float = default("beam", "tip_inertia")  #: its rotary inertia [kg m^2]

    def __post_init__(self) -> None:
        check_fields(self, "beam")
        if self.h >= self.L:
            raise RotbeamInputError(
                f"beam.h must be < beam.L (a slender beam), got h={self.h!r} m, L={self.L!r} m"
            )
        if self.R <= self.L:
            raise RotbeamInputError(
                f"beam.R must be > beam.L (clamp off the axis, R_o = R - L > 0), "
                f"got R={self.R!r} m, L={self.L!r} m"
            )

    # --- section and scales -------------------------------------------------------------
    @property
    def A(self) -> float:
        """Cross-section area b h [m^2]."""
        return self.b * self.h

    @property
    def I(self) -> float:  # noqa: E743 - the paper's symbol
        """Second moment of area b h^3 / 12 [m^4]."""
        return self.b * self.h**3 / 12.0

    @property
    def EI(self) -> float:
        """Bending stiffness E I [N m^2]."""
        return self.E * self.I

    @property
    def rhoA(self) -> float:
        """Mass per unit length rho A [kg/m]."""
        return self.rho * self.A

    @property
    def T(self) -> float:
        """Time scale sqrt(rho A L^4 / (E I)) [s]."""
        return math.sqrt(self.rhoA * self.L**4 / self.EI)

    @property
    def f_s(self) -> float:
        """Bending frequency scale 1/(2 pi T) [Hz]."""
        return 1.0 / (2.0 * math.pi * self.T)

    @property
    def f_n(self) -> float:
        """First natural frequency b^2 f_s of the non-rotating cantilever [Hz]: b = beta_1
        without a payload, else the first root of the tip-loaded characteristic equation
        (`tip_loaded_root`)."""
        if self.tip_mass == 0.0 and self.tip_inertia == 0.0:
            return BETA1**2 * self.f_s
        return tip_loaded_root(*self.payload_ratios) ** 2 * self.f_s

    @property
    def payload_ratios(self) -> tuple[float, float]:
        """The payload in units of the beam: (m_t / (rho A L), J_t / (rho A L^3)),
        dimensionless."""
        return self.tip_mass / (self.rhoA * self.L), self.tip_inertia / (self.rhoA * self.L**3)

    @property
    def R_o(self) -> float:
        """Clamp distance from the axis [m]."""
        return self.R - self.L

    @property
    def G(self) -> float:
        """G = rho A R L^3 / (E I) [s^2]; C = G Omega^2, E = G dOmega/dt."""
        return self.rhoA * self.R * self.L**3 / self.EI

    @property
    def delta(self) -> float:
        """The paper's delta = L / R, dimensionless."""
        return self.L / self.R

    @property
    def hub_ratio(self) -> float:
        """R_o / L = 1/delta - 1."""
        return self.R_o / self.L

    @property
    def eta(self) -> float:
        """Dimensionless damping gamma L^2 / sqrt(rho A E I)."""
        return self.gamma * self.L**2 / math.sqrt(self.rhoA * self.EI)

    @property
    def zeta(self) -> float:
        """Damping ratio of the first mode at rest, dimensionless.

        eta / (2 beta_1^2) for the bare beam (Table systems, cantilever row); with a payload
        eta s / (2 b^2), b the tip-loaded root (`tip_loaded_root`) and s the share of the mode's
        mass that the beam's damping acts on (`damped_mass_share`): the payload has no damping
        of its own.
        """
        if self.tip_mass == 0.0 and self.tip_inertia == 0.0:
            return self.eta / (2.0 * BETA1**2)
        mu, j = self.payload_ratios
        return self.eta * damped_mass_share(mu, j) / (2.0 * tip_loaded_root(mu, j) ** 2)

    def derived(self) -> dict[str, float]:
        """Every derived group, for tables and JSON output.

        Returns
        -------
        dict
            ``A`` [m^2], ``I`` [m^4], ``T`` [s], ``f_s`` and ``f_n`` [Hz], ``G`` [s^2] and the
            dimensionless ``delta``, ``hub_ratio``, ``eta``, ``zeta``.
        """
        return {
            "A": self.A,
            "I": self.I,
            "T": self.T,
            "f_s": self.f_s,
            "f_n": self.f_n,
            "G": self.G,
            "delta": self.delta,
            "hub_ratio": self.hub_ratio,
            "eta": self.eta,
            "zeta": self.zeta,
        }


@dataclass(frozen=True)
class Harmonic:
    """One harmonic of a periodic drive: amplitude sin(2 pi k f_d t + phase).

    `Drive.harmonics` is a tuple of them, distinct in k; the sine drive is the single harmonic
    k = 1.

    Parameters
    ----------
    k : int
        Harmonic number, >= 1.
    amplitude : float
        Velocity amplitude a_k [rad/s], >= 0.
    phase : float
        Phase [rad].

    Raises
    ------
    RotbeamInputError
        For k not an integer >= 1, a negative amplitude or a phase that is not finite.
    """

    k: int
    amplitude: float
    phase: float = 0.0

    def __post_init__(self) -> None:
        if isinstance(self.k, bool) or not isinstance(self.k, int) or self.k < 1:
            raise RotbeamInputError(f"drive.harmonics.k must be an integer >= 1, got {self.k!r}")
        check_nonnegative("drive.harmonics.amplitude", self.amplitude)
        check_finite("drive.harmonics.phase", self.phase)


#: fewest samples of a sampled period or of a move
MIN_SAMPLES = 8


@dataclass(frozen=True)
class Samples:
    """Samples of the angular velocity: one period (x = phase in [0, 1)) or a move (x = t [s]).

    What a CSV file or a named profile gives; `Drive.law` turns a period into its trigonometric
    interpolant and a move into a cubic spline (docs/model.md, "Drives").  The samples are
    checked here so that a bad file fails with one line naming it.

    Parameters
    ----------
    x : tuple of float
        Phases in [0, 1) of one period, or instants [s] of a move; increasing.
    omega : tuple of float
        Omega at those phases or instants [rad/s].
    kind : str
        "profile" (one period, closed on itself) or "move".
    source : str
        Where the samples come from (a file name), for messages.
    keep : int or None
        A profile's highest harmonic kept (default `PROFILE_HARMONICS`): its low-pass.

    Raises
    ------
    RotbeamInputError
        For fewer than MIN_SAMPLES samples, values that are not finite, instants that do not
        increase, phases outside [0, 1), a period that does not close on itself (its step from
        the last sample back to the first more than twice its largest step inside) or a bad
        `keep`.
    """

    x: tuple[float, ...]
    omega: tuple[float, ...]
    kind: str = "profile"
    source: str = ""
    keep: int | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "x", tuple(float(v) for v in self.x))
        object.__setattr__(self, "omega", tuple(float(v) for v in self.omega))
        where = f"drive.{self.kind}{f' ({self.source})' if self.source else ''}"
        x, w = np.asarray(self.x, dtype=float), np.asarray(self.omega, dtype=float)
        if x.shape != w.shape or x.ndim != 1:
            raise RotbeamInputError(f"{where}: {x.size} instants but {w.size} speeds")
        if x.size < MIN_SAMPLES:
            raise RotbeamInputError(f"{where}: {x.size} samples; allowed: at least {MIN_SAMPLES}")
        bad = np.flatnonzero(~(np.isfinite(x) & np.isfinite(w)))
        if bad.size:
            raise RotbeamInputError(
                f"{where}: sample {bad[0]} is not a finite number (x = {float(x[bad[0]])!r}, "
                f"omega = {float(w[bad[0]])!r})"
            )
        back = np.flatnonzero(np.diff(x) <= 0)
        if back.size:
            name = "phase" if self.kind == "profile" else "t"
            raise RotbeamInputError(
                f"{where}: {name} does not increase at sample {back[0] + 1} "
                f"({float(x[back[0]])!r} then {float(x[back[0] + 1])!r}); allowed: strictly "
                f"increasing"
            )
        if self.kind == "profile":
            self._check_period(where, x, w)
        if self.keep is not None and (isinstance(self.keep, bool) or not isinstance(
                self.keep, int) or self.keep < 1):  # fmt: skip
            raise RotbeamInputError(f"{where}: harmonics = {self.keep!r}; allowed: an integer >= 1")

    @staticmethod
    def _check_period(where: str, x: np.ndarray, w: np.ndarray) -> None:
        """Phases in [0, 1) and a profile that closes on itself: the step from the last sample
        back to the first no larger than twice the largest step inside the period."""
        if not (x[0] >= 0.0 and x[-1] < 1.0):
            raise RotbeamInputError(
                f"{where}: phase from {x[0]!r} to {x[-1]!r}; allowed: phases in [0, 1) (one "
                f"period, the sample at phase 1 is the one at 0)"
            )
        inside = float(np.max(np.abs(np.diff(w))))
        seam = abs(float(w[0] - w[-1]))
        if seam > 2.0 * inside + 1e-9 * max(1.0, float(np.max(np.abs(w)))):
            raise RotbeamInputError(
                f"{where}: the profile does not close on itself: it jumps by {seam:.4g} rad/s "
                f"from its last sample back to its first, more than twice its largest step "
                f"inside the period ({inside:.4g} rad/s)"
            )


@dataclass(frozen=True)
class Drive:
    """How the disk turns: Omega(t) [rad/s].

    A periodic drive repeats at f_d: Omega_0 + a sin(2 pi f_d t) (the paper's), a sum of
    `harmonics` Omega_0 + sum_k a_k sin(2 pi k f_d t + phase_k), or a sampled `profile` of one
    period.  A `move` is a single run through sampled (t, Omega), followed by `settle` seconds
    at its last speed.  `law` gives the drive in the model's units (docs/model.md, "Drives").

    Raises
    ------
    RotbeamInputError
        For a field outside its range, repeated harmonics, more than one of harmonics, profile
        and move, samples of the wrong kind or `settle` without a move.
    """

    omega0: float = default("drive", "omega0")  #: mean angular velocity Omega_0 [rad/s]
    amplitude: float = default("drive", "amplitude")  #: velocity amplitude a [rad/s]
    f_d: float = default("drive", "f_d")  #: drive (repetition) frequency [Hz]
    #: harmonics (k, a_k [rad/s], phase_k [rad]) replacing `amplitude`; () for the sine
    harmonics: tuple[Harmonic, ...] = default("drive", "harmonics")
    profile: Samples | None = default("drive", "profile")  #: one sampled period (phase, Omega)
    move: Samples | None = default("drive", "move")  #: a single move (t [s], Omega)
    settle: float | None = default("drive", "settle")  #: after a move [s]; None: until calm
    #: how a move starts: "rest" (static at its first speed) or "quasistatic" (moving)
    move_start: str = default("drive", "move_start")
    #: the fields of registered drive kinds beside these, name -> value (read as attributes)
    extra: tuple[tuple[str, Any], ...] = default("drive", "extra")

    def __post_init__(self) -> None:
        object.__setattr__(self, "extra", checked_extra(self.extra))
        check_fields(self, "drive")
        object.__setattr__(self, "harmonics", tuple(self.harmonics))
        ks = [h.k for h in self.harmonics]
        if len(set(ks)) != len(ks):
            raise RotbeamInputError(
                f"drive.harmonics: k = {sorted(ks)} repeats a harmonic; allowed: distinct k"
            )
        keys = key_fields()
        together = [n for n in keys if given(getattr(self, n))]
        if len(together) > 1:
            raise RotbeamInputError(
                f"drive: {' and '.join(together)} given together; allowed: one of {', '.join(keys)}"
            )
        for name, kind in (("profile", "profile"), ("move", "move")):
            value = getattr(self, name)
            if value is not None and value.kind != kind:
                raise RotbeamInputError(f"drive.{name}: samples of a {value.kind}, not a {kind}")
        reads = self.as_kind.fields
        if self.settle is not None and "settle" not in reads:
            raise RotbeamInputError(f"drive.settle = {self.settle!r}: only a move settles")
        for name in refusable_fields():
            value = getattr(self, name)
            if name not in reads and value != default("drive", name):
                raise unused_drive_field(self.kind, name, value)

    def __getattr__(self, name: str) -> Any:
        """A registered drive kind's own field: its value in `extra`, else its default."""
        if name.startswith("__") or name == "extra":
            raise AttributeError(name)
        for key, value in self.extra:
            if key == name:
                return value
        if name in own_fields():
            return default("drive", name)
        raise AttributeError(f"'Drive' object has no attribute {name!r}")

    @property
    def kind(self) -> str:
        """The registered kind whose key field is given: "sine", "harmonics", "profile",
        "move" or a kind registered beside them (rotbeam.model.drives)."""
        return kind_of({key: getattr(self, key) for key in key_fields()})

    @property
    def as_kind(self) -> DriveKind:
        """This drive as its registered kind: its law, speeds and the words of its refusals."""
        return kind_class(self.kind)(self)

    @property
    def periodic(self) -> bool:
        """Whether Omega repeats at f_d (every built-in kind but a move)."""
        return self.as_kind.periodic

    @property
    def terms(self) -> tuple[Harmonic, ...]:
        """The harmonics of a harmonic drive (the sine: one, k = 1, `amplitude`)."""
        return self.harmonics or (Harmonic(1, self.amplitude, 0.0),)

    @property
    def mean_speed(self) -> float:
        """The mean angular velocity [rad/s]: Omega_0 for the sine and harmonics, the period
        mean of a profile, the time mean over a move (what tables report as omega0)."""
        return self.as_kind.mean_speed()

    @property
    def swing(self) -> float:
        """The largest |Omega - mean_speed| [rad/s]: a for the sine (what tables report as
        amplitude)."""
        return self.as_kind.swing()

    def law(self, T: float) -> DriveLaw:
        """The drive in the model's units: lam(tau) = Omega(tau T) T, by its kind.

        A sine or harmonics become a `HarmonicLaw`, a sampled period the `HarmonicLaw` of its
        trigonometric interpolant, a move a `MoveLaw` whose time starts at its first sample, a
        registered kind what its `DriveKind.law` gives.

        Parameters
        ----------
        T : float
            Time scale [s]; 1.0 gives the drive in SI units (lam = Omega in rad/s, tau = t in s).

        Returns
        -------
        DriveLaw
            lam(tau) = Omega T and lam_dot(tau), time in units of T.
        """
        return self.as_kind.law(T)

    def omega(self, t: float) -> float:
        """The angular velocity at one instant.

        Parameters
        ----------
        t : float
            Time [s] (from the first sample, for a move).

        Returns
        -------
        float
            Omega(t) [rad/s].
        """
        return self.law(1.0).lam(t)

    def angle(self, t: float) -> float:
        """The disk's angle at one instant, phi(t) = int_0^t Omega dt.

        Parameters
        ----------
        t : float
            Time [s] (from the first sample, for a move).

        Returns
        -------
        float
            phi [rad]: what turns the rotating frame into the lab frame.
        """
        return self.law(1.0).angle(t)

    def omega_dot(self, t: float) -> float:
        """The angular acceleration at one instant.

        Parameters
        ----------
        t : float
            Time [s] (from the first sample, for a move).

        Returns
        -------
        float
            dOmega/dt (t) [rad/s^2].
        """
        return self.law(1.0).lam_dot(t)

    @property
    def omega_max(self) -> float:
        """The largest |Omega| [rad/s]: |Omega_0| + a for the sine."""
        return self.as_kind.omega_max()

    @property
    def omega_dot_max(self) -> float:
        """The largest |dOmega/dt| [rad/s^2]: a 2 pi f_d for the sine."""
        return self.as_kind.omega_dot_max()


@dataclass(frozen=True)
class Effects:
    """Which loads enter the model.  Terms that are off are not computed.

    Defaults follow the paper: Coriolis off (Sec. 2), the inextensible beam (`extension` off),
    everything else on.  `softening` is the in-plane centrifugal softening, the delta C y term of
    Eq. (EOM2); it needs `centrifugal`.  `extension` stretches the centerline by the centrifugal
    tension, strain N/(EA) (not in the paper; docs/model.md, "Axial stretching"); it needs
    `centrifugal` (without it there is no tension to stretch the beam) and the slenderness h/L
    of `Dimensionless`.

    Raises
    ------
    RotbeamInputError
        For a field that is not a bool.
    """

    centrifugal: bool = default("effects", "centrifugal")
    softening: bool = default("effects", "softening")
    euler: bool = default("effects", "euler")
    coriolis: bool = default("effects", "coriolis")
    damping: bool = default("effects", "damping")
    extension: bool = default("effects", "extension")

    def __post_init__(self) -> None:
        check_fields(self, "effects")

    @classmethod
    def from_list(cls, names: str | list[str]) -> Effects:
        """The effects switched on by name, the others off (the command line's `--effects`).

        Parameters
        ----------
        names : str or list of str
            Effect names, as a list or comma-separated, e.g. "centrifugal,euler,damping";
            "all" and "none" are allowed.

        Returns
        -------
        Effects

        Raises
        ------
        RotbeamInputError
            For an empty list or an unknown name (the message lists the allowed ones).
        """
        given = names
        if isinstance(names, str):
            names = [n.strip() for n in names.split(",") if n.strip()]
        allowed = [f.name for f in fields(cls)]
        if not names:
            raise RotbeamInputError(
                f"effects {given!r} names no effect; allowed: {', '.join(allowed)} "
                f"(or 'all', 'none')"
            )
        if names == ["all"]:
            return cls(**{n: True for n in allowed})
        if names == ["none"]:
            return cls(**{n: False for n in allowed})
        bad = [n for n in names if n not in allowed]
        if bad:
            raise RotbeamInputError(
                f"effects {given!r}: unknown effect(s) {', '.join(map(str, bad))}; allowed: "
                f"{', '.join(allowed)} (or 'all', 'none')"
            )
        return cls(**{n: (n in names) for n in allowed})

    def active(self) -> list[str]:
        """The names of the effects that are on.

        Returns
        -------
        list of str
            In the order of the fields.
        """
        return [k for k, v in asdict(self).items() if v]


@dataclass(frozen=True)
class Dimensionless:
    """The dimensionless problem: everything the discrete model needs, nothing else.

    Lengths are in units of L, forces in units of EI/L^2 and time in units of
    T = sqrt(rho A L^4 / (E I)), so two scenes with equal `Dimensionless` are the same
    numerical problem, whatever their size.  The drive is `law` (lam(tau) = Omega T); without
    one, the paper's sine lam0 + alpha sin(omega tau).  For any drive lam0 is the mean rotation,
    alpha the largest swing about it and omega 2 pi over the period (docs/model.md,
    "Dimensionless groups").

    `slenderness` h/L is read by the `extension` effect only: the axial compliance in units of
    the bending one is EI / (EA L^2) = (h/L)^2 / 12 (`kappa`); `from_physical` fills it only
    with `extension` on, so that scenes without it compare equal whatever their thickness.
    `tip_mass` and `tip_inertia` are a payload at the free end, m / (rho A L) and
    J / (rho A L^3) (docs/model.md, "A payload at the tip").

    Raises
    ------
    RotbeamInputError
        For a negative hub ratio, eta, alpha or payload, omega <= 0, a lam0 that is not finite,
        or `extension` without a slenderness.
    """

    hub_ratio: float  #: r_o = R_o / L
    eta: float  #: damping
    lam0: float  #: Omega_0 T (the period mean of lam)
    alpha: float  #: a T (the largest |lam - lam0|)
    omega: float  #: 2 pi f_d T (2 pi / period)
    effects: Effects = field(default_factory=Effects)
    slenderness: float | None = None  #: h / L (read by `extension` only)
    law: DriveLaw | None = None  #: the drive; None: lam0 + alpha sin(omega tau)
    tip_mass: float = 0.0  #: m_tip / (rho A L)
    tip_inertia: float = 0.0  #: J_tip / (rho A L^3)

    def __post_init__(self) -> None:
        check_nonnegative("hub_ratio", self.hub_ratio)
        check_nonnegative("eta", self.eta)
        check_finite("lam0", self.lam0)
        check_nonnegative("alpha", self.alpha)
        check_positive("omega", self.omega)
        check_nonnegative("tip_mass", self.tip_mass)
        check_nonnegative("tip_inertia", self.tip_inertia)
        if self.slenderness is not None:
            check_positive("slenderness", self.slenderness)
        if self.effects.extension and self.slenderness is None:
            raise RotbeamInputError(
                "effects.extension needs the slenderness h/L (Dimensionless.slenderness)"
            )
        law = self.law
        if law is None:
            law = HarmonicLaw(self.lam0, ((1, self.alpha, 0.0),), self.omega)
        elif law.periodic and law.omega != self.omega:  # replace(dl, omega=...) moves the law
            law = law.with_omega(self.omega)
        object.__setattr__(self, "law", law)

    @property
    def kappa(self) -> float:
        """EI / (EA L^2) = (h/L)^2 / 12, the strain per unit dimensionless tension (0 without
        `extension`: the inextensible beam)."""
        if not self.effects.extension:
            return 0.0
        return self.slenderness**2 / 12.0

    @property
    def lam_stretch(self) -> float:
        """The rotation whose steady centrifugal tension stretches the beam: the root of the
        period mean of lam^2 (lam0^2 + alpha^2 / 2 for the sine; docs/model.md, extension)."""
        return math.sqrt(self.law.mean_square)

    @classmethod
    def from_physical(
        cls, beam: Beam, drive: Drive, effects: Effects | None = None
    ) -> Dimensionless:
        """The dimensionless problem of a beam, a drive and the effects.

        Parameters
        ----------
        beam : Beam
            The beam (and its payload).
        drive : Drive
            How the disk turns.
        effects : Effects or None
            The loads (default: the paper's).

        Returns
        -------
        Dimensionless
        """
        T = beam.T
        effects = effects if effects is not None else Effects()
        law = drive.law(T)
        lam0, alpha = drive.as_kind.scales(law, T)
        omega = law.omega
        return cls(
            hub_ratio=beam.hub_ratio,
            eta=beam.eta,
            lam0=lam0,
            alpha=alpha,
            omega=omega,
            effects=effects,
            slenderness=beam.h / beam.L if effects.extension else None,
            law=law,
            tip_mass=beam.tip_mass / (beam.rhoA * beam.L),
            tip_inertia=beam.tip_inertia / (beam.rhoA * beam.L**3),
        )

    @property
    def period(self) -> float:
        """Drive period in units of T (a move: its duration)."""
        return 2.0 * math.pi / self.omega

    def lam(self, tau: float) -> float:
        """The rotation rate of the drive at one instant.

        Parameters
        ----------
        tau : float
            Time in units of T.

        Returns
        -------
        float
            lam = Omega T, dimensionless.
        """
        return self.law.lam(tau)

    def lam_dot(self, tau: float) -> float:
        """The rate of change of lam at one instant (what the Euler load scales with).

        Parameters
        ----------
        tau : float
            Time in units of T.

        Returns
        -------
        float
            d lam / d tau = (dOmega/dt) T^2, dimensionless.
        """
        return self.law.lam_dot(tau)

    def scaled_drive(self, factor: float) -> Dimensionless:
        """The scene with the drive's swing about its mean times `factor`.

        Continuation in the drive's amplitude walks from 0 (the straight beam) to 1 (the
        scene) along these.

        Parameters
        ----------
        factor : float
            Scale of the swing, dimensionless (1: the scene itself).

        Returns
        -------
        Dimensionless
            The same problem with the law scaled and alpha times `factor`.
        """
        return replace(self, law=self.law.scaled(factor), alpha=self.alpha * factor)


def drive_groups(beam: Beam, drive: Drive) -> dict[str, float]:
    """The largest centrifugal and Euler numbers (Eqs. max C num, max E num), E_n and f_d / f_n.

    For the sine C_max = G (|Omega_0| + a)^2 and E_max = G a 2 pi f_d; for any other drive
    C_max = G max Omega^2 and E_max = G max |dOmega/dt| over its period (or its move), and E_n
    is E_max at f_d = f_n (NaN for a move, which has no f_d).

    Parameters
    ----------
    beam : Beam
        The beam (G, f_n, T).
    drive : Drive
        How the disk turns.

    Returns
    -------
    dict
        C_max, E_max, E_n, I_max (= max |Omega| T) and fd_over_fn.
    """
    G = beam.G
    w = drive.omega_max
    e_max, e_n = drive.as_kind.euler_numbers(G, beam.f_n)
    return {
        "C_max": G * w**2,
        "E_max": e_max,
        "E_n": e_n,
        "I_max": w * beam.T,
        "fd_over_fn": drive.f_d / beam.f_n if drive.periodic else math.nan,
    }


#: The model's range: C_max = G (|Omega_0| + a)^2 and E_max = G a 2 pi f_d up to 1e12, f_d up
#: to 1e6 f_n.  Far beyond the paper's scenes (C_max <= 787); beyond it the discrete model's
#: loads swamp its bending terms and, further out, overflow (the solvers then fail or stall).
C_MAX_LIMIT = 1e12
E_MAX_LIMIT = 1e12
FD_OVER_FN_LIMIT = 1e6
#: The largest axial strain the centrifugal tension may put at the clamp: beyond it the beam
#: would stretch past twice its length, which no beam theory (and no material) follows.  The
#: paper's scenes reach 14 % (C_max = 787); a unit slip (E in GPa written as Pa) reaches 10^3.
CLAMP_STRAIN_LIMIT = 1.0


def clamp_strain(beam: Beam, omega: float) -> float:
    """The axial strain of the centrifugal tension at the clamp of the straight beam, to first
    order: eps(0) = Omega^2 [rho (R_o L + L^2 / 2) + m_tip R / A] / E.

    N(0) = rho A Omega^2 int_0^L (R_o + x) dx + m_tip Omega^2 R, over EA (docs/model.md, "Axial
    stretching"); what the inextensible model neglects, and what tells a physically impossible
    scene from a stiff one.

    Parameters
    ----------
    beam : Beam
        The beam and its payload.
    omega : float
        Angular velocity [rad/s].

    Returns
    -------
    float
        eps(0), dimensionless.
    """
    pull = beam.rho * (beam.R_o * beam.L + 0.5 * beam.L**2) + beam.tip_mass * beam.R / beam.A
    return omega * omega * pull / beam.E


def unit_hint(beam: Beam) -> str:
    """A likely unit slip in a beam's fields, for the message that refuses its scene.

    Parameters
    ----------
    beam : Beam
        The beam.

    Returns
    -------
    str
        E.g. "; beam.E = 200 Pa is softer than any solid beam (the paper's elastomer: 1.22e6
        Pa): 200 GPa is 2e+11 Pa", or "" where every field is in a usual range.
    """
    hints = []
    if beam.E < 1e4:
        hints.append(
            f"beam.E = {beam.E:g} Pa is softer than any solid beam (the paper's elastomer: "
            f"1.22e6 Pa): {beam.E:g} GPa is {beam.E * 1e9:g} Pa, {beam.E:g} MPa {beam.E * 1e6:g} Pa"
        )
    if beam.rho < 50.0:
        hints.append(
            f"beam.rho = {beam.rho:g} kg/m^3 is lighter than any solid: {beam.rho:g} g/cm^3 is "
            f"{beam.rho * 1e3:g} kg/m^3"
        )
    for name in ("L", "h", "b", "R"):
        value = getattr(beam, name)
        if value > 10.0:
            hints.append(f"beam.{name} = {value:g} m: {value:g} mm is {value * 1e-3:g} m")
    return "; check the units: " + "; ".join(hints) if hints else ""


def check_model_range(beam: Beam, drive: Drive) -> None:
    """Refuse a scene outside the model's range, with one line naming the drive (and G, f_n).

    The range is C_max <= C_MAX_LIMIT, E_max <= E_MAX_LIMIT, a clamp strain of the centrifugal
    tension up to CLAMP_STRAIN_LIMIT (`clamp_strain`) and f_d <= FD_OVER_FN_LIMIT f_n (far
    beyond the paper's scenes), with C_max and E_max from the drive's largest Omega and
    dOmega/dt; a message names a likely unit slip (`unit_hint`).

    Parameters
    ----------
    beam : Beam
        The beam (G, f_n).
    drive : Drive
        The drive.

    Raises
    ------
    RotbeamInputError
        If C_max, E_max, the clamp strain or f_d / f_n exceeds its limit.
    """
    G = beam.G
    w = drive.omega_max
    c_max = G * w * w  # x * x: inf rather than OverflowError
    e_max = G * drive.omega_dot_max
    ratio = drive.f_d / beam.f_n if drive.periodic else 0.0
    what = drive.as_kind.speed_source()
    hint = unit_hint(beam)
    if not c_max <= C_MAX_LIMIT:
        raise RotbeamInputError(
            f"C_max = G max Omega^2 = {c_max:.3g} from {what}, G = {G:.3g} s^2 (beam); "
            f"allowed: C_max <= {C_MAX_LIMIT:g}{hint}"
        )
    strain = clamp_strain(beam, w)
    if not strain <= CLAMP_STRAIN_LIMIT:
        raise RotbeamInputError(
            f"the centrifugal tension would stretch the beam by {100 * strain:.3g} % at its "
            f"clamp (C_max = {c_max:.3g} from {what}): no beam holds that; allowed: a clamp "
            f"strain up to {100 * CLAMP_STRAIN_LIMIT:g} %{hint}"
        )
    if not e_max <= E_MAX_LIMIT:
        accel = drive.as_kind.acceleration_source()
        raise RotbeamInputError(
            f"E_max = G max |dOmega/dt| = {e_max:.3g} from {accel}, G = {G:.3g} s^2 (beam); "
            f"allowed: E_max <= {E_MAX_LIMIT:g}{hint}"
        )
    if not ratio <= FD_OVER_FN_LIMIT:
        raise RotbeamInputError(
            f"f_d / f_n = {ratio:.3g} from drive.f_d = {drive.f_d!r} Hz, f_n = {beam.f_n:.4g} Hz "
            f"(beam); allowed: f_d <= {FD_OVER_FN_LIMIT:g} f_n"
        )


def omega0_for_cmax(beam: Beam, c_max: float, amplitude: float = 1.0) -> float:
    """The mean speed Omega_0 at which the sine drive reaches a given C_max.

    The inverse of Eq. (max C num), C_max = G (Omega_0 + a)^2: the paper's figures are drawn
    against C_max, the model runs at Omega_0.

    Parameters
    ----------
    beam : Beam
        The beam (G).
    c_max : float
        The largest centrifugal number, dimensionless, > 0.
    amplitude : float
        The drive's velocity amplitude a [rad/s].

    Returns
    -------
    float
        Omega_0 = sqrt(C_max / G) - a [rad/s].

    Raises
    ------
    RotbeamInputError
        If `c_max` is not a number > 0.
    """
    c_max = check_positive("C_max", c_max)
    return math.sqrt(c_max / beam.G) - amplitude


def fd_for_emax(beam: Beam, e_max: float, amplitude: float = 1.0) -> float:
    """The drive frequency f_d at which the sine drive reaches a given E_max.

    The inverse of Eq. (max E num), E_max = G a 2 pi f_d.

    Parameters
    ----------
    beam : Beam
        The beam (G).
    e_max : float
        The largest Euler number, dimensionless, > 0.
    amplitude : float
        The drive's velocity amplitude a [rad/s], > 0.

    Returns
    -------
    float
        f_d = E_max / (G a 2 pi) [Hz].

    Raises
    ------
    RotbeamInputError
        If `e_max` or `amplitude` is not a number > 0.
    """
    e_max = check_positive("E_max", e_max)
    amplitude = check_positive("drive.amplitude", amplitude)
    return e_max / (beam.G * amplitude * 2.0 * math.pi)
