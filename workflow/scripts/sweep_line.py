"""One sweep line: dynamic and quasi-static RMS at each drive frequency (a row per point)."""
# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)

from rotbeam.model.params import Effects
from rotbeam.paper.studies import line_columns, run_line, scan_frequencies
from rotbeam.report.io import write_records
from rotbeam.report.joblog import job_log
from rotbeam.runs.sweeps import numerics_from_config

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    say = log.info  # one line per point of the line (scan_line's progress)
    spec = snakemake.params.spec
    f_ds = scan_frequencies(spec)
    say(f"line {snakemake.wildcards.line} of beam {snakemake.wildcards.beam}: {len(f_ds)} points")
    rows = run_line(
        spec,
        f_ds,
        Effects.from_list(snakemake.params.effects),
        numerics_from_config(snakemake.params.numerics),
        log=say,
    )
    failed = sum(not row["converged"] for row in rows)
    say(f"done: {len(rows) - failed} converged, {failed} failed or unverified")
    write_records(rows, line_columns("c_max" in spec), snakemake.output[0])
