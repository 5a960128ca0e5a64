"""The one-mode Galerkin surrogate with Southwell stiffening (Sec. 6 of the paper).

The beam linearised about the straight, centrifugally stretched state and projected on the first
non-rotating cantilever mode is a Hill-type oscillator in the tip deflection q(tau); harmonic
balance gives its periodic steady state under any harmonic drive, its frozen-lam frequency is
the Southwell line, and Eq. (analytical_sol) follows from it.  It is cheap (about 6e-5 s a
point) and good for f_d*, not for RMS amplitudes.  The derivation, the payload and what it gets
right: docs/model.md, "The one-mode surrogate".
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_banded

from ..config.checks import check_threshold
from ..config.errors import RotbeamInputError
from .criterion import delta_rms, first_crossing
from .modes import modes
from .params import BETA1, Beam, Dimensionless, Drive, Effects

#: Gauss-Legendre nodes on [0, 1]; the integrands are entire functions, 48 nodes reach round-off.
_GL_NODES = 48
#: Relative size of the last retained harmonics below which the harmonic balance is accepted.
_HB_TOL = 1e-13
_HB_K0 = 16
_HB_KMAX = 4096
#: harmonics of a sampled drive the surrogate keeps (a harmonic drive keeps all of its own)
_DRIVE_K = 64


def _sigma1() -> float:
    b = BETA1
    return (math.sinh(b) - math.sin(b)) / (math.cosh(b) + math.cos(b))


def mode_shape(s: np.ndarray, derivative: int = 0) -> np.ndarray:
    """The first non-rotating cantilever mode phi(s), normalised to phi(1) = 1, or a derivative.

    With phi(1) = 1 the surrogate's coordinate q is the one-mode tip deflection.

    Parameters
    ----------
    s : numpy.ndarray
        Arc length in units of L, in [0, 1], any shape.
    derivative : int
        0, 1 or 2: phi, d phi / ds or d^2 phi / ds^2.

    Returns
    -------
    numpy.ndarray
        The shape of `s`, dimensionless.

    Raises
    ------
    RotbeamInputError
        For a derivative other than 0, 1 or 2.
    """
    b, sg = BETA1, _sigma1()
    s = np.asarray(s, dtype=float)
    bs = b * s
    ch, sh, c, sn = np.cosh(bs), np.sinh(bs), np.cos(bs), np.sin(bs)
    if derivative == 0:
        v = ch - c - sg * (sh - sn)
    elif derivative == 1:
        v = b * (sh + sn - sg * (ch - c))
    elif derivative == 2:
        v = b * b * (ch + c - sg * (sh + sn))
    else:
        raise RotbeamInputError(f"derivative must be 0, 1 or 2, got {derivative!r}")
    return v / 2.0  # the classical form has phi(1) = 2


@functools.cache
def _gauss() -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(_GL_NODES)
    return 0.5 * (x + 1.0), 0.5 * w


@functools.cache
def _mode_integrals() -> dict[str, float]:
    """Hub-independent integrals of the normalised mode (cached)."""
    s, w = _gauss()
    p, p1, p2 = mode_shape(s), mode_shape(s, 1), mode_shape(s, 2)
    return {
        "m": float(w @ (p * p)),
        "k_b": float(w @ (p2 * p2)),
        "k_c_hub": float(w @ ((1.0 - s) * p1 * p1)),  # multiplies r_o
        "k_c_tip": float(w @ (0.5 * (1.0 - s * s) * p1 * p1)),
        "f_hub": float(w @ p),  # multiplies r_o
        "f_tip": float(w @ (s * p)),
        "phi_mid": float(mode_shape(np.array(0.5))),
        "k_c_mass": float(w @ (p1 * p1)),  # a tip mass's tension, uniform along the beam
        "phi1": float(mode_shape(np.array(1.0))),
        "dphi1": float(mode_shape(np.array(1.0), 1)),
    }


def _check_hub(hub_ratio: float) -> float:
    if isinstance(hub_ratio, bool) or not isinstance(hub_ratio, (int, float, np.floating)):
        raise RotbeamInputError(f"hub ratio R_o/L must be a number, got {hub_ratio!r}")
    if not (math.isfinite(hub_ratio) and hub_ratio >= 0):
        raise RotbeamInputError(f"hub ratio R_o/L must be finite and >= 0, got {hub_ratio!r}")
    return float(hub_ratio)


def southwell_coefficient(
    hub_ratio: float, softening: bool = True, tip_mass: float = 0.0, tip_inertia: float = 0.0
) -> float:
    """First Southwell coefficient S_1 from the Rayleigh quotient of the non-rotating mode.

    (2 pi f_0)^2 = (2 pi f_n)^2 + S_1 Omega^2 is the Southwell line (Eq. centrifugal_stiffening);
    S_1 = [int n0 phi'^2 - sigma m_t] / m, n0 the straight beam's centrifugal tension per
    Omega^2 (with a tip mass mu: plus mu (r_o + 1) all along), m_t = int phi^2 + mu phi(1)^2 the
    mass the softening acts on, m = m_t + j phi'(1)^2; sigma = 1 with in-plane softening (the
    paper's planar model), 0 flapwise.  Hub 0 flapwise, no payload: the classical 1.1933; the
    reference beam (r_o = 2.875): 4.7096 in-plane.

    Parameters
    ----------
    hub_ratio : float
        R_o / L, dimensionless, >= 0.
    softening : bool
        In-plane (True) or flapwise.
    tip_mass, tip_inertia : float
        A payload, m / (rho A L) and J / (rho A L^3), dimensionless.

    Returns
    -------
    float
        S_1, dimensionless.

    Raises
    ------
    RotbeamInputError
        If `hub_ratio` is not a finite number >= 0.
    """
    r_o = _check_hub(hub_ratio)
    g = _mode_integrals()
    k_c = r_o * g["k_c_hub"] + g["k_c_tip"] + tip_mass * (r_o + 1.0) * g["k_c_mass"]
    m_soft = g["m"] + tip_mass * g["phi1"] ** 2
    m = m_soft + tip_inertia * g["dphi1"] ** 2
    return (k_c - (1.0 if softening else 0.0) * m_soft) / m


def southwell_frequency_hz(beam: Beam, omega: float, softening: bool = True) -> float:
    """The first frequency on the Southwell line, (2 pi f0)^2 = (2 pi f_n)^2 + S_1 Omega^2.

    Eq. (centrifugal_stiffening), with the beam's payload in f_n and S_1.  It lies above the
    exact first frequency (+3.8 % at C_max = 787 for the reference beam; `rotbeam.model.modes`
    has the exact one).

    Parameters
    ----------
    beam : Beam
        The beam and its payload.
    omega : float
        Steady angular velocity Omega [rad/s].
    softening : bool
        In-plane (True) or flapwise.

    Returns
    -------
    float
        f0 [Hz].
    """
    s1 = southwell_coefficient(beam.hub_ratio, softening, *beam.payload_ratios)
    return math.sqrt((2.0 * math.pi * beam.f_n) ** 2 + s1 * omega * omega) / (2.0 * math.pi)


@dataclass(frozen=True)
class SurrogateModel:
    """Projected coefficients of the one-mode model, plus the drive it is run with.

    The oscillator m q'' + eta m_beam q' + [k_b + lam^2 (k_c - sigma m_soft)] q = -lam_dot F_e
    in the one-mode tip deflection q (units of L, time in units of T); build it with
    `from_dimensionless`.  The integrals are over the mode normalised to phi(1) = 1
    (docs/model.md, "The one-mode surrogate").
    """

    dl: Dimensionless
    m: float  #: modal mass: int phi^2 + mu phi(1)^2 + j phi'(1)^2
    k_b: float  #: int phi''^2 (= beta_1^4 int phi^2)
    k_c: float  #: int n0_unit phi'^2 (0 with centrifugal loads off)
    sigma: float  #: 1 with in-plane softening, else 0
    F_e: float  #: int (r_o + s) phi + mu (r_o + 1) phi(1) + j phi'(1) (0 with Euler loads off)
    phi_mid: float  #: phi(1/2): y_m = q phi(1/2)
    eta: float  #: damping actually applied (0 with damping off)
    m_soft: float  #: the mass the softening acts on: int phi^2 + mu phi(1)^2
    m_beam: float  #: the mass the damping acts on: int phi^2

    @classmethod
    def from_dimensionless(cls, dl: Dimensionless) -> SurrogateModel:
        """The surrogate of a scene: the mode integrals with its hub ratio, payload and effects.

        A load that is off contributes nothing (k_c = 0 without centrifugal loads, sigma = 0
        without softening, F_e = 0 without the Euler load, eta = 0 without damping).  Coriolis
        and extension do not enter: the surrogate is linear and inextensible.

        Parameters
        ----------
        dl : Dimensionless
            The scene (hub ratio, damping, drive, effects, payload).

        Returns
        -------
        SurrogateModel
        """
        g = _mode_integrals()
        ef = dl.effects
        r_o = float(dl.hub_ratio)
        mu, j = dl.tip_mass, dl.tip_inertia
        k_c = 0.0
        if ef.centrifugal:
            k_c = r_o * g["k_c_hub"] + g["k_c_tip"] + mu * (r_o + 1.0) * g["k_c_mass"]
        sigma = 1.0 if (ef.centrifugal and ef.softening) else 0.0
        F_e = 0.0
        if ef.euler:
            F_e = r_o * g["f_hub"] + g["f_tip"] + mu * (r_o + 1.0) * g["phi1"] + j * g["dphi1"]
        m_soft = g["m"] + mu * g["phi1"] ** 2
        return cls(
            dl=dl,
            m=m_soft + j * g["dphi1"] ** 2,
            k_b=g["k_b"],
            k_c=k_c,
            sigma=sigma,
            F_e=F_e,
            phi_mid=g["phi_mid"],
            eta=float(dl.eta) if ef.damping else 0.0,
            m_soft=m_soft,
            m_beam=g["m"],
        )

    # --- frozen-rotation quantities ---------------------------------------------------------
    @property
    def southwell(self) -> float:
        """S_1 = (k_c - sigma m_soft) / m of this model (0 with centrifugal loads off)."""
        return (self.k_c - self.sigma * self.m_soft) / self.m

    @property
    def damping(self) -> float:
        """eta m_beam / m: the damping per unit modal mass (a payload has none of its own)."""
        return self.eta * (self.m_beam / self.m)

    def frequency(self, lam: float) -> float:
        """The oscillator's undamped frequency with lam held fixed: the Southwell line.

        w0 = sqrt(k_b/m + lam^2 (k_c - sigma m_soft)/m), the Rayleigh quotient of the bare mode
        (an upper bound of the exact first frequency).

        Parameters
        ----------
        lam : float
            Omega T, dimensionless.

        Returns
        -------
        float
            w0 = omega_0 T, dimensionless.

        Raises
        ------
        RotbeamInputError
            If the modal stiffness is not positive (the softening exceeds the stiffening).
        """
        w2 = (self.k_b + lam * lam * (self.k_c - self.sigma * self.m_soft)) / self.m
        if w2 <= 0:
            raise RotbeamInputError(f"non-positive modal stiffness {w2:.3g} at lam={lam!r}")
        return math.sqrt(w2)

    def frozen_rms(self) -> dict[str, float]:
        """The steady state with lam held at lam0 in the stiffness, for comparison with App. E.

        The one-degree-of-freedom oscillator's |H(k omega)| on each harmonic of the drive's
        forcing -lam_dot F_e, summed by Parseval.  For the sine, Delta RMS is
        1 - sqrt((1 - c0^2)^2 + (2 zeta c0)^2), c0 = omega/w0, 2 zeta = eta/w0 (App. E).

        Returns
        -------
        dict
            ``rms_dynamic`` and ``rms_quasistatic`` of y_m (units of L), ``delta_rms``
            (dimensionless) and ``w0`` (the frequency at lam0, units of 1/T).
        """
        dl = self.dl
        w0 = self.frequency(dl.lam0)
        k, d = self._forcing()
        kw = k * dl.omega
        amp = np.abs(d) * self.F_e / self.m  # forcing amplitudes per unit modal mass
        qs = amp / (w0 * w0)
        dyn = amp / np.hypot(w0 * w0 - kw * kw, self.damping * kw)
        scale = abs(self.phi_mid) / math.sqrt(2.0)
        r_dyn = float(np.sqrt(np.sum(dyn * dyn))) * scale
        r_qs = float(np.sqrt(np.sum(qs * qs))) * scale
        return {
            "rms_dynamic": r_dyn,
            "rms_quasistatic": r_qs,
            "delta_rms": delta_rms(r_dyn, r_qs),
            "w0": w0,
        }

    # --- harmonic balance -------------------------------------------------------------------
    @functools.cached_property
    def _drive_coefficients(self) -> np.ndarray:
        """Two-sided Fourier coefficients a_{-K..K} of lam, lam = sum_k a_k exp(i k omega tau),
        trailing harmonics below 1e-14 of the largest dropped (worked out once per model: every
        harmonic-balance solve reads them twice)."""
        c = self.dl.law.coefficients(_DRIVE_K)
        keep = np.flatnonzero(np.abs(c[1:]) > 1e-14 * max(float(np.max(np.abs(c))), 1e-300))
        c = c[: (int(keep[-1]) + 2 if keep.size else 2)]
        return np.concatenate([np.conj(c[:0:-1]) / 2.0, c[:1], c[1:] / 2.0])

    def _forcing(self) -> tuple[np.ndarray, np.ndarray]:
        """(k >= 1, one-sided complex amplitudes of lam_dot at k omega)."""
        a = self._drive_coefficients
        K = (a.size - 1) // 2
        k = np.arange(1, K + 1)
        return k, 2.0 * (1j * k * self.dl.omega) * a[K + 1 :]

    def _stiffness_harmonics(self) -> np.ndarray:
        """Fourier coefficients P_{-2K..2K} of (k_b + lam^2 (k_c - sigma m_soft)) / m, K the
        drive's highest harmonic."""
        a = self._drive_coefficients
        b = (self.k_c - self.sigma * self.m_soft) / self.m
        p = b * np.convolve(a, a)
        p[p.size // 2] += self.k_b / self.m
        return p

    def _solve(self, K: int, dynamic: bool) -> np.ndarray:
        """Harmonics Q_{-K..K} of q for truncation K (dynamic or quasi-static)."""
        dl = self.dl
        n = 2 * K + 1
        k = np.arange(-K, K + 1)
        p = self._stiffness_harmonics()
        u = p.size // 2  # band half-width: lam^2 couples harmonics up to u apart
        # banded storage: ab[u + i - j, j] = A[i, j]; A[i, j] = P_{i-j} (+ diag)
        ab = np.zeros((2 * u + 1, n), dtype=complex)
        for d in range(-u, u + 1):  # d = i - j
            ab[u + d] = p[d + u]
        if dynamic:
            kw = k * dl.omega
            ab[u] += -kw * kw + 1j * kw * self.damping
        a = self._drive_coefficients
        Kd = (a.size - 1) // 2
        rhs = np.zeros(n, dtype=complex)
        j = np.arange(-Kd, Kd + 1)
        inside = np.abs(j) <= K
        rhs[K + j[inside]] = -(1j * j[inside] * dl.omega) * a[inside] * (self.F_e / self.m)
        return solve_banded((u, u), ab, rhs, check_finite=False)

    def harmonics(self, dynamic: bool = True) -> np.ndarray:
        """The Fourier coefficients of the periodic q(tau), by harmonic balance.

        The truncation K starts at 16 and doubles until the two outermost harmonics at each end
        are below 1e-13 of the total (at most 4096).

        Parameters
        ----------
        dynamic : bool
            The steady state (True) or the quasi-static response (no inertia, no damping).

        Returns
        -------
        numpy.ndarray
            Complex Q_k, k = -K..K, shape (2 K + 1,): q(tau) = Re sum_k Q_k exp(i k omega tau),
            units of L.

        Raises
        ------
        RotbeamInputError
            If the tail is still above the tolerance at K = 4096.
        """
        K = _HB_K0
        while True:
            Q = self._solve(K, dynamic)
            a = np.abs(Q)
            total = float(np.sqrt(np.sum(a * a)))
            tail = float(max(a[:2].max(), a[-2:].max()))
            if total == 0.0 or tail <= _HB_TOL * total:
                return Q
            if 2 * K > _HB_KMAX:
                raise RotbeamInputError(
                    f"harmonic balance did not converge with {K} harmonics "
                    f"(tail/total = {tail / total:.2e})"
                )
            K *= 2

    def rms_midspan(self, dynamic: bool = True) -> float:
        """RMS over one drive period of y_m = q phi(1/2), by Parseval on the harmonics.

        Parameters
        ----------
        dynamic : bool
            The steady state (True) or the quasi-static response.

        Returns
        -------
        float
            RMS(y_m) in units of L.
        """
        Q = self.harmonics(dynamic)
        return abs(self.phi_mid) * float(np.sqrt(np.sum(np.abs(Q) ** 2)))

    def midspan_series(self, tau: np.ndarray, dynamic: bool = True) -> np.ndarray:
        """y_m(tau) = q(tau) phi(1/2) of the steady state or the quasi-static response.

        Parameters
        ----------
        tau : numpy.ndarray
            Instants in units of T, any shape.
        dynamic : bool
            The steady state (True) or the quasi-static response.

        Returns
        -------
        numpy.ndarray
            y_m in units of L, the shape of `tau`.
        """
        Q = self.harmonics(dynamic)
        K = (Q.size - 1) // 2
        k = np.arange(-K, K + 1)
        tau = np.asarray(tau, dtype=float)
        q = np.real(np.exp(1j * self.dl.omega * np.multiply.outer(tau, k)) @ Q)
        return self.phi_mid * q


def steady_rms(dl: Dimensionless) -> dict[str, float]:
    """The surrogate's answer for one scene: RMS(y_m) dynamic and quasi-static, and Delta RMS.

    With time-varying lam (harmonic balance), beside the frozen-lam closed forms.

    Parameters
    ----------
    dl : Dimensionless
        The scene.

    Returns
    -------
    dict
        ``rms_dynamic``, ``rms_quasistatic`` (units of L), ``delta_rms``; the same with lam
        held at lam0, ``frozen_rms_dynamic``, ``frozen_rms_quasistatic``,
        ``frozen_delta_rms``; ``w0_lam0`` (units of 1/T) and ``southwell`` (S_1), all
        dimensionless but the RMS values.
    """
    model = SurrogateModel.from_dimensionless(dl)
    r_dyn = model.rms_midspan(dynamic=True)
    r_qs = model.rms_midspan(dynamic=False)
    frozen = model.frozen_rms()
    return {
        "rms_dynamic": r_dyn,
        "rms_quasistatic": r_qs,
        "delta_rms": delta_rms(r_dyn, r_qs),
        "frozen_rms_dynamic": frozen["rms_dynamic"],
        "frozen_rms_quasistatic": frozen["rms_quasistatic"],
        "frozen_delta_rms": frozen["delta_rms"],
        "w0_lam0": frozen["w0"],
        "southwell": model.southwell,
    }


def _delta_at(beam: Beam, omega0: float, amplitude: float, f_d: float, effects: Effects) -> float:
    """`steady_rms`'s Delta RMS alone (the scan of `critical_frequency` reads nothing else)."""
    model = SurrogateModel.from_dimensionless(
        Dimensionless.from_physical(beam, Drive(omega0, amplitude, f_d), effects)
    )
    return delta_rms(model.rms_midspan(dynamic=True), model.rms_midspan(dynamic=False))


def critical_frequency(
    beam: Beam,
    omega0: float,
    threshold: float = 0.10,
    amplitude: float = 1.0,
    effects: Effects | None = None,
    n_scan: int = 200,
    f_max: float | None = None,
) -> float:
    """The surrogate's f_d*: the first drive frequency at which Delta RMS reaches `threshold`.

    f_d is scanned linearly on (0, f_max] (default f_max = 1.5 f0, f0 the Southwell frequency at
    Omega_0 + a), the first bracket with Delta RMS >= threshold is refined with Brent's method.
    Within 5 % of the full model's f_d* on every line of the paper's range.

    Parameters
    ----------
    beam : Beam
        The beam.
    omega0 : float
        Mean angular velocity Omega_0 [rad/s] of the sine drive.
    threshold : float
        Delta RMS threshold, dimensionless, in (0, 1).
    amplitude : float
        Velocity amplitude a [rad/s].
    effects : Effects or None
        The loads (default: the paper's).
    n_scan : int
        Scan points, >= 4.
    f_max : float or None
        Upper end of the scan [Hz].

    Returns
    -------
    float
        f_d* [Hz].

    Raises
    ------
    RotbeamInputError
        For a bad `threshold` or `n_scan`, or when no scanned frequency reaches the threshold.
    """
    threshold = check_threshold(threshold)
    effects = effects if effects is not None else Effects()
    if not (isinstance(n_scan, int) and n_scan >= 4):
        raise RotbeamInputError(f"n_scan must be an integer >= 4, got {n_scan!r}")
    if f_max is None:
        f_max = 1.5 * southwell_frequency_hz(beam, abs(omega0) + amplitude, effects.softening)
    fs = np.linspace(f_max / n_scan, f_max, n_scan)
    vals = np.array([_delta_at(beam, omega0, amplitude, f, effects) for f in fs])
    cr = first_crossing(
        fs,
        vals,
        threshold,
        refine=lambda f: _delta_at(beam, omega0, amplitude, f, effects),
        xtol=1e-9 * f_max,
    )
    if not cr.found or not math.isfinite(cr.root):
        raise RotbeamInputError(
            f"no crossing of Delta RMS = {threshold} for f_d in ({fs[0]:.4g}, {f_max:.4g}] Hz "
            f"at Omega_0 = {omega0!r} rad/s ({cr.message})"
        )
    return cr.root


def phase_boundary(
    beam: Beam,
    c_max_values: np.ndarray | list[float],
    threshold: float = 0.10,
    amplitude: float = 1.0,
    effects: Effects | None = None,
    n_scan: int = 200,
) -> dict[str, np.ndarray]:
    """The surrogate's boundary E*(C_max) = G a 2 pi f_d* (Eq. max E num), as in Fig. 7.

    One `critical_frequency` per C_max, at Omega_0 = sqrt(C_max / G) - a.

    Parameters
    ----------
    beam : Beam
        The beam.
    c_max_values : numpy.ndarray or list of float
        Largest centrifugal numbers C_max, dimensionless, > 0.
    threshold : float
        Delta RMS threshold, dimensionless, in (0, 1).
    amplitude : float
        Velocity amplitude a [rad/s].
    effects : Effects or None
        The loads (default: the paper's).
    n_scan : int
        Scan points of each line.

    Returns
    -------
    dict
        Arrays of the length of `c_max_values`: ``c_max``, ``omega0`` [rad/s], ``f_d_star``
        [Hz], ``e_star`` (dimensionless), ``f0_southwell`` [Hz] (at Omega_0 + a) and
        ``c`` = f_d* / f0.

    Raises
    ------
    RotbeamInputError
        For a C_max that is not finite and > 0, or a line without a crossing.
    """
    effects = effects if effects is not None else Effects()
    c_max = np.atleast_1d(np.asarray(c_max_values, dtype=float))
    if np.any(~np.isfinite(c_max)) or np.any(c_max <= 0):
        raise RotbeamInputError(f"C_max values must be finite and > 0, got {c_max_values!r}")
    G = beam.G
    omega_max = np.sqrt(c_max / G)
    omega0 = omega_max - amplitude
    f_star = np.array(
        [critical_frequency(beam, float(o), threshold, amplitude, effects, n_scan) for o in omega0]
    )
    f0 = np.array([southwell_frequency_hz(beam, float(o), effects.softening) for o in omega_max])
    return {
        "c_max": c_max,
        "omega0": omega0,
        "f_d_star": f_star,
        "e_star": G * amplitude * 2.0 * math.pi * f_star,
        "f0_southwell": f0,
        "c": f_star / f0,
    }


def analytical_boundary(
    beam: Beam,
    c_max: float | np.ndarray,
    c: float,
    S1: float | None = None,
    amplitude: float = 1.0,
) -> float | np.ndarray:
    """The paper's closed-form boundary, Eq. (analytical_sol): E* = c sqrt(E_n^2 + S_1 G a^2 C_max).

    E_n = G a 2 pi f_n; it is c G a 2 pi f0 with f0 on the Southwell line at Omega_0 + a.

    Parameters
    ----------
    beam : Beam
        The beam (G, f_n, hub ratio).
    c_max : float or numpy.ndarray
        Largest centrifugal numbers, dimensionless.
    c : float
        The ratio f_d* / f0, dimensionless.
    S1 : float or None
        Southwell coefficient; default the in-plane one of the beam's hub ratio and payload.
    amplitude : float
        Velocity amplitude a [rad/s].

    Returns
    -------
    float or numpy.ndarray
        E*, dimensionless, a float for a scalar `c_max`.
    """
    if S1 is None:
        S1 = southwell_coefficient(beam.hub_ratio, True, *beam.payload_ratios)
    s1 = float(S1)
    G = beam.G
    e_n = G * amplitude * 2.0 * math.pi * beam.f_n
    out = c * np.sqrt(e_n * e_n + s1 * G * amplitude**2 * np.asarray(c_max, dtype=float))
    return out if np.ndim(c_max) else float(out)


def analytical_boundary_exact(
    beam: Beam,
    c_max: float | np.ndarray,
    c: float,
    amplitude: float = 1.0,
    N: int = 40,
    softening: bool = True,
) -> float | np.ndarray:
    """Eq. (analytical_sol) with the exact first frequency: E* = c G a 2 pi f0.

    f0 is the first frequency of the linearised discrete model (`rotbeam.model.modes.modes`,
    N intervals) at Omega_0 + a = sqrt(C_max / G), instead of the Southwell line.

    Parameters
    ----------
    beam : Beam
        The beam.
    c_max : float or numpy.ndarray
        Largest centrifugal numbers, dimensionless.
    c : float
        The ratio f_d* / f0, dimensionless.
    amplitude : float
        Velocity amplitude a [rad/s].
    N : int
        Grid intervals of the modes.
    softening : bool
        In-plane (True) or flapwise.

    Returns
    -------
    float or numpy.ndarray
        E*, dimensionless, a float for a scalar `c_max`.
    """
    G = beam.G
    cm = np.atleast_1d(np.asarray(c_max, dtype=float))
    f0 = np.array([modes(beam, math.sqrt(x / G), 1, N, softening)[0] for x in cm])
    out = c * G * amplitude * 2.0 * math.pi * f0
    return out if np.ndim(c_max) else float(out[0])
