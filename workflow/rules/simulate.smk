# The expensive jobs, keyed by their parameters: one per sweep line of Figs. 3 and 4, per (E, L)
# column of the Fig. 7 grid and per kept scene, one for the reference beam's boundary lines and
# one for the Fig. B.8 lines.


rule sweep_line:
    output:
        "results/sims/{beam}/{line}.csv",
    log:
        "logs/sweep_line/{beam}/{line}.log",
    benchmark:
        "benchmarks/sweep_line/{beam}/{line}.tsv"
    wildcard_constraints:
        beam=REF,  # the Fig. 7 grid beams run all their lines in one job (sweep_grid_column)
        line="(?!cmax)[A-Za-z0-9_.+-]+",  # the boundary lines: sweep_boundary_lines
    priority: 1  # long jobs first: the quick figures and tables fill the cores at the end
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("sweep_line"),
        spec=line_spec,
        numerics=config["numerics"],
        effects=config["effects"],
    script:
        "../scripts/sweep_line.py"


# The reference beam's boundary lines (one per C_max of config boundary) in one job: each is
# 0.5-0.9 s of work, not much more than a job's start-up (0.3 s).  A change of the boundary
# config, the beam, numerics or effects reruns all of them (about 6 s of work for the full
# config).
rule sweep_boundary_lines:
    output:
        boundary_line_files(REF),
    log:
        "logs/sweep_boundary_lines.log",
    benchmark:
        "benchmarks/sweep_boundary_lines.tsv"
    priority: 1  # long jobs first: the quick figures and tables fill the cores at the end
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("sweep_boundary_lines"),
        lines=boundary_lines(REF),
        numerics=config["numerics"],
        effects=config["effects"],
    script:
        "../scripts/sweep_boundary_lines.py"


# One job per (E, L) column of the Fig. 7 grid: its beams (one per h/L), each 3-4 boundary lines
# of a few points; a job's start-up costs about as much as such a line.  A job writes every beam
# of its column, so reruns follow the column: a change of fig7's c_max, scan, h/L values,
# numerics or effects reruns every column, a new E or L only the new columns.
rule sweep_grid_column:
    output:
        expand("results/sims/{{column}}{hl}/lines.csv", hl=FIG7_HL),
    log:
        "logs/sweep_grid_column/{column}.log",
    benchmark:
        "benchmarks/sweep_grid_column/{column}.tsv"
    wildcard_constraints:
        column="E[^/_]+_L[^/_]+",
    priority: 1  # long jobs first: the quick figures and tables fill the cores at the end
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("sweep_grid_column"),
        beams=lambda w: FIG7_COLUMNS[w.column],
        spec={k: config["fig7"][k] for k in ("c_max", "lo", "hi", "points")},
        amplitude=config["amplitude"],
        numerics=config["numerics"],
        effects=config["effects"],
    script:
        "../scripts/sweep_grid_column.py"


# The grid-convergence lines of Fig. B.8 in one job (each is 0.01-0.6 s of work, most less than
# a job's start-up): a change of the convergence config, the beam, effects or numerics other than
# N and extrapolate (each line sets its own N, never extrapolated) reruns all of them (about 3 s
# of work for the full config).  sweep_line's pattern matches this file too; snakemake takes the
# rule whose output has no wildcards.
rule sweep_convergence:
    output:
        "results/sims/ref/convergence.csv",
    log:
        "logs/sweep_convergence.log",
    benchmark:
        "benchmarks/sweep_convergence.tsv"
    priority: 1  # long jobs first: the quick figures and tables fill the cores at the end
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("sweep_convergence"),
        lines=CONVERGENCE_LINES,
        numerics={
            k: v
            for k, v in config["numerics"].items()
            if k not in ("N", "extrapolate")
        },
        effects=config["effects"],
    script:
        "../scripts/sweep_convergence.py"


rule scene_series:
    output:
        "results/series/{name}.csv",
    log:
        "logs/scene_series/{name}.log",
    benchmark:
        "benchmarks/scene_series/{name}.tsv"
    priority: 1  # a long job: it starts before the quick figures and tables
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
