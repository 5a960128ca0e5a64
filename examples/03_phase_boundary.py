"""
The phase boundary of your own beam
===================================

Where does the quasi-static model stop being good enough for a beam of your own?  Here a
10 cm steel strip (0.5 mm thick, 10 mm wide) clamped on a hub of 30 cm radius, so its tip
turns at R = 40 cm, with a damping ratio of about 1 %.  At a handful of mean speeds Omega_0
``rotbeam.critical`` finds f_d*, the drive frequency at which Delta RMS reaches 0.10; below it
the quasi-static answer is good enough, above it inertia matters.
"""

import matplotlib.pyplot as plt
import numpy as np

import rotbeam

# %%
# The beam
# --------
# SI units throughout: E = 200 GPa and rho = 7850 kg/m^3 for steel; gamma, the viscous damping
# per unit length, is chosen for a damping ratio zeta of 1 % (measure yours from a ring-down:
# the last example).

strip = rotbeam.Beam(L=0.10, h=0.5e-3, b=10e-3, E=200e9, rho=7850.0, R=0.40, gamma=0.20)
print(f"first natural frequency at rest f_n = {strip.f_n:.2f} Hz, zeta = {strip.zeta:.4f}")
print(f"hub ratio R_o / L = {strip.hub_ratio:.1f}, G = rho A R L^3 / (E I) = {strip.G:.3g} s^2")

# %%
# f_d* at six speeds
# ------------------
# The drive's speed amplitude is a = 1 rad/s at every speed.  N = 20: on this beam f_d* moves by
# 0.07-0.1 % between N = 20 and N = 40, below the search's tolerance of 0.1 %; each search costs
# four or five runs of the full model.

speeds = np.array([0.0, 25.0, 50.0, 100.0, 150.0, 200.0])  # Omega_0 [rad/s]
numerics = rotbeam.Numerics(N=20)
searches = []
for omega0 in speeds:
    scene = rotbeam.Scene(strip, rotbeam.Drive(omega0=omega0, amplitude=1.0), numerics=numerics)
    searches.append(rotbeam.critical(scene, threshold=0.10))
assert all(s.found for s in searches), [s.message for s in searches if not s.found]

print(" Omega_0 [rad/s]   f_0 [Hz]   f_d* [Hz]   c = f_d*/f_0   runs")
for omega0, s in zip(speeds, searches, strict=True):
    print(
        f"{omega0:16.0f} {s.f0_hz:10.2f} {s.f_d_star:11.3f} {s.f_d_star / s.f0_hz:14.4f} "
        f"{len(s.visited):6d}"
    )
print(f"total cost: {sum(s.seconds for s in searches):.2f} s")

# %%
# Centrifugal stiffening raises the first in-plane frequency f_0 (at Omega_0 + a) from 41 Hz
# at rest to 81 Hz at 200 rad/s, and f_d* follows it: the ratio c = f_d*/f_0 stays near
# sqrt(0.10) = 0.316, App. E's value for a lightly damped oscillator.
#
# The phase diagram
# -----------------

fd_star = np.array([s.f_d_star for s in searches])
f0 = np.array([s.f0_hz for s in searches])
fig, ax = plt.subplots(figsize=(6.4, 4.2), layout="constrained")
top = 1.15 * f0.max()
ax.fill_between(speeds, 0.0, fd_star, color="C2", alpha=0.15, lw=0)
ax.fill_between(speeds, fd_star, top, color="C3", alpha=0.10, lw=0)
ax.plot(speeds, fd_star, "o-", color="C2", label="f_d*, full model (Delta RMS = 0.10)")
ax.plot(speeds, f0, "^--", color="0.4", ms=5, label="f_0, first in-plane frequency")
ax.text(100.0, 0.45 * fd_star[3], "quasi-static is good enough", ha="center", color="C2")
ax.text(100.0, 0.5 * (fd_star[3] + f0[3]), "dynamic: inertia matters", ha="center", color="C3")
ax.set_xlim(speeds[0], speeds[-1])
ax.set_ylim(0.0, top)
ax.set_xlabel("mean angular velocity Omega_0 [rad/s]")
ax.set_ylabel("drive frequency f_d [Hz]")
ax.set_title("10 cm steel strip on a 30 cm hub, a = 1 rad/s")
ax.legend(loc="upper left")
plt.show()
