"""How the disk turns, in the model's units: lam(tau) = Omega(t) T and its rate lam_dot.

A sum of harmonics (`HarmonicLaw`; a sampled period becomes one by its trigonometric
interpolant) or a single move (`MoveLaw`, a cubic spline).  Time is in units of
T = sqrt(rho A L^4 / (E I)), so lam_dot = (dOmega/dt) T^2 is what the Euler load scales with.
Why these interpolants, and what noise in a logged profile does: docs/model.md, "Drives".
"""

from __future__ import annotations

import cmath
import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

#: samples of a period (or a move) that the extremes, means and spectra of a sampled law use
DENSE = 4096


class DriveLaw(ABC):
    """lam(tau) = Omega T of a drive, tau = t / T, and what the solvers read off it.

    The solvers read the drive only through `lam` and `lam_dot` (and, for the linear start
    and the surrogate, `coefficients`); the extremes and means set C_max, E_max and the
    rotation that stretches the beam.  Subclasses give `lam`, `lam_dot`, `with_omega` and
    `scaled`; the rest is computed from DENSE samples unless a subclass knows it exactly.

    Attributes
    ----------
    omega : float
        2 pi / period (dimensionless): the repetition rate 2 pi f_d T of a periodic drive; for a
        single move, 2 pi over its duration.
    periodic : bool
        Whether lam repeats with the period.
    """

    omega: float
    periodic: bool = True

    @abstractmethod
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

    @abstractmethod
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

    def angle(self, tau: float) -> float:
        """The disk's angle at one instant, the integral of lam from 0 to tau (adaptive
        quadrature; `HarmonicLaw` knows it exactly).

        Parameters
        ----------
        tau : float
            Time in units of T, >= 0.

        Returns
        -------
        float
            phi [rad]: what turns the rotating frame into the lab frame.
        """
        from scipy.integrate import quad

        return float(quad(self.lam, 0.0, tau, limit=200)[0])

    @abstractmethod
    def with_omega(self, omega: float) -> DriveLaw:
        """The same profile repeated at another rate (a sweep in f_d changes only this).

        Parameters
        ----------
        omega : float
            The new 2 pi / period, dimensionless (2 pi f_d T).

        Returns
        -------
        DriveLaw
        """

    @abstractmethod
    def scaled(self, factor: float) -> DriveLaw:
        """lam0 + factor (lam - lam0): the profile's swing scaled, its mean kept.

        Continuation in the drive's amplitude uses it.

        Parameters
        ----------
        factor : float
            Scale of the swing, dimensionless.

        Returns
        -------
        DriveLaw
        """

    @property
    def period(self) -> float:
        """The period (or the move's duration) in units of T."""
        return 2.0 * math.pi / self.omega

    @property
    def duration(self) -> float:
        """A single run's length in units of T: its period (`MoveLaw` knows it from its samples)."""
        return self.period

    def rows(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """lam and lam_dot at many instants (`lam`, `lam_dot` one instant after the other; a
        law that can, sums them as arrays).

        Parameters
        ----------
        tau : numpy.ndarray
            Instants in units of T, shape (m,).

        Returns
        -------
        lam, lam_dot : numpy.ndarray
            Dimensionless, shape (m,) each.
        """
        return np.array([self.lam(t) for t in tau]), np.array([self.lam_dot(t) for t in tau])

    def dense(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The law sampled at DENSE equispaced instants of one period (or of the move).

        The extremes, means and spectra of a law that does not know them exactly.

        Returns
        -------
        tau, lam, lam_dot : numpy.ndarray
            Instants (units of T) from 0, and lam, lam_dot there; shape (DENSE,) each.
        """
        tau = np.arange(DENSE) * (self.period / DENSE)
        return (tau, *self.rows(tau))

    @property
    def mean(self) -> float:
        """Period mean of lam."""
        return float(np.mean(self.dense()[1]))

    @property
    def mean_square(self) -> float:
        """Period mean of lam^2 (the steady centrifugal tension's rotation, squared)."""
        return float(np.mean(self.dense()[1] ** 2))

    @property
    def lam_min(self) -> float:
        """The smallest |lam| over the period (a lower bound where exact is costly)."""
        return float(np.min(np.abs(self.dense()[1])))

    @property
    def lam_max(self) -> float:
        """The largest |lam| over the period."""
        return float(np.max(np.abs(self.dense()[1])))

    @property
    def lam_dot_max(self) -> float:
        """The largest |lam_dot| over the period."""
        return float(np.max(np.abs(self.dense()[2])))

    @property
    def highest_harmonic(self) -> int:
        """The highest harmonic of the period the law carries above round-off (of its DENSE
        samples' spectrum): what a sampling of the period must resolve.

        Returns
        -------
        int
            k >= 1, or 0 for a constant law.
        """
        a = np.abs(np.fft.rfft(self.dense()[1]))
        above = np.flatnonzero(a[1:] > 1e-12 * max(float(np.max(a)), 1e-300))
        return int(above[-1]) + 1 if above.size else 0

    def coefficients(self, K: int) -> np.ndarray:
        """c_0..c_K with lam(tau) = Re sum_k c_k exp(i k omega tau) (harmonics above K dropped).

        By FFT of the DENSE samples of one period.

        Parameters
        ----------
        K : int
            Highest harmonic kept.

        Returns
        -------
        numpy.ndarray
            Complex, dimensionless, shape (K + 1,).
        """
        c = np.fft.rfft(self.dense()[1]) / DENSE
        c[1:] *= 2.0
        return c[: K + 1]

    def harmonic_terms(self) -> tuple[tuple[int, float, float], ...]:
        """The law as lam = mean + sum_k alpha_k sin(k omega tau + phase_k).

        From `coefficients` (c_k = -i alpha_k exp(i phase_k)) up to half of DENSE, the terms
        above round-off; what the linear estimate of f_d* reads (`HarmonicLaw` knows them).

        Returns
        -------
        tuple of (int, float, float)
            (k, alpha_k >= 0, phase_k [rad]), alpha_k dimensionless.
        """
        c = self.coefficients(DENSE // 2 - 1)
        scale = max(float(np.max(np.abs(c[1:]))), 1e-300)
        return tuple((k, float(abs(c[k])), float(np.angle(c[k]) + 0.5 * math.pi))
                     for k in range(1, c.size) if abs(c[k]) > 1e-12 * scale)  # fmt: skip


@dataclass(frozen=True)
class HarmonicLaw(DriveLaw):
    """lam = lam0 + sum_k alpha_k sin(k omega tau + phase_k): a sum of harmonics.

    The paper's sine (one term, k = 1), a drive given by its harmonics and the trigonometric
    interpolant of a sampled period; lam_dot, the means and the Fourier coefficients are
    exact.

    Parameters
    ----------
    lam0 : float
        Mean rotation Omega_0 T, dimensionless.
    terms : tuple of (int, float, float)
        (k, alpha_k = a_k T, phase_k [rad]), distinct k >= 1.
    omega : float
        2 pi f_d T, dimensionless.
    """

    lam0: float
    terms: tuple[tuple[int, float, float], ...]
    omega: float

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
        out = self.lam0
        for k, a, ph in self.terms:
            out = out + a * math.sin(k * self.omega * tau + ph)
        return out

    def lam_dot(self, tau: float) -> float:
        """The rate of change of lam at one instant, sum_k alpha_k k omega cos(k omega tau + ph_k).

        Parameters
        ----------
        tau : float
            Time in units of T.

        Returns
        -------
        float
            d lam / d tau, dimensionless.
        """
        out = 0.0
        for k, a, ph in self.terms:
            out = out + a * (k * self.omega) * math.cos(k * self.omega * tau + ph)
        return out

    def angle(self, tau: float) -> float:
        """The disk's angle at one instant, lam0 tau + sum_k alpha_k (cos phase_k -
        cos(k omega tau + phase_k)) / (k omega).

        Parameters
        ----------
        tau : float
            Time in units of T.

        Returns
        -------
        float
            phi [rad]: what turns the rotating frame into the lab frame.
        """
        out = self.lam0 * tau
        for k, a, ph in self.terms:
            out = out + a * (math.cos(ph) - math.cos(k * self.omega * tau + ph)) / (k * self.omega)
        return out

    def with_omega(self, omega: float) -> HarmonicLaw:
        """The same harmonics at another repetition rate.

        Parameters
        ----------
        omega : float
            2 pi f_d T, dimensionless.

        Returns
        -------
        HarmonicLaw
        """
        return replace(self, omega=omega)

    def scaled(self, factor: float) -> HarmonicLaw:
        """Every harmonic's amplitude times `factor`, the mean kept.

        Parameters
        ----------
        factor : float
            Scale of the swing, dimensionless.

        Returns
        -------
        HarmonicLaw
        """
        return replace(self, terms=tuple((k, a * factor, ph) for k, a, ph in self.terms))

    def rows(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """lam and lam_dot at many instants, the harmonics summed as arrays.

        Parameters
        ----------
        tau : numpy.ndarray
            Instants in units of T, shape (m,).

        Returns
        -------
        lam, lam_dot : numpy.ndarray
            Dimensionless, shape (m,) each.
        """
        tau = np.asarray(tau, dtype=float)
        lam = np.full(tau.shape, float(self.lam0))
        lam_dot = np.zeros(tau.shape)
        for k, a, ph in self.terms:
            arg = k * self.omega * tau + ph
            lam += a * np.sin(arg)
            lam_dot += a * (k * self.omega) * np.cos(arg)
        return lam, lam_dot

    @property
    def highest_harmonic(self) -> int:
        """The largest k of the terms of nonzero amplitude: exact, no sampling.

        Returns
        -------
        int
            k >= 1, or 0 for a constant law.
        """
        return max((k for k, a, _ in self.terms if a != 0.0), default=0)

    @property
    def swing(self) -> float:
        """sum_k |alpha_k|: the largest |lam - lam0| can be."""
        return sum(abs(a) for _, a, _ in self.terms)

    @property
    def mean(self) -> float:
        """lam0 (the harmonics have zero mean)."""
        return self.lam0

    @property
    def mean_square(self) -> float:
        """lam0^2 + sum_k alpha_k^2 / 2 (distinct harmonics are orthogonal)."""
        out = self.lam0 * self.lam0
        for _, a, _ in self.terms:
            out = out + 0.5 * a * a
        return out

    @property
    def lam_min(self) -> float:
        """The smallest |lam|: max(0, |lam0| - |alpha|) for one harmonic, sampled for several."""
        if len(self.terms) == 1:
            return max(0.0, abs(self.lam0) - self.swing)
        return super().lam_min

    @property
    def lam_max(self) -> float:
        """The largest |lam|: |lam0| + |alpha| for one harmonic, sampled for several."""
        if len(self.terms) == 1:
            return abs(self.lam0) + self.swing
        return super().lam_max

    @property
    def lam_dot_max(self) -> float:
        """The largest |lam_dot|: |alpha omega| for one harmonic, sampled for several."""
        if len(self.terms) == 1:
            k, a, _ = self.terms[0]
            return abs(a * (k * self.omega))
        return float(np.max(np.abs(self.dense()[2])))

    def coefficients(self, K: int) -> np.ndarray:
        """c_0 = lam0, c_k = -i alpha_k exp(i phase_k): exact, no sampling.

        Parameters
        ----------
        K : int
            Highest harmonic kept (terms above it are dropped).

        Returns
        -------
        numpy.ndarray
            Complex, dimensionless, shape (K + 1,).
        """
        c = np.zeros(K + 1, dtype=complex)
        c[0] = self.lam0
        for k, a, ph in self.terms:
            if k <= K:
                c[k] += -1j * a * cmath.exp(1j * ph)
        return c

    def harmonic_terms(self) -> tuple[tuple[int, float, float], ...]:
        """The terms themselves: exact, no sampling.

        Returns
        -------
        tuple of (int, float, float)
            (k, alpha_k, phase_k [rad]), as given.
        """
        return self.terms


#: harmonics of a sampled period kept by default (a low-pass: docs/model.md, "Drives")
PROFILE_HARMONICS = 32


def kept_harmonics(samples: int, keep: int | None = None) -> int:
    """The highest harmonic `harmonics_of_samples` keeps of a period sampled `samples` times.

    Parameters
    ----------
    samples : int
        Samples of the period.
    keep : int or None
        The harmonics asked for (default PROFILE_HARMONICS).

    Returns
    -------
    int
        `keep`, at most half the samples.
    """
    return min(samples // 2, PROFILE_HARMONICS if keep is None else keep)


def harmonics_of_samples(
    phase: tuple[float, ...], values: tuple[float, ...], keep: int | None = None
) -> tuple[float, tuple[tuple[int, float, float], ...]]:
    """The trigonometric interpolant of one sampled period, as a mean and harmonics.

    Samples at unequal phases are first resampled at as many equal ones by a periodic cubic
    spline.  The interpolant is smooth (it is a sum of sines) and exact for a band-limited
    profile (a sampled sine is the sine); with every harmonic kept (at most 2 `keep` samples) it
    passes through the samples.  Noise in the samples reaches the rate lam_dot multiplied by
    the harmonic's number, hence `keep`, a low-pass (docs/model.md, "Drives").

    Parameters
    ----------
    phase : tuple of float
        Increasing phases in [0, 1).
    values : tuple of float
        The profile at them (any unit; the harmonics' amplitudes and the mean come in it).
    keep : int or None
        The highest harmonic kept (default PROFILE_HARMONICS, at most half the samples).

    Returns
    -------
    mean : float
        The period mean.
    terms : tuple of (int, float, float)
        (k, amplitude, phase): values = mean + sum amplitude sin(2 pi k x + phase).
    """
    x, y = np.asarray(phase, dtype=float), np.asarray(values, dtype=float)
    n = x.size
    uniform = np.arange(n) / n
    if np.max(np.abs(x - uniform)) > 1e-9:
        from scipy.interpolate import CubicSpline

        spline = CubicSpline(np.append(x, x[0] + 1.0), np.append(y, y[0]), bc_type="periodic")
        y = spline(uniform)
    c = np.fft.rfft(y) / n
    K = kept_harmonics(n, keep)
    scale = max(float(np.max(np.abs(c[1:]))), 1e-300) if c.size > 1 else 1.0
    terms = []
    for k in range(1, K + 1):
        ck = c[k] * (1.0 if 2 * k == n else 2.0)  # the Nyquist term is counted once
        if abs(ck) > 1e-12 * scale:
            terms.append((k, float(abs(ck)), float(np.angle(ck) + 0.5 * math.pi)))
    return float(c[0].real), tuple(terms)


@dataclass(frozen=True)
class MoveLaw(DriveLaw):
    """lam through the samples of a single move by a cubic spline, constant before and after it.

    The spline is not-a-knot: fourth order, lam_dot continuous.  Its slope is the Euler load:
    PCHIP's shape-preserving slopes put the residual vibration of a 61-sample move 7 % off,
    the spline 0.1 % (docs/model.md, "Drives").  `omega` is 2 pi over the duration and
    `periodic` is False.

    Parameters
    ----------
    tau : tuple of float
        Sample instants [units of T], from 0, increasing.
    values : tuple of float
        lam at those instants.
    """

    tau: tuple[float, ...]
    values: tuple[float, ...]
    periodic: bool = False
    _curve: Any = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        from scipy.interpolate import CubicSpline

        curve = CubicSpline(np.asarray(self.tau), np.asarray(self.values))
        object.__setattr__(self, "_curve", (curve, curve.derivative()))

    @property
    def omega(self) -> float:  # type: ignore[override]
        """2 pi over the move's duration."""
        return 2.0 * math.pi / self.duration

    @property
    def duration(self) -> float:
        """The move's length [units of T]."""
        return self.tau[-1] - self.tau[0]

    @property
    def spline(self) -> Any:
        """The cubic spline lam(tau) through the samples (scipy's `CubicSpline`, a `PPoly`)."""
        return self._curve[0]

    def dense(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The move sampled at DENSE equispaced instants of its duration, by the spline at once.

        Returns
        -------
        tau, lam, lam_dot : numpy.ndarray
            Instants (units of T) from 0, and lam, lam_dot there; shape (DENSE,) each.
        """
        tau = np.arange(DENSE) * (self.period / DENSE)
        return tau, self._curve[0](tau), self._curve[1](tau)

    def lam(self, tau: float) -> float:
        """The rotation rate at one instant (the end values outside the move).

        Parameters
        ----------
        tau : float
            Time in units of T from the move's first sample.

        Returns
        -------
        float
            lam = Omega T, dimensionless.
        """
        t = min(max(tau, self.tau[0]), self.tau[-1])
        return float(self._curve[0](t))

    def lam_dot(self, tau: float) -> float:
        """The rate of change of lam at one instant (0 outside the move).

        Parameters
        ----------
        tau : float
            Time in units of T from the move's first sample.

        Returns
        -------
        float
            d lam / d tau, dimensionless.
        """
        if not self.tau[0] <= tau <= self.tau[-1]:
            return 0.0
        return float(self._curve[1](tau))

    def with_omega(self, omega: float) -> MoveLaw:
        """A move is not repeated: it has no rate to change.

        Parameters
        ----------
        omega : float
            Not read.

        Returns
        -------
        MoveLaw
            Never: it raises.

        Raises
        ------
        ValueError
            Always.
        """
        raise ValueError("a single move has no repetition rate")

    def scaled(self, factor: float) -> MoveLaw:
        """The move's swing about its mean times `factor`.

        Parameters
        ----------
        factor : float
            Scale of the swing, dimensionless.

        Returns
        -------
        MoveLaw
            Through the scaled samples.
        """
        m = self.mean
        return MoveLaw(self.tau, tuple(m + factor * (v - m) for v in self.values))


#: named periodic speed profiles and the keys they take
PROFILE_SHAPES = {"trapezoid": ("omega_min", "omega_max", "ramp"),
                  "s-curve": ("omega_min", "omega_max", "ramp")}  # fmt: skip


def profile_samples(
    shape: str, omega_min: float, omega_max: float, ramp: float, samples: int = 512
) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """One period of a named velocity profile, sampled.

    From omega_min up to omega_max in a `ramp` fraction of the period, held, down again from
    phase 1/2 in another `ramp`, held; "trapezoid" ramps linearly (piecewise constant
    acceleration), "s-curve" by 3 x^2 - 2 x^3 (the acceleration itself ramps: no jerk spikes).
    The samples go the way of a sampled period (`harmonics_of_samples`); a trapezoid's corners
    leave slowly decaying harmonics (docs/model.md, "Drives").

    Parameters
    ----------
    shape : str
        "trapezoid" or "s-curve".
    omega_min, omega_max : float
        The two speeds [rad/s].
    ramp : float
        Each ramp's share of the period, in (0, 0.5].
    samples : int
        Samples of the period.

    Returns
    -------
    phase, omega : tuple of float
        Phases in [0, 1) and the speeds there.
    """
    x = np.arange(samples) / samples
    up = np.clip(x / ramp, 0.0, 1.0)
    down = np.clip((x - 0.5) / ramp, 0.0, 1.0)
    if shape == "s-curve":
        up, down = up * up * (3 - 2 * up), down * down * (3 - 2 * down)
    w = omega_min + (omega_max - omega_min) * (up - down)
    return tuple(float(v) for v in x), tuple(float(v) for v in w)
