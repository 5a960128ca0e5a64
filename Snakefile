# rotbeam: every simulated figure and table of the paper from one command.
#   snakemake --cores all                               full reproduction
#   snakemake --cores all --configfile config/quick.yaml   low resolution, minutes
import os

os.environ.setdefault(
    "OPENBLAS_NUM_THREADS", "1"
)  # one BLAS thread per job: jobs run in parallel
os.environ.setdefault("OMP_NUM_THREADS", "1")


configfile: "config/config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/boundary.smk"
include: "workflow/rules/tables.smk"
include: "workflow/rules/surrogate.smk"
include: "workflow/rules/performance.smk"
include: "workflow/rules/reproduction.smk"
include: "workflow/rules/about.smk"
include: "workflow/rules/cluster.smk"
include: "workflow/rules/c_hypotheses.smk"
include: "workflow/rules/nonlinear.smk"
include: "workflow/rules/scenes.smk"
include: "workflow/rules/atlas.smk"
include: "workflow/rules/moves.smk"


rule all:
    default_target: True
    input:
        all_targets(),


# every rule with a script reruns when the rotbeam code that script runs changes
check_code_versions(workflow.rules)
