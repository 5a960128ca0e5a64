"""Fig. 4: dynamic vs quasi-static RMS and Delta RMS at two mean speeds."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.analysis.boundary import boundary_table
from rotbeam.report.figures import fig4_compare
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    lines = [pd.read_csv(f) for f in snakemake.input.lines]
    th = snakemake.params.threshold
    crit = boundary_table(lines, [th], snakemake.params.beam)
    write_csv(crit, snakemake.output.table)
    log.info("critical frequencies:\n%s", crit.to_string())
    fig4_compare(lines, crit, th, snakemake.output.pdf, snakemake.output.png)
