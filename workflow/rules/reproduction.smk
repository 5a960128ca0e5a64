# Paper against reproduction: the claims table (results/reproduction/claims.csv) and the
# hypothesis studies behind its explanations (config: reproduction).  Every printed value comes
# from rotbeam/paper/paper_claims.yaml; every value of ours from an output of this workflow.


rule repro_fig7_variant:
    output:
        "results/reproduction/fig7/{variant}_lines.csv",
    log:
        "logs/repro_fig7_variant/{variant}.log",
    benchmark:
        "benchmarks/repro_fig7_variant/{variant}.tsv"
    priority: 1  # a long job: it starts before the quick figures and tables
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("repro_fig7_variant"),
        beams=lambda w: R7[w.variant],
        spec={k: REPRO["fig7"][k] for k in ("c_max", "lo", "hi", "points")},
        amplitude=config["amplitude"],
        numerics=config["numerics"],
        effects=config["effects"],
    script:
        "../scripts/repro_fig7_variant.py"


rule repro_fig7:
    input:
        lines=expand(
            "results/reproduction/fig7/{variant}_lines.csv", variant=sorted(R7)
        ),
        ref_fit="results/fig6/fit.json",
    output:
        csv="results/reproduction/fig7_hypotheses.csv",
        md=report(
            "results/reproduction/fig7_hypotheses.md",
            caption="../report/repro_fig7_table.rst",
            category="Reproduction",
        ),
        pdf=report(
            "results/reproduction/fig7_hypotheses.pdf",
            caption="../report/repro_fig7.rst",
            category="Reproduction",
        ),
        png="results/reproduction/fig7_hypotheses.png",
        long="results/reproduction/hypotheses/fig7.csv",
    log:
        "logs/repro_fig7.log",
    benchmark:
        "benchmarks/repro_fig7.tsv"
    priority: 1  # a long job: it starts before the quick figures and tables
    conda:
        "../envs/rotbeam.yaml"
    params:
        claims=CLAIMS_VERSION,
        code=code_version("repro_fig7"),
        variants=sorted(R7),
        beams=R7,
        threshold=config["main_threshold"],
    script:
        "../scripts/repro_fig7.py"


rule repro_estar:
    input:
        boundary="results/boundary/ref.csv",
        line50=fig5_line,
    output:
        csv="results/reproduction/estar_readings.csv",
        md=report(
            "results/reproduction/estar_readings.md",
            caption="../report/repro_estar.rst",
            category="Reproduction",
        ),
        long="results/reproduction/hypotheses/estar.csv",
    log:
        "logs/repro_estar.log",
    benchmark:
        "benchmarks/repro_estar.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        claims=CLAIMS_VERSION,
        code=code_version("repro_estar"),
        beam=config["beam"],
        amplitude=config["amplitude"],
        threshold=config["main_threshold"],
        fig5=config["fig5"],
    script:
        "../scripts/repro_estar.py"


rule repro_fn_zeta:
    output:
        csv="results/reproduction/fn_zeta.csv",
        md=report(
            "results/reproduction/fn_zeta.md",
            caption="../report/repro_fn_zeta.rst",
            category="Reproduction",
        ),
        long="results/reproduction/hypotheses/fn_zeta.csv",
    log:
        "logs/repro_fn_zeta.log",
    benchmark:
        "benchmarks/repro_fn_zeta.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        claims=CLAIMS_VERSION,
        code=code_version("repro_fn_zeta"),
        beam=config["beam"],
        N=config["numerics"]["N"],
    script:
        "../scripts/repro_fn_zeta.py"


rule repro_figD9:
    input:
        grid=lambda w: fig7_grid_files(0.05),
        cfit="results/tables/c_per_threshold.csv",
    output:
        pdf=report(
            "results/reproduction/figD9_window.pdf",
            caption="../report/repro_figD9.rst",
            category="Reproduction",
        ),
        png="results/reproduction/figD9_window.png",
        csv="results/reproduction/figD9_bound.csv",
        long="results/reproduction/hypotheses/figD9.csv",
    log:
        "logs/repro_figD9.log",
    benchmark:
        "benchmarks/repro_figD9.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        claims=CLAIMS_VERSION,
        code=code_version("repro_figD9"),
        delta_points=REPRO["figD9"]["delta_points"],
    script:
        "../scripts/repro_figD9.py"


rule repro_stretch:
    output:
        csv="results/reproduction/stretch.csv",
        md=report(
            "results/reproduction/stretch.md",
            caption="../report/repro_stretch.rst",
            category="Reproduction",
        ),
    log:
        "logs/repro_stretch.log",
    benchmark:
        "benchmarks/repro_stretch.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("repro_stretch"),
        beam=config["beam"],
        lines=config["boundary"]["c_max"],
        stretch=REPRO["stretch"],
        amplitude=config["amplitude"],
        threshold=config["main_threshold"],
        effects=config["effects"],
        numerics=config["numerics"],
    script:
        "../scripts/repro_stretch.py"


rule reproduction:
    input:
        table1="results/tables/table1.csv",
        c_per_threshold="results/tables/c_per_threshold.csv",
        c0_table="results/tables/c0_threshold.csv",
        boundary_ref="results/boundary/ref.csv",
        fig6_fit="results/fig6/fit.json",
        fig7_fit="results/fig7/fit.json",
        fig7_grid=fig7_grid_files(),
        fig3_line="results/sims/ref/fig3.csv",
        fig3_series="results/series/fig3.csv",
        fig5_series=expand(
            "results/series/fig5_E{e}.csv",
            e=[format(float(e), "g") for e in config["fig5"]["e_max"]],
        ),
        ref_lines=ref_line_files(),
        convergence="results/figB8/convergence.csv",
        studies=expand(
            "results/reproduction/hypotheses/{s}.csv",
            s=["fig7", "estar", "fn_zeta", "figD9"],
        ),
        c_hypotheses=c_hypotheses_input,
        stretch="results/reproduction/stretch.csv",
    output:
        csv="results/reproduction/claims.csv",
        md=report(
            "results/reproduction/claims.md",
            caption="../report/reproduction.rst",
            category="Reproduction",
        ),
    log:
        "logs/reproduction.log",
    benchmark:
        "benchmarks/reproduction.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        claims=CLAIMS_VERSION,
        code=code_version("reproduction"),
        threshold=config["main_threshold"],
        amplitude=config["amplitude"],
        convergence_tolerance=REPRO["convergence_tolerance"],
    script:
        "../scripts/reproduction.py"
