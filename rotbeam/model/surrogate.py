r"""One-mode Galerkin surrogate with Southwell stiffening (Sec. 6 of the paper).

Linearising the continuum model of `rotbeam.elastica` about the straight, centrifugally
stretched beam (dimensionless, time by T, see `rotbeam.params`) gives for small y(s, tau)

    y_tt + eta y_t + y_ssss - (n0 y_s)_s - sigma lam^2 y = -lam_t (r_o + s),
    n0(s) = lam^2 n0_unit(s),   n0_unit(s) = r_o (1 - s) + (1 - s^2) / 2,

with sigma = 1 for the in-plane motion the paper models (the "softening" lam^2 y of F_y) and
sigma = 0 for flapwise motion.  With the single trial function y = q(tau) phi(s), phi the first
non-rotating cantilever mode, **normalised to phi(1) = 1** (q is the one-mode tip deflection),
Galerkin projection gives the Hill-type oscillator

    m q'' + eta m q' + [k_b + lam(tau)^2 (k_c - sigma m)] q = -lam_t(tau) F_e,
    m = int phi^2,  k_b = int phi''^2 = beta_1^4 m,  k_c = int n0_unit phi'^2,
    F_e = int (r_o + s) phi                                (all integrals over s in [0, 1]).

Its frozen-lam frequency is exactly the Southwell line w0^2 = beta_1^4 + S_1 lam^2 with
S_1 = (k_c - sigma m) / m, the Rayleigh quotient of the centrifugal tension (Eq. Southwell);
in Hz, (2 pi f0)^2 = (2 pi f_n)^2 + S_1 Omega^2, since both sides scale by T^2.

The steady state of the periodic linear ODE is computed directly by harmonic balance: with
lam = lam0 + alpha sin(omega tau) the stiffness has harmonics 0, +-1, +-2 only, so the Fourier
coefficients Q_k of q solve a pentadiagonal system; truncation K is doubled until the tail is
negligible.  RMS(q) follows from Parseval.  The quasi-static response solves the same system
without the inertia and damping terms, i.e. q = -lam_t F_e / (k_b + lam^2 (k_c - sigma m)) at
every instant.  Coriolis loads drop out at this order (-2 lam x_t is quadratic in y).
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
    """First non-rotating cantilever mode, phi(1) = 1, or its 1st/2nd derivative in s."""
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

    S_1 = [int n0 phi'^2 - sigma m_t] / m, n0 the straight beam's centrifugal tension per
    Omega^2 (with a tip mass mu: plus mu (r_o + 1) all along), m_t = int phi^2 + mu phi(1)^2 the
    mass the softening acts on, m = m_t + j phi'(1)^2; sigma = 1 with in-plane softening (the
    paper's planar model), 0 flapwise.  Hub 0 flapwise, no payload: the classical 1.1933.

    Parameters
    ----------
    hub_ratio : float
        R_o / L, >= 0.
    softening : bool
        In-plane (True) or flapwise.
    tip_mass, tip_inertia : float
        A payload, m / (rho A L) and J / (rho A L^3).

    Returns
    -------
    float
    """
    r_o = _check_hub(hub_ratio)
    g = _mode_integrals()
    k_c = r_o * g["k_c_hub"] + g["k_c_tip"] + tip_mass * (r_o + 1.0) * g["k_c_mass"]
    m_soft = g["m"] + tip_mass * g["phi1"] ** 2
    m = m_soft + tip_inertia * g["dphi1"] ** 2
    return (k_c - (1.0 if softening else 0.0) * m_soft) / m


def southwell_frequency_hz(beam: Beam, omega: float, softening: bool = True) -> float:
    """f0 [Hz] from (2 pi f0)^2 = (2 pi f_n)^2 + S_1 Omega^2 (Eq. centrifugal_stiffening)."""
    mu, j = beam.tip_mass / (beam.rhoA * beam.L), beam.tip_inertia / (beam.rhoA * beam.L**3)
    s1 = southwell_coefficient(beam.hub_ratio, softening, mu, j)
    return math.sqrt((2.0 * math.pi * beam.f_n) ** 2 + s1 * omega * omega) / (2.0 * math.pi)


@dataclass(frozen=True)
class SurrogateModel:
    """Projected coefficients of the one-mode model, plus the drive it is run with."""

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
        """Linear frequency w0 = sqrt(k_b/m + lam^2 (k_c - sigma m_soft)/m) at frozen lam."""
        w2 = (self.k_b + lam * lam * (self.k_c - self.sigma * self.m_soft)) / self.m
        if w2 <= 0:
            raise RotbeamInputError(f"non-positive modal stiffness {w2:.3g} at lam={lam!r}")
        return math.sqrt(w2)

    def frozen_rms(self) -> dict[str, float]:
        """The steady state with lam held at lam0: the 1-dof oscillator's |H(k omega)| on each
        harmonic of the drive's forcing -lam_dot F_e, summed by Parseval.

        For the sine, Delta RMS is 1 - sqrt((1 - c0^2)^2 + (2 zeta c0)^2), c0 = omega/w0,
        2 zeta = eta/w0 (App. E).

        Returns
        -------
        dict
            rms_dynamic, rms_quasistatic, delta_rms and w0 (at lam0).
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
    def _drive_coefficients(self) -> np.ndarray:
        """Two-sided Fourier coefficients a_{-K..K} of lam, lam = sum_k a_k exp(i k omega tau),
        trailing harmonics below 1e-14 of the largest dropped."""
        c = self.dl.law.coefficients(_DRIVE_K)
        keep = np.flatnonzero(np.abs(c[1:]) > 1e-14 * max(float(np.max(np.abs(c))), 1e-300))
        c = c[: (int(keep[-1]) + 2 if keep.size else 2)]
        return np.concatenate([np.conj(c[:0:-1]) / 2.0, c[:1], c[1:] / 2.0])

    def _forcing(self) -> tuple[np.ndarray, np.ndarray]:
        """(k >= 1, one-sided complex amplitudes of lam_dot at k omega)."""
        a = self._drive_coefficients()
        K = (a.size - 1) // 2
        k = np.arange(1, K + 1)
        return k, 2.0 * (1j * k * self.dl.omega) * a[K + 1 :]

    def _stiffness_harmonics(self) -> np.ndarray:
        """Fourier coefficients P_{-2K..2K} of (k_b + lam^2 (k_c - sigma m_soft)) / m, K the
        drive's highest harmonic."""
        a = self._drive_coefficients()
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
        a = self._drive_coefficients()
        Kd = (a.size - 1) // 2
        rhs = np.zeros(n, dtype=complex)
        j = np.arange(-Kd, Kd + 1)
        inside = np.abs(j) <= K
        rhs[K + j[inside]] = -(1j * j[inside] * dl.omega) * a[inside] * (self.F_e / self.m)
        return solve_banded((u, u), ab, rhs, check_finite=False)

    def harmonics(self, dynamic: bool = True) -> np.ndarray:
        """Converged Fourier coefficients Q_k, k = -K..K, of the periodic q(tau)."""
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
        """RMS over one drive period of y_m = q phi(1/2) (Parseval)."""
        Q = self.harmonics(dynamic)
        return abs(self.phi_mid) * float(np.sqrt(np.sum(np.abs(Q) ** 2)))

    def midspan_series(self, tau: np.ndarray, dynamic: bool = True) -> np.ndarray:
        """y_m(tau) of the periodic steady state (dynamic) or the quasi-static response."""
        Q = self.harmonics(dynamic)
        K = (Q.size - 1) // 2
        k = np.arange(-K, K + 1)
        tau = np.asarray(tau, dtype=float)
        q = np.real(np.exp(1j * self.dl.omega * np.multiply.outer(tau, k)) @ Q)
        return self.phi_mid * q


def steady_rms(dl: Dimensionless) -> dict[str, float]:
    """RMS(y_m) dynamic and quasi-static of the surrogate with time-varying lam, and Delta RMS.

    Also the frozen-lam (lam = lam0) closed forms, keys `frozen_*`.
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
    dl = Dimensionless.from_physical(beam, Drive(omega0, amplitude, f_d), effects)
    return steady_rms(dl)["delta_rms"]


def critical_frequency(
    beam: Beam,
    omega0: float,
    threshold: float = 0.10,
    amplitude: float = 1.0,
    effects: Effects | None = None,
    n_scan: int = 200,
    f_max: float | None = None,
) -> float:
    """First drive frequency f_d* [Hz] with Delta RMS = threshold (surrogate).

    f_d is scanned linearly on (0, f_max] (default f_max = 1.5 f0, f0 the Southwell frequency at
    Omega_0 + a), the first bracket with Delta RMS >= threshold is refined with Brent's method.
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
    """Surrogate boundary E*(C_max) = G a 2 pi f_d* (Eq. max E num) with f_d* and c = f_d*/f0."""
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
    """Eq. (analytical_sol): E* = c sqrt(E_n^2 + S_1 G a^2 C_max), E_n = G a 2 pi f_n.

    S1 defaults to the in-plane coefficient of the beam's hub ratio (softening on).
    """
    s1 = southwell_coefficient(beam.hub_ratio, True) if S1 is None else float(S1)
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
    """E* = c G a 2 pi f0 with f0 the exact first frequency at Omega_0 + a = sqrt(C_max / G).

    f0 from `rotbeam.modes.modes` (discrete model, N intervals) instead of
    the Southwell line.
    """
    G = beam.G
    cm = np.atleast_1d(np.asarray(c_max, dtype=float))
    f0 = np.array([modes(beam, math.sqrt(x / G), 1, N, softening)[0] for x in cm])
    out = c * G * amplitude * 2.0 * math.pi * f0
    return out if np.ndim(c_max) else float(out[0])
