# The expensive jobs: one per sweep line or kept scene, keyed by their parameters.


rule sweep_line:
    output:
        "results/sims/{beam}/{line}.csv",
    params:
        spec=line_spec,
        numerics=config["numerics"],
        effects=config["effects"],
    log:
        "logs/sweep_line/{beam}/{line}.log",
    benchmark:
        "benchmarks/sweep_line/{beam}/{line}.tsv"
    script:
        "../scripts/sweep_line.py"


rule scene_series:
    output:
        "results/series/{name}.csv",
    params:
        spec=lambda w: SERIES[w.name],
        numerics=config["numerics"],
        effects=config["effects"],
    log:
        "logs/scene_series/{name}.log",
    benchmark:
        "benchmarks/scene_series/{name}.tsv"
    script:
        "../scripts/scene_series.py"


rule shapes:
    output:
        "results/series/shapes_fig2.csv",
    params:
        beam=config["beam"],
        drive=config["fig2"],
        amplitude=config["amplitude"],
        numerics=config["numerics"],
        effects=config["effects"],
    log:
        "logs/shapes/fig2.log",
    benchmark:
        "benchmarks/shapes/fig2.tsv"
    script:
        "../scripts/shapes.py"
