"""The grid-convergence lines of Fig. B.8, in one job: a row per point, the lines one after the
other (column `N` tells them apart with `omega0`)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.model.params import Effects
from rotbeam.paper.studies import run_convergence_lines
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    df = run_convergence_lines(
        snakemake.params.lines,
        Effects.from_list(snakemake.params.effects),
        dict(snakemake.params.numerics),
        log=log.info,  # one line per point, in the job's log
    )
    failed = int((~df["converged"].astype(bool)).sum())
    log.info(f"done: {len(snakemake.params.lines)} lines, {len(df) - failed} points converged, "
             f"{failed} failed or unverified")  # fmt: skip
    write_csv(df, snakemake.output[0])
