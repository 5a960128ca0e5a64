# One-mode Galerkin surrogate with Southwell stiffening (Sec. 6) beside the full model.
# Cheap: no simulation of its own, the full model's numbers come from the sweep lines.
SURROGATE_FIG4_LINES = expand(
    "results/sims/ref/fig4_w{w}.csv",
    w=[format(float(w), "g") for w in config["fig4"]["omega0"]],
)


rule surrogate_southwell:
    input:
        lines=["results/sims/ref/fig3.csv", *SURROGATE_FIG4_LINES],
    output:
        csv="results/surrogate/southwell.csv",
        md=report(
            "results/surrogate/southwell.md",
            caption="../report/surrogate_southwell_table.rst",
            category="Surrogate",
        ),
        pdf=report(
            "results/surrogate/southwell.pdf",
            caption="../report/surrogate_southwell.rst",
            category="Surrogate",
        ),
        png="results/surrogate/southwell.png",
    log:
        "logs/surrogate_southwell.log",
    benchmark:
        "benchmarks/surrogate_southwell.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("surrogate_southwell"),
        beam=config["beam"],
        amplitude=config["amplitude"],
        c_max=config["surrogate"]["c_max"],
        N=config["surrogate"]["N"],
    script:
        "../scripts/surrogate_southwell.py"


rule surrogate_vs_full:
    input:
        fig4=SURROGATE_FIG4_LINES,
        lines=boundary_line_files(REF),
        boundary="results/boundary/ref.csv",
        fit="results/fig6/fit.json",
    output:
        csv="results/surrogate/vs_full.csv",
        md=report(
            "results/surrogate/vs_full.md",
            caption="../report/surrogate_vs_full_table.rst",
            category="Surrogate",
        ),
        pdf=report(
            "results/surrogate/vs_full.pdf",
            caption="../report/surrogate_vs_full.rst",
            category="Surrogate",
        ),
        png="results/surrogate/vs_full.png",
        points="results/surrogate/vs_full_points.csv",
        boundary="results/surrogate/boundary.csv",
        speed="results/surrogate/speed.json",
    log:
        "logs/surrogate_vs_full.log",
    benchmark:
        "benchmarks/surrogate_vs_full.tsv"
    priority: 1  # a long job: it starts before the quick figures and tables
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("surrogate_vs_full"),
        beam=config["beam"],
        amplitude=config["amplitude"],
        effects=config["effects"],
        threshold=config["main_threshold"],
        N=config["surrogate"]["N"],
        n_scan=config["surrogate"]["n_scan"],
        boundary_points=config["surrogate"]["boundary_points"],
        curve_points=config["surrogate"]["curve_points"],
        tolerance=config["surrogate"]["tolerance"],
    script:
        "../scripts/surrogate_vs_full.py"
