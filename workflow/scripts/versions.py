"""results/about/versions.txt: the versions this run used, each against constraints.txt."""

# ruff: noqa: F821
# (`snakemake` is injected by Snakemake)
from pathlib import Path

checked = {k.lower(): v for k, v in snakemake.params.checked.items()}
checked.setdefault("python", "3.11.7")
rows = [("package", "this run", "checked with (constraints.txt)", "")]
for name, version in snakemake.params.versions.items():
    ref = checked.get(name.lower(), "-")
    rows.append((name, version, ref, "" if version == ref else "differs"))
rows.append(("rotbeam MODEL_VERSION", str(snakemake.params.model_version), "", ""))
width = [max(len(r[i]) for r in rows) for i in range(4)]
lines = ("  ".join(c.ljust(w) for c, w in zip(r, width, strict=True)).rstrip() for r in rows)
text = "\n".join(lines)
Path(snakemake.output[0]).write_text(text + "\n")
Path(snakemake.log[0]).write_text(f"{sum(r[3] == 'differs' for r in rows)} versions differ\n")
