"""The parameter registry is the one source of truth: the workflow's JSON schema, the classes and
the CLI help agree with it, and its checks give one line naming key, value and range."""

from dataclasses import fields
from pathlib import Path

import pytest

from rotbeam.config.errors import RotbeamInputError
from rotbeam.config.parameters import SECTIONS, check_value
from rotbeam.config.scenefile import load_yaml
from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.solve.numerics import Numerics

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = load_yaml((ROOT / "workflow/schemas/config.schema.yaml").read_text())


def _resolve(node: dict) -> dict:
    while "$ref" in node:
        node = {**SCHEMA["definitions"][node["$ref"].split("/")[-1]], **node}
        node.pop("$ref")
    return node


def _bounds_from_schema(node: dict) -> tuple:
    lo = node.get("exclusiveMinimum", node.get("minimum"))
    return lo, "exclusiveMinimum" in node, node.get("maximum")


@pytest.mark.parametrize("section", ["beam", "numerics"])
def test_schema_matches_registry(section):
    props = SCHEMA["properties"][section]["properties"]
    assert set(props) == set(SECTIONS[section])
    for name, p in SECTIONS[section].items():
        node = _resolve(props[name])
        if p.kind == "choice":
            assert tuple(node["enum"]) == p.choices, name
        elif p.kind == "bool":
            assert node["type"] == "boolean", name
        else:
            assert node["type"] == ("integer" if p.kind == "int" else "number"), name
            assert _bounds_from_schema(node) == (p.lo, p.lo_open, p.hi), name


def test_schema_effects_are_the_registry_effects():
    assert SCHEMA["properties"]["effects"]["items"]["enum"] == list(SECTIONS["effects"])


def test_schema_observables_are_the_registry_observables():
    """config user_scenes_observe allows exactly the observables of the registry, and the
    config's own list is among them."""
    from rotbeam.runs.observables import OBSERVABLES

    node = SCHEMA["properties"]["user_scenes_observe"]
    assert node["items"]["enum"] == list(OBSERVABLES)
    full = load_yaml((ROOT / "config/config.yaml").read_text())
    assert set(full["user_scenes_observe"]) <= set(OBSERVABLES)


@pytest.mark.parametrize(
    "cls, section", [(Beam, "beam"), (Drive, "drive"), (Effects, "effects"), (Numerics, "numerics")]
)
def test_classes_take_fields_and_defaults_from_registry(cls, section):
    assert [f.name for f in fields(cls)] == list(SECTIONS[section])
    obj = cls()
    for name, p in SECTIONS[section].items():
        assert getattr(obj, name) == p.default


@pytest.mark.parametrize(
    "section, name, value, words",
    [
        ("beam", "L", 0.0, ["beam.L", "> 0", "0.0"]),
        ("beam", "gamma", -1.0, ["beam.gamma", ">= 0"]),
        ("numerics", "N", 2001, ["numerics.N", "[3, 2000]", "2001"]),
        ("numerics", "N", 12.0, ["numerics.N", "integer"]),
        ("numerics", "rtol", 1.0, ["numerics.rtol", "[1e-13, 0.1]"]),
        ("numerics", "method", "Euler", ["numerics.method", "'Euler'", "Radau"]),
        ("effects", "euler", 1, ["effects.euler", "true or false"]),
        ("drive", "f_d", float("inf"), ["drive.f_d", "finite"]),
    ],
)
def test_check_value_names_key_value_and_range(section, name, value, words):
    with pytest.raises(RotbeamInputError) as exc:
        check_value(section, name, value)
    msg = str(exc.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, (w, msg)


def test_bounds_are_inclusive_where_the_registry_says():
    assert check_value("numerics", "N", 3) == 3
    assert check_value("numerics", "rtol", 0.1) == 0.1
    assert check_value("beam", "gamma", 0) == 0.0
    with pytest.raises(RotbeamInputError):
        check_value("beam", "L", 0)


def test_quick_config_only_overrides_the_default():
    """config/quick.yaml holds only what differs from config/config.yaml."""
    full = load_yaml((ROOT / "config/config.yaml").read_text())
    quick = load_yaml((ROOT / "config/quick.yaml").read_text())

    def same(a, b, path=()):
        if isinstance(a, dict) and isinstance(b, dict):
            for k in a:
                assert k in b, f"{'.'.join(map(str, (*path, k)))} is not in config.yaml"
                same(a[k], b[k], (*path, k))
        else:
            assert a != b, f"{'.'.join(map(str, path))} repeats config.yaml's value {a!r}"

    same(quick, full)
