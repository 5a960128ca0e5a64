"""Fig. 6: f_0, f_d* and the fitted c f_0 vs C_max."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import numpy as np
import pandas as pd

from rotbeam.analysis.boundary import fit_c
from rotbeam.paper.figures import fig6_critical
from rotbeam.report.io import write_json
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    b = pd.read_csv(snakemake.input.boundary)
    th = snakemake.params.threshold
    fit = fit_c(b[np.isclose(b["threshold"], th)])
    write_json(fit, snakemake.output.fit)
    log.info("fit of f_d* = c f_0: %s", fit)
    fig6_critical(b, th, fit["c"], fit["c_stderr"], snakemake.output.pdf, snakemake.output.png)
