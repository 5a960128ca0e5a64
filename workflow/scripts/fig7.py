"""Fig. 7: boundary over a grid of beams and its collapse on Eq. (scaled_analytical_sol)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import numpy as np
import pandas as pd

from rotbeam.analysis.boundary import fit_c
from rotbeam.paper.figures import ZETA_UNDERDAMPED, fig7_collapse
from rotbeam.report.io import write_json
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    b = pd.concat([pd.read_csv(f) for f in snakemake.input.beams], ignore_index=True)
    b = b[np.isclose(b["threshold"], snakemake.params.threshold)]
    # c from the underdamped beams only (App. E: c is constant for zeta << 1)
    fit = fit_c(b[b["zeta"] <= ZETA_UNDERDAMPED])
    fit["zeta_max_used"] = ZETA_UNDERDAMPED
    fit["beams_excluded_overdamped"] = int(b.loc[b["zeta"] > ZETA_UNDERDAMPED, "beam"].nunique())
    write_json(fit, snakemake.output.fit)
    log.info("fit of the collapse: %s", fit)
    fig7_collapse(b, fit["c"], snakemake.output.pdf, snakemake.output.png)
