"""Scene files: YAML with sections `beam`, `drive`, `effects`, `numerics` whose keys are the
registry's fields (rotbeam.config.parameters); unknown sections or keys are errors naming the key,
its value and what is allowed.  The objects are built in rotbeam.runs.scene.

`effects: auto` (or `effects: {auto: TOL}`, or the flag's spelling `auto:TOL`) asks for the effects
the scene's effect budget calls for (rotbeam.analysis.effect_budget.auto_effects); `split_auto`
takes it out of the spec before the sections are checked."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import yaml

from .errors import RotbeamInputError
from .parameters import SECTIONS
from .schema import show


class _Loader(getattr(yaml, "CSafeLoader", yaml.SafeLoader)):
    """SafeLoader (libyaml's where PyYAML has it: 8x faster on the workflow's schema) that also
    reads 1e6 and 2.0e6 as floats (YAML 1.1 wants 1.0e+6)."""


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(
        r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
        |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
        |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
        |[-+]?\.(?:inf|Inf|INF)
        |\.(?:nan|NaN|NAN))$""",
        re.X,
    ),
    list("-+0123456789."),
)


def load_yaml(text: str) -> Any:
    """YAML with scientific notation read as numbers.

    PyYAML follows YAML 1.1, which reads 1e6 as a string; scene files write numbers as people
    do.

    Parameters
    ----------
    text : str
        The YAML document.

    Returns
    -------
    object
        The parsed document (a dict for a scene file).

    Raises
    ------
    yaml.YAMLError
        For text that is not YAML.
    """
    return yaml.load(text, Loader=_Loader)


#: default TOL of `effects: auto` and `--effects auto`: keep the effects whose |share of RMS(y_m)|
#: is at least this (0.1 %)
AUTO_TOL = 1e-3


def auto_tol(value: Any, where: str) -> float:
    """TOL of an `auto` request: the share of RMS(y_m) below which an effect is dropped.

    Parameters
    ----------
    value : object
        "auto" (AUTO_TOL), "auto:TOL" or a number.
    where : str
        The key or flag, named in the one-line error.

    Returns
    -------
    float
        TOL, dimensionless, in [0, 1).

    Raises
    ------
    RotbeamInputError
        For anything else, or a TOL outside [0, 1).
    """
    if value == "auto":
        return AUTO_TOL
    if isinstance(value, str) and value.startswith("auto:"):
        value = value[5:]
    try:
        tol = math.nan if isinstance(value, bool) else float(value)
    except (TypeError, ValueError):
        tol = math.nan
    if not 0.0 <= tol < 1.0:
        raise RotbeamInputError(
            f"{where}: {show(value)}: TOL must be a number in [0, 1) (a share of RMS(y_m)), "
            f"e.g. auto:0.01"
        )
    return tol


def split_auto(spec: Any) -> tuple[Any, float | None]:
    """The scene spec without its `effects: auto` request, and that request's TOL.

    `effects: auto`, `effects: {auto: TOL}` and `effects: auto:TOL` are taken out before the
    sections are checked; other keys beside `auto` stay: they are the effects the budget starts
    from.

    Parameters
    ----------
    spec : object
        A scene spec (a dict of sections); anything else is returned as it is.

    Returns
    -------
    spec : object
        The spec without the request (a new dict when it had one).
    tol : float or None
        TOL in [0, 1), None without a request.

    Raises
    ------
    RotbeamInputError
        For a TOL that `auto_tol` refuses.
    """
    if not isinstance(spec, dict):
        return spec, None
    eff = spec.get("effects")
    if isinstance(eff, str) and (eff == "auto" or eff.startswith("auto:")):
        rest = {k: v for k, v in spec.items() if k != "effects"}
        return rest, auto_tol(eff, "effects")
    if isinstance(eff, dict) and "auto" in eff:
        rest = dict(spec)
        rest["effects"] = {k: v for k, v in eff.items() if k != "auto"}
        return rest, auto_tol(eff["auto"], "effects.auto")
    return spec, None


def scene_sections(spec: Any) -> dict[str, dict[str, Any]]:
    """The sections of a scene spec as fresh dicts, their keys checked against the registry.

    Only the names are checked here; the values are the classes' (rotbeam.runs.scene builds
    them).

    Parameters
    ----------
    spec : object
        A scene spec: None or a mapping of sections (beam, drive, effects, numerics) to
        mappings of keys.

    Returns
    -------
    dict
        Section name -> a new dict of its keys and values ({} for None).

    Raises
    ------
    RotbeamInputError
        One line naming the key, its value and what is allowed: a spec or a section that is
        not a mapping, an unknown section or an unknown key.
    """
    if spec is None:
        return {}
    if not isinstance(spec, dict):
        raise RotbeamInputError(
            f"a scene must be a mapping of sections ({', '.join(SECTIONS)}), "
            f"got {show(spec)} ({type(spec).__name__})"
        )
    out = {}
    for name, values in spec.items():
        if name not in SECTIONS:
            raise RotbeamInputError(
                f"{name} = {show(values)}: unknown scene section; allowed: {', '.join(SECTIONS)}"
            )
        values = {} if values is None else values
        if not isinstance(values, dict):
            raise RotbeamInputError(
                f"{name} = {show(values)}: a scene section must be a mapping of keys, "
                f"e.g. {name}: {{{next(iter(_fields(name)))}: ...}}; got {type(values).__name__}"
            )
        for key, value in values.items():
            if key not in _fields(name):
                raise RotbeamInputError(
                    f"{name}.{key} = {show(value)}: unknown key; allowed in {name}: "
                    f"{', '.join(_fields(name))}"
                )
        out[name] = dict(values)
    return out


def _fields(section: str) -> list[str]:
    return list(SECTIONS[section])


def load_scene_file(path: str | Path) -> dict[str, Any]:
    """The raw content of a YAML scene file, as a mapping of sections.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    dict
        Its top-level mapping ({} for an empty file); the sections are not checked here
        (`scene_sections`).

    Raises
    ------
    RotbeamInputError
        One line naming the file: it does not exist, cannot be read, is not valid YAML (with
        the line and column) or does not hold a mapping.
    """
    path = Path(path)
    if path.is_dir():
        raise RotbeamInputError(
            f"scene file {str(path)!r} is a directory; allowed: a YAML file (sections "
            f"{', '.join(SECTIONS)})"
        )
    if not path.is_file():
        raise RotbeamInputError(f"scene file {str(path)!r} does not exist")
    try:
        data = load_yaml(path.read_text(encoding="utf-8-sig"))
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" (line {mark.line + 1}, column {mark.column + 1})" if mark else ""
        what = getattr(exc, "problem", None) or str(exc)
        raise RotbeamInputError(
            " ".join(f"scene file {str(path)!r} is not valid YAML: {what}{where}".split())
        ) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise RotbeamInputError(f"scene file {str(path)!r} cannot be read: {exc}") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise RotbeamInputError(
            f"scene file {str(path)!r} must hold a mapping of sections ({', '.join(SECTIONS)}), "
            f"got {show(data)} ({type(data).__name__})"
        )
    return data


def read_columns(path: str | Path, columns: tuple[str, ...], where: str) -> dict[str, tuple]:
    """Named numeric columns of a CSV file (a header row, then one number per cell).

    Parameters
    ----------
    path : str or Path
        The file.
    columns : tuple of str
        The columns to read; others are ignored.
    where : str
        The scene key the file was given for, named in an error.

    Returns
    -------
    dict
        Column name -> its values, a tuple of floats (blank lines skipped).

    Raises
    ------
    RotbeamInputError
        One line naming `where` and the file: no such file, unreadable, a column missing from
        the header, or a cell that is not a number (with its line and column).
    """
    import csv

    path = Path(path)
    if path.is_dir():
        raise RotbeamInputError(f"{where} = {str(path)!r} is a directory; allowed: a CSV file")
    if not path.is_file():
        raise RotbeamInputError(f"{where} = {str(path)!r}: no such file")
    try:  # utf-8-sig: a spreadsheet's byte-order mark is not part of the first column's name
        with path.open(newline="", encoding="utf-8-sig") as f:
            rows = list(csv.reader(f))
    except (OSError, UnicodeDecodeError) as exc:
        raise RotbeamInputError(f"{where} = {str(path)!r} cannot be read: {exc}") from None
    header = [h.strip() for h in rows[0]] if rows else []
    missing = [c for c in columns if c not in header]
    if missing:
        raise RotbeamInputError(
            f"{where} = {str(path)!r}: no column {', '.join(missing)}; it has "
            f"{', '.join(header) or 'no header'}; allowed: a header row naming {', '.join(columns)}"
        )
    out: dict[str, list[float]] = {c: [] for c in columns}
    for line, row in enumerate(rows[1:], start=2):
        if not any(cell.strip() for cell in row):
            continue
        for c in columns:
            cell = row[header.index(c)].strip() if header.index(c) < len(row) else ""
            try:
                out[c].append(float(cell))
            except ValueError:
                raise RotbeamInputError(
                    f"{where} = {str(path)!r}, line {line}, column {c}: {cell!r} is not a number"
                ) from None
    return {c: tuple(v) for c, v in out.items()}
