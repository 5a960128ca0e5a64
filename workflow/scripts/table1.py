"""Table 1 with the derived groups."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Beam
from rotbeam.paper.printed import read_claims
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule):
    b = Beam(**snakemake.params.beam)
    inputs, claims = read_claims()
    printed = claims.set_index("id")["paper"]

    def paper(name: str, scale: float = 1.0) -> str:
        """The printed input in the table's unit (paper_claims.yaml), as %g."""
        return f"{inputs[name]['paper'] * scale:g}"

    rows = [
        ("L", b.L * 1e3, "mm", paper("L", 1e3)), ("h", b.h * 1e3, "mm", paper("h", 1e3)),
        ("b", b.b * 1e3, "mm", paper("b", 1e3)), ("E", b.E / 1e6, "MPa", paper("E", 1e-6)),
        ("rho", b.rho, "kg/m^3", paper("rho")),
        ("R (assumed)", b.R * 1e3, "mm", "not printed"),
        ("gamma", b.gamma, "N s/m^2", paper("gamma")),
        ("T", b.T, "s", ""), ("f_n", b.f_n, "Hz", f"{printed['f_n_hz']:g}"),
        ("zeta", b.zeta, "", f"{printed['zeta']:g}"),
        ("G", b.G, "s^2", ""), ("eta", b.eta, "", ""), ("delta = L/R", b.delta, "", ""),
        ("R_o / L", b.hub_ratio, "", ""),
    ]  # fmt: skip
    df = pd.DataFrame(rows, columns=["quantity", "value", "unit", "paper"])
    write_table(df, snakemake.output.csv, snakemake.output.md, "Table 1 and derived groups.")
