"""f_d* and E* for every line of one beam and every threshold."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.analysis.boundary import boundary_table
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    lines = [pd.read_csv(f) for f in snakemake.input.lines]
    table = boundary_table(lines, snakemake.params.thresholds, snakemake.params.beam,
                           snakemake.wildcards.beam)  # fmt: skip
    log.info("boundary of beam %s:\n%s", snakemake.wildcards.beam, table.to_string())
    write_csv(table, snakemake.output[0])
