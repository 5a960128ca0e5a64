"""Fig. 7 study: every boundary line of one damping/geometry hypothesis's small grid."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.model.params import Effects
from rotbeam.paper.studies import line_columns, run_grid_lines
from rotbeam.report.io import write_records
from rotbeam.report.joblog import job_log
from rotbeam.runs.sweeps import numerics_from_config

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    lines = run_grid_lines(
        snakemake.params.beams,
        snakemake.params.spec,
        snakemake.params.amplitude,
        Effects.from_list(snakemake.params.effects),
        numerics_from_config(snakemake.params.numerics),
        log=log.info,  # one line per point, in the job's log
    )
    rows = [{**row, "beam": bid} for bid, records in lines.items() for row in records]
    write_records(rows, line_columns(True, "beam"), snakemake.output[0])
