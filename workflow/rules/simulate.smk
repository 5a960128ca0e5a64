# The expensive jobs: one per sweep line or kept scene, keyed by their parameters.


rule sweep_line:
    output:
        "results/sims/{beam}/{line}.csv",
    log:
        "logs/sweep_line/{beam}/{line}.log",
    benchmark:
        "benchmarks/sweep_line/{beam}/{line}.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("sweep_line"),
        spec=line_spec,
        numerics=config["numerics"],
        effects=config["effects"],
    script:
        "../scripts/sweep_line.py"


rule scene_series:
    output:
        "results/series/{name}.csv",
    log:
        "logs/scene_series/{name}.log",
    benchmark:
        "benchmarks/scene_series/{name}.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("scene_series"),
        spec=lambda w: SERIES[w.name],
        numerics=config["numerics"],
        effects=config["effects"],
    script:
        "../scripts/scene_series.py"


rule shapes:
    output:
        "results/series/shapes_fig2.csv",
    log:
        "logs/shapes/fig2.log",
    benchmark:
        "benchmarks/shapes/fig2.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("shapes"),
        beam=config["beam"],
        drive=config["fig2"],
        amplitude=config["amplitude"],
        numerics=config["numerics"],
        effects=config["effects"],
    script:
        "../scripts/shapes.py"
