"""Bad input through every entry point, drawn at random (hypothesis): a command-line flag, a
scene file's key, a scene given to the API as a dict, a constructor (`Beam`, `Drive`,
`Effects`, `Numerics`), a drive's CSV file and a scene file's YAML.  Every draw is refused in one
line that names the bad value (and on the command line the flag or the file), exit status 2
from the command line and `RotbeamInputError` from the API; never a traceback.

The bad values come from the registry (`rotbeam.config.parameters.SECTIONS`): for every field,
values beyond each bound it has, values that are not finite, and values of the wrong type.  The
draws: `DRAWS` per test, `test_the_draws_are_counted` holds the total.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st
from test_bad_input import run_main

from rotbeam.cli.options import flag_name
from rotbeam.config.errors import RotbeamInputError
from rotbeam.config.parameters import SECTIONS
from rotbeam.config.scenefile import auto_tol
from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.runs.scene import build_scene
from rotbeam.solve.numerics import Numerics

CLASSES = {"beam": Beam, "drive": Drive, "effects": Effects, "numerics": Numerics}
#: the fields a user sets by value (harmonics, profile and move are structures: their own tests)
FIELDS = [(s, n) for s, fields in SECTIONS.items() for n, p in fields.items() if p.kind != "data"]
#: examples per test (the closing note's count is their sum)
DRAWS = {"flags": 150, "scene keys": 150, "constructors": 150, "csv": 120, "yaml": 80}
SETTINGS = {"deadline": None, "suppress_health_check": [HealthCheck.function_scoped_fixture]}


def one_line(rc: int, out: str, err: str) -> str:
    """The refusal's one line (exit 2, nothing on stdout, no traceback)."""
    assert rc == 2, (rc, err)
    assert out == "" and "Traceback" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    return lines[0]


@st.composite
def bad_value(draw, section: str, name: str):
    """A value the registry refuses for section.name: beyond a bound, not finite, or of the
    wrong type."""
    p = SECTIONS[section][name]
    kinds = ["type"]
    if p.kind in ("real", "int"):
        kinds.append("nonfinite" if p.kind == "real" else "fraction")
        if p.lo is not None:
            kinds.append("below")
        if p.hi is not None:
            kinds.append("above")
    if p.kind == "choice":
        kinds.append("choice")
    kind = draw(st.sampled_from(kinds))
    if kind == "below":
        if p.kind == "int":
            return draw(st.integers(-(10**6), math.ceil(p.lo) - 1))
        top = p.lo if p.lo_open else math.nextafter(p.lo, -math.inf)
        return draw(st.floats(max_value=top, min_value=-1e30, allow_nan=False))
    if kind == "above":
        if p.kind == "int":
            return draw(st.integers(math.floor(p.hi) + 1, 10**6))
        low = p.hi if p.hi_open else math.nextafter(p.hi, math.inf)
        return draw(st.floats(min_value=low, max_value=1e30, allow_nan=False))
    if kind == "nonfinite":
        return draw(st.sampled_from([math.nan, math.inf, -math.inf]))
    if kind == "fraction":
        return draw(st.floats(0.1, 0.9)) + draw(st.integers(3, 50))
    if kind == "choice":
        return draw(st.text("abcdefXYZ-_", min_size=1, max_size=8).filter(
            lambda t: t not in p.choices))  # fmt: skip
    wrong = [
        st.text(max_size=6).filter(lambda t: not _number(t)),
        st.lists(st.integers(), max_size=2),
    ]
    if p.kind == "bool":
        wrong += [st.integers(0, 3), st.floats(allow_nan=False)]
    else:
        wrong.append(st.booleans())
    return draw(st.one_of(wrong))


def _effects_word(text: str) -> bool:
    """Whether --effects takes `text` as it is: a list of effects, 'all', 'none', auto or
    auto:TOL (a bad value for one effect's switch can still be a good word for the flag)."""
    try:
        if text == "auto" or text.startswith("auto:"):
            auto_tol(text, "argument --effects")
        else:
            Effects.from_list(text)
    except RotbeamInputError:
        return False
    return True


def _number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


@st.composite
def bad_field(draw):
    section, name = draw(st.sampled_from(FIELDS))
    return section, name, draw(bad_value(section, name))


@settings(max_examples=DRAWS["constructors"], **SETTINGS)
@given(case=bad_field())
def test_a_constructor_refuses_a_bad_field_naming_it(case):
    section, name, value = case
    with pytest.raises(RotbeamInputError) as info:
        CLASSES[section](**{name: value})
    message = str(info.value)
    assert f"{section}.{name}" in message and "\n" not in message, message


@settings(max_examples=DRAWS["scene keys"], **SETTINGS)
@given(case=bad_field())
def test_a_scene_key_is_refused_naming_it(case, tmp_path):
    """The same value as a scene file's key: through the API's build_scene and through
    `rotbeam simulate --scene`."""
    section, name, value = case
    with pytest.raises(RotbeamInputError) as info:
        build_scene({section: {name: value}})
    assert f"{section}.{name}" in str(info.value), str(info.value)
    if isinstance(value, float) and not math.isfinite(value):
        return  # YAML writes .nan and .inf: read back as the same value, checked above
    path = tmp_path / "scene.yaml"
    path.write_text(yaml.safe_dump({section: {name: value}}))
    line = one_line(*run_main(["simulate", "--scene", str(path), "--quiet"]))
    assert f"{section}.{name}" in line, line


@settings(max_examples=DRAWS["flags"], **SETTINGS)
@given(case=bad_field())
@example(case=("effects", "centrifugal", "none"))  # a bad switch, a good word: --effects none
@example(case=("effects", "centrifugal", "nonee"))
def test_a_flag_is_refused_naming_it(case):
    section, name, value = case
    flag = flag_name(section, name)
    if section == "effects":  # the command line sets effects by name: --effects a,b
        assume(not _effects_word(str(value)))
        argv = ["simulate", "--effects", f"{value}"]
        line = one_line(*run_main(argv))
        assert "--effects" in line, line
        return
    if SECTIONS[section][name].kind == "bool":  # --flag / --no-flag take no value
        argv = ["simulate", f"{flag}={value}"]
    else:
        argv = ["simulate", flag, str(value)]
    line = one_line(*run_main(argv))
    assert flag in line, line


#: malformed contents of a drive's CSV file (t or phase, omega)
CSV_TEXTS = st.one_of(
    st.just(""),
    st.just("t,omega\n"),
    st.just("\ufefftime,speed\n0,1\n"),
    st.text(max_size=80),
    st.binary(max_size=60).map(lambda b: b.decode("latin-1")),
    st.lists(st.tuples(st.floats(), st.floats()), min_size=1, max_size=12).map(
        lambda rows: "t,omega\n" + "".join(f"{a},{b}\n" for a, b in rows)),
)  # fmt: skip


@settings(max_examples=DRAWS["csv"], **SETTINGS)
@given(text=CSV_TEXTS, kind=st.sampled_from(["move", "profile"]))
def test_a_malformed_drive_file_is_refused_naming_it(text, kind, tmp_path):
    path = tmp_path / "drive.csv"
    path.write_bytes(text.encode("utf-8", "surrogatepass"))
    spec = {"drive": {kind: str(path), **({"f_d": 1.0} if kind == "profile" else {})}}
    try:
        build_scene(spec)
    except RotbeamInputError as exc:
        assert f"drive.{kind}" in str(exc) and "\n" not in str(exc), str(exc)
    else:  # a draw that happens to be a valid drive: the command line must answer it too
        return
    argv = ["simulate", f"--{kind}", str(path), "--quiet"] + (["--fd", "1"] if kind == "profile"
                                                               else [])  # fmt: skip
    line = one_line(*run_main(argv))
    assert "drive.csv" in line, line


YAML_TEXTS = st.one_of(
    st.text(max_size=60),
    st.sampled_from(["beam: [1, 2", "beam: {L: }", "- 1\n- 2", "beam: 3", "drive:\n\t f_d: 1",
                     "numerics: {N: 1e3.5}", "effects: {euler: maybe}", "unknown: {}"]),
)  # fmt: skip


@settings(max_examples=DRAWS["yaml"], **SETTINGS)
@given(text=YAML_TEXTS)
def test_a_malformed_scene_file_is_one_line(text, tmp_path):
    path = tmp_path / "scene.yaml"
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    rc, out, err = run_main(["simulate", "--scene", str(path), "--quiet", "--omega0", "5",
                            "--fd", "2", "--N", "6", "--max-seconds", "5"])  # fmt: skip
    if rc != 2:  # valid YAML that is a valid (empty or partial) scene: it answers
        assert rc in (0, 1) and "Traceback" not in err, err
        return
    line = one_line(rc, out, err)
    assert "scene" in line or "." in line, line


def test_the_draws_are_counted():
    assert sum(DRAWS.values()) == 650


def test_a_drawn_bad_value_is_bad():
    """The strategy itself can fail: a value drawn for a bounded field is outside its range."""
    from hypothesis import find

    value = find(bad_value("numerics", "N"), lambda v: isinstance(v, int) and v > 2000)
    assert value == 2001
    assert Path(__file__).name.startswith("test_")
