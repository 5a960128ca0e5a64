"""Loads as parts (`rotbeam.model.loads`): the table from effects to parts, a model built from
an explicit list of parts, `with_parts` and `at`, and the compiled kernel over the standard
parts and its one-line refusal of the others."""

from __future__ import annotations

import numpy as np
import pytest

from rotbeam.model.elastica import DiscreteElastica
from rotbeam.model.loads import (
    PARTS,
    Centrifugal,
    Coriolis,
    Damping,
    Euler,
    Load,
    Softening,
    default_parts,
)
from rotbeam.model.params import Dimensionless, Effects
from rotbeam.solve import stepping


def _dl(effects: Effects, **kw) -> Dimensionless:
    return Dimensionless(2.875, 0.14, 5.0, 2.0, 1.7, effects, **kw)


def _residual(model: DiscreteElastica, seed: int = 4):
    rng = np.random.default_rng(seed)
    th, tt, ta = (rng.standard_normal((3, model.n)) for _ in range(3))
    lam, ld = rng.standard_normal(3), rng.standard_normal(3)
    rows = model.residual_rows(0.5 * th, tt, ta, lam, ld, True)
    return rows.R, rows.blocks()


def test_the_table_names_every_load_effect_and_not_extension():
    assert list(PARTS) == [n for n in Effects().__dataclass_fields__ if n != "extension"]
    assert [type(p) for p in default_parts(Effects.from_list("all"))] == list(PARTS.values())
    # softening needs the centrifugal load: without it there is no softening part
    assert [type(p) for p in default_parts(Effects.from_list("softening,euler"))] == [Euler]


@pytest.mark.parametrize(
    "names, parts",
    [
        ("centrifugal,euler", [Centrifugal(), Euler()]),
        (
            "centrifugal,softening,coriolis,damping",
            [Centrifugal(), Softening(), Coriolis(), Damping()],
        ),
        ("none", []),
    ],
)
def test_an_explicit_list_of_parts_is_the_model_of_those_effects(names, parts):
    """The model of a scene with every load's effect on, given the parts of `names`, is the
    model of the scene with only `names` on, bit for bit (residual and blocks)."""
    every = Effects.from_list(list(PARTS))
    given = DiscreteElastica(_dl(every), 8, parts=parts)
    by_effects = DiscreteElastica(_dl(Effects.from_list(names)), 8)
    assert given.eta == by_effects.eta
    R1, B1 = _residual(given)
    R2, B2 = _residual(by_effects)
    np.testing.assert_array_equal(R1, R2)
    for a, b in zip(B1, B2, strict=True):
        np.testing.assert_array_equal(a, b)


class _Nothing(Load):
    """A part without a term."""


def test_with_parts_and_at_keep_the_parts():
    model = DiscreteElastica(_dl(Effects()), 8)
    extra = model.with_parts(_Nothing())
    assert [p.name for p in extra.parts] == [p.name for p in model.parts] + ["_Nothing"]
    np.testing.assert_array_equal(_residual(extra)[0], _residual(model)[0])
    other = extra.at(_dl(Effects.from_list("euler")))
    assert [p.name for p in other.parts] == ["Euler", "_Nothing"]
    explicit = DiscreteElastica(_dl(Effects()), 8, parts=[Coriolis()])
    assert [p.name for p in explicit.at(_dl(Effects.from_list(list(PARTS)))).parts] == ["Coriolis"]


@pytest.mark.parametrize(
    "parts, reason",
    [
        ([Centrifugal(), _Nothing()], "the kernel does not know the part(s) _Nothing"),
        ([Centrifugal(), Centrifugal()], "each standard part once"),
        ([Softening(), Euler()], "softening goes with the centrifugal load"),
    ],
)
def test_the_kernel_refuses_other_parts_in_one_line(parts, reason):
    model = DiscreteElastica(_dl(Effects()), 6, parts=parts)
    why = stepping.compiled_cover(model)
    assert reason in why and "\n" not in why


def test_the_kernel_of_explicit_standard_parts_is_the_numpy_model():
    """Parts given in another order than the table's: the kernel's flags follow the parts, and
    its right-hand side and tangent equal the numpy model's to round-off."""
    from rotbeam.model import elastica_kernel

    parts = [Damping(), Euler(), Coriolis(), Centrifugal()]
    m = DiscreteElastica(_dl(Effects.from_list("none")), 9, parts=parts)
    assert stepping.compiled_cover(m) == ""
    n, args = m.n, stepping.model_kernel(m).arguments
    rng = np.random.default_rng(5)
    th, tt, p, q = 0.9 * rng.normal(size=n), *rng.normal(size=(3, n))
    out = np.empty(4 * n)
    elastica_kernel.rates(0.6, np.concatenate([th, tt, p, q]), out, True, *args)
    F, Jv = m.first_order_jvp(th, tt, m.dl.lam(0.6), m.dl.lam_dot(0.6), p, q)
    np.testing.assert_allclose(out[: 2 * n], F, rtol=0, atol=1e-13 * np.abs(F).max())
    np.testing.assert_allclose(out[2 * n :], Jv, rtol=0, atol=1e-13 * np.abs(Jv).max())
