# What accuracy costs in time: the work-precision benchmark.  Not in `all`: run it as
# `snakemake --cores all benchmark_accuracy`; it takes every core so that nothing else runs beside
# the timings.


rule benchmark_accuracy:
    output:
        csv="results/performance/work_precision.csv",
        refs="results/performance/work_precision_references.csv",
        md=report(
            "results/performance/work_precision.md",
            caption="../report/work_precision.rst",
            category="Performance",
        ),
        pdf="results/performance/work_precision.pdf",
        png=report(
            "results/performance/work_precision.png",
            caption="../report/work_precision.rst",
            category="Performance",
        ),
    log:
        "logs/benchmark_accuracy.log",
    benchmark:
        "benchmarks/benchmark_accuracy.tsv"
    conda:
        "../envs/rotbeam.yaml"
    threads: BENCHMARK_THREADS
    params:
        code=code_version("benchmark_accuracy"),
        plan=config.get("benchmark", {}),
    script:
        "../scripts/benchmark_accuracy.py"
