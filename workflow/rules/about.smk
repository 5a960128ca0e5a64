# The software this run used, beside the versions the reproduction was checked with
# (constraints.txt): the "About" entry of `snakemake --report`.
rule versions:
    output:
        report(
            "results/about/versions.txt",
            caption="../report/versions.rst",
            category="About",
        ),
    log:
        "logs/versions.log",
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("versions"),
        # a changed version reruns this rule (and only this one)
        versions=installed_versions(),
        checked=checked_versions(),
    script:
        "../scripts/versions.py"
