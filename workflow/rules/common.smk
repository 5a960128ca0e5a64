import sys
from pathlib import Path

from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

import rotbeam

from rotbeam.config.errors import RotbeamInputError
from rotbeam.simulate.studies import (
    REF,
    fig7_beams,
    lines_from_config,
    series_from_config,
    validate_config,
)

# Before any job: the JSON schema (snakemake's validate), then what it cannot express (NaN and
# inf, ranges, physics).  A bad value stops the run with one line naming key, value and what is
# allowed, and exit status 2.
SCHEMA = workflow.source_path("../schemas/config.schema.yaml")
try:
    config.update(
        validate_config(dict(config), SCHEMA, lambda c: validate(c, schema=SCHEMA))
    )
except RotbeamInputError as exc:
    print(f"rotbeam: invalid config: {exc}", file=sys.stderr)
    sys.exit(2)

LINES = lines_from_config(config)
SERIES = series_from_config(config)
FIG7_BEAMS = fig7_beams(config)


wildcard_constraints:
    beam="[A-Za-z0-9_.+-]+",
    line="[A-Za-z0-9_.+-]+",
    name="[A-Za-z0-9_.+-]+",


# Threads of the work-precision benchmark: every core of a local run, so that nothing runs beside
# its timings.  With a cluster executor there is no --cores and `workflow.cores` raises; the job
# then asks for two cores of its node (the timings are serial, the second keeps the node quiet).
try:
    BENCHMARK_THREADS = workflow.cores
except WorkflowError:
    BENCHMARK_THREADS = 2

PKG = Path(rotbeam.__file__).parent
# cheap downstream rules rerun when the package code they use changes
CODE_ANALYSIS = [str(PKG / f) for f in ("analysis/boundary.py", "model/criterion.py")]
CODE_FIGURES = [str(PKG / f) for f in ("report/figures.py", "report/style.py")]
CODE_SOLVER = [
    str(PKG / f)
    for f in (
        "bench/plan.py",
        "bench/run.py",
        "bench/report.py",
        "model/elastica.py",
        "solve/steady.py",
        "solve/periodic.py",
        "solve/trbdf2.py",
    )
]


def line_spec(wildcards):
    return LINES[(wildcards.beam, wildcards.line)]


def boundary_line_files(beam):
    return sorted(
        f"results/sims/{b}/{line}.csv"
        for (b, line) in LINES
        if b == beam and line.startswith("cmax")
    )


def figure(stem):
    return [f"results/{stem}.pdf", f"results/{stem}.png"]


def all_targets():
    figs = [
        "fig1/drive_profiles",
        "fig2/shapes_lab_frame",
        "fig3/resonance",
        "fig4/dynamic_vs_quasistatic",
        "fig5/phase_diagram",
        "fig6/critical_frequency",
        "fig7/collapse",
        "figB8/convergence",
        "figD9/thresholds",
        "figE10/c0_vs_zeta",
    ]
    tables = ["table1", "systems", "c0_threshold", "c_per_threshold", "boundary_ref"]
    out = [f for stem in figs for f in figure(stem)]
    out += [f"results/tables/{t}.{ext}" for t in tables for ext in ("csv", "md")]
    out += [
        f"results/surrogate/{s}.{e}"
        for s in ("southwell", "vs_full")
        for e in ("csv", "md", "pdf", "png")
    ]
    out += ["results/surrogate/speed.json"]
    return out
