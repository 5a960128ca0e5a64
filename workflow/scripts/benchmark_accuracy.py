"""Work-precision benchmark: every run's error and wall time, speed-ups, the figure."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import sys

from rotbeam.bench.plan import plan_from_dict
from rotbeam.bench.report import write_outputs
from rotbeam.bench.run import run_benchmark
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    plan = plan_from_dict(snakemake.params.plan)

    def say(msg: str) -> None:
        log.info(msg)
        print(f"[benchmark_accuracy] {msg}", file=sys.stderr, flush=True)

    runs, refs = run_benchmark(plan, progress=say)
    write_outputs(runs, refs, plan, snakemake.output.csv.removesuffix(".csv"))
