"""Reruns follow the code: an edit to a rotbeam module reruns exactly the rules whose
scripts import it, transitively (and what consumes their outputs), and no simulation unless the
simulations run it; an edit to comments and docstrings only reruns nothing.

The finished quick run is copied with the package beside it (the copy runs with PYTHONPATH on it),
and the copy's modules are edited.  The expected rules are read off the scripts by hand, not by
rotbeam.provenance: boundary.py is imported by boundary_table, boundary_grid, c_per_threshold,
fig4, fig6 and fig7, through report/surrogate_figures.py by the two surrogate rules, and through
analysis/hypotheses.py (fig7_variant_study) by the four study rules repro_* that import it and by
reproduction (analysis/claims.py imports hypotheses).  table1 and c0_table read the printed values
through analysis/paper_claims.py, which imports neither boundary nor the elastica."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from conftest import QUICK, ROOT, snakemake

pytestmark = pytest.mark.slow  # needs the quick run, then four plans

BOUNDARY_RULES = {
    "boundary_table",
    "boundary_grid",
    "c_per_threshold",
    "fig4",
    "fig6",
    "fig7",
    "surrogate_southwell",
    "surrogate_vs_full",
    "repro_estar",
    "repro_fig7",
    "repro_figD9",
    "repro_fn_zeta",
    "reproduction",
}
SIMULATIONS = {"sweep_line", "sweep_boundary_lines", "sweep_grid_column", "sweep_convergence",
               "scene_series", "shapes"}  # fmt: skip


def plan(work: Path) -> tuple[set[str], set[str], list[str]]:
    """``snakemake --summary`` of the quick run's targets: (the rules whose outputs' params
    changed, the code hash being one; the rules that would run, those and what reads their
    outputs; the output files that would be remade)."""
    p = snakemake(work, "--summary", "--cores", "1", *QUICK, package_root=work, timeout=300)
    assert p.returncode == 0, p.stderr[-3000:]
    rows = [r.split("\t") for r in p.stdout.splitlines()[1:] if r.startswith("results/")]
    changed = {r[2] for r in rows if r[-2] == "params changed"}
    pending = [r for r in rows if r[-1] == "update pending"]
    return changed, {r[2] for r in pending}, [r[0] for r in pending]


def edit(path: Path, old: str, new: str) -> str:
    """Replace ``old`` (present once) by ``new`` in ``path``; return the original text."""
    text = path.read_text()
    assert text.count(old) == 1, (path, old)
    path.write_text(text.replace(old, new))
    return text


@pytest.fixture(scope="module")
def work(quick_run, tmp_path_factory) -> Path:
    work = tmp_path_factory.mktemp("rerun") / "wf"
    shutil.copytree(quick_run, work, symlinks=True)  # results, logs and .snakemake's records
    shutil.copytree(
        ROOT / "rotbeam", work / "rotbeam", ignore=shutil.ignore_patterns("__pycache__")
    )
    return work


def test_the_copy_has_nothing_to_do(work):
    """The code hash does not depend on where the package is (the run used ROOT's)."""
    assert plan(work) == (set(), set(), [])


def test_docstring_and_comment_edits_rerun_nothing(work):
    boundary = work / "rotbeam" / "analysis" / "boundary.py"
    text = boundary.read_text()
    # a module docstring reworded over more lines, a comment, a blank line
    boundary.write_text('"""Reworded.\n\nOver lines."""\n# a comment\n\n' + text.split('"""', 2)[2])
    elastica = work / "rotbeam" / "model" / "elastica.py"
    old = elastica.read_text()
    elastica.write_text(old + "\n# a trailing comment\n")
    try:
        assert plan(work) == (set(), set(), [])
    finally:
        boundary.write_text(text)
        elastica.write_text(old)


def test_a_code_edit_in_boundary_reruns_its_importers_only(work):
    boundary = work / "rotbeam" / "analysis" / "boundary.py"
    text = boundary.read_text()
    boundary.write_text(text + "\n_UNUSED = 1  # a real (harmless) statement\n")
    try:
        changed, rerun, _ = plan(work)
    finally:
        boundary.write_text(text)
    assert changed == BOUNDARY_RULES, changed
    # and what reads their outputs: fig5 and figD9 read boundary_table's; nothing else, and no
    # simulation
    assert rerun == BOUNDARY_RULES | {"fig5", "figD9"}, rerun


def test_a_code_edit_in_the_model_reruns_the_simulations(work):
    elastica = work / "rotbeam" / "model" / "elastica.py"
    text = elastica.read_text()
    elastica.write_text(text + "\n_UNUSED = 1  # a real (harmless) statement\n")
    try:
        changed, rerun, files = plan(work)
    finally:
        elastica.write_text(text)
    assert SIMULATIONS <= changed, changed
    sims = {str(f.relative_to(work)) for f in (work / "results" / "sims").rglob("*.csv")}
    assert sims and sims <= set(files), sorted(sims - set(files))
    # the tables that never touch the elastica stay
    assert not {"table1", "systems_table", "c0_table"} & rerun, rerun
