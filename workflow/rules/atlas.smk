# The atlas of the phase plane (README "An atlas of the phase plane"): Delta RMS at every
# (Omega_0, f_d) of a grid, one job per Omega_0 line (a sweep line; Slurm spreads them over its
# nodes, profiles/slurm) and one that gathers them with the f_d* boundary.  Not in `all`: run it
# as `snakemake --cores all atlas`.
from rotbeam.runs.atlas import grid_axes

ATLAS = config.get("atlas") or {}
try:
    ATLAS_OMEGA0S, ATLAS_FDS = (
        grid_axes(ATLAS["omega0"], ATLAS["f_d"]) if ATLAS else ([], [])
    )
except RotbeamInputError as exc:
    print(f"rotbeam: invalid config: {exc}", file=sys.stderr)
    sys.exit(2)


wildcard_constraints:
    index="[0-9]+",


rule atlas:
    input:
        expand("results/atlas/atlas.{ext}", ext=["csv", "png"]),


rule atlas_line:
    output:
        "results/atlas/lines/line{index}.csv",
    log:
        "logs/atlas_line_{index}.log",
    benchmark:
        "benchmarks/atlas_line_{index}.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("atlas_line"),
        beam=config["beam"],
        effects=config["effects"],
        numerics=atlas_numerics(config["numerics"], ATLAS),
        atlas=ATLAS,
    script:
        "../scripts/atlas_line.py"


rule atlas_gather:
    input:
        expand("results/atlas/lines/line{index}.csv", index=range(len(ATLAS_OMEGA0S))),
    output:
        csv="results/atlas/atlas.csv",
        png=report(
            "results/atlas/atlas.png",
            caption="../report/atlas.rst",
            category="Atlas",
        ),
    log:
        "logs/atlas_gather.log",
    benchmark:
        "benchmarks/atlas_gather.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("atlas_gather"),
        beam=config["beam"],
        threshold=config["main_threshold"],
    script:
        "../scripts/atlas_gather.py"
