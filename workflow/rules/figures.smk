# Figures of single lines and scenes (Figs. 1-4, B.8, E.10).


rule fig1:
    output:
        pdf=report(
            "results/fig1/drive_profiles.pdf",
            caption="../report/fig1.rst",
            category="Figures",
        ),
        png="results/fig1/drive_profiles.png",
    log:
        "logs/fig1.log",
    benchmark:
        "benchmarks/fig1.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("fig1"),
        drive=config["fig1"],
        amplitude=config["amplitude"],
    script:
        "../scripts/fig1.py"


rule fig2:
    input:
        "results/series/shapes_fig2.csv",
    output:
        pdf=report(
            "results/fig2/shapes_lab_frame.pdf",
            caption="../report/fig2.rst",
            category="Figures",
        ),
        png="results/fig2/shapes_lab_frame.png",
    log:
        "logs/fig2.log",
    benchmark:
        "benchmarks/fig2.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("fig2"),
    script:
        "../scripts/fig2.py"


rule fig3:
    input:
        line="results/sims/ref/fig3.csv",
        series="results/series/fig3.csv",
        measured=MEASURED_FIG3,
    output:
        pdf=report(
            "results/fig3/resonance.pdf",
            caption="../report/fig3.rst",
            category="Figures",
        ),
        png="results/fig3/resonance.png",
    log:
        "logs/fig3.log",
    benchmark:
        "benchmarks/fig3.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("fig3"),
    script:
        "../scripts/fig3.py"


rule fig4:
    input:
        lines=expand(
            "results/sims/ref/fig4_w{w}.csv",
            w=[format(float(w), "g") for w in config["fig4"]["omega0"]],
        ),
        measured=list(MEASURED_FIG4.values()),
    output:
        pdf=report(
            "results/fig4/dynamic_vs_quasistatic.pdf",
            caption="../report/fig4.rst",
            category="Figures",
        ),
        png="results/fig4/dynamic_vs_quasistatic.png",
        table="results/fig4/critical.csv",
    log:
        "logs/fig4.log",
    benchmark:
        "benchmarks/fig4.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("fig4"),
        threshold=config["main_threshold"],
        beam=config["beam"],
        measured_omega0=[float(w) for w in MEASURED_FIG4],
    script:
        "../scripts/fig4.py"


rule figB8:
    input:
        lines="results/sims/ref/convergence.csv",
    output:
        pdf=report(
            "results/figB8/convergence.pdf",
            caption="../report/figB8.rst",
            category="Figures",
        ),
        png="results/figB8/convergence.png",
        table="results/figB8/convergence.csv",
    log:
        "logs/figB8.log",
    benchmark:
        "benchmarks/figB8.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("figB8"),
    script:
        "../scripts/figB8.py"


rule figE10:
    output:
        pdf=report(
            "results/figE10/c0_vs_zeta.pdf",
            caption="../report/figE10.rst",
            category="Figures",
        ),
        png="results/figE10/c0_vs_zeta.png",
    log:
        "logs/figE10.log",
    benchmark:
        "benchmarks/figE10.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("figE10"),
        spec=config["figE10"],
        beam=config["beam"],
    script:
        "../scripts/figE10.py"
