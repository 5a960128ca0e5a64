"""One line of the atlas: the sweep at the line's Omega_0 over the atlas's drive frequencies, a
row per grid point (those its time budget did not reach marked)."""
# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)

from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.report.io import write_records
from rotbeam.report.joblog import job_log
from rotbeam.runs.atlas import ATLAS_COLUMNS, grid_axes, line_records, run_line
from rotbeam.runs.scene import Scene
from rotbeam.runs.sweeps import numerics_from_config

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    spec = snakemake.params.atlas
    index = int(snakemake.wildcards.index)
    omega0s, f_ds = grid_axes(spec["omega0"], spec["f_d"])
    amplitude = spec.get("amplitude", 1.0)
    scene = Scene(
        Beam(**snakemake.params.beam),
        Drive(omega0=omega0s[index], amplitude=amplitude, f_d=f_ds[0]),
        Effects.from_list(snakemake.params.effects),
        numerics_from_config(snakemake.params.numerics),
    )
    log.info(f"line {index + 1} of {len(omega0s)}: Omega_0 = {omega0s[index]:g} rad/s, "
             f"{len(f_ds)} points")  # fmt: skip

    def point(k, row):
        log.info(f"[{k + 1}/{len(f_ds)}] f_d={row['f_d']:.4g} Hz dRMS={row['delta_rms']:.4g} "
                 f"({row['seconds']:.2f} s)")  # fmt: skip

    line = run_line(scene, omega0s[index], f_ds, progress=point)
    if line.message:
        log.info(line.message)
    rows = line_records(scene, omega0s[index], f_ds, line, index, line.message)
    write_records(rows, ATLAS_COLUMNS, snakemake.output[0])
