"""What the Floquet step count costs and buys: each benchmark scene solved with the workflow's
numerics (N = 40 and N = 20: two Floquet passes a point); for every pass, the step count the
monodromy takes (FIRST_STEPS, or a count of STEP_LADDER when that spread is too large), the
spread, and |mu|max as taken and from 2 M steps, each against the same rule converged in the
step count (16 M steps, at least 3000), with CPU seconds side by side (best of `repeats`).

    python3 -m rotbeam.paper.floquet_steps [repeats]
    python3 -m rotbeam.paper.floquet_steps --column E100000_L0.01 [config/config.yaml]

The second form takes the passes of one (E, L) column of the Fig. 7 grid instead (the config's
fig7 beams, c_max lines, amplitude, numerics and effects; one repeat).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pandas as pd

from ..bench.plan import SCENES
from ..bench.stability_cost import WORKFLOW_NUMERICS
from ..config.errors import RotbeamInputError
from ..model.params import Beam, Drive, Effects
from ..runs.scene import Scene, simulate
from ..solve import floquet


@contextmanager
def captured_passes() -> Iterator[list[tuple]]:
    """Record the arguments of every `floquet.orbit_floquet` call made inside the block.

    The calls still run; `floquet.orbit_floquet` is restored on leaving the block.

    Yields
    ------
    list of tuple
        Filled as the block runs: (jac, Z, period, rhs, rows) per call, Z copied.
    """
    calls: list[tuple] = []
    original = floquet.orbit_floquet

    def capture(jac, Z, period, steps=None, rhs=None, rows=None, *args, **kwargs):
        calls.append((jac, Z.copy(), period, rhs, rows))
        return original(jac, Z, period, steps, rhs, rows, *args, **kwargs)

    floquet.orbit_floquet = capture
    try:
        yield calls
    finally:
        floquet.orbit_floquet = original


def _best_of(repeats: int, run) -> tuple[floquet.FloquetResult, float]:
    best = None
    for _ in range(repeats):
        t0 = time.process_time()
        result = run()
        cpu = time.process_time() - t0
        best = (result, cpu) if best is None or cpu < best[1] else best
    return best


def pass_rows(label: str, call: tuple, repeats: int) -> dict:
    """One Floquet pass, replayed: the step count taken and 2 M, each against the converged
    rule.

    Parameters
    ----------
    label : str
        The scene or column the pass belongs to.
    call : tuple
        The pass's arguments as `captured_passes` records them.
    repeats : int
        Runs of each step count; the fastest is timed.

    Returns
    -------
    dict
        scene, dim (the state's dimension), M (collocation instants), steps (the count taken),
        spread (against the product it was checked against), mu_converged (|mu|max at
        max(16 M, 3000) steps), error_taken and error_2M (|mu|max minus it, as taken and at
        2 M steps), cpu_taken and cpu_2M (CPU seconds).
    """
    jac, Z, period, rhs, rows = call
    M = Z.shape[0]

    def run(steps):
        return floquet.orbit_floquet(jac, Z, period, steps, rhs, rows)

    taken, cpu_taken = _best_of(repeats, lambda: run(None))
    fixed, cpu_fixed = _best_of(repeats, lambda: run(2 * M))
    ref = run(max(16 * M, 3000))
    return {"scene": label, "dim": Z.shape[1], "M": M, "steps": taken.steps,
            "spread": taken.spread, "mu_converged": ref.max_abs,
            "error_taken": taken.max_abs - ref.max_abs,
            "error_2M": fixed.max_abs - ref.max_abs,
            "cpu_taken": cpu_taken, "cpu_2M": cpu_fixed}  # fmt: skip


def step_table(
    scenes: tuple[tuple[str, float, float], ...] = SCENES, repeats: int = 3
) -> pd.DataFrame:
    """One row per Floquet pass of each benchmark scene, solved with the workflow's numerics.

    Parameters
    ----------
    scenes : tuple of (str, float, float)
        (label, Omega_0 [rad/s], f_d [Hz]) of each scene, on the reference beam.
    repeats : int
        Runs of each step count; the fastest is timed.

    Returns
    -------
    pandas.DataFrame
        The `pass_rows` of every pass.
    """
    out = []
    for label, omega0, f_d in scenes:
        scene = Scene(Beam(), Drive(omega0=omega0, f_d=f_d), Effects(), WORKFLOW_NUMERICS)
        with captured_passes() as calls:
            simulate(scene)
        out += [pass_rows(label, call, repeats) for call in calls]
    return pd.DataFrame(out)


def column_table(column: str, config_path: str = "config/config.yaml") -> pd.DataFrame:
    """One row per Floquet pass of a Fig. 7 grid column, as `sweep_grid_column` runs it.

    Parameters
    ----------
    column : str
        The column id, e.g. "E100000_L0.01" (`rotbeam.paper.studies.grid_columns`).
    config_path : str
        The workflow config whose fig7 beams, c_max lines, amplitude, numerics and effects
        are used.

    Returns
    -------
    pandas.DataFrame
        The `pass_rows` of every pass, one repeat each.

    Raises
    ------
    RotbeamInputError
        When the config file does not exist or the column is not one of its grid.
    """
    from ..config.scenefile import load_yaml
    from ..runs.sweeps import numerics_from_config
    from .studies import fig7_beams, grid_columns, run_grid_lines

    path = Path(config_path)
    if not path.is_file():
        raise RotbeamInputError(f"config {config_path}: no such file")
    config = load_yaml(path.read_text())
    columns, _ = grid_columns(fig7_beams(config))
    if column not in columns:
        raise RotbeamInputError(f"--column {column}: not a Fig. 7 column of {config_path}; "
                                f"one of {', '.join(columns)}")  # fmt: skip
    spec = {k: config["fig7"][k] for k in ("c_max", "lo", "hi", "points")}
    with captured_passes() as calls:
        run_grid_lines(columns[column], spec, config["amplitude"],
                       Effects.from_list(config["effects"]),
                       numerics_from_config(config["numerics"]))  # fmt: skip
    return pd.DataFrame([pass_rows(column, call, 1) for call in calls])


def _table(args: list[str]) -> pd.DataFrame:
    """The table the command line asks for: a column's passes or the benchmark scenes'."""
    if args and args[0] == "--column":
        if len(args) < 2:
            raise RotbeamInputError("--column needs a column id, e.g. --column E100000_L0.01")
        return column_table(*args[1:3])
    try:
        repeats = int(args[0]) if args else 3
    except ValueError:
        raise RotbeamInputError(f"repeats = {args[0]!r}: must be a whole number >= 1") from None
    if repeats < 1:
        raise RotbeamInputError(f"repeats = {repeats}: must be a whole number >= 1")
    return step_table(repeats=repeats)


def main(argv: list[str] | None = None) -> None:
    """The command line: print the table and a summary of what the step counts cost and buy.

    Parameters
    ----------
    argv : list of str or None
        ``[repeats]`` or ``--column <id> [config]``; None: the process's arguments.  A bad
        argument exits with one line naming it.
    """
    args = sys.argv[1:] if argv is None else argv
    try:
        df = _table(args)
    except RotbeamInputError as exc:
        sys.exit(f"floquet_steps: {exc}")
    with pd.option_context("display.width", 200, "display.float_format", "{:.3g}".format):
        print(df.to_string(index=False))
    kept = df["steps"] == floquet.FIRST_STEPS
    print(f"first try kept in {int(kept.sum())} of {len(df)} passes; |error| of |mu|max: "
          f"as taken <= {df['error_taken'].abs().max():.2g} (kept first tries "
          f"<= {df.loc[kept, 'error_taken'].abs().max():.2g}), "
          f"2 M steps <= {df['error_2M'].abs().max():.2g}")  # fmt: skip
    print(f"CPU of all passes: {df['cpu_taken'].sum():.3f} s as taken, "
          f"{df['cpu_2M'].sum():.3f} s with 2 M steps")  # fmt: skip


if __name__ == "__main__":
    main()
