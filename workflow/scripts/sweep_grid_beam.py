"""Every boundary line of one Fig. 7 grid beam, in one job (a row per point, `c_max_target`
naming the line)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Effects
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log
from rotbeam.simulate.studies import run_grid_lines
from rotbeam.simulate.sweeps import numerics_from_config

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    beam = snakemake.wildcards.beam
    lines = run_grid_lines(
        {beam: snakemake.params.beam},
        snakemake.params.spec,
        snakemake.params.amplitude,
        Effects.from_list(snakemake.params.effects),
        numerics_from_config(snakemake.params.numerics),
        log=log.info,  # one line per point, in the job's log
    )[beam]
    df = pd.concat(lines, ignore_index=True)
    failed = int((~df["converged"].astype(bool)).sum())
    log.info(f"done: {len(lines)} lines, {len(df) - failed} points converged, {failed} not")
    write_csv(df, snakemake.output[0])
