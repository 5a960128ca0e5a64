r"""The beam as a PyElastica Cosserat rod: a third-party peer of rotbeam (tests only).

PyElastica (pyelastica, a test extra) integrates a 3-D Cosserat rod in the lab frame: it stretches,
shears and has rotary inertia, and its bending couple is B kappa / e^3 (e the Voronoi dilatation,
a rod that keeps its volume). Nothing of rotbeam's model is used to build it; rotbeam only gives
the beam's numbers and, to shorten the transient, the starting state (`start_from`).

Set-up (physical units, lab frame, the disk turning about e_z by phi(t),
Omega(t) = Omega_0 + a sin(2 pi f_d t), phi(0) = 0):

- n elements of length dx = L / (n - 1/2); node 0 sits dx/2 inside the clamp, at radius
  R_o - dx/2, so element 0 is centred on the clamp (radius R_o). `RotatingClamp` holds node 0 on
  its circle and element 0's directors turned by phi(t), values and rates. (With node 0 at the
  clamp the first half element cannot bend and every result converges only first-order in n.)
- Directors d1 = e_z, d3 = the tangent: in-plane bending is about d1. The rectangular section
  b x h is set by hand: B_11 = E b h^3 / 12, B_22 = E h b^3 / 12, rotary inertia rho I dx,
  shear k G A with Timoshenko's rectangle value k = 10 (1 + nu) / (12 + 11 nu) = 0.857 and
  G = E / 3 (rubber, nu = 1/2), axial EA; mass rho b h per reference length.
- `RotatingFrameDamping`: -gamma (v - Omega e_z x r) on each node's share of the reference length
  (rotbeam's damping acts on the velocity relative to the disk; PyElastica's own dampers act on
  the lab velocity and would drag against the rotation itself). Every mode then decays at the
  same rate gamma / (2 rho A) (0.833 / s for the Table 1 beam).
- PositionVerlet at dt <= dt_max(n) (2.5e-5 s at n = 40, 1e-5 s at n = 80; the axial and shear
  waves set it, so dt ~ dx), rounded so a drive period is a whole number of steps.
- y_m: the rod's point at reference arc length L/2 from the clamp (cubic interpolation in the
  reference arc length), in the disk's frame, over whole drive periods after the transient.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from elastica import (
    BaseSystemCollection,
    Constraints,
    CosseratRod,
    Forcing,
    NoForces,
    PositionVerlet,
)
from elastica.boundary_conditions import ConstraintBase
from scipy.interpolate import CubicSpline

from rotbeam.model.params import Beam

NU = 0.5  #: Poisson ratio of rubber (G = E / 3)
SHEAR_K = 10 * (1 + NU) / (12 + 11 * NU)  #: Timoshenko's shear coefficient of a rectangle


def dt_max(n: int, shear_scale: float = 1.0) -> float:
    """Largest stable PositionVerlet step [s] for the Table 1 beam with n elements (measured:
    2.5e-5 s at n = 40, 1e-5 s at n = 80). Below n = 40 it stays 2.5e-5 s: the shear-rotation
    mode, sqrt(k G A / (rho I)) = 3e4 rad/s whatever dx, blows up at 5e-5 s (n = 20). The axial
    waves set it (c = sqrt(E / rho)); shear `shear_scale` times stiffer makes the shear waves the
    faster, by sqrt(shear_scale k G / E) (1.69 at x 10), and the step shrinks by that, with a
    20 % margin."""
    base = 2.5e-5 if n <= 40 else 1e-5 * 80.0 / n
    return base / max(1.0, 1.2 * math.sqrt(shear_scale * SHEAR_K / (2 * (1 + NU))))


@dataclass(frozen=True)
class Drive:
    """Omega(t) = omega0 + a sin(2 pi f_d t) and its angle phi(t), phi(0) = 0."""

    omega0: float
    f_d: float
    a: float = 1.0

    def omega(self, t: float) -> float:
        return self.omega0 + self.a * math.sin(2 * math.pi * self.f_d * t)

    def phi(self, t: float) -> float:
        w = 2 * math.pi * self.f_d
        return self.omega0 * t + self.a / w * (1.0 - math.cos(w * t))


def _directors(psi: float) -> np.ndarray:
    """Rows d1 = e_z, d2 = d3 x d1, d3 = (cos psi, sin psi, 0)."""
    c, s = math.cos(psi), math.sin(psi)
    return np.array([[0.0, 0.0, 1.0], [s, -c, 0.0], [c, s, 0.0]])


class RotatingClamp(ConstraintBase):
    """Node 0 on the circle of radius r0 at angle phi(t); element 0's directors turned by phi."""

    def __init__(self, position0: np.ndarray, director0: np.ndarray, r0: float, drive: Drive,
                 **kwargs) -> None:  # fmt: skip
        super().__init__(**kwargs)  # PyElastica passes node 0's and element 0's start values
        self.r0 = r0
        self.drive = drive

    def constrain_values(self, system, time: np.float64) -> None:
        p = self.drive.phi(float(time))
        system.position_collection[:, 0] = (self.r0 * math.cos(p), self.r0 * math.sin(p), 0.0)
        system.director_collection[..., 0] = _directors(p)

    def constrain_rates(self, system, time: np.float64) -> None:
        p, w = self.drive.phi(float(time)), self.drive.omega(float(time))
        system.velocity_collection[:, 0] = (
            -w * self.r0 * math.sin(p),
            w * self.r0 * math.cos(p),
            0,
        )
        system.omega_collection[:, 0] = (w, 0.0, 0.0)


class RotatingFrameDamping(NoForces):
    """-gamma (v - Omega e_z x r) times each node's share of the reference length."""

    def __init__(self, gamma: float, share: np.ndarray, drive: Drive) -> None:
        super().__init__()
        self.c = gamma * share
        self.drive = drive

    def apply_forces(self, system, time: float = 0.0) -> None:
        vx, vy = _relative_velocity(system, self.drive.omega(float(time)))
        f = system.external_forces
        f[0] -= self.c * vx
        f[1] -= self.c * vy
        f[2] -= self.c * system.velocity_collection[2]


def _relative_velocity(system, w: float) -> tuple[np.ndarray, np.ndarray]:
    """The nodes' in-plane velocity relative to the disk turning at w: v - w e_z x r."""
    x, v = system.position_collection, system.velocity_collection
    return v[0] + w * x[1], v[1] - w * x[0]


class CancelCoriolis(NoForces):
    """+2 m Omega e_z x v_rel on each node (v_rel = v - Omega e_z x r, the velocity relative to the
    disk): the Coriolis force of the rod's own motion in the disk's frame is cancelled. rotbeam's
    stretch is quasi-static, so the rod without it is rotbeam's model in this respect (the
    like-for-like comparison; docs/model.md)."""

    def __init__(self, mass: np.ndarray, drive: Drive) -> None:
        super().__init__()
        self.two_m = 2.0 * mass
        self.drive = drive

    def apply_forces(self, system, time: float = 0.0) -> None:
        w = self.drive.omega(float(time))
        vx, vy = _relative_velocity(system, w)
        f = system.external_forces
        f[0] -= self.two_m * w * vy
        f[1] += self.two_m * w * vx


class _Sim(BaseSystemCollection, Constraints, Forcing):
    pass


@dataclass
class RodRun:
    """y_m / L over the RMS window and its RMS."""

    rms: float
    t: np.ndarray  #: sample instants [s]
    y_m: np.ndarray  #: y_m / L at the samples (disk frame)
    n: int
    dt: float
    seconds: float


def build_rod(beam: Beam, drive: Drive, n: int, shear_scale: float = 1.0,
              coriolis: bool = True):  # fmt: skip
    """The simulator, the rod and dx (see the module docstring). `shear_scale` multiplies the
    shear stiffness k G A; `coriolis=False` adds `CancelCoriolis`."""
    L, h, b, E, rho = beam.L, beam.h, beam.b, beam.E, beam.rho
    dx = L / (n - 0.5)
    r0 = (beam.R - L) - dx / 2
    A = b * h
    sim = _Sim()
    rod = CosseratRod.straight_rod(
        n, np.array([r0, 0.0, 0.0]), np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]),
        n * dx, math.sqrt(A / math.pi), rho, youngs_modulus=E, shear_modulus=E / (2 * (1 + NU)),
    )  # fmt: skip
    I1, I2 = b * h**3 / 12, h * b**3 / 12
    rod.bend_matrix[0, 0, :] = E * I1
    rod.bend_matrix[1, 1, :] = E * I2
    J = np.diag([rho * I1 * dx, rho * I2 * dx, rho * (I1 + I2) * dx])
    rod.mass_second_moment_of_inertia[...] = J[:, :, None]
    rod.inv_mass_second_moment_of_inertia[...] = np.linalg.inv(J)[:, :, None]
    G = E / (2 * (1 + NU))
    rod.shear_matrix[0, 0, :] = shear_scale * SHEAR_K * G * A
    rod.shear_matrix[1, 1, :] = shear_scale * SHEAR_K * G * A
    rod.shear_matrix[2, 2, :] = E * A
    sim.append(rod)
    sim.constrain(rod).using(
        RotatingClamp, r0=r0, drive=drive, constrained_position_idx=(0,),
        constrained_director_idx=(0,),
    )  # fmt: skip
    share = np.full(n + 1, dx)
    share[[0, -1]] = dx / 2
    sim.add_forcing_to(rod).using(RotatingFrameDamping, gamma=beam.gamma, share=share, drive=drive)
    if not coriolis:
        sim.add_forcing_to(rod).using(CancelCoriolis, mass=rod.mass.copy(), drive=drive)
    sim.finalize()
    return sim, rod, dx


def start_from(rod, beam: Beam, drive: Drive, s: np.ndarray, x: np.ndarray, y: np.ndarray,
               x_t: np.ndarray, y_t: np.ndarray) -> None:  # fmt: skip
    """Put the rod on a shape given in the disk's frame at t = 0 (phi = 0): s the reference arc
    length from the clamp, x, y relative to the clamp (all by L), x_t, y_t their rates [1/s]
    relative to the disk. Directors follow the element chords; rates add Omega(0) e_z x r."""
    L = beam.L
    n = rod.n_elems
    dx = L / (n - 0.5)
    sig = (np.arange(n + 1) * dx - dx / 2) / L  # reference arc length of the nodes, by L
    inside = sig < 0
    fx, fy, gx, gy = (CubicSpline(s, u)(np.clip(sig, 0, None)) for u in (x, y, x_t, y_t))
    fx[inside], fy[inside], gx[inside], gy[inside] = sig[inside], 0.0, 0.0, 0.0
    X, Y = (beam.R - L) + L * fx, L * fy
    w = drive.omega(0.0)
    pos = rod.position_collection
    pos[0], pos[1], pos[2] = X, Y, 0.0
    vel = rod.velocity_collection
    vel[0], vel[1], vel[2] = L * gx - w * Y, L * gy + w * X, 0.0
    dX, dY = np.diff(X), np.diff(Y)
    dVx, dVy = np.diff(L * gx), np.diff(L * gy)
    psi = np.arctan2(dY, dX)
    psi_t = (dX * dVy - dY * dVx) / (dX**2 + dY**2)
    psi[0], psi_t[0] = 0.0, 0.0
    for i in range(n):
        rod.director_collection[..., i] = _directors(psi[i])
    rod.omega_collection[0] = psi_t + w
    rod.omega_collection[1:] = 0.0


def midpoint(rod, beam: Beam, drive: Drive, t: float) -> float:
    """y_m / L in the disk's frame: the point at reference arc length L/2 from the clamp."""
    L = beam.L
    n = rod.n_elems
    dx = L / (n - 0.5)
    q = (L / 2 + dx / 2) / dx  # node coordinate of the material midpoint
    j = int(q) - 1
    nodes = np.arange(j, j + 4)
    p = drive.phi(t)
    X, Y = rod.position_collection[0, nodes], rod.position_collection[1, nodes]
    yr = -math.sin(p) * X + math.cos(p) * Y
    # cubic Lagrange interpolation in the node coordinate
    wts = np.array([np.prod([(q - nodes[m]) / (nodes[k] - nodes[m]) for m in range(4) if m != k])
                    for k in range(4)])  # fmt: skip
    return float(wts @ yr) / L


def match_couple(rod) -> None:
    """Multiply B by the cube of the Voronoi dilatation of the rod's current shape, frozen: the
    couple B kappa / e^3 becomes B kappa, rotbeam's m = EI theta_s (moment per reference-length
    curvature, section unchanged). For a start on the stretched steady shape."""
    lengths = np.linalg.norm(np.diff(rod.position_collection, axis=1), axis=0)
    e_v = (lengths[1:] + lengths[:-1]) / (rod.rest_lengths[1:] + rod.rest_lengths[:-1])
    rod.bend_matrix[...] *= (e_v**3)[None, None, :]


def run(beam: Beam, drive: Drive, n: int, transient: float, periods: int = 1,
        samples: int = 64, start=None, dt: float | None = None,
        matched: bool = False, shear_scale: float = 1.0,
        coriolis: bool = True) -> RodRun:  # fmt: skip
    """Integrate for `transient` seconds (rounded up to whole drive periods), then sample y_m at
    `samples` instants per period over `periods` periods. `start(rod)` sets the initial state
    (default: the straight rod turning rigidly at Omega(0)); `matched` then applies
    `match_couple`; `shear_scale` and `coriolis` go to `build_rod`."""
    t0 = time.perf_counter()
    sim, rod, _ = build_rod(beam, drive, n, shear_scale, coriolis)
    w = drive.omega(0.0)
    rod.velocity_collection[0] = -w * rod.position_collection[1]
    rod.velocity_collection[1] = w * rod.position_collection[0]
    rod.omega_collection[0] = w
    if start is not None:
        start(rod)
    if matched:
        match_couple(rod)
    P = 1.0 / drive.f_d
    q = math.ceil(P / samples / (dt or dt_max(n, shear_scale)))
    step = P / samples / q
    k_tr = math.ceil(transient / P - 1e-9)
    stepper = PositionVerlet()
    t = 0.0
    for _ in range(k_tr * samples * q):
        t = stepper.step(sim, t, step)
    ts, ys = [], []
    for _ in range(periods * samples):
        ts.append(t)
        ys.append(midpoint(rod, beam, drive, t))
        for _ in range(q):
            t = stepper.step(sim, t, step)
    y = np.array(ys)
    if not np.all(np.isfinite(y)):
        raise FloatingPointError(f"PyElastica run blew up (n = {n}, dt = {step:.3g} s)")
    return RodRun(float(np.sqrt(np.mean(y * y))), np.array(ts), y, n, step,
                  time.perf_counter() - t0)  # fmt: skip
