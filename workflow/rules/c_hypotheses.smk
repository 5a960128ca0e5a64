# Why the paper's c is larger than ours: candidate mechanisms, each run through our model, and
# the paper's first-grid-point rule on coarse scans (docs/c_hypotheses.md).  Its own simulations
# (a few lines at C_max of config c_hypotheses); consumed by the reproduction's claims table.


rule c_hypotheses:
    output:
        csv="results/reproduction/c_hypotheses.csv",
        md="results/reproduction/c_hypotheses.md",
        pdf=report(
            "results/reproduction/c_hypotheses.pdf",
            caption="../report/c_hypotheses.rst",
            category="Reproduction",
        ),
        png="results/reproduction/c_hypotheses.png",
    log:
        "logs/c_hypotheses.log",
    benchmark:
        "benchmarks/c_hypotheses.tsv"
    priority: 1  # a long job: it starts before the quick figures and tables
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("c_hypotheses"),
        study=config["c_hypotheses"],
        beam=config["beam"],
        amplitude=config["amplitude"],
    script:
        "../scripts/c_hypotheses.py"
