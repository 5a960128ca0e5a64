"""Atomic writers: a killed job leaves no file that looks complete."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import pandas as pd


def _tmp(path: Path) -> Path:
    return path.with_name(f".{path.name}.{os.getpid()}.part")


def _atomic(path: str | Path, write) -> None:
    """write(tmp) then rename onto `path`; the temporary file is removed if writing fails."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = _tmp(path)
    try:
        write(tmp)
        tmp.replace(path)
    finally:
        tmp.unlink(missing_ok=True)


def write_csv(df: pd.DataFrame, path: str | Path) -> None:
    _atomic(path, lambda tmp: df.to_csv(tmp, index=False))


def write_text(text: str, path: str | Path) -> None:
    _atomic(path, lambda tmp: tmp.write_text(text))


def write_json(data: Any, path: str | Path) -> None:
    write_text(json.dumps(data, indent=2, default=float) + "\n", path)


def markdown_table(df: pd.DataFrame, floatfmt: str = ".4g") -> str:
    """A GitHub-flavoured Markdown table (no tabulate dependency)."""

    def fmt(v: Any) -> str:
        if isinstance(v, float):
            return format(v, floatfmt)
        return str(v)

    head = "| " + " | ".join(map(str, df.columns)) + " |"
    rule = "| " + " | ".join("---" for _ in df.columns) + " |"
    rows = ["| " + " | ".join(fmt(v) for v in row) + " |" for row in df.itertuples(index=False)]
    return "\n".join([head, rule, *rows]) + "\n"


def write_table(
    df: pd.DataFrame, csv_path: str | Path, md_path: str | Path, title: str = ""
) -> None:
    write_csv(df, csv_path)
    text = (f"{title}\n\n" if title else "") + markdown_table(df)
    write_text(text, md_path)
