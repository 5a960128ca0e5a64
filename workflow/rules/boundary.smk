# The phase boundary: thresholds act here, downstream of every simulation.


rule boundary_table:
    input:
        lines=lambda w: boundary_line_files(w.beam),
    output:
        "results/boundary/{beam}.csv",
    log:
        "logs/boundary_table/{beam}.log",
    benchmark:
        "benchmarks/boundary_table/{beam}.tsv"
    wildcard_constraints:
        beam=REF,  # the Fig. 7 grid beams: boundary_grid
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("boundary_table"),
        thresholds=sorted(set(config["thresholds"]) | {config["main_threshold"]}),
        beam=lambda w: config["beam"] if w.beam == REF else FIG7_BEAMS[w.beam],
    script:
        "../scripts/boundary_table.py"


# Every Fig. 7 grid beam's boundary in one job (reading a beam's lines takes less than a job's
# start-up); a threshold change reruns this and no simulation.
rule boundary_grid:
    input:
        lines=expand("results/sims/{beam}/lines.csv", beam=sorted(FIG7_BEAMS)),
    output:
        expand("results/boundary/{beam}.csv", beam=sorted(FIG7_BEAMS)),
    log:
        "logs/boundary_grid.log",
    benchmark:
        "benchmarks/boundary_grid.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("boundary_grid"),
        thresholds=sorted(set(config["thresholds"]) | {config["main_threshold"]}),
        beam_ids=sorted(FIG7_BEAMS),
        beams=FIG7_BEAMS,
    script:
        "../scripts/boundary_grid.py"


rule c_per_threshold:
    input:
        ref="results/boundary/ref.csv",
        beams=expand("results/boundary/{beam}.csv", beam=sorted(FIG7_BEAMS)),
    output:
        csv="results/tables/c_per_threshold.csv",
        md=report(
            "results/tables/c_per_threshold.md",
            caption="../report/c_per_threshold.rst",
            category="Tables",
        ),
        boundary_csv="results/tables/boundary_ref.csv",
        boundary_md="results/tables/boundary_ref.md",
    log:
        "logs/c_per_threshold.log",
    benchmark:
        "benchmarks/c_per_threshold.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        claims=CLAIMS_VERSION,
        code=code_version("c_per_threshold"),
    script:
        "../scripts/c_per_threshold.py"


rule fig5:
    input:
        boundary="results/boundary/ref.csv",
        series=expand(
            "results/series/fig5_E{e}.csv",
            e=[format(float(e), "g") for e in config["fig5"]["e_max"]],
        ),
    output:
        pdf=report(
            "results/fig5/phase_diagram.pdf",
            caption="../report/fig5.rst",
            category="Figures",
        ),
        png="results/fig5/phase_diagram.png",
    log:
        "logs/fig5.log",
    benchmark:
        "benchmarks/fig5.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("fig5"),
        threshold=config["main_threshold"],
    script:
        "../scripts/fig5.py"


rule fig6:
    input:
        boundary="results/boundary/ref.csv",
    output:
        pdf=report(
            "results/fig6/critical_frequency.pdf",
            caption="../report/fig6.rst",
            category="Figures",
        ),
        png="results/fig6/critical_frequency.png",
        fit="results/fig6/fit.json",
    log:
        "logs/fig6.log",
    benchmark:
        "benchmarks/fig6.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("fig6"),
        threshold=config["main_threshold"],
    script:
        "../scripts/fig6.py"


rule figD9:
    input:
        ref="results/boundary/ref.csv",
        beams=expand("results/boundary/{beam}.csv", beam=sorted(FIG7_BEAMS)),
        cfit="results/tables/c_per_threshold.csv",
    output:
        pdf=report(
            "results/figD9/thresholds.pdf",
            caption="../report/figD9.rst",
            category="Figures",
        ),
        png="results/figD9/thresholds.png",
    log:
        "logs/figD9.log",
    benchmark:
        "benchmarks/figD9.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("figD9"),
    script:
        "../scripts/figD9.py"


rule fig7:
    input:
        beams=expand("results/boundary/{beam}.csv", beam=sorted(FIG7_BEAMS)),
    output:
        pdf=report(
            "results/fig7/collapse.pdf",
            caption="../report/fig7.rst",
            category="Figures",
        ),
        png="results/fig7/collapse.png",
        fit="results/fig7/fit.json",
    log:
        "logs/fig7.log",
    benchmark:
        "benchmarks/fig7.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("fig7"),
        threshold=config["main_threshold"],
    script:
        "../scripts/fig7.py"
