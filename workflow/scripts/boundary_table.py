"""f_d* and E* for every line of one beam and every threshold."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.analysis.boundary import boundary_table
from rotbeam.report.io import write_csv

lines = [pd.read_csv(f) for f in snakemake.input.lines]
table = boundary_table(lines, snakemake.params.thresholds, snakemake.params.beam,
                       snakemake.wildcards.beam)  # fmt: skip
with open(snakemake.log[0], "w") as log:
    print(table.to_string(), file=log)
write_csv(table, snakemake.output[0])
