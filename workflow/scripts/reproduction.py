"""The claims table: every printed number beside ours, with a status and its reason."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import json

import pandas as pd

from rotbeam.paper.claims import (
    HYPOTHESIS_COLUMNS,
    Outputs,
    builtin_hypotheses,
    c_hypotheses_long,
    claims_markdown,
    judge,
    ours_values,
)
from rotbeam.paper.printed import read_claims
from rotbeam.report.io import write_csv, write_text
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    inp = snakemake.input
    _, claims = read_claims()
    out = Outputs(
        table1=pd.read_csv(inp.table1),
        c_per_threshold=pd.read_csv(inp.c_per_threshold),
        boundary_ref=pd.read_csv(inp.boundary_ref),
        fig6_fit=json.load(open(inp.fig6_fit)),
        fig7_fit=json.load(open(inp.fig7_fit)),
        fig7_boundary=pd.concat([pd.read_csv(f) for f in inp.fig7_grid], ignore_index=True),
        fig3_line=pd.read_csv(inp.fig3_line),
        fig3_series=pd.read_csv(inp.fig3_series),
        fig5_series=[pd.read_csv(f) for f in inp.fig5_series],
        ref_lines=pd.concat([pd.read_csv(f) for f in inp.ref_lines], ignore_index=True),
        c0_table=pd.read_csv(inp.c0_table),
        convergence=pd.read_csv(inp.convergence),
        stretch=pd.read_csv(inp.stretch),
        main_threshold=float(snakemake.params.threshold),
        amplitude=float(snakemake.params.amplitude),
        convergence_tolerance=float(snakemake.params.convergence_tolerance),
    )
    ours = ours_values(out, claims)
    hyp = [pd.read_csv(f) for f in inp.studies] + [builtin_hypotheses(out, claims, ours)]
    hyp += [c_hypotheses_long(pd.read_csv(f), claims) for f in inp.c_hypotheses]
    hyp = pd.concat(
        [h.reindex(columns=[*HYPOTHESIS_COLUMNS, "counts"]) for h in hyp if len(h)],
        ignore_index=True,
    )
    hyp["counts"] = hyp["counts"].fillna(True).astype(bool)
    table = judge(claims, ours, hyp)
    log.info("claims:\n%s", table[["id", "paper", "ours", "status"]].to_string())
    write_csv(table, snakemake.output.csv)
    write_text(claims_markdown(table), snakemake.output.md)
