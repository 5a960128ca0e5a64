"""Fig. D.9: the boundary for each threshold, scaled by E_n."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.paper.figures import figD9_thresholds
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    ref = pd.read_csv(snakemake.input.ref)
    figD9_thresholds(ref, pd.read_csv(snakemake.input.cfit), snakemake.output.pdf,
                     snakemake.output.png)  # fmt: skip
