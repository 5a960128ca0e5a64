"""results/about/versions.txt: the versions this run used, each against constraints.txt."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)

from rotbeam.report.io import write_text
from rotbeam.report.joblog import job_log

with job_log(snakemake.log[0], snakemake.input, snakemake.output, snakemake.rule) as log:
    checked = {k.lower(): v for k, v in snakemake.params.checked.items()}
    checked.setdefault("python", "3.11.7")
    rows = [("package", "this run", "checked with (constraints.txt)", "")]
    for name, version in snakemake.params.versions.items():
        ref = checked.get(name.lower(), "-")
        rows.append((name, version, ref, "" if version == ref else "differs"))
    rows.append(("rotbeam code hash", str(snakemake.params.code)[:16], "", ""))
    width = [max(len(r[i]) for r in rows) for i in range(4)]
    lines = ("  ".join(c.ljust(w) for c, w in zip(r, width, strict=True)).rstrip() for r in rows)
    text = "\n".join(lines)
    write_text(text + "\n", snakemake.output[0])
    log.info("%d versions differ", sum(r[3] == "differs" for r in rows))
