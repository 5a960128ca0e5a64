"""Fig. 7 study: which damping/geometry hypothesis makes every beam of the grid collapse."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import json

import pandas as pd

from rotbeam.paper.hypotheses import fig7_variant_study
from rotbeam.paper.printed import read_claims
from rotbeam.paper.reproduction_figures import fig7_variants
from rotbeam.report.io import write_csv, write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    _, claims = read_claims()
    within = float(claims.set_index("id").loc["fig7_collapse", "at"]["within"])
    c_ref = json.load(open(snakemake.input.ref_fit))["c"]
    files = zip(snakemake.params.variants, snakemake.input.lines, strict=True)
    lines = {v: pd.read_csv(f) for v, f in files}
    th = snakemake.params.threshold
    table, long, boundaries = fig7_variant_study(lines, snakemake.params.beams, c_ref, th, within)
    write_table(table, snakemake.output.csv, snakemake.output.md,
                f"Fig. 7 per damping/geometry hypothesis: beams whose every E*/E_n lies within "
                f"{within:g} of c sqrt(1 + x), c = {c_ref:.4g} (reference beam), and c fitted "
                f"over the hypothesis's grid.")  # fmt: skip
    write_csv(long, snakemake.output.long)
    fig7_variants(boundaries, c_ref, th, within, snakemake.output.pdf, snakemake.output.png)
