"""What the beam does from rest at one large-drive scene: its response class, Lyapunov exponent
and its convergence, the Poincare section."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
import pandas as pd

from rotbeam.model.params import Beam, Drive
from rotbeam.report.io import write_csv, write_json
from rotbeam.report.joblog import job_log
from rotbeam.report.nonlinear_figures import response_figure
from rotbeam.runs.response import response_of
from rotbeam.runs.scene import Scene
from rotbeam.solve.numerics import Numerics

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    p = snakemake.params
    r = p.response
    drive = Drive(omega0=p.omega0, f_d=r["f_d"], amplitude=r["amplitude"])
    scene = Scene(beam=Beam(**p.beam), drive=drive, numerics=Numerics(N=r["N"]))

    def progress(done: int, total: int) -> None:
        if done % 10 == 0 or done == total:
            log.info("%d of %d periods", done, total)

    res = response_of(scene.model(), scene.beam.T, r["transient_periods"], r["section_periods"],
                      start=r["start"], max_seconds=r["max_seconds"], rtol=r["rtol"],
                      progress=progress)  # fmt: skip
    log.info("%s", res.message)
    out = {**res.as_dict(), "omega0": p.omega0, "amplitude": r["amplitude"], "f_d": r["f_d"],
           "start": res.start, "section_distances": res.distances,
           "seconds": res.seconds}  # fmt: skip
    write_json(out, snakemake.output.json)
    write_csv(
        pd.DataFrame({"y_m": res.section[:, 0], "y_m_rate": res.section[:, 1]}),
        snakemake.output.csv,
    )
    title = (f"a = {r['amplitude']:g} rad/s, f_d = {r['f_d']:g} Hz from {res.start}: "
             f"{res.response}, lambda_max = {res.lyapunov_max:.3g} +- "
             f"{res.lyapunov_spread:.2g} 1/s (N = {res.N})")  # fmt: skip
    response_figure(res.section, res.lyapunov_running, r["f_d"], title, snakemake.output.png,
                    late=res.lyapunov_max)  # fmt: skip
