"""Fig. D.9 as described: the h/L = 1/20 grid per threshold, the magnified window, the bound."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import numpy as np
import pandas as pd

from rotbeam.paper.hypotheses import figD9_study
from rotbeam.paper.printed import read_claims
from rotbeam.paper.reproduction_figures import figD9_window
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    _, claims = read_claims()
    window = claims.set_index("id").loc["figD9_range", "at"]
    cfit = pd.read_csv(snakemake.input.cfit)
    printed_c = claims.loc[claims["id"].str.match(r"c_\d"), "paper"].tolist()
    grid = pd.concat([pd.read_csv(f) for f in snakemake.input.grid], ignore_index=True)
    deltas = np.logspace(-4, np.log10(0.999), snakemake.params.delta_points)
    bound, long = figD9_study(grid, cfit["ref_c_root"].tolist() + printed_c, window, deltas)
    write_csv(bound, snakemake.output.csv)
    write_csv(long, snakemake.output.long)
    figD9_window(grid, bound, window, float(window["C_max"][1]), snakemake.output.pdf,
                 snakemake.output.png)  # fmt: skip
