"""How the disk turns, in the model's units: lam(tau) = Omega(t) T and its rate lam_dot, for a
sum of harmonics, a sampled period or a single move (docs/model.md, "Drives")."""

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
        """Omega T at the instant tau."""

    @abstractmethod
    def lam_dot(self, tau: float) -> float:
        """d lam / d tau = Omega-dot T^2 at the instant tau."""

    @abstractmethod
    def with_omega(self, omega: float) -> DriveLaw:
        """The same profile repeated at another rate (a new 2 pi / period)."""

    @abstractmethod
    def scaled(self, factor: float) -> DriveLaw:
        """lam0 + factor (lam - lam0): the profile's swing scaled, its mean kept."""

    @property
    def period(self) -> float:
        """The period (or the move's duration) in units of T."""
        return 2.0 * math.pi / self.omega

    def dense(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """tau, lam, lam_dot at DENSE equispaced instants of one period (or of the move)."""
        tau = np.arange(DENSE) * (self.period / DENSE)
        lam = np.array([self.lam(t) for t in tau])
        return tau, lam, np.array([self.lam_dot(t) for t in tau])

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

    def coefficients(self, K: int) -> np.ndarray:
        """c_0..c_K with lam(tau) = Re sum_k c_k exp(i k omega tau) (harmonics above K dropped).

        Parameters
        ----------
        K : int
            Highest harmonic kept.

        Returns
        -------
        numpy.ndarray
            Complex, shape (K + 1,).
        """
        c = np.fft.rfft(self.dense()[1]) / DENSE
        c[1:] *= 2.0
        return c[: K + 1]


@dataclass(frozen=True)
class HarmonicLaw(DriveLaw):
    """lam = lam0 + sum_k alpha_k sin(k omega tau + phase_k): a sum of harmonics.

    Parameters
    ----------
    lam0 : float
        Mean rotation Omega_0 T.
    terms : tuple of (int, float, float)
        (k, alpha_k = a_k T, phase_k [rad]), distinct k >= 1.
    omega : float
        2 pi f_d T.
    """

    lam0: float
    terms: tuple[tuple[int, float, float], ...]
    omega: float

    def lam(self, tau: float) -> float:
        """Omega T at the instant tau."""
        out = self.lam0
        for k, a, ph in self.terms:
            out = out + a * math.sin(k * self.omega * tau + ph)
        return out

    def lam_dot(self, tau: float) -> float:
        """d lam / d tau at the instant tau."""
        out = 0.0
        for k, a, ph in self.terms:
            out = out + a * (k * self.omega) * math.cos(k * self.omega * tau + ph)
        return out

    def with_omega(self, omega: float) -> HarmonicLaw:
        """The same harmonics at another repetition rate."""
        return replace(self, omega=omega)

    def scaled(self, factor: float) -> HarmonicLaw:
        """Every harmonic's amplitude times `factor`."""
        return replace(self, terms=tuple((k, a * factor, ph) for k, a, ph in self.terms))

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
        """max(0, |lam0| - sum_k |alpha_k|): a lower bound of |lam|, exact for one harmonic."""
        return max(0.0, abs(self.lam0) - self.swing)

    @property
    def lam_max(self) -> float:
        """|lam0| + sum_k |alpha_k|: an upper bound of |lam|, exact for one harmonic."""
        return abs(self.lam0) + self.swing

    @property
    def lam_dot_max(self) -> float:
        """The largest |lam_dot|: |alpha omega| for one harmonic, sampled for several."""
        if len(self.terms) == 1:
            k, a, _ = self.terms[0]
            return abs(a * (k * self.omega))
        return float(np.max(np.abs(self.dense()[2])))

    def coefficients(self, K: int) -> np.ndarray:
        """c_0 = lam0, c_k = -i alpha_k exp(i phase_k) (exact, no sampling)."""
        c = np.zeros(K + 1, dtype=complex)
        c[0] = self.lam0
        for k, a, ph in self.terms:
            if k <= K:
                c[k] += -1j * a * cmath.exp(1j * ph)
        return c


def periodic_pchip(x: np.ndarray, y: np.ndarray, period: float) -> Any:
    """The shape-preserving cubic (PCHIP) through (x, y) on [0, period), continued periodically:
    three samples wrapped round each end, so that the slopes at the seam are those of a
    periodic curve (PCHIP's slope at a knot depends on its neighbours only)."""
    from scipy.interpolate import PchipInterpolator

    xs = np.concatenate([x[-3:] - period, x, x[:3] + period])
    ys = np.concatenate([y[-3:], y, y[:3]])
    return PchipInterpolator(xs, ys)


@dataclass(frozen=True)
class SampledLaw(DriveLaw):
    """lam through samples of one period, by a periodic shape-preserving cubic (PCHIP).

    PCHIP keeps flat stretches flat and ramps monotone (a spline or a Fourier interpolant rings
    at a trapezoid's corners: Euler loads the motor never applies), and lam_dot is continuous.

    Parameters
    ----------
    phase : tuple of float
        Sample phases in [0, 1), increasing.
    values : tuple of float
        lam at those phases.
    omega : float
        2 pi f_d T.
    """

    phase: tuple[float, ...]
    values: tuple[float, ...]
    omega: float
    _curve: Any = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        curve = periodic_pchip(np.asarray(self.phase), np.asarray(self.values), 1.0)
        object.__setattr__(self, "_curve", (curve, curve.derivative()))

    def lam(self, tau: float) -> float:
        """Omega T at the instant tau."""
        return float(self._curve[0]((tau / self.period) % 1.0))

    def lam_dot(self, tau: float) -> float:
        """d lam / d tau at the instant tau."""
        return float(self._curve[1]((tau / self.period) % 1.0)) / self.period

    def with_omega(self, omega: float) -> SampledLaw:
        """The same samples repeated at another rate."""
        return SampledLaw(self.phase, self.values, omega)

    def scaled(self, factor: float) -> SampledLaw:
        """The samples' swing about their mean times `factor`."""
        m = self.mean
        return SampledLaw(self.phase, tuple(m + factor * (v - m) for v in self.values), self.omega)


@dataclass(frozen=True)
class MoveLaw(DriveLaw):
    """lam through the samples of a single move by PCHIP, constant before and after it.

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
        from scipy.interpolate import PchipInterpolator

        curve = PchipInterpolator(np.asarray(self.tau), np.asarray(self.values))
        object.__setattr__(self, "_curve", (curve, curve.derivative()))

    @property
    def omega(self) -> float:  # type: ignore[override]
        """2 pi over the move's duration."""
        return 2.0 * math.pi / self.duration

    @property
    def duration(self) -> float:
        """The move's length [units of T]."""
        return self.tau[-1] - self.tau[0]

    def lam(self, tau: float) -> float:
        """Omega T at the instant tau (the end values outside the move)."""
        t = min(max(tau, self.tau[0]), self.tau[-1])
        return float(self._curve[0](t))

    def lam_dot(self, tau: float) -> float:
        """d lam / d tau at the instant tau (0 outside the move)."""
        if not self.tau[0] <= tau <= self.tau[-1]:
            return 0.0
        return float(self._curve[1](tau))

    def with_omega(self, omega: float) -> MoveLaw:
        """A move is not repeated: it has no rate to change."""
        raise ValueError("a single move has no repetition rate")

    def scaled(self, factor: float) -> MoveLaw:
        """The move's swing about its mean times `factor`."""
        m = self.mean
        return MoveLaw(self.tau, tuple(m + factor * (v - m) for v in self.values))
