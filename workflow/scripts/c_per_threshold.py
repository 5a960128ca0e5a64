"""Fitted c of f_d* = c f_0 per threshold, beside the paper's values and App. E's c_0."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.analysis.boundary import c_per_threshold
from rotbeam.paper.printed import printed_per_threshold, read_claims
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    _, claims = read_claims()
    paper = printed_per_threshold(claims, "c_")
    ref = pd.read_csv(snakemake.input.ref)
    beams = pd.concat([pd.read_csv(f) for f in snakemake.input.beams], ignore_index=True)
    t_ref = (
        c_per_threshold(ref, paper)
        .add_prefix("ref_")
        .rename(columns={"ref_threshold": "threshold"})
    )
    t_all = c_per_threshold(beams)[
        ["threshold", "c_root", "c_root_stderr", "lines_used", "lines_dropped"]
    ]
    t_all = t_all.rename(columns=lambda c: c if c == "threshold" else "fig7_beams_" + c)
    table = t_ref.merge(t_all, on="threshold", how="left")
    log.info("c per threshold:\n%s", table.to_string())
    write_table(
        table, snakemake.output.csv, snakemake.output.md,
        "Fitted c (f_d* = c f_0, curve_fit) per threshold: reference beam (root of the scan and the"
        " paper's first-grid-point rule) and the Fig. 7 beams; c_paper from App. D. lines_used /"
        " lines_dropped: sweep lines in / out of the fit (out: no crossing of the threshold, or an"
        " empty or failed line; their reasons are in results/boundary/*.csv).",
    )  # fmt: skip
    cols = ["C_max", "omega0", "threshold", "f0_hz", "f_d_grid", "f_d_root", "E_star_grid",
            "E_star_root", "points_used", "points_failed", "points_unconverged"]  # fmt: skip
    write_table(ref[cols], snakemake.output.boundary_csv, snakemake.output.boundary_md,
                "Phase boundary of the reference beam (Fig. 5a).")  # fmt: skip
