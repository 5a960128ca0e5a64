"""Fig. 3: resonance curve, time series, power spectrum (and a measured curve, if configured)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.analysis.measurements import load_resonance
from rotbeam.paper.figures import fig3_resonance
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    measured = [load_resonance(f) for f in snakemake.input.measured]
    fig3_resonance(
        pd.read_csv(snakemake.input.line), pd.read_csv(snakemake.input.series),
        snakemake.output.pdf, snakemake.output.png, measured=measured[0] if measured else None,
    )  # fmt: skip
