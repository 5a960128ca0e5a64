"""Table (systems) of App. E evaluated where the reference beam defines it."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Beam
from rotbeam.paper.appendix_e import systems_table
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    df = pd.DataFrame(systems_table(Beam(**snakemake.params.beam)))
    write_table(df, snakemake.output.csv, snakemake.output.md,
                "Table (systems): zeta, k, f_n; the beam row for the reference beam.")  # fmt: skip
