"""One scene whose dynamic and quasi-static time series are kept (Fig. 3b,c; Fig. 5b,c)."""
# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)

from dataclasses import replace

from rotbeam.model.params import Beam, Drive, Effects
from rotbeam.report.io import write_records
from rotbeam.report.joblog import job_log
from rotbeam.runs.scene import Scene, simulate
from rotbeam.runs.sweeps import numerics_from_config

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    spec = snakemake.params.spec
    num = numerics_from_config(snakemake.params.numerics)
    num = replace(
        num, rms_periods=int(spec["periods"]), samples_per_period=max(64, num.samples_per_period)
    )
    scene = Scene(
        Beam(**spec["beam"]),
        Drive(spec["omega0"], spec["amplitude"], spec["f_d"]),
        Effects.from_list(snakemake.params.effects),
        num,
    )
    res = simulate(scene)
    s = res.summary()
    keys = ("rms_dynamic", "rms_quasistatic", "delta_rms", "converged", "message", "C_max",
            "E_max", "seconds")  # fmt: skip
    log.info("scene %s: %s", snakemake.wildcards.name, {k: s[k] for k in keys})
    series = res.time_series()  # column -> samples; the scene's numbers repeat on every row
    kept = ("rms_dynamic", "rms_quasistatic", "delta_rms", "C_max", "E_max", "f_d", "omega0",
            "f_n_hz", "converged")  # fmt: skip
    scalars = {key: s[key] for key in kept}
    rows = (
        {**dict(zip(series, values, strict=True)), **scalars}
        for values in zip(*series.values(), strict=True)
    )
    write_records(rows, [*series, *scalars], snakemake.output[0])
