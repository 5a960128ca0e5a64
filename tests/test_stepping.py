"""The tangent of the first-order system without its Jacobian (`first_order_jvp`) against the
Jacobian and against finite differences of the right-hand side."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import numerical_first_order_jacobian

from rotbeam.model.drive import HarmonicLaw
from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.params import Dimensionless, Effects
from rotbeam.paper.printed_model import PrintedElastica

TWO = HarmonicLaw(1.1, ((1, 0.6, 0.0), (3, 0.25, 0.7)), 2.3)  # two harmonics


def scene_dl(effects: Effects, law: HarmonicLaw = TWO, **kw) -> Dimensionless:
    """A scene of two harmonics (hub ratio 2.875, eta 0.14); kw: tip_mass, tip_inertia."""
    slender = 0.05 if effects.extension else None
    swing = sum(abs(a) for _, a, _ in law.terms)
    return Dimensionless(2.875, 0.14, law.lam0, swing, law.omega, effects, slender, law, **kw)


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
