"""Your own scenes (config user_scenes): simulated, judged, tabulated and drawn."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.analysis.scenes import judge_scenes
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log
from rotbeam.report.scene_figures import scenes_figure

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    p = snakemake.params
    table = judge_scenes(p.scenes, p.threshold, p.base, p.observe)
    for row in table.itertuples():
        log.info("%s: %s (%.2f s)", row.scene, row.verdict, row.seconds)
    write_table(table, snakemake.output.csv, snakemake.output.md,
                f"Your scenes against Delta RMS = {p.threshold:g}.")  # fmt: skip
    scenes_figure(table, p.threshold, snakemake.output.pdf, snakemake.output.png)
