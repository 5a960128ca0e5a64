"""f_n = 6.37 Hz and zeta = 0.017: which single change of a printed input gives each."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Beam
from rotbeam.paper.hypotheses import fn_zeta_study
from rotbeam.paper.printed import read_claims
from rotbeam.report.io import write_csv, write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    inputs, claims = read_claims()
    paper = claims.set_index("id")["paper"]
    table, long = fn_zeta_study(Beam(**snakemake.params.beam), inputs, float(paper["f_n_hz"]),
                                float(paper["zeta"]), int(snakemake.params.N))  # fmt: skip
    write_table(
        table,
        snakemake.output.csv,
        snakemake.output.md,
        "f_n and zeta: the value of each printed input (alone) that gives the printed f_n, "
        "or zeta, whether it lies within the input's printed precision, and what the other "
        "quantity then is; last rows: the discrete model's f_n and the (E, gamma) pair.",
    )
    write_csv(pd.DataFrame(long), snakemake.output.long)
