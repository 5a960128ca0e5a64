"""The steppers of the response classification (rotbeam/solve/stepping.py): the tangent without
the Jacobian against the Jacobian and against finite differences, the compiled kernel against
the numpy model for every effect it covers, the compiled DOP853 against scipy's, the new path
against the Radau path it replaces, the fallback for the models the kernel does not cover, a
classified periodic response against its Floquet rate, and the switch to Radau where the grid
is stiff."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from conftest import numerical_first_order_jacobian

from rotbeam.model.drive import HarmonicLaw
from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.params import Beam, Dimensionless, Drive, Effects
from rotbeam.paper.printed_model import PrintedElastica
from rotbeam.runs.response import _atol, response_of
from rotbeam.runs.scene import Scene
from rotbeam.solve import stepping
from rotbeam.solve.steady import initial_state

HARD = Scene(drive=Drive(omega0=5.0, amplitude=3.0, f_d=7.0))  # no stable periodic state
TWO = HarmonicLaw(1.1, ((1, 0.6, 0.0), (3, 0.25, 0.7)), 2.3)  # two harmonics


def scene_dl(effects: Effects, law: HarmonicLaw = TWO, **kw) -> Dimensionless:
    """A scene of two harmonics (hub ratio 2.875, eta 0.14); kw: tip_mass, tip_inertia."""
    slender = 0.05 if effects.extension else None
    swing = sum(abs(a) for _, a, _ in law.terms)
    return Dimensionless(2.875, 0.14, law.lam0, swing, law.omega, effects, slender, law, **kw)


CALM = TWO.scaled(0.2)  # a gentle drive: the fallback's run against Radau


def models() -> dict[str, object]:
    """Models with every kind of term the tangent has: effects, payload, printed variants."""
    out = {
        "default": DiscreteElastica(scene_dl(Effects()), 8),
        "coriolis, extension": DiscreteElastica(
            scene_dl(Effects(coriolis=True, extension=True)), 8
        ),
        "no effect": DiscreteElastica(scene_dl(Effects.from_list("none")), 8),
        "payload": DiscreteElastica(
            scene_dl(Effects(coriolis=True), tip_mass=0.4, tip_inertia=0.01), 8
        ),
    }
    for misprint in ("bracket", "U3", "symS", "Kds"):
        out[f"printed {misprint}"] = PrintedElastica(scene_dl(Effects()), 8, (misprint,))
    return out


def random_point(n: int, seed: int) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    return 0.9 * rng.normal(size=n), rng.normal(size=n), rng.normal(size=n), rng.normal(size=n)


@pytest.mark.parametrize("name", list(models()))
def test_tangent_without_the_jacobian_is_the_jacobian_times_the_direction(name):
    """`first_order_jvp` gives `first_order_jacobian` @ (p, q) to round-off and the
    acceleration itself; for the models whose Jacobian is exact (all but the symmetric printed
    S, whose Jacobian is the derivation's by design) also central differences of the
    right-hand side along (p, q)."""
    m = models()[name]
    n = m.n
    th, tt, p, q = random_point(n, 3)
    F, Jv = m.first_order_jvp(th, tt, 1.3, 0.7, p, q)
    np.testing.assert_array_equal(F, np.concatenate([tt, m.acceleration(th, tt, 1.3, 0.7)]))
    J = m.first_order_jacobian(th, tt, 1.3, 0.7)
    ref = J @ np.concatenate([p, q])
    np.testing.assert_allclose(Jv, ref, rtol=0, atol=1e-13 * np.abs(ref).max())
    if name != "printed symS":
        fd = numerical_first_order_jacobian(m, th, tt, 1.3, 0.7) @ np.concatenate([p, q])
        np.testing.assert_allclose(Jv, fd, rtol=0, atol=1e-6 * np.abs(fd).max())


EFFECTS = [
    Effects(centrifugal=c, softening=s, euler=e, coriolis=o, damping=d, extension=x)
    for c, s, e, o, d, x in itertools.product([False, True], repeat=6)
    if c or not x  # extension needs the centrifugal tension
]


@pytest.mark.parametrize("effects", EFFECTS, ids=lambda e: "+".join(e.active()) or "none")
def test_compiled_kernel_is_the_numpy_model(effects):
    """The compiled right-hand side and tangent equal the numpy model's (`acceleration`,
    `first_order_jvp`) to round-off, for every combination of effects it covers."""
    from rotbeam.model import elastica_kernel as elastica_rk

    m = DiscreteElastica(scene_dl(effects), 9)
    assert stepping.compiled_cover(m) == ""
    n, args = m.n, stepping.model_kernel(m).arguments
    for seed in range(3):
        th, tt, p, q = random_point(n, seed)
        t = 0.37 + seed
        out = np.empty(4 * n)
        elastica_rk.rates(t, np.concatenate([th, tt, p, q]), out, True, *args)
        F, Jv = m.first_order_jvp(th, tt, m.dl.lam(t), m.dl.lam_dot(t), p, q)
        np.testing.assert_allclose(out[: 2 * n], F, rtol=0, atol=1e-13 * np.abs(F).max())
        np.testing.assert_allclose(out[2 * n :], Jv, rtol=0, atol=1e-13 * np.abs(Jv).max())
        state = np.empty(2 * n)
        elastica_rk.rates(t, np.concatenate([th, tt]), state, False, *args)
        np.testing.assert_array_equal(state, out[: 2 * n])


@pytest.mark.parametrize(
    "model, reason",
    [
        (PrintedElastica(scene_dl(Effects(), CALM), 6, ("symS",)), "PrintedElastica"),
        (DiscreteElastica(scene_dl(Effects(), CALM, tip_mass=0.3), 6), "payload"),
        (DiscreteElastica(scene_dl(Effects(), CALM, tip_inertia=0.01), 6), "payload"),
    ],
)
def test_models_the_kernel_does_not_cover_take_the_numpy_path(model, reason):
    """A model the kernel does not compute is refused by name and stepped by scipy's DOP853
    on the numpy model.  Over a quarter period against Radau at rtol 1e-8 its error is below
    2e-5 and a fifth of the Radau path's at the classification's rtol 1e-5 (measured 3e-7 to
    5e-6 against 7e-5 to 4e-4)."""
    assert reason in stepping.compiled_cover(model)
    P, n = model.dl.period / 4, model.n
    z0 = initial_state(model, "quasistatic")[0]
    atol = _atol(z0[:n], 1e-5, model.dl.omega)
    explicit = stepping.period_stepper(model, 1e-5, atol, "dop853")
    assert type(explicit) is stepping.ExplicitStepper
    ref, msg = stepping.period_stepper(model, 1e-8, atol * 1e-3, "radau").state(0.0, P, z0)
    scale = np.concatenate([np.full(n, np.abs(ref[:n]).max()), np.full(n, np.abs(ref[n:]).max())])
    errors = {}
    for method in ("dop853", "radau"):
        z, msg = stepping.period_stepper(model, 1e-5, atol, method).state(0.0, P, z0)
        assert msg == ""
        errors[method] = np.max(np.abs(z - ref) / scale)
    assert errors["dop853"] < min(2e-5, 0.2 * errors["radau"]), errors


def test_compiled_dop853_follows_scipy_dop853():
    """The compiled loop against scipy's DOP853 on the numpy model over one period of the hard
    scene from the quasi-static state: at rtol 1e-10 both are within 1e-8 of each other
    (the step sequences part at round-off, so not closer), and a step never crosses a sample
    instant (the samples equal a run stopped there)."""
    from scipy.integrate import solve_ivp

    from rotbeam.solve.system import FirstOrderSystem

    model = HARD.model(6)
    P, n = model.dl.period, model.n
    z0 = initial_state(model, "quasistatic")[0]
    atol = _atol(z0[:n], 1e-10, model.dl.omega)
    compiled = stepping.CompiledStepper(model, 1e-10, atol)
    z, msg = compiled.state(0.0, P, z0)
    sol = solve_ivp(FirstOrderSystem(model).rhs, (0.0, P), z0, method="DOP853", rtol=1e-10,
                    atol=atol)  # fmt: skip
    scale = np.abs(sol.y).max(axis=1)
    assert msg == "" and np.max(np.abs(z - sol.y[:, -1]) / scale) < 1e-8
    # a run with samples equals runs stopped at each sample instant, bit for bit
    y0 = np.concatenate([z0, np.ones(2 * n) / math.sqrt(2 * n)])
    t_eval = np.linspace(0.0, P / 4, 5)
    y, samples, _ = stepping.CompiledStepper(model, 1e-10, atol).tangent(0.0, P / 4, y0, t_eval)
    assert samples.shape == (4, 2 * n)
    np.testing.assert_array_equal(samples[0], z0)
    again, yk = stepping.CompiledStepper(model, 1e-10, atol), y0
    for k in range(1, 5):
        yk, _, _ = again.tangent(t_eval[k - 1], t_eval[k], yk, None)
        np.testing.assert_array_equal(samples[k] if k < 4 else y[: 2 * n], yk[: 2 * n])


def test_new_path_against_the_radau_path_on_the_chaotic_attractor():
    """On the hard scene's chaotic attractor (N = 6, ten periods from the quasi-static state),
    half a period cut into 8 windows of P / 16, each started from the same state and tangent:
    the new path (compiled DOP853) and the Radau path it replaces (rtol 1e-5, the Jacobian
    formed at every call) end each window on the same state and tangent growth to within
    Radau's own error there (measured over a period: 2.6e-6 and 4e-6 against a 1e-12
    reference; the compiled path's 3e-8 and 3e-7)."""
    model = HARD.model(6)
    P, n = model.dl.period, model.n
    d = 2 * n
    qs = initial_state(model, "quasistatic")[0]
    atol = _atol(qs[:n], 1e-5, model.dl.omega)
    new = stepping.period_stepper(model, 1e-5, atol, "dop853")
    old = stepping.period_stepper(model, 1e-5, atol, "radau")
    assert type(new) is stepping.CompiledStepper
    z = qs
    for k in range(10):
        z, _ = new.state(k * P, (k + 1) * P, z)
    v = np.random.default_rng(12345).standard_normal(d)
    y = np.concatenate([z, v / np.linalg.norm(v)])
    t = 10 * P + np.arange(9) * P / 16
    dz, dg, size = [], [], np.abs(z).max()
    for k in range(8):
        a, _, _ = new.tangent(t[k], t[k + 1], y, None)
        b, _, _ = old.tangent(t[k], t[k + 1], y, None)
        dz.append(np.abs(a[:d] - b[:d]).max() / size)
        dg.append(abs(math.log(np.linalg.norm(a[d:]) / np.linalg.norm(b[d:]))))
        y = np.concatenate([a[:d], a[d:] / np.linalg.norm(a[d:])])
    assert max(dz) < 5e-5 and max(dg) < 5e-5, (max(dz), max(dg))


def test_classification_of_a_periodic_response_has_the_floquet_exponent():
    """A response that settles on a periodic orbit (5 rad/s, a = 1 rad/s, 2 Hz, N = 6; 20 + 40
    periods, compiled DOP853) is called periodic, and its exponent is the orbit's Floquet
    rate ln |mu|max f_d (an independent method: the monodromy of the collocated orbit) within
    its spread (measured -0.806 +- 0.23 against -0.833 1/s)."""
    from rotbeam.runs.scene import simulate
    from rotbeam.solve.numerics import Numerics

    scene = Scene(Beam(), Drive(omega0=5.0, amplitude=1.0, f_d=2.0), Effects(), Numerics(N=6))
    rate = math.log(simulate(scene).dynamic.floquet.max_abs) * 2.0
    r = response_of(scene.model(6), scene.beam.T, 20, 40)
    assert r.response == "periodic" and r.distances[0] < 1e-6, r.message
    assert abs(r.lyapunov_max - rate) < r.lyapunov_spread, (r.lyapunov_max, rate)
    assert "DOP853 (compiled)" in r.message


def test_switch_to_radau_where_the_grid_is_stiff():
    """From the quasi-static state the first period is calm: on N = 20 the explicit method's
    steps are held by its stability (h rho ~ 4.6, ~7000 steps), so the switching stepper hands
    the next period to Radau, and Radau's steps there (h rho ~ 40) keep it; on N = 6 the same
    period stays explicit.  On the attractor at N = 6 (accuracy-bound) it stays explicit."""
    for N, stiff in ((20, True), (6, False)):
        model = HARD.model(N)
        P, n = model.dl.period, model.n
        qs = initial_state(model, "quasistatic")[0]
        sw = stepping.period_stepper(model, 1e-5, _atol(qs[:n], 1e-5, model.dl.omega))
        assert isinstance(sw, stepping.SwitchingStepper)
        z, _ = sw.state(0.0, P, qs)
        assert sw.stiff is stiff, (N, sw.steps, sw.rho)
        if stiff:
            sw.state(P, 2 * P, z)
            assert sw.stiff and sw.intervals == {"DOP853 (compiled)": 1, "Radau": 1}
    for k in range(1, 6):
        z, _ = sw.state(k * P, (k + 1) * P, z)
        assert not sw.stiff
    assert sw.name == "DOP853 (compiled)"


def test_the_dop853_table_meets_the_order_conditions():
    """The compiled stepper's own copy of the Dormand-Prince 8(5,3) tableau: each stage's
    coefficients sum to its node, the weights integrate polynomials up to degree 7 exactly
    (sum B c^(q-1) = 1/q, q = 1..8), and the 5th-order error weights E5 annihilate them up to
    degree 4 (the difference of two solutions of order >= 5)."""
    from rotbeam.model import dop853_table as t

    assert np.allclose(t.A.sum(axis=1), t.C, rtol=0, atol=1e-14)
    for q in range(1, 9):
        assert t.B @ t.C ** (q - 1) == pytest.approx(1.0 / q, rel=1e-13)
    c = np.append(t.C, 1.0)  # E5 weighs the 12 stages and f at the new point
    for q in range(1, 6):
        assert abs(t.E5 @ c ** (q - 1)) < 1e-13


def _move_dl(effects: Effects, **kw) -> Dimensionless:
    """A scene whose drive is a move: lam through a smooth rise and fall over tau in [0, 3]."""
    from rotbeam.model.drive import MoveLaw

    tau = np.linspace(0.0, 3.0, 31)
    law = MoveLaw(tuple(tau), tuple(0.8 * np.sin(np.pi * tau / 3.0) ** 2))
    slender = 0.05 if effects.extension else None
    return Dimensionless(2.875, 0.14, law.mean, 0.8, law.omega, effects, slender, law, **kw)


PAYLOAD = {"tip_mass": 0.4, "tip_inertia": 0.01}


@pytest.mark.parametrize("modes", [0, 3], ids=["full", "3 modes"])
@pytest.mark.parametrize("payload", [False, True], ids=["bare", "payload"])
@pytest.mark.parametrize("move", [False, True], ids=["harmonics", "move"])
@pytest.mark.parametrize("effects", [Effects(), Effects.from_list("none"),
                                     Effects(coriolis=True, extension=True)],
                         ids=["default", "none", "coriolis+extension"])  # fmt: skip
def test_the_kernel_without_a_tangent_is_the_numpy_model(effects, move, payload, modes):
    """Without a tangent the kernel also covers a payload, a move's spline and the modal model
    (the residual projected on its modes): its right-hand side equals the numpy model's
    `acceleration` to round-off, at instants before, inside and after a move."""
    from rotbeam.model import elastica_kernel
    from rotbeam.model.modal import ModalModel

    kw = PAYLOAD if payload else {}
    dl = _move_dl(effects, **kw) if move else scene_dl(effects, **kw)
    m = DiscreteElastica(dl, 9)
    m = ModalModel(m, modes) if modes else m
    kernel, why = m.kernel(tangent=False)
    assert why == "" and kernel is not None
    n = m.n
    for seed, t in enumerate((-0.5, 0.37, 1.6, 2.95, 3.5)):
        th, tt, _, _ = random_point(n, seed)
        out = np.empty(2 * n)
        elastica_kernel.rates(t, np.concatenate([th, tt]), out, False, *kernel.arguments)
        acc = m.acceleration(th, tt, dl.lam(t), dl.lam_dot(t))
        np.testing.assert_array_equal(out[:n], tt)
        np.testing.assert_allclose(out[n:], acc, rtol=0, atol=1e-12 * np.abs(acc).max())


def test_a_tangent_is_refused_where_the_kernel_has_none_in_one_line():
    """The modal model and a payload have no compiled tangent: asked with one, the kernel says
    why in one line, and a march built without one refuses a tangent."""
    from rotbeam.model.modal import ModalModel

    modal = ModalModel(DiscreteElastica(scene_dl(Effects()), 8), 2)
    payload = DiscreteElastica(scene_dl(Effects(), **PAYLOAD), 8)
    assert "modal model's tangent" in modal.kernel()[1]
    assert "payload" in payload.kernel()[1] and "\n" not in payload.kernel()[1]
    march = stepping.CompiledStepper(modal, 1e-6, np.full(4, 1e-9), tangent=False)
    with pytest.raises(ValueError, match="without a tangent"):
        march.tangent(0.0, 0.1, np.zeros(8), None)


@pytest.mark.parametrize("name", ["default", "payload", "printed"])
def test_the_compiled_first_order_system_is_the_numpy_one(name):
    """`FirstOrderSystem(compiled=True)` (the steady state's time stepping, Radau's
    classification periods, a move) takes the kernel's right-hand side where the model offers
    one without a tangent, equal to the numpy model's to round-off, and the numpy model's
    itself where it offers none (the printed appendix)."""
    from rotbeam.solve.system import FirstOrderSystem

    m = {"default": DiscreteElastica(scene_dl(Effects(coriolis=True)), 8),
         "payload": DiscreteElastica(scene_dl(Effects(), **PAYLOAD), 8),
         "printed": PrintedElastica(scene_dl(Effects(), CALM), 6, ("symS",))}[name]  # fmt: skip
    compiled, numpy_ = FirstOrderSystem(m, compiled=True), FirstOrderSystem(m)
    assert (compiled.kernel is None) == (name == "printed")
    for seed, t in enumerate((0.1, 0.9, 2.3)):
        th, tt, _, _ = random_point(m.n, seed)
        z = np.concatenate([th, tt])
        want = numpy_.rhs(t, z)
        np.testing.assert_allclose(compiled.rhs(t, z), want, rtol=0,
                                   atol=1e-12 * np.abs(want).max())  # fmt: skip
