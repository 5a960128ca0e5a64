"""The atlas of the phase plane: Delta RMS at every (Omega_0, f_d) of a grid, and the f_d*
boundary through it, one crossing per Omega_0 line (`boundary_table`, the sweep lines' own)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from ..config.checks import check_threshold
from ..config.threads import one_blas_thread
from ..model.params import Beam
from ..runs.atlas import ATLAS_COLUMNS, Progress, cut_notes, run_atlas, where_cut
from ..runs.scene import Scene
from .boundary import boundary_table

#: the boundary's columns: one row per Omega_0 line
BOUNDARY_COLUMNS = ["line", "omega0", "C_max", "f0_hz", "f_d_grid", "f_d_root", "E_star_grid",
                    "E_star_root", "found", "points_used", "points_failed", "message"]  # fmt: skip


@dataclass
class Atlas:
    """Delta RMS over a grid of (Omega_0, f_d) and the f_d* boundary through it.

    `rows` holds every grid point (a sweep's row, its line and whether it ran), `boundary` one
    row per Omega_0 line: f_d* of that line at `threshold` (`f_d_grid`, the first grid point at
    or above it, the paper's rule; `f_d_root`, the root of the line's PCHIP interpolant between
    the grid points around the crossing) and E* = G a 2 pi f_d*.
    """

    rows: pd.DataFrame  #: one row per grid point, the columns `ATLAS_COLUMNS`
    boundary: pd.DataFrame  #: one row per line, the columns `BOUNDARY_COLUMNS`
    threshold: float  #: the Delta RMS threshold of the boundary
    seconds: float = math.nan  #: wall time of the atlas [s] (NaN: gathered from files)
    message: str = ""  #: where the time budget cut it ('' when every point ran)
    workers: int = 1  #: processes that ran the lines
    beam: Beam = field(default_factory=Beam)  #: the beam

    @property
    def omega0s(self) -> np.ndarray:
        """The lines' Omega_0 [rad/s], increasing."""
        return np.unique(self.rows["omega0"].to_numpy(float))

    @property
    def f_ds(self) -> np.ndarray:
        """The drive frequencies [Hz], increasing."""
        return np.unique(self.rows["f_d"].to_numpy(float))

    @property
    def complete(self) -> bool:
        """Whether the time budget cut no grid point (every point ran to its answer)."""
        return not where_cut(self.rows.to_dict(orient="records"))[0]

    def grid(self, column: str = "delta_rms") -> np.ndarray:
        """One column over the grid: shape (I, J), row i the line at omega0s[i].

        Parameters
        ----------
        column : str
            A column of `rows` with numbers.

        Returns
        -------
        numpy.ndarray
            The values, NaN where a point did not run or failed.
        """
        table = self.rows.pivot_table(index="omega0", columns="f_d", values=column,
                                      aggfunc="first", dropna=False)  # fmt: skip
        return table.reindex(index=self.omega0s, columns=self.f_ds).to_numpy(float)

    def summary(self) -> dict[str, Any]:
        """The atlas in a few numbers (what `rotbeam atlas` prints and its --json holds).

        Returns
        -------
        dict
            ``points`` (I x J), ``ran``, ``converged``, ``failed``, ``not_run``, ``lines``,
            ``lines_with_boundary``, ``threshold``, ``delta_rms_min`` and ``_max``,
            ``floquet_max`` (the largest |mu|max), the grid's ranges (``omega0_min``,
            ``omega0_max`` [rad/s], ``f_d_min``, ``f_d_max`` [Hz], ``C_max_min``,
            ``C_max_max``, ``E_max_min``, ``E_max_max``), ``seconds``, ``points_per_second``,
            ``workers``, ``complete`` and ``message``.
        """
        r = self.rows
        ran = r["ran"].astype(bool)
        conv = r["converged"].astype(bool) & ran
        delta = r.loc[conv, "delta_rms"].to_numpy(float)
        mu = r.loc[conv, "floquet_max"].to_numpy(float)
        n = int(ran.sum())

        def bound(col: str, f: Any) -> float:
            v = r[col].to_numpy(float)
            return float(f(v)) if np.isfinite(v).any() else math.nan

        return {
            "points": f"{len(self.omega0s)} x {len(self.f_ds)}", "ran": n,
            "converged": int(conv.sum()), "failed": int((ran & ~conv).sum()),
            "not_run": int((~ran).sum()), "lines": len(self.boundary),
            "lines_with_boundary": int(np.isfinite(self.boundary["f_d_root"]).sum()),
            "threshold": self.threshold,
            "delta_rms_min": float(np.nanmin(delta)) if np.isfinite(delta).any() else math.nan,
            "delta_rms_max": float(np.nanmax(delta)) if np.isfinite(delta).any() else math.nan,
            "floquet_max": float(np.nanmax(mu)) if np.isfinite(mu).any() else math.nan,
            "omega0_min": bound("omega0", np.nanmin), "omega0_max": bound("omega0", np.nanmax),
            "f_d_min": bound("f_d", np.nanmin), "f_d_max": bound("f_d", np.nanmax),
            "C_max_min": bound("C_max", np.nanmin), "C_max_max": bound("C_max", np.nanmax),
            "E_max_min": bound("E_max", np.nanmin), "E_max_max": bound("E_max", np.nanmax),
            "seconds": self.seconds,
            "points_per_second": n / self.seconds if self.seconds > 0 else math.nan,
            "workers": self.workers, "complete": self.complete, "message": self.message,
        }  # fmt: skip


def boundary_of(rows: pd.DataFrame, beam: Beam, threshold: float) -> pd.DataFrame:
    """f_d* of every Omega_0 line of an atlas's rows (`boundary_table` of each line).

    Parameters
    ----------
    rows : pandas.DataFrame
        An atlas's rows (`ATLAS_COLUMNS`).
    beam : Beam
        The beam.
    threshold : float
        The Delta RMS threshold, in (0, 1).

    Returns
    -------
    pandas.DataFrame
        One row per line, in increasing Omega_0, the columns `BOUNDARY_COLUMNS` (NaN f_d*
        where the line does not cross the threshold; `message` says why).
    """
    threshold = check_threshold(threshold)
    lines = [line for _, line in rows.groupby("omega0", sort=True)]
    ran = [line[line["ran"].astype(bool)] for line in lines]
    table = boundary_table(ran, [threshold], asdict(beam))
    table["line"] = [int(line["line"].iloc[0]) for line in lines]
    table["omega0"] = [float(line["omega0"].iloc[0]) for line in lines]
    table["C_max"] = [float(line["C_max"].iloc[0]) for line in lines]
    table["f0_hz"] = [float(line["f0_hz"].iloc[0]) for line in lines]
    return table[BOUNDARY_COLUMNS].reset_index(drop=True)


def atlas_from_rows(
    rows: pd.DataFrame,
    beam: Beam,
    threshold: float = 0.10,
    seconds: float = math.nan,
    message: str = "",
    workers: int = 1,
) -> Atlas:
    """An `Atlas` of rows run elsewhere (the workflow's lines, one file each, gathered).

    Parameters
    ----------
    rows : pandas.DataFrame
        Every grid point's row, the columns `ATLAS_COLUMNS`.
    beam : Beam
        The beam the rows were run with.
    threshold : float
        The Delta RMS threshold of the boundary, in (0, 1).
    seconds : float
        Wall time of the atlas [s], NaN if not known.
    message : str
        Where a time budget cut it; '': said from the rows (`where_cut`).
    workers : int
        Processes that ran it.

    Returns
    -------
    Atlas

    Raises
    ------
    RotbeamInputError
        If the threshold is not in (0, 1).
    """
    missing = [c for c in ATLAS_COLUMNS if c not in rows]
    if missing:
        raise ValueError(f"atlas rows lack the columns {missing}")
    rows = rows.sort_values(["omega0", "f_d"]).reset_index(drop=True)[ATLAS_COLUMNS]
    threshold = check_threshold(threshold)
    if not message:
        cut, notes = where_cut(rows.to_dict(orient="records"))
        if cut:
            records = rows.to_dict(orient="records")
            message = (
                f"the time budget cut {len(cut)} of {rows['line'].nunique()} lines: "
                f"{cut_notes(records, notes)}"
            )
    return Atlas(rows, boundary_of(rows, beam, threshold), threshold, seconds, message, workers,
                 beam)  # fmt: skip


@one_blas_thread
def atlas(
    scene: Scene,
    omega0s: Sequence[float],
    f_ds: Sequence[float],
    threshold: float = 0.10,
    workers: int | None = None,
    progress: Progress | None = None,
) -> Atlas:
    """Delta RMS at every (Omega_0, f_d) of the grid omega0s x f_ds, and the f_d* boundary.

    Each Omega_0 is one sweep line over `f_ds` (`rotbeam.runs.sweeps.sweep`: its rows are
    `simulate`'s at each point, continued from the neighbour's orbit); the lines run in
    parallel processes (`workers`, default one per core); `scene.numerics.max_seconds` bounds
    the whole atlas, and a point it does not reach has a marked row (`ran` False).

    Parameters
    ----------
    scene : Scene
        Beam, drive (a sine or a sum of harmonics, whose Omega_0 and f_d the grid sets), effects
        and numerics.
    omega0s : sequence of float
        Omega_0 of the lines [rad/s], at least 2, increasing.
    f_ds : sequence of float
        Drive frequencies [Hz], at least 2, > 0, increasing.
    threshold : float
        The Delta RMS threshold of the boundary, in (0, 1) (the paper's 0.10).
    workers : int or None
        Processes that run the lines; 1: here, one line after the other; None: one per core,
        at most one per line.
    progress : callable or None
        progress(line, k, row) after each point run.

    Returns
    -------
    Atlas
        The rows, the boundary, what it cost and where the budget cut it.

    Raises
    ------
    RotbeamInputError
        For a bad axis or threshold, a drive without Omega_0 (a profile, a move), or input the
        scenes reject.
    """
    threshold = check_threshold(threshold)
    run = run_atlas(scene, omega0s, f_ds, workers, progress)
    rows = pd.DataFrame(run.records, columns=ATLAS_COLUMNS)
    return atlas_from_rows(rows, scene.beam, threshold, run.seconds, run.message, run.workers)
