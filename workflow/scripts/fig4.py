"""Fig. 4: dynamic vs quasi-static RMS and Delta RMS at two mean speeds (and measured curves,
if configured)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.analysis.boundary import boundary_table
from rotbeam.analysis.measurements import load_resonance
from rotbeam.paper.figures import fig4_compare
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    lines = [pd.read_csv(f) for f in snakemake.input.lines]
    th = snakemake.params.threshold
    crit = boundary_table(lines, [th], snakemake.params.beam)
    write_csv(crit, snakemake.output.table)
    log.info("critical frequencies:\n%s", crit.to_string())
    measured = {
        w: load_resonance(f)
        for w, f in zip(snakemake.params.measured_omega0, snakemake.input.measured, strict=True)
    }
    fig4_compare(lines, crit, th, snakemake.output.pdf, snakemake.output.png, measured=measured)
