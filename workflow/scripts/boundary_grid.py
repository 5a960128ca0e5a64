"""f_d* and E* for every line of every Fig. 7 grid beam and every threshold, a table per beam
(one job: each table is a second of reading, less than a job's start-up)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.analysis.boundary import boundary_table, lines_of
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    beams = snakemake.params.beams
    for beam, lines_file, out in zip(
        snakemake.params.beam_ids, snakemake.input.lines, snakemake.output, strict=True
    ):
        lines = lines_of(pd.read_csv(lines_file))
        table = boundary_table(lines, snakemake.params.thresholds, beams[beam], beam)
        log.info("boundary of beam %s: %d rows", beam, len(table))
        write_csv(table, out)
