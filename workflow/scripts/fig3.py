"""Fig. 3: resonance curve, time series, power spectrum."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.report.figures import fig3_resonance
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    fig3_resonance(
        pd.read_csv(snakemake.input.line), pd.read_csv(snakemake.input.series),
        snakemake.output.pdf, snakemake.output.png,
    )  # fmt: skip
