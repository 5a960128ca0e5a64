# Large drive around the first resonance (docs/stability.md): branches of periodic
# orbits with their multipliers beside time-stepped sweeps that follow the beam, and the response
# from rest at one scene.  Not in `all`: run it as `snakemake --cores all nonlinear`.
NONLINEAR = config.get("nonlinear") or {}
NONLINEAR_SPEC = {
    k: v for k, v in NONLINEAR.items() if k not in ("omega0", "amplitudes", "response")
}
NONLINEAR_AMPS = [format(float(a), "g") for a in NONLINEAR.get("amplitudes", [])]


wildcard_constraints:
    amp="[0-9.]+",


rule nonlinear:
    input:
        expand(
            "results/nonlinear/{stem}.{ext}",
            stem=["branches"],
            ext=["csv", "pdf", "png"],
        ),
        expand("results/nonlinear/folds.{ext}", ext=["csv", "md"]),
        expand("results/nonlinear/response.{ext}", ext=["json", "csv", "png"]),


rule nonlinear_amplitude:
    output:
        rows="results/nonlinear/a{amp}/rows.csv",
        folds="results/nonlinear/a{amp}/folds.csv",
    log:
        "logs/nonlinear_amplitude_a{amp}.log",
    benchmark:
        "benchmarks/nonlinear_amplitude_a{amp}.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("nonlinear_branch"),
        beam=config["beam"],
        spec={"omega0": NONLINEAR.get("omega0"), **NONLINEAR_SPEC},
    script:
        "../scripts/nonlinear_branch.py"


rule nonlinear_collect:
    input:
        rows=expand("results/nonlinear/a{amp}/rows.csv", amp=NONLINEAR_AMPS),
        folds=expand("results/nonlinear/a{amp}/folds.csv", amp=NONLINEAR_AMPS),
    output:
        csv="results/nonlinear/branches.csv",
        pdf=report(
            "results/nonlinear/branches.pdf",
            caption="../report/nonlinear_branches.rst",
            category="Nonlinear",
        ),
        png="results/nonlinear/branches.png",
        folds_csv="results/nonlinear/folds.csv",
        folds_md=report(
            "results/nonlinear/folds.md",
            caption="../report/nonlinear_folds.rst",
            category="Nonlinear",
        ),
    log:
        "logs/nonlinear_collect.log",
    benchmark:
        "benchmarks/nonlinear_collect.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("nonlinear_collect"),
        omega0=NONLINEAR.get("omega0"),
    script:
        "../scripts/nonlinear_collect.py"


rule nonlinear_response:
    output:
        json="results/nonlinear/response.json",
        csv="results/nonlinear/response.csv",
        png=report(
            "results/nonlinear/response.png",
            caption="../report/nonlinear_response.rst",
            category="Nonlinear",
        ),
    log:
        "logs/nonlinear_response.log",
    benchmark:
        "benchmarks/nonlinear_response.tsv"
    conda:
        "../envs/rotbeam.yaml"
    params:
        code=code_version("nonlinear_response"),
        beam=config["beam"],
        omega0=NONLINEAR.get("omega0"),
        response=NONLINEAR.get("response"),
    script:
        "../scripts/nonlinear_response.py"
