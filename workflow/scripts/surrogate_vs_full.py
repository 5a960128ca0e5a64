"""Surrogate vs full model: RMS along f_d, f_d* per line, phase boundary, cost per point."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import json
from pathlib import Path

import numpy as np
import pandas as pd

from rotbeam.boundary import boundary_table
from rotbeam.io import write_csv, write_json, write_table
from rotbeam.params import Effects
from rotbeam.surrogate_figures import (
    surrogate_boundary,
    surrogate_curve,
    validity_statement,
    vs_full_figure,
    vs_full_table,
)

p = snakemake.params
effects = Effects.from_list(p.effects)
th = float(p.threshold)
c_fit = float(json.loads(Path(snakemake.input.fit).read_text())["c"])
fig4 = {Path(f).stem: pd.read_csv(f) for f in snakemake.input.fig4}
bnd = {Path(f).stem: pd.read_csv(f) for f in snakemake.input.lines}

# full model's f_d* (PCHIP root of the scan): fig4 lines as rule fig4 does, boundary lines from
# the boundary table at the main threshold
full_crit = {}
for name, line in fig4.items():
    crit = boundary_table([line], [th], p.beam)
    full_crit[name] = float(crit["f_d_root"].iloc[0]) if not crit.empty else np.nan
ref = pd.read_csv(snakemake.input.boundary)
ref = ref[np.isclose(ref["threshold"], th)]
for name, line in bnd.items():
    row = ref[np.isclose(ref["omega0"], float(line["omega0"].iloc[0]))]
    full_crit[name] = float(row["f_d_root"].iloc[0]) if not row.empty else np.nan

table, points, speed = vs_full_table(
    p.beam, {**fig4, **bnd}, full_crit, th, effects, p.n_scan, p.N, c_fit, p.tolerance
)
statement = validity_statement(table, p.tolerance)
speed["validity"] = statement
curves = [surrogate_curve(p.beam, line, effects, p.curve_points) for line in fig4.values()]
boundary = surrogate_boundary(
    p.beam, table["C_max"].min(), table["C_max"].max(), p.boundary_points, th,
    float(p.amplitude), effects, p.n_scan, p.N, c_fit,
)  # fmt: skip
title = (
    f"Surrogate (one-mode Galerkin, Southwell stiffening) vs full model: f_d* per line at "
    f"Delta RMS = {th:g} (full: PCHIP root of its scan; surrogate: brentq on the model, and on "
    f"the full scan's points, `_grid`), E* of both and of Eq. (analytical_sol) with c = "
    f"{c_fit:.4f} (fig6 fit). Measured: {statement}. Speed per point: surrogate "
    f"{speed['surrogate_seconds_per_point']:.3g} s, full {speed['full_seconds_per_point_mean']:.3g}"
    f" s (mean; N = {speed['full_N']})."
)
with open(snakemake.log[0], "w") as log:
    print(title, file=log)
    print(table.to_string(), file=log)
    print(boundary.to_string(), file=log)
write_table(table, snakemake.output.csv, snakemake.output.md, title)
write_csv(points, snakemake.output.points)
write_csv(boundary, snakemake.output.boundary)
write_json(speed, snakemake.output.speed)
vs_full_figure(list(fig4.values()), curves, table, boundary, th, p.tolerance, c_fit,
               snakemake.output.pdf, snakemake.output.png)  # fmt: skip
