# Tables that need no simulation.


rule table1:
    output:
        csv="results/tables/table1.csv",
        md=report(
            "results/tables/table1.md",
            caption="../report/table1.rst",
            category="Tables",
        ),
    log:
        "logs/table1.log",
    benchmark:
        "benchmarks/table1.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        claims=CLAIMS_VERSION,
        code=code_version("table1"),
        beam=config["beam"],
    script:
        "../scripts/table1.py"


rule systems_table:
    output:
        csv="results/tables/systems.csv",
        md=report(
            "results/tables/systems.md",
            caption="../report/systems.rst",
            category="Tables",
        ),
    log:
        "logs/systems_table.log",
    benchmark:
        "benchmarks/systems_table.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("systems_table"),
        beam=config["beam"],
    script:
        "../scripts/systems_table.py"


rule c0_table:
    output:
        csv="results/tables/c0_threshold.csv",
        md=report(
            "results/tables/c0_threshold.md",
            caption="../report/c0_threshold.rst",
            category="Tables",
        ),
    log:
        "logs/c0_table.log",
    benchmark:
        "benchmarks/c0_table.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        claims=CLAIMS_VERSION,
        code=code_version("c0_table"),
        thresholds=config["c0_thresholds"],
        beam=config["beam"],
    script:
        "../scripts/c0_table.py"
