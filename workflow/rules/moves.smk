# Motion design (config move_designs): each designed move beside its rigid, ZV and ZVD
# baselines, one table, one move file each and the figure of the first design.  Target `moves`
# (not part of `all`: `snakemake --cores all moves`).


rule moves:
    input:
        move_design_targets(),


rule move_designs:
    output:
        csv="results/moves/designs.csv",
        md=report(
            "results/moves/designs.md",
            caption="../report/move_designs.rst",
            category="Tables",
        ),
        profiles=expand(
            "results/moves/{name}.csv", name=[d["name"] for d in MOVE_DESIGNS]
        ),
        pdf="results/moves/design.pdf",
        png=report(
            "results/moves/design.png",
            caption="../report/move_designs.rst",
            category="Figures",
        ),
    log:
        "logs/move_designs.log",
    benchmark:
        "benchmarks/move_designs.tsv"
    priority: 1  # a long job: it starts before the quick figures and tables
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("move_designs"),
        designs=MOVE_DESIGNS,
        base=lambda wildcards: CONFIG_DIR,
    script:
        "../scripts/move_designs.py"
