"""Axial stretching on the Fig. 5 lines: clamp strain, and f_d*, RMS, Delta RMS off and on."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from rotbeam.model.params import Beam, Effects
from rotbeam.paper.stretch_study import stretch_study
from rotbeam.report.io import write_table
from rotbeam.report.joblog import job_log
from rotbeam.solve.numerics import Numerics

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    p = snakemake.params
    spec = p.stretch
    table = stretch_study(Beam(**p.beam), p.lines, spec["c_max"], float(p.amplitude),
                          float(p.threshold), Effects.from_list(p.effects),
                          Numerics(**p.numerics), float(spec["rtol"]))  # fmt: skip
    log.info("stretch study:\n%s", table.to_string())
    write_table(
        table,
        snakemake.output.csv,
        snakemake.output.md,
        "Axial stretching on the Fig. 5 lines: clamp strain N/(EA) (closed form, at the "
        "rotation the model freezes it at); on the studied lines f_d* with stretching off and "
        "on (root finding) and RMS(y_m), Delta RMS at the inextensible f_d* (claims: "
        "inextensible_*).",
    )
