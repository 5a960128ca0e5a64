import functools
import hashlib
import os
import importlib.metadata
import platform
import sys
from pathlib import Path

from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

import rotbeam
from rotbeam import provenance
from rotbeam.config.errors import RotbeamInputError
from rotbeam.runs.scene import scene_files
from rotbeam.paper.studies import (
    REF,
    convergence_lines,
    fig7_beams,
    grid_columns,
    lines_from_config,
    repro_fig7_variants,
    series_from_config,
    validate_config,
)

# Before any job: the JSON schema (snakemake's validate), then what it cannot express (NaN and
# inf, ranges, physics).  A bad value stops the run with one line naming key, value and what is
# allowed, and exit status 2.
SCHEMA = workflow.source_path("../schemas/config.schema.yaml")
try:
    config.update(
        validate_config(
            dict(config),
            SCHEMA,
            lambda c: validate(c, schema=SCHEMA),
            Path(workflow.basedir) / "config",
        )
    )
except RotbeamInputError as exc:
    print(f"rotbeam: invalid config: {exc}", file=sys.stderr)
    sys.exit(2)

LINES = lines_from_config(config)
SERIES = series_from_config(config)
FIG7_BEAMS = fig7_beams(config)
FIG7_COLUMNS, FIG7_HL = grid_columns(FIG7_BEAMS)  # one sweep job per (E, L) column
CONVERGENCE_LINES = convergence_lines(config)  # Fig. B.8's lines, one sweep job


wildcard_constraints:
    beam="[A-Za-z0-9_.+-]+",
    line="[A-Za-z0-9_.+-]+",
    name="[A-Za-z0-9_.+-]+",


# Threads of the work-precision benchmark: every core of a local run, so that nothing runs beside
# its timings.  With a cluster executor and no --cores `workflow.cores` raises; the job then asks
# for two cores of its node (the timings are serial, the second keeps the node quiet).  With
# --cores (profiles/slurm sets 1, the cores of one Slurm job) it asks for that many.
try:
    BENCHMARK_THREADS = workflow.cores
except WorkflowError:
    BENCHMARK_THREADS = 2

# A job reruns when the package code its script runs changes.  `code_version(script)` is a hash
# of exactly the rotbeam modules the script imports (transitively: rotbeam.provenance), passed as
# a params: entry, which Snakemake compares with the one each output was made with.  A params
# entry rather than the module files as input: (their mtime changes with every comment, and a
# docstring edit would rerun a 3-minute sweep): the hash is of the code without comments and
# docstrings, so only what runs counts.  Derived, not a hand-bumped model version nor
# hand-written file lists (they drifted).  Every rule with a script carries it
# (check_code_versions, at the end of the Snakefile, stops the parse otherwise).
PACKAGE_DIR = Path(rotbeam.__file__).parent
SCRIPTS_DIR = Path(workflow.basedir) / "workflow" / "scripts"

# The jobs run this same package, also in a conda env (--use-conda), which holds the numerical
# stack but not rotbeam: Snakemake appends its own sys.path to every script job's, and an
# editable install is found through an import hook that a job's interpreter does not load, so
# the package's directory goes on that path here.  Whatever directory snakemake runs in, a job
# imports the code code_version hashes.
if str(PACKAGE_DIR.parent) not in sys.path:
    sys.path.append(str(PACKAGE_DIR.parent))


@functools.cache
def code_version(script):
    """The code hash of workflow/scripts/{script}.py (see above), once per script and parse."""
    return provenance.code_version(SCRIPTS_DIR / f"{script}.py", PACKAGE_DIR)[1]


def check_code_versions(rules):
    """Every rule with a script carries params.code = code_version(that script)."""
    for r in rules:
        if r.script is None:
            continue
        script = Path(r.script).stem
        if r.params.get("code") != code_version(script):
            raise WorkflowError(
                f"{r.name} (a rule with a script) needs params code=code_version({script!r}) "
                "to rerun when the package code its script runs changes"
            )


# Measured curves to draw over Figs. 3 and 4 (config "measurements"; none by default).
MEASUREMENTS = config.get("measurements") or {}
MEASURED_FIG3 = [MEASUREMENTS["fig3"]] if MEASUREMENTS.get("fig3") else []
MEASURED_FIG4 = {k: v for k, v in (MEASUREMENTS.get("fig4") or {}).items() if v}


def line_spec(wildcards):
    return LINES[(wildcards.beam, wildcards.line)]


def boundary_lines(beam):
    """{line id: spec} of a beam's boundary lines (one per C_max), in id order."""
    return {
        line: LINES[(b, line)]
        for (b, line) in sorted(LINES)
        if b == beam and line.startswith("cmax")
    }


def boundary_line_files(beam):
    return [f"results/sims/{beam}/{line}.csv" for line in boundary_lines(beam)]


def figure(stem):
    return [f"results/{stem}.pdf", f"results/{stem}.png"]


def all_targets():
    figs = [
        "fig1/drive_profiles",
        "fig2/shapes_lab_frame",
        "fig3/resonance",
        "fig4/dynamic_vs_quasistatic",
        "fig5/phase_diagram",
        "fig6/critical_frequency",
        "fig7/collapse",
        "figB8/convergence",
        "figD9/thresholds",
        "figE10/c0_vs_zeta",
    ]
    tables = ["table1", "systems", "c0_threshold", "c_per_threshold", "boundary_ref"]
    out = [f for stem in figs for f in figure(stem)]
    out += [f"results/tables/{t}.{ext}" for t in tables for ext in ("csv", "md")]
    out += [
        f"results/surrogate/{s}.{e}"
        for s in ("southwell", "vs_full")
        for e in ("csv", "md", "pdf", "png")
    ]
    out += ["results/surrogate/speed.json", "results/about/versions.txt"]
    out += [f"results/reproduction/claims.{e}" for e in ("csv", "md")]
    if config.get("user_scenes"):
        out += [f"results/scenes/scenes.{e}" for e in ("csv", "md", "pdf", "png")]
    out += [
        f"results/reproduction/c_hypotheses.{e}" for e in ("csv", "md", "pdf", "png")
    ]
    return out


# The scene files (CSV) that user scenes name are relative to config/; CONFIG_DIR is that folder
# relative to the working directory, so the rule's params do not depend on where the workflow is.
CONFIG_DIR = os.path.relpath(Path(workflow.basedir) / "config")


# Motion designs (config move_designs; rules/moves.smk): a list of entries, each named
MOVE_DESIGNS = config.get("move_designs") or []


def user_scene_files():
    """The CSV files the user scenes read (a move, a sampled profile): the rule's inputs, so an
    edited file reruns it."""
    specs = (config.get("user_scenes") or {}).values()
    return sorted(
        {os.path.join(CONFIG_DIR, f) for spec in specs for f in scene_files(spec)}
    )


# --- paper against reproduction (rules/reproduction.smk) ---
# The paper's printed values ship with the package (rotbeam/paper/paper_claims.yaml) and the
# jobs read them there; a rule that reads them reruns when they change by its params entry
# claims=CLAIMS_VERSION, a hash of the file (its path depends on where the package is).
CLAIMS_VERSION = hashlib.sha256(
    (PACKAGE_DIR / "paper" / "paper_claims.yaml").read_bytes()
).hexdigest()[:16]
REPRO = config["reproduction"]
R7 = repro_fig7_variants(config)


wildcard_constraints:
    variant="[A-Za-z0-9_.+-]+",


def fig5_line(wildcards):
    """The reference boundary line at Fig. 5's C_max, if the config has one (else nothing)."""
    key = (REF, f"cmax{float(config['fig5']['c_max']):g}")
    return [f"results/sims/{key[0]}/{key[1]}.csv"] if key in LINES else []


def fig7_grid_files(h_over_L=None):
    return sorted(
        f"results/boundary/{b}.csv"
        for b, beam in FIG7_BEAMS.items()
        if h_over_L is None or abs(beam["h"] / beam["L"] - h_over_L) < 1e-9
    )


def ref_line_files():
    """Every reference-beam sweep line (the grid-convergence ones are not among them)."""
    return sorted(f"results/sims/{b}/{line}.csv" for (b, line) in LINES if b == REF)


def c_hypotheses_input(wildcards):
    if REPRO["c_hypotheses"]:
        return ["results/reproduction/c_hypotheses.csv"]
    return []


# Versions of the About page (workflow/rules/about.smk)
ABOUT_PACKAGES = [
    "numpy",
    "scipy",
    "pandas",
    "matplotlib",
    "PyYAML",
    "snakemake",
    "snakemake-executor-plugin-slurm",
]


def installed_versions():
    out = {"python": platform.python_version()}
    for name in ABOUT_PACKAGES:
        try:
            out[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            out[name] = "not installed"
    return out


def checked_versions():
    """name -> version of constraints.txt beside the Snakefile ({} in a copy without it)."""
    path = Path(workflow.basedir) / "constraints.txt"
    if not path.exists():
        return {}
    pins = (line.split("#")[0].strip() for line in path.read_text().splitlines())
    return dict(p.split("==") for p in pins if "==" in p)


def move_design_targets():
    """What the target `moves` builds (rules/moves.smk): the designs' table, figure and move
    files; nothing without designs (not part of `all`: a design's search takes minutes).
    """
    if not MOVE_DESIGNS:
        return []
    out = [f"results/moves/designs.{e}" for e in ("csv", "md")]
    out += [f"results/moves/design.{e}" for e in ("pdf", "png")]
    out += [f"results/moves/{d['name']}.csv" for d in MOVE_DESIGNS]
    return out


def atlas_numerics(numerics, atlas):
    """The numerics of a line's job: the config's, with the atlas's line_seconds (if set) as
    its time budget."""
    if "line_seconds" not in atlas:
        return numerics
    return {**numerics, "max_seconds": atlas["line_seconds"]}
