"""Atomic writers: a killed job leaves no file that looks complete.

Every file rotbeam writes goes through `atomic_write` (tables, text and JSON here, figures in
`rotbeam.report.style.save`, the time series of `rotbeam simulate --out`).
"""

from __future__ import annotations

import csv
import json
import math
import os
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # pandas loads where a table is made: a job that only writes rows skips it
    import pandas as pd


def temporary_name(path: Path) -> Path:
    """The hidden name `path` is written under first: same folder (so the rename is atomic),
    the process id (two writers never share it), ending in `.part` (a leftover says what it is).

    Parameters
    ----------
    path : Path
        The final file.

    Returns
    -------
    Path
        ``.<name>.<pid>.part`` beside it.
    """
    return path.with_name(f".{path.name}.{os.getpid()}.part")


def atomic_write(path: str | Path, write: Callable[[Path], object]) -> None:
    """write(tmp) to `temporary_name(path)`, then rename it onto `path`: a killed job leaves no
    file at `path` that looks complete.  The temporary file is removed if writing fails.

    Parameters
    ----------
    path : str or Path
        The final file; its folder is created if missing.
    write : callable
        Writes the content to the path it is given (the temporary file).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_name(path)
    try:
        write(tmp)
        tmp.replace(path)
    finally:
        tmp.unlink(missing_ok=True)


def write_csv(df: pd.DataFrame, path: str | Path) -> None:
    """Write a table as CSV (no index column), atomically.

    Parameters
    ----------
    df : pandas.DataFrame
        The table.
    path : str or Path
        The CSV file.
    """
    atomic_write(path, lambda tmp: df.to_csv(tmp, index=False))


def write_records(records: Iterable[dict], columns: Sequence[str], path: str | Path) -> None:
    """Write rows (dicts) as CSV (no index column), atomically, without pandas: the file that
    ``write_csv(pandas.DataFrame(records, columns=columns), path)`` writes (NaN and None as
    empty cells, a key missing from a row too), for the simulation jobs, which so skip pandas'
    import (0.2 s a job).

    Parameters
    ----------
    records : iterable of dict
        The rows; keys outside `columns` are left out.
    columns : sequence of str
        The header, in order.
    path : str or Path
        The CSV file.
    """

    def cell(value: Any) -> Any:
        if value is None or (isinstance(value, float) and math.isnan(value)):
            return ""
        return value

    def write(tmp: Path) -> None:
        with open(tmp, "w", newline="") as f:
            out = csv.writer(f, lineterminator="\n")
            out.writerow(columns)
            out.writerows([cell(row.get(c)) for c in columns] for row in records)

    atomic_write(path, write)


def write_text(text: str, path: str | Path) -> None:
    """Write text to a file, atomically.

    Parameters
    ----------
    text : str
        The content.
    path : str or Path
        The file.
    """
    atomic_write(path, lambda tmp: tmp.write_text(text))


def write_json(data: Any, path: str | Path) -> None:
    """Write data as indented JSON (NumPy numbers as floats), atomically.

    Parameters
    ----------
    data : object
        Anything `json.dumps` takes, NumPy numbers included.
    path : str or Path
        The JSON file.
    """
    write_text(json.dumps(data, indent=2, default=float) + "\n", path)


def markdown_table(df: pd.DataFrame, floatfmt: str = ".4g") -> str:
    """A GitHub-flavoured Markdown table (no tabulate dependency).

    Parameters
    ----------
    df : pandas.DataFrame
        The table; its columns are the header.
    floatfmt : str
        Format spec of float cells.

    Returns
    -------
    str
        The table, one line per row, ending in a newline.
    """

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
    """Write a table as CSV and as a Markdown file (under an optional title), atomically.

    Parameters
    ----------
    df : pandas.DataFrame
        The table.
    csv_path : str or Path
        The CSV file.
    md_path : str or Path
        The Markdown file.
    title : str
        A first line of the Markdown file (none if empty).
    """
    write_csv(df, csv_path)
    text = (f"{title}\n\n" if title else "") + markdown_table(df)
    write_text(text, md_path)


def write_series(path: str | Path, series: dict[str, Any]) -> None:
    """Columns of equal length to a CSV file, or Parquet when `path` ends in .parquet.

    Parameters
    ----------
    path : str or Path
        The file (.csv or .parquet).
    series : dict
        Column name -> values.

    Raises
    ------
    RotbeamInputError
        If `path` ends in .parquet and no Parquet engine is installed.
    """
    import pandas as pd

    from ..config.errors import RotbeamInputError

    df = pd.DataFrame(series)

    def write(tmp: Path) -> None:
        if Path(path).suffix == ".parquet":
            try:
                df.to_parquet(tmp)
            except ImportError:
                raise RotbeamInputError(
                    "--out .parquet needs pyarrow or fastparquet (pip install pyarrow); use .csv"
                ) from None
        else:
            df.to_csv(tmp, index=False)

    atomic_write(path, write)
