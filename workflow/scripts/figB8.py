"""Fig. B.8: convergence of RMS(y_m) with N."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.paper.figures import figB8_convergence
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    df = pd.read_csv(snakemake.input.lines)  # every line of sweep_convergence, one after another
    write_csv(df, snakemake.output.table)
    figB8_convergence(df, snakemake.output.pdf, snakemake.output.png)
