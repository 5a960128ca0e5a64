"""The paper's printed values: reading and checking rotbeam/paper/paper_claims.yaml, the one
data file that holds them.

One row per claim (id, source in the paper, printed value, unit, tolerance and its kind) plus the
printed inputs the studies start from.  Kept apart from `claims` (which judges ours against them)
so that a table that only quotes the printed values does not depend on the studies' code.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pandas as pd

from ..config.errors import RotbeamInputError
from ..config.scenefile import load_yaml

#: the kinds of tolerance a claim can have, and how the claims table words each
KINDS = {
    "stated": "the paper's stated uncertainty",
    "rounding": "the printed rounding",
    "exact": "exactly (a count or identity)",
    "at_least": "the claimed side (>=)",
    "at_most": "the claimed side (<=)",
    "below": "the claimed side (<)",
}


def load_claims(data: dict[str, Any]) -> tuple[dict[str, dict], pd.DataFrame]:
    """The printed inputs and the claims table of a parsed paper_claims.yaml, every row checked.

    Parameters
    ----------
    data : dict
        The parsed file: ``claims``, a list of rows each with id, source, paper (the printed
        value), unit, tolerance and kind (and optionally ``at``, where it is evaluated), and
        ``inputs``, the printed inputs by name.

    Returns
    -------
    inputs : dict
        The printed inputs, by name.
    claims : pandas.DataFrame
        One row per claim, in file order.

    Raises
    ------
    RotbeamInputError
        When a row lacks a field, its kind is not one of `KINDS`, its tolerance is not a
        number >= 0, or two rows share an id.
    """
    rows = data.get("claims") or []
    need = ("id", "source", "paper", "unit", "tolerance", "kind")
    for i, r in enumerate(rows):
        missing = [k for k in need if k not in r]
        if missing:
            raise RotbeamInputError(f"paper_claims claims[{i}] lacks {', '.join(missing)}")
        if r["kind"] not in KINDS:
            raise RotbeamInputError(
                f"paper_claims {r['id']}: kind = {r['kind']!r}; allowed: {', '.join(KINDS)}"
            )
        if not (isinstance(r["tolerance"], (int, float)) and r["tolerance"] >= 0):
            raise RotbeamInputError(f"paper_claims {r['id']}: tolerance must be a number >= 0")
    ids = [r["id"] for r in rows]
    dup = sorted({i for i in ids if ids.count(i) > 1})
    if dup:
        raise RotbeamInputError(f"paper_claims: duplicate ids {', '.join(dup)}")
    return dict(data.get("inputs") or {}), pd.DataFrame(rows)


#: the printed values, shipped with the package
CLAIMS_FILE = Path(__file__).with_name("paper_claims.yaml")


def read_claims(path: str | Path = CLAIMS_FILE) -> tuple[dict[str, dict], pd.DataFrame]:
    """The printed inputs and the claims table of a claims file (`load_claims`).

    Parameters
    ----------
    path : str or Path
        A claims file; default the packaged paper_claims.yaml.

    Returns
    -------
    inputs : dict
        The printed inputs, by name.
    claims : pandas.DataFrame
        One row per claim.

    Raises
    ------
    RotbeamInputError
        When a row of the file is malformed (`load_claims`).
    """
    return load_claims(load_yaml(Path(path).read_text()))


def printed_per_threshold(claims: pd.DataFrame, prefix: str) -> dict[float, float]:
    """The printed values whose id is a prefix followed by a threshold, by threshold.

    Parameters
    ----------
    claims : pandas.DataFrame
        The claims table (`read_claims`).
    prefix : str
        The ids' prefix: "c_" for "c_0.10", "c0_" for "c0_0.02".

    Returns
    -------
    dict
        {threshold rounded to 4 decimals: printed value}; ids whose rest is not a number (such
        as "c0_small_zeta") are left out.
    """
    out = {}
    for cid, value in zip(claims["id"], claims["paper"], strict=True):
        rest = str(cid)[len(prefix) :] if str(cid).startswith(prefix) else ""
        try:
            out[round(float(rest), 4)] = float(value)
        except ValueError:
            continue
    return out
