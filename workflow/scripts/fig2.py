"""Fig. 2c stand-in: simulated lab-frame shapes over one period."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.paper.figures import fig2_shapes
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    fig2_shapes(pd.read_csv(snakemake.input[0]), snakemake.output.pdf, snakemake.output.png)
