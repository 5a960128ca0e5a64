"""The package's layers point one way (README "Layout"): a module imports only from its own layer
or the layers below it, rotbeam never imports snakemake, and no module outside `rotbeam.paper`
imports it (an engineer who never heard of the paper uses the core alone).

Every import is read from the source with `ast`, imports inside functions included (a lazy
import is still a dependency).  `test_the_check_can_fail` feeds the same check a module with an
upward import, a snakemake import and a lazy one, so that a check that never fires fails here.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "rotbeam"

#: bottom to top; a module may import from its own layer and those before it.  `provenance`
#: (the workflow's code hashes) stands alone at the bottom: it imports nothing of rotbeam.
LAYERS = (
    "provenance",
    "config",
    "model",
    "solve",
    "runs",
    "analysis",
    "report",
    "bench",
    "cli",
    "paper",
)

#: the package's own namespace (`import rotbeam`) gathers the public API from the core layers
ROOT_MAY_IMPORT = ("config", "model", "solve", "runs", "analysis", "report")


def layer_of(module: str) -> str | None:
    """Layer of a dotted module name inside rotbeam ("rotbeam.solve.steady" -> "solve"), "root"
    for the package itself, None outside rotbeam."""
    parts = module.split(".")
    if parts[0] != "rotbeam":
        return None
    if parts[1:2] == ["__main__"]:  # `python -m rotbeam`: the command line
        return "cli"
    return parts[1] if len(parts) > 1 else "root"


def module_name(path: Path) -> str:
    """Dotted name of a source file ("rotbeam/solve/__init__.py" -> "rotbeam.solve")."""
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imported_modules(source: str, module: str, is_package: bool) -> list[tuple[int, str]]:
    """(line, absolute module name) of every import in `source`, at any depth."""
    package = module.split(".") if is_package else module.split(".")[:-1]
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            out += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            name = node.module or ""
            if node.level:
                base = package[: len(package) - node.level + 1]
                name = ".".join(base + ([node.module] if node.module else []))
            if name == "rotbeam":  # `from rotbeam import cli`: the names are the modules
                out += [(node.lineno, f"rotbeam.{alias.name}") for alias in node.names]
            else:
                out.append((node.lineno, name))
    return out


def violations(source: str, module: str, is_package: bool = False) -> list[str]:
    """Upward imports and snakemake imports of one module, one line each."""
    own = layer_of(module)
    rank = {name: i for i, name in enumerate(LAYERS)}
    bad = []
    for line, name in imported_modules(source, module, is_package):
        top = name.split(".")[0]
        if top == "snakemake":
            bad.append(f"{module}:{line} imports snakemake")
            continue
        target = layer_of(name)
        if target is None or target == "root":
            continue
        if own == "root":
            if target not in ROOT_MAY_IMPORT:
                bad.append(f"{module}:{line} (package root) imports {name}")
        elif target == "paper" and own != "paper":
            bad.append(f"{module}:{line} ({own}) imports {name}: the core never imports the paper")
        elif own == "paper" and target == "cli":
            bad.append(f"{module}:{line} (paper) imports {name} (cli)")
        elif target not in rank or own not in rank:
            bad.append(f"{module}:{line} imports {name}: layer {target!r} or {own!r} unknown")
        elif rank[target] > rank[own]:
            bad.append(f"{module}:{line} ({own}) imports {name} ({target}, a higher layer)")
    return bad


def modules() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


def test_every_module_is_in_a_layer():
    for path in modules():
        layer = layer_of(module_name(path))
        assert layer == "root" or layer in LAYERS, f"{path} is in no layer of {LAYERS}"


@pytest.mark.parametrize("path", modules(), ids=lambda p: str(p.relative_to(PACKAGE.parent)))
def test_imports_point_down(path):
    bad = violations(path.read_text(), module_name(path), path.name == "__init__.py")
    assert not bad, "\n".join(bad)


def test_the_check_can_fail():
    lazy = "def f():\n    from ..report.style import save\n    return save\n"
    assert violations(lazy, "rotbeam.solve.steady") == [
        "rotbeam.solve.steady:2 (solve) imports rotbeam.report.style (report, a higher layer)"
    ]
    assert violations("from ..runs import scene\n", "rotbeam.model.surrogate") == [
        "rotbeam.model.surrogate:1 (model) imports rotbeam.runs (runs, a higher layer)"
    ]
    assert violations("from .. import cli\n", "rotbeam.solve", is_package=True) == [
        "rotbeam.solve:1 (solve) imports rotbeam.cli (cli, a higher layer)"
    ]
    assert violations("import snakemake\n", "rotbeam.report.io") == [
        "rotbeam.report.io:1 imports snakemake"
    ]
    assert violations("from rotbeam.cli import main\n", "rotbeam.bench.run") == [
        "rotbeam.bench.run:1 (bench) imports rotbeam.cli (cli, a higher layer)"
    ]
    assert violations("from .paper.studies import REF\n", "rotbeam.cli") == [
        "rotbeam.cli:1 (cli) imports rotbeam.paper.studies: the core never imports the paper"
    ]
    assert violations("from .cli import main\n", "rotbeam", is_package=True) == [
        "rotbeam:1 (package root) imports rotbeam.cli"
    ]
    assert violations("from .runs.scene import Scene\n", "rotbeam", is_package=True) == []
    # the same layer and the layers below are allowed, relative or absolute
    ok = "from .criterion import rms\nfrom ..model import params\nimport rotbeam.model.modes\n"
    assert violations(ok, "rotbeam.model.surrogate") == []
    assert violations("from .model.params import Beam\n", "rotbeam.cli") == []


#: what a solver must not name: a model class or a drive law (it sees `DiscreteModel` and
#: `dl.lam`, `dl.lam_dot` only: README "Layout")
MODEL_AND_DRIVE_CLASSES = {"DiscreteElastica", "PrintedElastica", "HarmonicLaw", "MoveLaw"}


def named_classes(source: str) -> set[str]:
    """Every identifier a module's code uses (names, attributes, imported names), docstrings
    and comments left out."""
    out = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Name):
            out.add(node.id)
        elif isinstance(node, ast.Attribute):
            out.add(node.attr)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            out.update(alias.name.split(".")[-1] for alias in node.names)
    return out


def test_no_solver_names_a_model_class_or_a_drive_law():
    bad = {
        path.name: sorted(named_classes(path.read_text()) & MODEL_AND_DRIVE_CLASSES)
        for path in sorted((PACKAGE / "solve").glob("*.py"))
    }
    assert {k: v for k, v in bad.items() if v} == {}
    # the check can fail
    assert named_classes("from ..model.elastica import DiscreteElastica\nx = HarmonicLaw") >= {
        "DiscreteElastica",
        "HarmonicLaw",
    }
