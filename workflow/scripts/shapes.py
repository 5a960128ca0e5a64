"""Centerline shapes over one drive period in the rotating and the lab frame (Fig. 2c)."""
# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)

from dataclasses import replace

from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.model.shapes import shapes_over_period
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log
from rotbeam.runs.scene import Scene, simulate
from rotbeam.runs.sweeps import numerics_from_config

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    p = snakemake.params
    num = replace(
        numerics_from_config(p.numerics),
        rms_periods=1,
        samples_per_period=max(8, 4 * p.drive["frames"]),
    )
    scene = Scene(
        Beam(**p.beam), Drive(p.drive["omega0"], p.amplitude, p.drive["f_d"]),
        Effects.from_list(p.effects), num,
    )  # fmt: skip
    res = simulate(scene)
    log.info("scene: %s", res.summary())
    write_csv(shapes_over_period(res, p.drive["frames"]), snakemake.output[0])
