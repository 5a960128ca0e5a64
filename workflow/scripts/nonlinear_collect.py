"""Every amplitude's branch and sweeps in one table and figure, and the folds table."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.report.io import write_csv, write_table
from rotbeam.report.joblog import job_log
from rotbeam.report.nonlinear_figures import branches_figure

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    rows = pd.concat([pd.read_csv(f) for f in snakemake.input.rows], ignore_index=True)
    folds = pd.concat([pd.read_csv(f) for f in snakemake.input.folds], ignore_index=True)
    write_csv(rows, snakemake.output.csv)
    title = (
        f"Where each arm of the branch of periodic orbits first loses stability (loss_kind at "
        f"f_loss [Hz]; f_fold the arm's first fold) against where the time-stepped sweep in the "
        f"same direction leaves the arm's stable orbits (sweep_last_on, sweep_first_off [Hz]: RMS "
        f"within 2 % of the arm's, and the next point); agrees when f_loss lies between them "
        f"(distance [Hz] outside); jump_from -> jump_to: the sweep's largest RMS change; "
        f"hysteresis_from..to: where the up and down sweeps differ by > 10 % of the largest RMS; "
        f"M: the arm's collocation instants, tail: the harmonic tail of its orbit at the loss "
        f"(the arm is followed again on 2 M - 1 while it is above tail_tol, up to M_max), "
        f"loss_kind_coarse, f_loss_coarse: the loss on M_coarse instants. "
        f"Omega_0 = {snakemake.params.omega0:g} rad/s."
    )
    log.info("%s", folds.to_string())
    write_table(folds, snakemake.output.folds_csv, snakemake.output.folds_md, title)
    out = snakemake.output
    branches_figure(rows, folds, snakemake.params.omega0, out.pdf, out.png)
