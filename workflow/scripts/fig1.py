"""Fig. 1b,c: drive profiles."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.paper.figures import fig1_drive
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    d = snakemake.params.drive
    fig1_drive(d["omega0"], snakemake.params.amplitude, d["f_d"], *snakemake.output)
