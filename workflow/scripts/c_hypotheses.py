"""c of f_d* = c f_0 per threshold for each candidate mechanism of the paper's c (long table,
Markdown with the verdict, figure)."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.model.params import Beam
from rotbeam.paper.c_hypotheses import study_from_config
from rotbeam.paper.c_hypotheses_figures import c_hypotheses_figure, c_hypotheses_markdown
from rotbeam.report.io import write_csv, write_text
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    study = study_from_config(snakemake.params.study, snakemake.params.amplitude)
    table = study.run(Beam(**snakemake.params.beam), log.info)
    write_csv(table, snakemake.output.csv)
    write_text(c_hypotheses_markdown(table, study.describe()), snakemake.output.md)
    c_hypotheses_figure(table, snakemake.output.pdf, snakemake.output.png)
