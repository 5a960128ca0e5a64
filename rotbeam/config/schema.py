"""Words for the workflow config's JSON schema: what a key allows, and one line per schema error.

`jsonschema` says "-1 is less than or equal to the minimum of 0"; a user wants
"beam.L = -1: must be a finite number > 0".  These helpers read the schema itself, so the words
follow it.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any


def g(x: float) -> str:
    """A number as %g (1e-05, 0.155, 787).

    Parameters
    ----------
    x : float
        The number.

    Returns
    -------
    str
    """
    return format(float(x), "g")


def key_name(path: Any) -> str:
    """Dotted key of a config path: ('fig4', 'omega0', 1) -> 'fig4.omega0[1]'.

    Parameters
    ----------
    path : iterable of str or int
        Keys and list indices from the top of the config.

    Returns
    -------
    str
        The key as a user writes it; "the config" for the empty path.
    """
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out or "the config"


def show(value: Any, width: int = 60) -> str:
    """repr(value), cut to `width` characters (for one-line error messages).

    Parameters
    ----------
    value : object
        The value.
    width : int
        Most characters; a longer repr ends in "...".

    Returns
    -------
    str
    """
    text = repr(value)
    return text if len(text) <= width else text[: width - 3] + "..."


def _resolve(schema: dict, root: dict) -> dict:
    """Follow local `$ref`s ("#/definitions/...") of the config schema."""
    while isinstance(schema, dict) and "$ref" in schema:
        node: Any = root
        for part in schema["$ref"].lstrip("#/").split("/"):
            node = node[part]
        schema = {**node, **{k: v for k, v in schema.items() if k != "$ref"}}
    return schema


def subschema(root: dict, path: Any) -> dict | None:
    """The schema of the value at `path` (None where the schema says nothing).

    Parameters
    ----------
    root : dict
        The whole config schema (its local ``$ref`` links are followed).
    path : iterable of str or int
        Keys and list indices from the top of the config.

    Returns
    -------
    dict or None
        The sub-schema.
    """
    node = _resolve(root, root)
    for p in path:
        if isinstance(p, int):
            prefix = node.get("prefixItems", [])
            node = prefix[p] if p < len(prefix) else node.get("items")
        else:
            node = node.get("properties", {}).get(p)
        if not isinstance(node, dict):
            return None
        node = _resolve(node, root)
    return node


def describe_allowed(schema: dict | None, root: dict | None = None) -> str:
    """What a JSON-schema node allows, in words: 'a finite number in (0, 1)'.

    Parameters
    ----------
    schema : dict or None
        The node; None or empty: "a finite number".
    root : dict or None
        The whole schema, for its ``$ref`` links.

    Returns
    -------
    str
    """
    if not schema:
        return "a finite number"
    s = _resolve(schema, root or {})
    if "enum" in s:
        return "one of " + ", ".join(map(str, s["enum"]))
    if "anyOf" in s:
        return " or ".join(describe_allowed(x, root) for x in s["anyOf"])
    t = s.get("type")
    if t == "boolean":
        return "true or false"
    if t in ("number", "integer"):
        noun = "a finite number" if t == "number" else "an integer"
        lo = ("(", s["exclusiveMinimum"]) if "exclusiveMinimum" in s else None
        lo = lo or (("[", s["minimum"]) if "minimum" in s else None)
        hi = (")", s["exclusiveMaximum"]) if "exclusiveMaximum" in s else None
        hi = hi or (("]", s["maximum"]) if "maximum" in s else None)
        if lo and hi:
            return f"{noun} in {lo[0]}{g(lo[1])}, {g(hi[1])}{hi[0]}"
        if lo:
            return f"{noun} {'>' if lo[0] == '(' else '>='} {g(lo[1])}"
        if hi:
            return f"{noun} {'<' if hi[0] == ')' else '<='} {g(hi[1])}"
        return noun
    if t == "array":
        n_min, n_max = s.get("minItems", 0), s.get("maxItems")
        what = "distinct values" if s.get("uniqueItems") else "values"
        if n_max is not None and n_max == n_min:
            head = f"a list of exactly {n_min} {what}"
        elif n_min > 1:
            head = f"a list of {n_min} or more {what}"
        else:
            head = f"a{' non-empty' if n_min == 1 else ''} list of {what}"
        if "prefixItems" in s:
            parts = ", ".join(describe_allowed(x, root) for x in s["prefixItems"])
            return f"{head} [{parts}]"
        if "items" in s:
            return f"{head}, each {describe_allowed(s['items'], root)}"
        return head
    if t == "object":
        return "a mapping with keys " + ", ".join(s.get("properties", {}))
    if t == "string":
        return f"a string matching {s['pattern']}" if "pattern" in s else "a string"
    return "valid"


def schema_error_message(error: Any, root: dict) -> str:
    """One line naming key, value and what is allowed, from a jsonschema ValidationError.

    Parameters
    ----------
    error : jsonschema.ValidationError
        The error.
    root : dict
        The whole config schema.

    Returns
    -------
    str
        E.g. "beam.L = -1: must be a finite number > 0".
    """
    path = list(error.absolute_path)
    kind, value = error.validator, error.instance
    schema = _resolve(error.schema, root)
    if kind == "required":
        missing = [k for k in error.validator_value if k not in value]
        k = missing[0] if missing else "?"
        return (
            f"{key_name([*path, k])} is missing: it must be "
            f"{describe_allowed(schema.get('properties', {}).get(k), root)}"
        )
    if kind == "additionalProperties":
        allowed = list(schema.get("properties", {}))
        unknown = [k for k in value if k not in allowed]
        k = unknown[0] if unknown else "?"
        where = f"in {key_name(path)}" if path else "at the top level"
        return (
            f"{key_name([*path, k])} = {show(value.get(k))}: unknown key; allowed {where}: "
            + ", ".join(allowed)
        )
    return f"{key_name(path)} = {show(value)}: must be {describe_allowed(schema, root)}"


def json_numbers(value: Any, path: tuple = ()) -> Iterator[tuple[tuple, Any]]:
    """Every (path, number) of a nested config.

    Parameters
    ----------
    value : object
        The config, or a part of it.
    path : tuple
        Where `value` sits in the whole config.

    Yields
    ------
    tuple
        (path, number) for each int or float leaf (bools excepted).
    """
    if isinstance(value, dict):
        for k, v in value.items():
            yield from json_numbers(v, (*path, k))
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            yield from json_numbers(v, (*path, i))
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield path, value


def coerce_numbers(value: Any) -> Any:
    """Numbers given as strings (``--config thresholds=[0.05,0.2]`` arrives as ['0.05', '0.2'])
    become numbers; everything else is left for the schema to judge.

    Parameters
    ----------
    value : object
        The config, or a part of it.

    Returns
    -------
    object
        The same structure with numeric strings as int or float and "true"/"false" as bools.
    """
    if isinstance(value, dict):
        return {k: coerce_numbers(v) for k, v in value.items()}
    if isinstance(value, list):
        return [coerce_numbers(v) for v in value]
    if isinstance(value, str):
        text = value.strip()
        for cast in (int, float):
            try:
                return cast(text)
            except ValueError:
                pass
        if text.lower() in ("true", "false"):
            return text.lower() == "true"
    return value


def merge_config(base: dict[str, Any], override: dict[str, Any]) -> dict[str, Any]:
    """`override` merged over `base` key by key (lists replaced whole): what snakemake does with
    `--configfile config/quick.yaml` over the Snakefile's config/config.yaml.

    Parameters
    ----------
    base : dict
        The config underneath.
    override : dict
        The config on top; its mappings merge, its other values replace.

    Returns
    -------
    dict
        A new mapping; neither argument is changed.
    """
    out = dict(base)
    for key, value in override.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = merge_config(out[key], value)
        else:
            out[key] = value
    return out
