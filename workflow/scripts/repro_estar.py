"""E* ~ 5: what each reading of the Euler number gives on the plateau and at Fig. 5b,c."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Beam
from rotbeam.paper.hypotheses import estar_study
from rotbeam.paper.printed import read_claims
from rotbeam.report.io import write_csv, write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    _, claims = read_claims()
    paper = claims.set_index("id")["paper"]
    f5 = snakemake.params.fig5
    line50 = pd.read_csv(snakemake.input.line50[0]) if snakemake.input.line50 else None
    table, long = estar_study(
        pd.read_csv(snakemake.input.boundary), Beam(**snakemake.params.beam),
        snakemake.params.threshold, float(paper["c_0.10"]), float(paper["f_n_hz"]),
        float(f5["c_max"]), tuple(float(e) for e in f5["e_max"]), line50,
        snakemake.params.amplitude,
    )  # fmt: skip
    write_table(table, snakemake.output.csv, snakemake.output.md,
                "E* ~ 5 (Sec. 5): each reading of the Euler number, its E* on the plateau "
                "(C_max <= 10) and at Fig. 5's C_max, whether Fig. 5b (dynamic) and 5c "
                "(quasi-static) then hold, and Delta RMS of the full model at the drive frequency "
                "the reading gives each Fig. 5 point.")  # fmt: skip
    write_csv(long, snakemake.output.long)
