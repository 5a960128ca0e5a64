"""rotbeam.provenance finds the package modules a script imports and hashes only what runs.

On a small package written here (so that the expected answer is known by construction), then on
the workflow's own scripts against imports read off their text."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

from conftest import ROOT

from rotbeam.provenance import code_dependencies, code_version

PKG = {
    "__init__.py": '"""top"""\n',
    "a/__init__.py": "",
    "a/low.py": '"""low"""\nX = 1\n',
    "a/mid.py": "from .low import X\n\n\ndef f():\n    from ..b import late\n    return late.Y\n",
    "b/__init__.py": "from . import helper\n",
    "b/helper.py": "Z = 3\n",
    "b/late.py": "import pkg.c.deep as d\nY = d.W\n",
    "c/__init__.py": "",
    "c/deep.py": "W = 2\n",
    "unused.py": "U = 4\n",
}


def make_package(tmp_path: Path) -> tuple[Path, Path]:
    pkg = tmp_path / "pkg"
    for name, text in PKG.items():
        (pkg / name).parent.mkdir(parents=True, exist_ok=True)
        (pkg / name).write_text(text)
    script = tmp_path / "script.py"
    script.write_text("import numpy as np\nfrom pkg.a import mid\nfrom . import nothing\n")
    return pkg, script


def test_transitive_relative_and_function_level_imports(tmp_path):
    pkg, script = make_package(tmp_path)
    found = {str(p.relative_to(pkg)) for p in code_dependencies(script, pkg)}
    # script -> a.mid -> a.low; a.mid's function -> b.late (and b, whose __init__ imports
    # b.helper) -> c.deep; never unused.py; every package __init__ on the way
    assert found == set(PKG) - {"unused.py"}


def test_hash_ignores_comments_and_docstrings_not_code(tmp_path):
    pkg, script = make_package(tmp_path)
    h0 = code_version(script, pkg)[1]
    low = pkg / "a" / "low.py"
    low.write_text('"""low, reworded\n\nover lines"""\n\n# a comment\nX = 1  # same value\n')
    assert code_version(script, pkg)[1] == h0
    low.write_text('"""low"""\nX = 2\n')
    h1 = code_version(script, pkg)[1]
    assert h1 != h0
    (pkg / "unused.py").write_text("U = 5\n")  # not imported: no effect
    assert code_version(script, pkg)[1] == h1
    # the same code in another place hashes the same (paths count from the package's parent)
    other = tmp_path / "elsewhere"
    shutil.copytree(pkg, other / "pkg")
    shutil.copy(script, other / "script.py")
    assert code_version(other / "script.py", other / "pkg")[1] == h1


def test_workflow_scripts_depend_on_what_they_import():
    """Each script's list holds every rotbeam module its text names (one level), e.g. fig4 on
    analysis/boundary.py, which the hand-written lists left out; and sweep_line reaches the
    solver through simulate/scene.py."""
    pkg = ROOT / "rotbeam"
    for script in sorted((ROOT / "workflow" / "scripts").glob("*.py")):
        named = re.findall(r"^from rotbeam\.([\w.]+) import", script.read_text(), re.M)
        found = {p.relative_to(pkg).as_posix() for p in code_dependencies(script, pkg)}
        for module in named:
            assert module.replace(".", "/") + ".py" in found, (script.name, module)
        assert "__init__.py" in found
    sweep = {p.relative_to(pkg).as_posix() for p in code_dependencies(
        ROOT / "workflow/scripts/sweep_line.py", pkg)}  # fmt: skip
    assert {"model/elastica.py", "solve/steady.py", "solve/periodic.py"} <= sweep
    assert "analysis/boundary.py" not in sweep and "report/figures.py" not in sweep
