"""Motion design (config move_designs): each move designed, checked beside its baselines,
tabulated, written as a move file; the first drawn."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.analysis.move_design import design_move, design_spec
from rotbeam.report.design_figures import design_figure
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    p = snakemake.params
    rows, first = [], None
    for spec, profile in zip(p.designs, snakemake.output.profiles, strict=True):
        name, scene, request = design_spec(spec, p.base)
        design = design_move(scene, **request)
        design.write_csv(profile)
        log.info("%s: %s (search %.1f s, baselines %.1f s)", name, design.message,
                 design.seconds, design.baseline_seconds)  # fmt: skip
        s = design.summary()
        for row in design.rows():
            rows.append({"design": name, **row, "tolerance": s["tolerance"],
                         "observable": s["observable"], "found": design.found,
                         "robust_residual": s["robust_residual"], "search_s": s["seconds"],
                         "family": s["family"], "settle_s": s["settle_s"],
                         "profile": profile})  # fmt: skip
        first = first or design
    write_table(pd.DataFrame(rows), snakemake.output.csv, snakemake.output.md,
                "Designed moves beside the rigid-body time-optimal move and its ZV and ZVD "
                "shapings (full model).")  # fmt: skip
    design_figure(first, snakemake.output.pdf, snakemake.output.png)
