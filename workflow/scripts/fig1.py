"""Fig. 1b,c: drive profiles."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.report.figures import fig1_drive

d = snakemake.params.drive
fig1_drive(d["omega0"], snakemake.params.amplitude, d["f_d"], *snakemake.output)
