"""A payload at the free end (beam.tip_mass, beam.tip_inertia) against independent answers: the
tip-loaded cantilever's characteristic equation at rest, the tests' rigid-link chain extended by
a tip mass under rotation and in statics, and the bare beam unchanged when the payload is 0."""

from __future__ import annotations

import math

import numpy as np
import pytest
from chain_model import ChainModel
from scipy.optimize import brentq

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.modes import damping_ratio, dimensionless_frequencies, modes
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects, damped_mass_share
from rotbeam.model.surrogate import SurrogateModel, analytical_boundary
from rotbeam.runs.scene import Scene, build_scene, simulate
from rotbeam.solve.numerics import Numerics
from rotbeam.solve.quasistatic import solve_static

HUB = 2.875


def characteristic_root(mu: float, j: float = 0.0) -> float:
    """First root of 1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b)
    - j b^3 (sin b cosh b + cos b sinh b) + mu j b^4 (1 - cos b cosh b) = 0 (Blevins,
    table 8-1), bracketed by hand below the bare beam's 1.8751."""

    def f(b: float) -> float:
        c, ch, s, sh = math.cos(b), math.cosh(b), math.sin(b), math.sinh(b)
        return (1 + c * ch + mu * b * (c * sh - s * ch) - j * b**3 * (s * ch + c * sh)
                + mu * j * b**4 * (1 - c * ch))  # fmt: skip

    return brentq(f, 0.5, 1.8751040687119611, xtol=1e-15)


def richardson(coarse: float, fine: float, order: int = 2) -> float:
    q = 2.0**order
    return (q * fine - coarse) / (q - 1.0)


def test_the_characteristic_root_is_the_published_one():
    assert characteristic_root(0.5) == pytest.approx(1.4200, abs=5e-5)  # mass ratio 0.5
    assert characteristic_root(1.0) == pytest.approx(1.24792, abs=1e-5)


@pytest.mark.parametrize("mu", [0.5, 2.0])
def test_tip_mass_at_rest_is_the_characteristic_equation(mu):
    """Second order in 1/N (errors at N = 80 and 160 in the ratio 4), Richardson within 1e-6."""
    exact = characteristic_root(mu) ** 2
    w = [dimensionless_frequencies(0.0, HUB, 1, N, True, None, mu)[0] for N in (80, 160)]
    errors = [abs(x / exact - 1) for x in w]
    assert 3.5 < errors[0] / errors[1] < 4.5
    assert richardson(*w) == pytest.approx(exact, rel=1e-6)


def test_tip_inertia_at_rest_converges_at_first_order():
    """The rotary inertia acts on the last angle's row: first order in 1/N (docs/model.md)."""
    j = 0.1
    exact = characteristic_root(0.0, j) ** 2
    w = [dimensionless_frequencies(0.0, HUB, 1, N, True, None, 0.0, j)[0] for N in (40, 80, 160)]
    errors = [abs(x / exact - 1) for x in w]
    assert all(1.8 < errors[k] / errors[k + 1] < 2.2 for k in range(2))
    assert richardson(w[1], w[2], order=1) == pytest.approx(exact, rel=2e-5)


def test_physical_beam_with_a_payload_has_the_loaded_first_frequency():
    beam = Beam()
    m = 0.5 * beam.rhoA * beam.L  # 4.68e-4 kg
    loaded = Beam(tip_mass=m)
    f_s = math.sqrt(beam.EI / (beam.rhoA * beam.L**4)) / (2 * math.pi)
    assert loaded.f_n == pytest.approx(characteristic_root(0.5) ** 2 * f_s, rel=1e-12)
    assert modes(loaded, 0.0, 1, N=160)[0] == pytest.approx(loaded.f_n, rel=2e-5)


@pytest.mark.parametrize("lam", [3.0, 8.0])
def test_tip_mass_under_rotation_against_the_chain(lam):
    """In-plane first frequency at Omega T = lam, both discretisations extrapolated from
    N = 80 and 160 (second order): equal to 2e-6 (measured 4e-8 and 8e-7)."""
    mu = 0.5
    chain = [ChainModel(n, 1 / (1 + HUB), eta=0.0, damping=False, tip_mass=mu).linear_modes(lam)[0]
             for n in (80, 160)]  # fmt: skip
    ours = [dimensionless_frequencies(lam, HUB, 1, N, True, None, mu)[0] for N in (80, 160)]
    assert richardson(*ours) == pytest.approx(richardson(*chain), rel=2e-6)
    bare = dimensionless_frequencies(lam, HUB, 1, 160, True)[0]
    assert richardson(*ours) < 0.95 * bare  # and the payload matters (11-16 % lower here)


def test_tip_mass_static_deflection_against_the_chain():
    """The payload's centrifugal and Euler loads: the static tip deflection under (lam,
    lam_dot) = (3, 20) against the chain's statics, both extrapolated (measured 3e-6)."""
    mu, lam, lam_dot = 0.5, 3.0, 20.0
    chain = []
    for n in (80, 160):
        model = ChainModel(n, 1 / (1 + HUB), eta=0.0, damping=False, tip_mass=mu)
        chain.append(model.nodes(model.static_angles(lam, lam_dot))[1][-1])
    ours = []
    for N in (80, 160):
        dl = Dimensionless(HUB, 0.0, lam, 0.0, 1.0, tip_mass=mu)
        m = DiscreteElastica(dl, N)
        res = solve_static(m, lam, lam_dot)
        assert res.converged
        ours.append(m.tip(res.theta)[1])
    assert richardson(*ours) == pytest.approx(richardson(*chain), rel=2e-5)


def test_no_payload_is_the_bare_beam_bit_for_bit():
    drive = {"omega0": 10.0, "f_d": 1.5}
    bare = simulate(build_scene({"drive": drive, "numerics": {"N": 12}}))
    zero = simulate(
        build_scene(
            {"beam": {"tip_mass": 0.0, "tip_inertia": 0.0}, "drive": drive, "numerics": {"N": 12}}
        )  # fmt: skip
    )
    assert zero.rms_dynamic == bare.rms_dynamic and zero.rms_quasistatic == bare.rms_quasistatic
    assert zero.dynamic.floquet.max_abs == bare.dynamic.floquet.max_abs


def test_surrogate_with_a_payload_bounds_the_frequency_from_above():
    """The one-mode surrogate (the bare beam's mode as trial function) is a Rayleigh quotient:
    above the exact loaded frequency, within 1 % at mu = 0.5 (measured +0.7 %)."""
    dl = Dimensionless(HUB, 0.0, 0.0, 0.0, 1.0, tip_mass=0.5)
    w = SurrogateModel.from_dimensionless(dl).frequency(0.0)
    exact = characteristic_root(0.5) ** 2
    assert exact < w < 1.01 * exact


def test_a_payload_in_a_scene_and_its_verdict():
    """A simulated scene with the payload of 0.5 rho A L reaches its steady state, and the
    payload lowers f_0 (the linear estimate's anchor) as the modes say."""
    beam = Beam(tip_mass=0.5 * Beam().rhoA * Beam().L)
    res = simulate(Scene(beam, Drive(omega0=10.0, f_d=1.5), numerics=Numerics(N=16)))
    assert res.converged and res.dynamic.floquet.stable
    assert res.summary()["f_n_hz"] == pytest.approx(beam.f_n)
    assert np.isfinite(res.delta_rms) and 0 < res.delta_rms < 1


@pytest.mark.parametrize("payload", [{"tip_mass": 0.5}, {"tip_inertia": 0.05},
                                     {"tip_mass": 0.5, "tip_inertia": 0.05}])  # fmt: skip
def test_the_damping_acts_on_the_beam_alone(payload):
    """A payload adds mass, not damping: the damped mass matrix of a beam with a payload is the
    bare beam's mass matrix (built without one), at any shape."""
    theta = np.random.default_rng(3).normal(0.0, 0.4, (2, 19))
    eff = Dimensionless(HUB, 0.0, 0.5, 0.0, 1.0).effects
    loaded = DiscreteElastica(Dimensionless(HUB, 0.0, 0.5, 0.0, 1.0, eff, None, None,
                                            payload.get("tip_mass", 0.0),
                                            payload.get("tip_inertia", 0.0)), 20)  # fmt: skip
    bare = DiscreteElastica(Dimensionless(HUB, 0.0, 0.5, 0.0, 1.0), 20)
    Md, Bd = loaded.damping_rows(theta)
    M, B = bare.inertia_rows(theta)
    assert np.array_equal(Md, M) and np.array_equal(Bd, B)


def damped_decay_ratio(beam: Beam, N: int) -> float:
    """-Re lam / |lam| of the discrete model's first damped eigenvalue at rest: the linearised
    model about the straight beam, lam^2 M + lam eta Md + K = 0 (Md the beam's own mass, no
    payload), solved as the pencil [0 I; -K -eta Md] - lam [I 0; 0 M] (no M^-1 K, whose
    round-off reaches 1e-4 at N = 160)."""
    import scipy.linalg as sla

    dl = Dimensionless.from_physical(beam, Drive(omega0=0.0, amplitude=0.0, f_d=1.0),
                                     Effects())  # fmt: skip
    model = DiscreteElastica(dl, N)
    M, K, _ = model.linear_operators(0.0)
    Md = model.damping_rows(np.zeros((1, model.n)))[0][0]
    eye, zero = np.eye(model.n), np.zeros((model.n, model.n))
    lam = sla.eigvals(np.block([[zero, eye], [-K, -beam.eta * Md]]),
                      np.block([[eye, zero], [zero, M]]))  # fmt: skip
    lam = lam[np.isfinite(lam)]
    first = lam[np.argmin(np.abs(lam))]
    return float(-first.real / abs(first))


@pytest.mark.parametrize(
    "mu, j, gamma, tol",
    [
        # tip mass: second-order scheme, Richardson to ~1e-6; zeta^2 ~ 1e-6 (first order in eta)
        (0.5, 0.0, 0.0039, 1e-5),
        (2.0, 0.0, 0.0039, 1e-5),
        # the default damping: the first-order formula's error is O(zeta^2) = 1.3e-4 at most
        (0.5, 0.0, 0.039, 1e-5 + 0.0115**2),
        # rotary inertia: first-order scheme, its extrapolation leaves O(N^-2) ~ 1e-4
        (0.0, 0.05, 0.0039, 2e-4),
        (0.5, 0.05, 0.0039, 2e-4),
    ],
)
def test_zeta_with_a_payload_is_the_discrete_models_decay(mu, j, gamma, tol):
    """Beam.zeta = eta s / (2 b^2) (the closed-form tip-loaded mode) against the decay of the
    discrete model's first damped eigenvalue, extrapolated from N = 80 and 160 at the scheme's
    order (2 for a tip mass, 1 with a rotary inertia): damping on the beam only.  The payload
    matters: the damped share s is 0.11-0.65 here, so eta / (2 b^2) alone is off by 50-800 %."""
    bare = Beam()
    beam = Beam(tip_mass=mu * bare.rhoA * bare.L, tip_inertia=j * bare.rhoA * bare.L**3,
                gamma=gamma)  # fmt: skip
    order = 1 if j else 2
    decay = richardson(damped_decay_ratio(beam, 80), damped_decay_ratio(beam, 160), order)
    assert beam.zeta == pytest.approx(decay, rel=tol)
    assert damping_ratio(beam) == beam.zeta  # what the verdict reads
    b = characteristic_root(mu, j)
    assert beam.zeta < beam.eta / (2 * b * b) * 0.7


@pytest.mark.parametrize(
    ("mu", "j", "static", "stiffness"),
    [(1e3, 0.0, 33 / 140, 3.0), (1e4, 0.0, 33 / 140, 3.0), (0.0, 1e3, 1 / 20, 1.0),
     (0.0, 1e4, 1 / 20, 1.0)],
)  # fmt: skip
def test_heavy_payload_damped_share_is_the_static_shapes(mu, j, static, stiffness):
    """A payload much heavier than the beam moves it in its static shape: under a tip force
    phi = s^2 (3 - s) / 2 (phi(1) = 1, int phi^2 = 33/140, the beam's effective mass), under a
    tip moment phi = s^2 / 2 (phi'(1) = 1, int phi^2 = 1/20), so mu s -> 33/140 and j s -> 1/20.
    The shape departs from the static one by O(b^4), b^4 ~ the tip stiffness (3 for a force,
    1 for a moment, in units of EI / L^3 and EI / L) over the payload."""
    share = damped_mass_share(mu, j)
    assert (mu + j) * share == pytest.approx(static, rel=stiffness / (mu + j))


def test_zeta_of_the_bare_beam_is_unchanged():
    """Without a payload zeta is eta / (2 beta_1^2) bit for bit (the paper's numbers), and a
    vanishing payload tends to it."""
    bare = Beam()
    assert bare.zeta == bare.eta / (2.0 * 1.8751040687119611**2)
    assert damped_mass_share(0.0, 0.0) == 1.0
    assert Beam(tip_mass=1e-12).zeta == pytest.approx(bare.zeta, rel=1e-6)
    assert Beam(tip_inertia=1e-18).zeta == pytest.approx(bare.zeta, rel=1e-6)


def test_analytical_boundary_carries_the_payload():
    """E*^2 = E_n^2 + S_1 G a^2 C_max: its slope in C_max is the loaded beam's Southwell
    coefficient, the slope of (2 pi f_0)^2 in Omega^2 of the discrete model's loaded first mode
    (N = 80, Omega <= 2 rad/s).  S_1 is a Rayleigh quotient on the bare beam's mode: 1.8 % below
    the loaded slope at mu = 0.5; the bare beam's S_1 would be 18 % above it."""
    bare = Beam()
    beam = Beam(tip_mass=0.5 * bare.rhoA * bare.L)
    G, a, c_max, omega = beam.G, 1.0, 1e-3 * beam.G, 2.0
    e0, e1 = (analytical_boundary(beam, c, 1.0, amplitude=a) for c in (0.0, c_max))
    slope = (e1 * e1 - e0 * e0) / (G * a * a * c_max)
    f0, f1 = modes(beam, 0.0, 1, 80)[0], modes(beam, omega, 1, 80)[0]
    loaded = ((2 * math.pi * f1) ** 2 - (2 * math.pi * f0) ** 2) / omega**2
    assert slope == pytest.approx(loaded, rel=0.025)
    assert e0 == pytest.approx(G * a * 2 * math.pi * f0, rel=1e-3)
