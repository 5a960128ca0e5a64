"""App. E table: c_0 per threshold, printed vs exact, and at the reference beam's zeta."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Beam
from rotbeam.model.secondorder import c0_limit, c0_root
from rotbeam.paper.printed import printed_per_threshold, read_claims
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    zeta = Beam(**snakemake.params.beam).zeta
    _, claims = read_claims()
    printed = printed_per_threshold(claims, "c0_")
    rows = [
        {"threshold": t, "c0_zeta0": c0_limit(t), "c0_paper": printed.get(round(t, 4)),
         "c0_at_beam_zeta": c0_root(zeta, t), "beam_zeta": zeta}
        for t in snakemake.params.thresholds
    ]  # fmt: skip
    write_table(pd.DataFrame(rows), snakemake.output.csv, snakemake.output.md,
                "c_0 for the canonical second-order system (App. E).")  # fmt: skip
