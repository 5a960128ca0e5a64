"""The atlas from its lines: every grid point's row in one table, and the figure with the f_d*
boundary."""
# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)

import pandas as pd

from rotbeam.analysis.atlas import atlas_from_rows
from rotbeam.model.params import Beam
from rotbeam.report.atlas_figure import plot_atlas
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    rows = pd.concat([pd.read_csv(f) for f in snakemake.input], ignore_index=True)
    atlas = atlas_from_rows(rows, Beam(**snakemake.params.beam), snakemake.params.threshold)
    log.info("%s", atlas.boundary.to_string())
    if atlas.message:
        log.info(atlas.message)
    write_csv(atlas.rows, snakemake.output.csv)
    plot_atlas(atlas, snakemake.output.png)
