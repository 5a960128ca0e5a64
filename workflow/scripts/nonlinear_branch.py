"""One drive amplitude: the branch of periodic orbits in f_d (two arms) and the sweeps up and down
that follow the beam, with where each arm first loses stability against where its sweep jumps."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Beam
from rotbeam.report.io import write_csv
from rotbeam.report.joblog import job_log
from rotbeam.runs.nonlinear import NonlinearSpec, run_amplitude

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    p = snakemake.params
    spec = NonlinearSpec(amplitude=float(snakemake.wildcards.amp), **p.spec)
    log.info("%s", spec)
    rows, folds = run_amplitude(Beam(**p.beam), spec, log=log)
    for f in folds:
        log.info("%s", f)
    write_csv(pd.DataFrame(rows), snakemake.output.rows)
    write_csv(pd.DataFrame(folds), snakemake.output.folds)
