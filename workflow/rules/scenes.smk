# Your own scenes (config user_scenes): each simulated and judged, one table and one figure.


rule user_scenes:
    input:
        user_scene_files(),
    output:
        csv="results/scenes/scenes.csv",
        md=report(
            "results/scenes/scenes.md",
            caption="../report/user_scenes.rst",
            category="Tables",
        ),
        pdf="results/scenes/scenes.pdf",
        png=report(
            "results/scenes/scenes.png",
            caption="../report/user_scenes.rst",
            category="Figures",
        ),
    log:
        "logs/user_scenes.log",
    benchmark:
        "benchmarks/user_scenes.tsv"
    priority: 1  # a long job: it starts before the quick figures and tables
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("user_scenes"),
        scenes=config.get("user_scenes") or {},
        threshold=config["main_threshold"],
        observe=config.get("user_scenes_observe") or [],
        base=lambda wildcards: CONFIG_DIR,
    script:
        "../scripts/user_scenes.py"
