"""
Damping from a ring-down
========================

The model's damping gamma (viscous, per unit length, in N s/m^2) is the input a rig knows least.
A ring-down gives it: pluck the beam, record its free decay, and fit a damped oscillation,
gamma = 2 rho A / t_decay (App. B; ``rotbeam damping FILE.csv`` on the command line).

Here the record is synthetic, and made by a different model than the one fitted: the closed-form
free decay of a damped harmonic oscillator released from rest, plus an offset and noise.  Its
gamma is known, so the fit can be checked against it.
"""

import math
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import rotbeam
from rotbeam.analysis.measurements import load_ringdown
from rotbeam.analysis.ringdown import fit_ringdown

# %%
# The record
# ----------
# An oscillator m x'' + c x' + k x = 0 released from x(0) = x_0 at rest decays as::
#
#     x(t) = x_0 exp(-s t) (cos w_d t + (s / w_d) sin w_d t),   w_d = sqrt(w_n^2 - s^2),
#
# with the amplitude decay rate s = 1 / t_decay.  For the Table 1 beam (rho A = 0.0234 kg/m) and
# gamma = 0.039 N s/m^2, s = gamma / (2 rho A) = 0.83 1/s.  The record: 3 s at 200 samples/s of
# a 6.4 Hz decay from 2 mm, a 0.1 mm offset and white noise of 0.1 mm (5 % of x_0).

beam = rotbeam.Beam()
gamma_true = 0.039  # N s/m^2, what the record is made with
s = gamma_true / (2.0 * beam.rhoA)
w_n = 2.0 * math.pi * 6.4
w_d = math.sqrt(w_n**2 - s**2)
t = np.arange(0.0, 3.0, 1.0 / 200.0)
x = 2.0 * np.exp(-s * t) * (np.cos(w_d * t) + s / w_d * np.sin(w_d * t))
rng = np.random.default_rng(0)
y = x + 0.1 + 0.1 * rng.standard_normal(t.size)

# %%
# The fit
# -------
# ``load_ringdown`` reads and checks a CSV file with columns t [s] and y (any unit), the file
# ``rotbeam damping`` takes; ``fit_ringdown`` fits the decay by nonlinear least squares and
# gives gamma for the beam's rho A, with a standard error from the Jacobian and the residual
# variance.  The 95 % interval is gamma +- 1.96 standard errors.

with tempfile.TemporaryDirectory() as tmp:
    path = Path(tmp) / "ringdown.csv"
    np.savetxt(path, np.column_stack([t, y]), delimiter=",", header="t,y", comments="")
    record = load_ringdown(path)
fit = fit_ringdown(record, beam)
low, high = fit.gamma - 1.96 * fit.gamma_stderr, fit.gamma + 1.96 * fit.gamma_stderr

print(
    f"f = {fit.f_hz:.4f} +- {fit.f_hz_stderr:.2g} Hz, t_decay = {fit.t_decay:.4f} "
    f"+- {fit.t_decay_stderr:.2g} s, SNR {fit.snr:.0f}, {fit.cycles:.1f} cycles"
)
print(f"gamma = {fit.gamma:.5f} +- {fit.gamma_stderr:.2g} N s/m^2 (zeta = {fit.zeta:.4f})")
# one line for tests/test_tutorial.py, which checks that the interval holds gamma_true
print(
    f"calibration: gamma_true={gamma_true:.6g} gamma_fit={fit.gamma:.6g} "
    f"ci95_low={low:.6g} ci95_high={high:.6g}"
)

# %%
# The record, the fitted curve, and gamma against the gamma the record was made with:

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(7.6, 3.6), width_ratios=(3, 1), layout="constrained")
ax1.plot(t, y, ".", color="0.6", ms=2.5, label="record (with noise)")
ax1.plot(t, fit.curve(t, t[0]), color="C0", lw=1.2, label="fit")
ax1.set_xlabel("time t [s]")
ax1.set_ylabel("deflection y [mm]")
ax1.set_ylim(y.min() - 0.1, y.max() + 0.5 * np.ptp(y))  # room for the legend
ax1.legend(loc="upper right", ncol=2)
ax2.errorbar(
    [0],
    [fit.gamma],
    yerr=[[fit.gamma - low], [high - fit.gamma]],
    fmt="o",
    color="C0",
    capsize=5,
    label="fit, 95 %",
)
ax2.axhline(gamma_true, color="C3", ls="--", label="made with")
ax2.set_xlim(-1.0, 1.0)
ax2.set_xticks([])
ax2.set_ylabel("gamma [N s/m^2]")
ax2.legend(loc="lower center", fontsize="small")
bottom, top = min(low, gamma_true), max(high, gamma_true)
ax2.set_ylim(bottom - 0.9 * (top - bottom), top + 0.3 * (top - bottom))  # legend below
plt.show()
