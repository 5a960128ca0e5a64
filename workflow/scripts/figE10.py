"""Fig. E.10: c_0 vs zeta (canonical second-order system)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.model.params import Beam
from rotbeam.report.figures import figE10_c0

s = snakemake.params.spec
figE10_c0(s["zeta_max"], s["points"], Beam(**snakemake.params.beam), *snakemake.output)
