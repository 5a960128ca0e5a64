"""Fig. 5: phase diagram of the reference beam and two time series."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.paper.figures import fig5_phase
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    fig5_phase(
        pd.read_csv(snakemake.input.boundary), snakemake.params.threshold,
        [pd.read_csv(f) for f in snakemake.input.series],
        snakemake.output.pdf, snakemake.output.png,
    )  # fmt: skip
