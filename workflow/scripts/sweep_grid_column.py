"""Every boundary line of the beams of one (E, L) column of the Fig. 7 grid (one beam per h/L),
in one job: per beam its file (a row per point, `c_max_target` naming the line)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from pathlib import Path

from rotbeam.model.params import Effects
from rotbeam.paper.studies import line_columns, run_grid_lines
from rotbeam.report.io import write_records
from rotbeam.report.joblog import job_log
from rotbeam.runs.sweeps import numerics_from_config

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    out = {Path(f).parent.name: f for f in snakemake.output}  # beam id -> its lines.csv
    beams = snakemake.params.beams
    if set(out) != set(beams):
        raise ValueError(f"outputs for beams {sorted(out)}, params for {sorted(beams)}")
    lines = run_grid_lines(
        beams,
        snakemake.params.spec,
        snakemake.params.amplitude,
        Effects.from_list(snakemake.params.effects),
        numerics_from_config(snakemake.params.numerics),
        log=log.info,  # one line per point, in the job's log
    )
    for beam, rows in lines.items():
        failed = sum(not row["converged"] for row in rows)
        log.info(f"{beam}: {len(rows) - failed} points converged, {failed} not")
        write_records(rows, line_columns(True), out[beam])
