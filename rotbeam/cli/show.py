"""What the commands print: aligned name-value lines, tables, the chosen effects, the
uncertainty."""

from __future__ import annotations

import json
import math
from collections.abc import Iterable
from typing import Any

WIDTH = 16


def line(name: str, text: str) -> None:
    """Print one `name value` line, names aligned.

    Parameters
    ----------
    name : str
        The name, padded to WIDTH characters.
    text : str
        The value as text.
    """
    print(f"{name:{WIDTH}s} {text}")


def values(out: dict[str, Any], keys: tuple[str, ...], fmt: str = ".6g") -> None:
    """Print a `line` for each key of `out`, numbers formatted with `fmt`.

    Parameters
    ----------
    out : dict
        The command's results.
    keys : tuple of str
        The keys to print, in order.
    fmt : str
        Format spec of the values.
    """
    for key in keys:
        line(key, format(out[key], fmt))


def table(rows: Iterable[dict[str, Any]], columns: tuple[tuple[str, str, str], ...]) -> None:
    """Print rows as a right-aligned table under a heading line.

    Parameters
    ----------
    rows : iterable of dict
        The rows, each with every column's key.
    columns : tuple
        (row key, heading, format) of each column: a format spec, "d" (an integer) or "s"
        (the value as text); a number that is not finite prints as nan.
    """
    widths = [max(len(head), 12) for _, head, _ in columns]
    print("  ".join(f"{head:>{w}s}" for (_, head, _), w in zip(columns, widths, strict=True)))
    for row in rows:
        cells = [_cell(row[key], fmt) for key, _, fmt in columns]
        print("  ".join(f"{c:>{w}s}" for c, w in zip(cells, widths, strict=True)))


def _cell(value: Any, fmt: str) -> str:
    """One table cell as text."""
    if fmt == "s" or value is None:
        return str(value)
    if not math.isfinite(value):
        return "nan"
    return str(int(value)) if fmt == "d" else format(value, fmt)


def as_json(out: dict[str, Any]) -> None:
    """Print one JSON object on stdout (NumPy numbers as floats).

    Parameters
    ----------
    out : dict
        The command's results.
    """
    print(json.dumps(out, default=float))


def auto_effects(auto: dict[str, Any]) -> None:
    """Print what `effects: auto` kept and dropped, and what the budget cost.

    Parameters
    ----------
    auto : dict
        `auto_dict`'s mapping.
    """
    dropped = ",".join(auto["dropped"]) or "none"
    line("effects auto", f"kept {','.join(auto['kept'])}; dropped {dropped} (worth "
         f"{auto['dropped_share']:.2g} of RMS at f_d = {auto['budget_f_d']:.4g} Hz; the budget "
         f"took {auto['budget_seconds']:.3g} s)")  # fmt: skip


def uncertainty(prop: Any) -> None:
    """Print the mean, sd and 95 % interval of each output, and P(quasi-static).

    Parameters
    ----------
    prop : Propagated
        The propagated uncertainty (`rotbeam.analysis.uncertainty`).
    """
    spread = ", ".join(f"{k} = {m:g} +- {s:g}" for k, (m, s) in prop.inputs.items())
    failed = f", {prop.failed} failed" if prop.failed else ""
    line("uncertainty", f"{spread} (normal; {prop.method}, {prop.runs} runs, "
         f"{prop.seconds:.3g} s{failed})")  # fmt: skip
    for k in prop.mean:
        line("  " + k, f"{prop.mean[k]:.6g} +- {prop.sd[k]:.3g}  95 %: "
             f"[{prop.low[k]:.6g}, {prop.high[k]:.6g}]")  # fmt: skip
    if prop.p_quasistatic is not None:
        line("  verdict", f"quasi-static with probability {prop.p_quasistatic:.3g}")


def auto_dict(auto: Any, budget: Any, f_d: float) -> dict[str, Any]:
    """`effects_auto` of the JSON output: the choice, the budget's cost and where it ran.

    Parameters
    ----------
    auto : AutoEffects
        The choice (`auto_effects`).
    budget : EffectBudget
        The budget it rests on.
    f_d : float
        The drive frequency the budget ran at [Hz].

    Returns
    -------
    dict
        `AutoEffects.as_dict` with budget_seconds [s] and budget_f_d [Hz].
    """
    return auto.as_dict() | {"budget_seconds": budget.total_seconds, "budget_f_d": f_d}
