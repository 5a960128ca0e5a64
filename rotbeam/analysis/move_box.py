"""A box of beam inputs that a robust move must hold over: "E=+-5%,gamma=+-25%,tip_mass=+-10%".

Each input varies by a share of the scene's value (``+-5%``) or by an amount in its own SI
unit (``+-0.05e6``); the robust design holds at every corner of the box (every input at either
end), the inputs being the beam fields an uncertainty names (`rotbeam.analysis.uncertainty`)
and the payload's.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import replace

from ..config.errors import RotbeamInputError
from ..runs.scene import Scene
from .uncertainty import BEAM_FIELDS

#: the inputs a box may hold: the uncertainty's beam fields and the payload
BOX_FIELDS = (*BEAM_FIELDS, "tip_mass", "tip_inertia")
_HALF = re.compile(r"^\s*(?:\+-|\+/-|±)\s*([^%\s]+)\s*(%?)\s*$")


def parse_box(text: str | None) -> dict[str, tuple[float, bool]]:
    """The box of a --robust string: name -> (half width, relative?).

    Parameters
    ----------
    text : str or None
        Comma-separated name=+-X% (a share of the scene's value) or name=+-X (SI units), as
        "E=+-5%,gamma=+-25%,tip_mass=+-10%"; None or empty: no box.

    Returns
    -------
    dict
        Name -> (X, True) for X % (X / 100 stored) or (X, False) for an amount.

    Raises
    ------
    RotbeamInputError
        One line for a part that is not name=+-X[%], an unknown name, a name given twice, or a
        half width that is not a finite number >= 0 (a share below 100 %).
    """
    out: dict[str, tuple[float, bool]] = {}
    for part in (text or "").split(","):
        if not part.strip():
            continue
        name, _, value = part.partition("=")
        name = name.strip()
        m = _HALF.match(value)
        if not _ or not m:
            raise RotbeamInputError(
                f"robust {part.strip()!r}: expected name=+-X% or name=+-X, e.g. E=+-5%"
            )
        if name not in BOX_FIELDS:
            raise RotbeamInputError(
                f"robust {name!r}: unknown input; allowed: {', '.join(BOX_FIELDS)}"
            )
        if name in out:
            raise RotbeamInputError(f"robust {name!r} given twice; allowed: once each")
        try:
            half = float(m.group(1))
        except ValueError:
            half = math.nan
        relative = m.group(2) == "%"
        if not math.isfinite(half) or half < 0 or (relative and half >= 100):
            allowed = "0 <= X < 100 %" if relative else "a finite X >= 0"
            raise RotbeamInputError(f"robust {name} = {value.strip()!r}: allowed {allowed}")
        out[name] = (half / 100 if relative else half, relative)
    return out


def corners(scene: Scene, box: dict[str, tuple[float, bool]]) -> list[tuple[str, Scene]]:
    """The scene at every corner of the box, with a label such as "E+ gamma-".

    Parameters
    ----------
    scene : Scene
    box : dict
        `parse_box`'s answer.

    Returns
    -------
    list of (str, Scene)
        2 ** k corners, k the inputs whose two ends differ (a share of a zero payload does
        not); none for an empty box.

    Raises
    ------
    RotbeamInputError
        If a corner lies outside a field's range.
    """
    names = [n for n in box if _ends(scene, n, box[n])[0] != _ends(scene, n, box[n])[1]]
    if not names:
        return []
    out = []
    for signs in itertools.product((1, -1), repeat=len(names)):
        values, label = {}, []
        for name, sign in zip(names, signs, strict=True):
            values[name] = _ends(scene, name, box[name])[0 if sign > 0 else 1]
            label.append(f"{name}{'+' if sign > 0 else '-'}")
        try:
            out.append((" ".join(label), replace(scene, beam=replace(scene.beam, **values))))
        except RotbeamInputError as exc:
            raise RotbeamInputError(f"robust: corner {' '.join(label)} is outside the model's "
                                    f"range ({exc})") from None  # fmt: skip
    return out


def _ends(scene: Scene, name: str, half: tuple[float, bool]) -> tuple[float, float]:
    """The input's upper and lower ends in the box."""
    width, relative = half
    mean = getattr(scene.beam, name)
    delta = abs(mean) * width if relative else width
    return mean + delta, mean - delta
