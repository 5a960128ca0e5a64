"""The grid-convergence lines of Fig. B.8, in one job: a row per point, the lines one after the
other (column `N` tells them apart with `omega0`)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.model.params import Effects
from rotbeam.paper.studies import line_columns, run_convergence_lines
from rotbeam.report.io import write_records
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    rows = run_convergence_lines(
        snakemake.params.lines,
        Effects.from_list(snakemake.params.effects),
        dict(snakemake.params.numerics),
        log=log.info,  # one line per point, in the job's log
    )
    failed = sum(not row["converged"] for row in rows)
    log.info(f"done: {len(snakemake.params.lines)} lines, {len(rows) - failed} points converged, "
             f"{failed} failed or unverified")  # fmt: skip
    write_records(rows, line_columns(False), snakemake.output[0])
