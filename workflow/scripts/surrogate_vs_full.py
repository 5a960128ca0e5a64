"""Surrogate vs full model: RMS along f_d, f_d* per line, phase boundary, cost per point."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import json
from pathlib import Path

import pandas as pd

from rotbeam.model.params import Effects
from rotbeam.paper.surrogate_figures import vs_full_figure
from rotbeam.paper.surrogate_study import (
    full_critical,
    surrogate_boundary,
    surrogate_curve,
    validity_statement,
    vs_full_table,
)
from rotbeam.report.io import write_csv, write_json, write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    p = snakemake.params
    effects = Effects.from_list(p.effects)
    th = float(p.threshold)
    c_fit = float(json.loads(Path(snakemake.input.fit).read_text())["c"])
    fig4 = {Path(f).stem: pd.read_csv(f) for f in snakemake.input.fig4}
    lines = {Path(f).stem: pd.read_csv(f) for f in snakemake.input.lines}
    crit = full_critical(fig4, lines, pd.read_csv(snakemake.input.boundary), th, p.beam)
    table, points, speed = vs_full_table(
        p.beam, {**fig4, **lines}, crit, th, effects, p.n_scan, p.N, c_fit, p.tolerance
    )
    speed["validity"] = validity_statement(table, p.tolerance)
    curves = [surrogate_curve(p.beam, line, effects, p.curve_points) for line in fig4.values()]
    boundary = surrogate_boundary(
        p.beam, table["C_max"].min(), table["C_max"].max(), p.boundary_points, th,
        float(p.amplitude), effects, p.n_scan, p.N, c_fit,
    )  # fmt: skip
    title = (
        f"Surrogate (one-mode Galerkin, Southwell stiffening) vs full model: f_d* per line at "
        f"Delta RMS = {th:g} (full: PCHIP root of its scan; surrogate: brentq on the model, and on "
        f"the full scan's points, `_grid`), E* of both and of Eq. (analytical_sol) with c = "
        f"{c_fit:.4f} (fig6 fit). Measured: {speed['validity']}. Time per point: surrogate "
        f"{speed['surrogate_seconds_per_point']:.3g} s, full "
        f"{speed['full_seconds_per_point_mean']:.3g} s (mean; N = {speed['full_N']})."
    )
    log.info("%s", title)
    log.info("%s", table.to_string())
    log.info("%s", boundary.to_string())
    write_table(table, snakemake.output.csv, snakemake.output.md, title)
    write_csv(points, snakemake.output.points)
    write_csv(boundary, snakemake.output.boundary)
    write_json(speed, snakemake.output.speed)
    vs_full_figure(list(fig4.values()), curves, table, boundary, th, p.tolerance, c_fit,
                   snakemake.output.pdf, snakemake.output.png)  # fmt: skip
