"""The reference beam's boundary lines, in one job: a file per line (a row per point, its
`c_max_target` naming the line), each written when its line is done."""
# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)

from pathlib import Path

from rotbeam.model.params import Effects
from rotbeam.paper.studies import line_columns, run_line, scan_frequencies
from rotbeam.report.io import write_records
from rotbeam.report.joblog import job_log
from rotbeam.runs.sweeps import numerics_from_config

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    lines = snakemake.params.lines
    out = {Path(f).stem: f for f in snakemake.output}  # line id -> its file
    if set(out) != set(lines):
        raise ValueError(f"outputs for lines {sorted(out)}, params for {sorted(lines)}")
    effects = Effects.from_list(snakemake.params.effects)
    numerics = numerics_from_config(snakemake.params.numerics)
    for line, spec in lines.items():
        f_ds = scan_frequencies(spec)
        log.info(f"line {line}: {len(f_ds)} points")
        rows = run_line(spec, f_ds, effects, numerics, log=log.info)
        failed = sum(not row["converged"] for row in rows)
        log.info(f"{line}: {len(rows) - failed} converged, {failed} failed or unverified")
        write_records(rows, line_columns(True), out[line])
