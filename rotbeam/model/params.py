"""Beam, drive and the dimensionless groups of the rotating cantilever.

Nondimensionalisation (used everywhere in the package; see README "Dimensionless groups"):
lengths by the beam length L, forces by EI/L^2, time by T = sqrt(rho A L^4 / (E I)).
With tau = t / T the dimensionless equations of motion have unit inertia, and the whole problem is
fixed by five numbers:

    hub_ratio r_o = R_o / L = 1/delta - 1       (clamp distance from the axis over L)
    eta  = gamma L^2 / sqrt(rho A E I)          (viscous damping, Eq. eta of the paper)
    lam(tau) = Omega(t) T = lam0 + alpha sin(omega tau)
    lam0 = Omega_0 T,  alpha = a T,  omega = 2 pi f_d T

The paper's groups map onto these as follows (G = rho A R L^3/(E I), in s^2, Sec. 6):

    C(tau) = G Omega^2 = lam^2 / delta                       (Eq. centrifugal_number)
    E(tau) = G dOmega/dt = (dlam/dtau) / delta               (Eq. euler_number without f_s, as
                                                              Eq. max E num: E_max = G a 2 pi f_d)
    I(tau) = Omega T = lam                                   (Eq. inertial_number without 1/2pi)

The printed Eqs. (euler_number) and (inertial_number) carry a factor f_s that would make them
dimensional (Euler) or 2 pi smaller (inertial); with time scaled by T the factors above are the ones
that make the printed Eqs. (EOM1-2) hold with unit inertia.  The centrifugal load C (1 - delta +
delta x) equals lam^2 (r_o + x), which is the form the code uses (no 1/delta for tiny beams).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, fields

from ..config.checks import check_finite, check_nonnegative, check_positive
from ..config.errors import RotbeamInputError
from ..config.parameters import check_fields, default

#: Root of 1 + cos(b) cosh(b) = 0 (first cantilever mode).  The paper rounds it to 1.875.
BETA1 = 1.8751040687119611


@dataclass(frozen=True)
class Beam:
    """Rectangular elastic beam clamped on the disk (SI units).

    Defaults are the paper's reference beam (Table 1) with R = 0.155 m (distance from the axis to
    the undeformed tip; not printed in the paper, inferred from the C and E ranges of Sec. 5) and
    gamma = 0.039 N s/m^2 (App. B).
    """

    L: float = default("beam", "L")  #: length [m]
    h: float = default("beam", "h")  #: thickness (bending direction) [m]
    b: float = default("beam", "b")  #: width [m]
    E: float = default("beam", "E")  #: Young's modulus [Pa]
    rho: float = default("beam", "rho")  #: density [kg/m^3]
    R: float = default("beam", "R")  #: axis to undeformed tip [m]; the clamp sits at R_o = R - L
    gamma: float = default("beam", "gamma")  #: viscous damping per unit length [N s / m^2]

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
        return self.E * self.I

    @property
    def rhoA(self) -> float:
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
        """First natural frequency beta_1^2 f_s of the non-rotating cantilever [Hz]."""
        return BETA1**2 * self.f_s

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
        """Damping ratio of the first mode, eta / (2 beta_1^2) (Table systems, cantilever row)."""
        return self.eta / (2.0 * BETA1**2)

    def derived(self) -> dict[str, float]:
        """Every derived group, for tables and JSON output."""
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
class Drive:
    """Harmonic angular velocity Omega(t) = Omega_0 + a sin(2 pi f_d t) [rad/s]."""

    omega0: float = default("drive", "omega0")  #: mean angular velocity Omega_0 [rad/s]
    amplitude: float = default("drive", "amplitude")  #: velocity amplitude a [rad/s]
    f_d: float = default("drive", "f_d")  #: drive frequency [Hz]

    def __post_init__(self) -> None:
        check_fields(self, "drive")

    def omega(self, t: float) -> float:
        return self.omega0 + self.amplitude * math.sin(2.0 * math.pi * self.f_d * t)

    def omega_dot(self, t: float) -> float:
        return 2.0 * math.pi * self.f_d * self.amplitude * math.cos(2.0 * math.pi * self.f_d * t)


@dataclass(frozen=True)
class Effects:
    """Which loads enter the model.  Terms that are off are not computed.

    Defaults follow the paper: Coriolis off (Sec. 2), the inextensible beam (`extension` off),
    everything else on.  `softening` is the in-plane centrifugal softening, the delta C y term of
    Eq. (EOM2); it needs `centrifugal`.  `extension` stretches the centerline by the centrifugal
    tension, strain N/(EA) (not in the paper; see `rotbeam.model.elastica` and docs/model.md); it
    needs `centrifugal` (without it there is no tension to stretch the beam) and the slenderness
    h/L of `Dimensionless`.
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
        """Effects switched on by name, e.g. "centrifugal,euler,damping" ("all", "none" allowed)."""
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
        return [k for k, v in asdict(self).items() if v]


@dataclass(frozen=True)
class Dimensionless:
    """The dimensionless problem: everything the discrete model needs, nothing else.

    Two scenes with equal `Dimensionless` are the same numerical problem, whatever their size.

    `slenderness` h/L is a sixth group that only the `extension` effect reads: the axial
    compliance in units of the bending one is EI / (EA L^2) = (h/L)^2 / 12 (`kappa`).
    `from_physical` fills it only when `extension` is on (None otherwise), so scenes without
    extension compare equal whatever their thickness, as before.
    """

    hub_ratio: float  #: r_o = R_o / L
    eta: float  #: damping
    lam0: float  #: Omega_0 T
    alpha: float  #: a T
    omega: float  #: 2 pi f_d T
    effects: Effects = field(default_factory=Effects)
    slenderness: float | None = None  #: h / L (read by `extension` only)

    def __post_init__(self) -> None:
        check_nonnegative("hub_ratio", self.hub_ratio)
        check_nonnegative("eta", self.eta)
        check_finite("lam0", self.lam0)
        check_nonnegative("alpha", self.alpha)
        check_positive("omega", self.omega)
        if self.slenderness is not None:
            check_positive("slenderness", self.slenderness)
        if self.effects.extension and self.slenderness is None:
            raise RotbeamInputError(
                "effects.extension needs the slenderness h/L (Dimensionless.slenderness)"
            )

    @property
    def kappa(self) -> float:
        """EI / (EA L^2) = (h/L)^2 / 12, the strain per unit dimensionless tension (0 without
        `extension`: the inextensible beam)."""
        if not self.effects.extension:
            return 0.0
        return self.slenderness**2 / 12.0

    @property
    def lam_stretch(self) -> float:
        """The rotation whose steady centrifugal tension stretches the beam: the period mean of
        lam^2, lam0^2 + alpha^2 / 2, as a rate (see `rotbeam.model.elastica`, extension)."""
        return math.sqrt(self.lam0 * self.lam0 + 0.5 * self.alpha * self.alpha)

    @classmethod
    def from_physical(
        cls, beam: Beam, drive: Drive, effects: Effects | None = None
    ) -> Dimensionless:
        T = beam.T
        effects = effects if effects is not None else Effects()
        return cls(
            hub_ratio=beam.hub_ratio,
            eta=beam.eta,
            lam0=drive.omega0 * T,
            alpha=drive.amplitude * T,
            omega=2.0 * math.pi * drive.f_d * T,
            effects=effects,
            slenderness=beam.h / beam.L if effects.extension else None,
        )

    @property
    def period(self) -> float:
        """Drive period in units of T."""
        return 2.0 * math.pi / self.omega

    def lam(self, tau: float) -> float:
        return self.lam0 + self.alpha * math.sin(self.omega * tau)

    def lam_dot(self, tau: float) -> float:
        return self.alpha * self.omega * math.cos(self.omega * tau)


def drive_groups(beam: Beam, drive: Drive) -> dict[str, float]:
    """Maximal centrifugal and Euler numbers (Eqs. max C num, max E num) and f_d / f_n."""
    G = beam.G
    return {
        "C_max": G * (drive.omega0 + drive.amplitude) ** 2,
        "E_max": G * drive.amplitude * 2.0 * math.pi * drive.f_d,
        "E_n": G * drive.amplitude * 2.0 * math.pi * beam.f_n,
        "I_max": (abs(drive.omega0) + drive.amplitude) * beam.T,
        "fd_over_fn": drive.f_d / beam.f_n,
    }


#: The model's range: C_max = G (|Omega_0| + a)^2 and E_max = G a 2 pi f_d up to 1e12, f_d up
#: to 1e6 f_n.  Far beyond the paper's scenes (C_max <= 787); beyond it the discrete model's
#: loads swamp its bending terms and, further out, overflow (the solvers then fail or stall).
C_MAX_LIMIT = 1e12
E_MAX_LIMIT = 1e12
FD_OVER_FN_LIMIT = 1e6


def check_model_range(beam: Beam, drive: Drive) -> None:
    """One-line error naming the drive (and G, f_n) when the scene is outside the model's range."""
    G = beam.G
    w = abs(drive.omega0) + drive.amplitude
    c_max = G * w * w  # x * x: inf rather than OverflowError
    e_max = G * drive.amplitude * 2.0 * math.pi * drive.f_d
    ratio = drive.f_d / beam.f_n
    if not c_max <= C_MAX_LIMIT:
        raise RotbeamInputError(
            f"C_max = G (|Omega_0| + a)^2 = {c_max:.3g} from drive.omega0 = {drive.omega0!r}, "
            f"drive.amplitude = {drive.amplitude!r}, G = {G:.3g} s^2 (beam); "
            f"allowed: C_max <= {C_MAX_LIMIT:g}"
        )
    if not e_max <= E_MAX_LIMIT:
        raise RotbeamInputError(
            f"E_max = G a 2 pi f_d = {e_max:.3g} from drive.amplitude = {drive.amplitude!r}, "
            f"drive.f_d = {drive.f_d!r}, G = {G:.3g} s^2 (beam); "
            f"allowed: E_max <= {E_MAX_LIMIT:g}"
        )
    if not ratio <= FD_OVER_FN_LIMIT:
        raise RotbeamInputError(
            f"f_d / f_n = {ratio:.3g} from drive.f_d = {drive.f_d!r} Hz, f_n = {beam.f_n:.4g} Hz "
            f"(beam); allowed: f_d <= {FD_OVER_FN_LIMIT:g} f_n"
        )


def omega0_for_cmax(beam: Beam, c_max: float, amplitude: float = 1.0) -> float:
    """Omega_0 that gives the maximal centrifugal number C_max (inverse of Eq. max C num)."""
    c_max = check_positive("C_max", c_max)
    return math.sqrt(c_max / beam.G) - amplitude


def fd_for_emax(beam: Beam, e_max: float, amplitude: float = 1.0) -> float:
    """Drive frequency that gives the maximal Euler number E_max (inverse of Eq. max E num)."""
    e_max = check_positive("E_max", e_max)
    amplitude = check_positive("drive.amplitude", amplitude)
    return e_max / (beam.G * amplitude * 2.0 * math.pi)
