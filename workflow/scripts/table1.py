"""Table 1 with the derived groups."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Beam
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    b = Beam(**snakemake.params.beam)
    rows = [
        ("L", b.L * 1e3, "mm", "40"), ("h", b.h * 1e3, "mm", "2"), ("b", b.b * 1e3, "mm", "10"),
        ("E", b.E / 1e6, "MPa", "1.22"), ("rho", b.rho, "kg/m^3", "1170.2"),
        ("R (assumed)", b.R * 1e3, "mm", "not printed"), ("gamma", b.gamma, "N s/m^2", "0.039"),
        ("T", b.T, "s", ""), ("f_n", b.f_n, "Hz", "6.37"), ("zeta", b.zeta, "", "0.017"),
        ("G", b.G, "s^2", ""), ("eta", b.eta, "", ""), ("delta = L/R", b.delta, "", ""),
        ("R_o / L", b.hub_ratio, "", ""),
    ]  # fmt: skip
    df = pd.DataFrame(rows, columns=["quantity", "value", "unit", "paper"])
    write_table(df, snakemake.output.csv, snakemake.output.md, "Table 1 and derived groups.")
