"""Southwell line vs exact first in-plane frequency over C_max, with dynamic resonance peaks."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from pathlib import Path

import pandas as pd

from rotbeam.model.params import Beam
from rotbeam.model.surrogate import southwell_coefficient
from rotbeam.paper.surrogate_figures import southwell_figure
from rotbeam.paper.surrogate_study import discretisation_floor, southwell_table
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    p = snakemake.params
    peaks = {Path(f).stem: pd.read_csv(f) for f in snakemake.input.lines}
    table, skipped = southwell_table(p.beam, p.c_max, p.amplitude, p.N, peaks)
    floor = discretisation_floor(p.beam, p.N)
    s1 = southwell_coefficient(Beam(**p.beam).hub_ratio, True)
    cur = table[table["kind"] == "curve"]
    last = cur.sort_values("C_max").iloc[-1] if not cur.empty else None
    title = (
        f"Southwell line (in-plane S_1 = {s1:.4f}) vs exact first in-plane frequency of the "
        f"linearised model (N = {p.N}) at Omega = Omega_0 + a; rows `dynamic_peak`: peak of the "
        f"dynamic RMS of full sweep lines (grid value; true peak between f_peak_lo_hz and "
        f"f_peak_hi_hz). Discretisation error of the exact frequency at Omega = 0: {floor:+.2e}."
    )
    if last is not None:
        title += (
            f" Southwell error at the largest C_max = {last['C_max']:g}: "
            f"{100 * last['rel_error_southwell']:+.3f} %."
        )
    if skipped:
        title += f" Skipped (Omega_0 < 0): C_max = {', '.join(format(c, 'g') for c in skipped)}."
    log.info("%s", title)
    log.info("%s", table.to_string())
    write_table(table, snakemake.output.csv, snakemake.output.md, title)
    southwell_figure(table, p.beam, p.N, snakemake.output.pdf, snakemake.output.png)
