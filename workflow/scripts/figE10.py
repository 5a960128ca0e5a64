"""Fig. E.10: c_0 vs zeta (canonical second-order system)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.model.params import Beam
from rotbeam.paper.figures import figE10_c0
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    s = snakemake.params.spec
    figE10_c0(s["zeta_max"], s["points"], Beam(**snakemake.params.beam), *snakemake.output)
