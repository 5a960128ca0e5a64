"""Damping from a ring-down (App. B): fit a damped oscillation, gamma = 2 rho A / t_decay.

    y(t) = exp(-(t - t0) / t_decay) (B1 cos w(t - t0) + B2 sin w(t - t0)) + c

by nonlinear least squares, with standard errors from the Jacobian; a record that cannot carry
the fit is refused (`RingdownRejected`) rather than reported (`rotbeam damping`).  The start, the
errors and the reasons for refusal: docs/calibration.md, "Damping from a ring-down".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares
from scipy.signal import hilbert

from ..model.params import Beam
from .measurements import Ringdown

MIN_CYCLES = 3.0
MIN_SNR = 3.0  #: initial amplitude over the residual's standard deviation
MAX_REL_STDERR = 0.25  #: on gamma (and t_decay)
MIN_Q = 0.5  #: pi f t_decay: below it the "oscillation" decays within a sixth of a cycle


class RingdownRejected(Exception):
    """The record does not support a trustworthy fit; the message says why (one line)."""


@dataclass(frozen=True)
class RingdownFit:
    """The fitted damped oscillation of a ring-down, gamma for the beam, and the fit's quality.

    Every value has its standard error (``*_stderr``) from the Jacobian and the residual
    variance.  ``f_hz`` is the oscillation's frequency [Hz]; ``zeta`` is dimensionless; ``snr``
    is the initial amplitude over the residual's standard deviation; ``cycles`` the record's
    length in cycles; ``rhoA`` the beam's mass per length [kg/m], taken as exact.
    """

    f_hz: float
    f_hz_stderr: float
    t_decay: float  #: amplitude decay time [s]
    t_decay_stderr: float
    amplitude: float  #: at the first sample (units of y)
    amplitude_stderr: float
    phase: float  #: [rad], y - c = A exp(-s t') cos(w t' + phase)
    phase_stderr: float
    offset: float
    offset_stderr: float
    gamma: float  #: 2 rho A / t_decay [N s / m^2]
    gamma_stderr: float
    zeta: float  #: damping ratio s / sqrt(s^2 + w^2) of the fitted oscillation
    snr: float
    cycles: float
    residual_std: float
    points: int
    rhoA: float

    def as_dict(self) -> dict[str, float | int]:
        """The fit as JSON-ready fields (`rotbeam damping --json`).

        Returns
        -------
        dict
            Every field by name.
        """
        return dict(vars(self))

    def curve(self, t: np.ndarray, t0: float) -> np.ndarray:
        """The fitted oscillation at times `t`, for drawing it over the record.

        Parameters
        ----------
        t : numpy.ndarray
            Times [s].
        t0 : float
            The record's first time [s], where the fit's amplitude and phase hold.

        Returns
        -------
        numpy.ndarray
            y(t) in the record's unit: A exp(-(t - t0) / t_decay) cos(w (t - t0) + phase) + c.
        """
        tt = np.asarray(t) - t0
        w = 2.0 * math.pi * self.f_hz
        return (
            self.amplitude * np.exp(-tt / self.t_decay) * np.cos(w * tt + self.phase) + self.offset
        )


def _model(p: np.ndarray, tt: np.ndarray) -> np.ndarray:
    f, s, b1, b2, c = p
    w = 2.0 * math.pi * f
    return np.exp(-s * tt) * (b1 * np.cos(w * tt) + b2 * np.sin(w * tt)) + c


def _jac(p: np.ndarray, tt: np.ndarray) -> np.ndarray:
    f, s, b1, b2, _ = p
    w = 2.0 * math.pi * f
    e, co, si = np.exp(-s * tt), np.cos(w * tt), np.sin(w * tt)
    osc = b1 * co + b2 * si
    return np.column_stack(
        [
            e * (-b1 * si + b2 * co) * 2.0 * math.pi * tt,
            -tt * e * osc,
            e * co,
            e * si,
            np.ones_like(tt),
        ]  # fmt: skip
    )


def _half_cycles(y: np.ndarray, level: float, band: float) -> int:
    """Crossings of y through `level` with hysteresis +-band (noise does not count)."""
    state, changes = 0, 0
    for v in y - level:
        new = 1 if v > band else (-1 if v < -band else state)
        if state and new != state:
            changes += 1
        state = new
    return changes


def _noise_std(y: np.ndarray) -> float:
    """Noise from second differences (the smooth signal's are tiny when well sampled)."""
    d2 = np.diff(y, 2)
    return float(1.4826 * np.median(np.abs(d2 - np.median(d2))) / math.sqrt(6.0))


def _start(tt: np.ndarray, y: np.ndarray, c0: float) -> np.ndarray:
    """(f, s, B1, B2, c) from the FFT peak and the log-envelope slope."""
    n = tt.size
    dt = float(tt[1] - tt[0])
    pad = 8 * (1 << int(math.ceil(math.log2(n))))
    spec = np.abs(np.fft.rfft((y - y.mean()) * np.hanning(n), pad))
    freq = np.fft.rfftfreq(pad, dt)
    k = int(np.argmax(spec[1:])) + 1
    if 1 <= k < spec.size - 1:  # parabolic interpolation of the peak
        a, b, c = np.log(spec[k - 1 : k + 2] + 1e-300)
        k = k + 0.5 * (a - c) / (a - 2 * b + c) if a - 2 * b + c != 0 else k
    f = float(k * (freq[1] - freq[0]))
    env = np.abs(hilbert(y - c0))
    lo, hi = n // 10, n - n // 10  # the envelope's ends are spoilt by the transform
    keep = np.arange(lo, hi)
    keep = keep[env[keep] > 3.0 * _noise_std(y)] if keep.size else keep
    if keep.size >= 3:
        slope, icpt = np.polyfit(tt[keep], np.log(env[keep]), 1)
        s, a0 = max(-float(slope), 0.0), math.exp(icpt)
    else:
        s, a0 = 1.0 / max(tt[-1], dt), float(np.max(np.abs(y - c0)))
    # phase by linear least squares at the start's f and s
    w = 2.0 * math.pi * f
    basis = np.column_stack([np.exp(-s * tt) * np.cos(w * tt), np.exp(-s * tt) * np.sin(w * tt),
                             np.ones_like(tt)])  # fmt: skip
    coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
    if not np.all(np.isfinite(coef)):
        coef = np.array([a0, 0.0, c0])
    return np.array([f, s, coef[0], coef[1], coef[2]])


def fit_ringdown(data: Ringdown, beam: Beam | None = None) -> RingdownFit:
    """Fit a damped oscillation to a ring-down and give gamma = 2 rho A / t_decay for the beam.

    Nonlinear least squares started from the FFT peak and the log Hilbert envelope; a record
    that cannot carry the fit is refused rather than reported (docs/calibration.md, "Damping
    from a ring-down").

    Parameters
    ----------
    data : Ringdown
        The record: times t [s] and deflection y (any unit), checked by `load_ringdown`.
    beam : Beam or None
        The beam whose rho A turns the decay time into gamma (default: Table 1).

    Returns
    -------
    RingdownFit
        Frequency [Hz], decay time [s], amplitude, phase [rad], offset, gamma [N s/m^2] and
        zeta, each with its standard error, and the fit's quality.

    Raises
    ------
    RingdownRejected
        If the record cannot carry the fit: no oscillation, too few cycles, no decay
        distinguishable from zero, overdamped, or too noisy (the message says which).
    """
    beam = beam or Beam()
    t, y = np.asarray(data.t, float), np.asarray(data.y, float)
    tt = t - t[0]
    duration = float(tt[-1])
    noise0 = _noise_std(y)
    c0 = float(np.median(y[-max(3, y.size // 4) :]))
    halves = _half_cycles(y, c0, max(3.0 * noise0, 1e-12 * np.ptp(y)))
    if halves < 2:
        head = y[: max(3, y.size // 4)] - c0  # the first quarter, where a ring-down is largest
        signal = float(np.sqrt(np.mean(head**2)))
        if signal < 2.0 * noise0:
            raise RingdownRejected(
                f"too noisy: the first quarter's RMS about the final value ({signal:.3g}) is "
                f"within twice the noise level ({noise0:.3g}, from second differences)"
            )
        raise RingdownRejected(
            f"no oscillation: y crosses its final value {c0:.4g} {halves} time(s) over "
            f"{duration:.4g} s (overdamped, or a record shorter than one cycle); nothing to fit"
        )
    p0 = _start(tt, y, c0)
    sol = least_squares(lambda p: _model(p, tt) - y, p0, jac=lambda p: _jac(p, tt),
                        method="lm", x_scale="jac")  # fmt: skip
    return _assess(sol, tt, y, duration, beam)


def _assess(sol, tt: np.ndarray, y: np.ndarray, duration: float, beam: Beam) -> RingdownFit:
    """Standard errors from the Jacobian and the residual variance; refuse what cannot be
    trusted (see the module docstring)."""
    f, s, b1, b2, c = sol.x
    J = sol.jac
    if f < 0:  # the same curve with w -> -w, B2 -> -B2, and its Jacobian's columns with them
        f, b2 = -f, -b2
        J = J * np.array([-1.0, 1.0, 1.0, -1.0, 1.0])
    n, p = y.size, 5
    rss = float(np.sum(sol.fun**2))
    s2 = rss / (n - p)
    try:
        cov = s2 * np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov = np.full((p, p), np.inf)
    se = np.sqrt(np.clip(np.diag(cov), 0.0, np.inf))
    amp = math.hypot(b1, b2)
    cycles = f * duration
    if not sol.success or not np.all(np.isfinite(sol.x)):
        raise RingdownRejected(f"the least-squares fit did not converge: {sol.message}")
    if cycles < MIN_CYCLES:
        raise RingdownRejected(
            f"too short: the record covers {cycles:.2g} cycles of the fitted {f:.4g} Hz; "
            f"allowed: >= {MIN_CYCLES:g} cycles"
        )
    if not s - 2.0 * se[1] > 0:
        raise RingdownRejected(
            f"not decaying: decay rate 1/t_decay = {s:.3g} +- {se[1]:.2g} 1/s is not "
            f"distinguishable from 0 over {duration:.4g} s (a longer record, or not a ring-down)"
        )
    q = math.pi * f / s
    if q < MIN_Q:
        raise RingdownRejected(
            f"overdamped: pi f t_decay = {q:.2g} < {MIN_Q:g} (f {f:.3g} Hz, t_decay "
            f"{1 / s:.3g} s): no oscillation to fit"
        )
    resid_std = math.sqrt(s2)
    snr = amp / resid_std if resid_std > 0 else math.inf
    rel = se[1] / s
    if snr < MIN_SNR or rel > MAX_REL_STDERR:
        raise RingdownRejected(
            f"too noisy: SNR {snr:.3g} (allowed >= {MIN_SNR:g}), relative standard error of "
            f"gamma {rel:.2g} (allowed <= {MAX_REL_STDERR:g})"
        )
    # A and phase from B1 = A cos(phi), B2 = -A sin(phi), by the delta method
    g_amp = np.array([b1, b2]) / amp
    g_ph = np.array([b2, -b1]) / amp**2
    c22 = cov[2:4, 2:4]
    rhoA = beam.rhoA
    return RingdownFit(
        f_hz=f, f_hz_stderr=float(se[0]), t_decay=1.0 / s, t_decay_stderr=float(se[1] / s**2),
        amplitude=amp, amplitude_stderr=float(math.sqrt(max(g_amp @ c22 @ g_amp, 0.0))),
        phase=math.atan2(-b2, b1), phase_stderr=float(math.sqrt(max(g_ph @ c22 @ g_ph, 0.0))),
        offset=float(c), offset_stderr=float(se[4]), gamma=2.0 * rhoA * s,
        gamma_stderr=float(2.0 * rhoA * se[1]), zeta=s / math.hypot(s, 2.0 * math.pi * f), snr=snr,
        cycles=cycles, residual_std=resid_std, points=n, rhoA=rhoA,
    )  # fmt: skip
