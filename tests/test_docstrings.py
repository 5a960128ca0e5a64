"""Docstrings for readers: every public module, class and function of rotbeam has one; a public
function that takes arguments says what they are (a numpydoc "Parameters" section) and one that
returns something says what (a "Returns" section); no module docstring is a derivation essay
(those live in docs/), and code and comments speak in the present tense, without history words.
`test_the_checks_can_fail` feeds the checks code that breaks each rule."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "rotbeam"
#: a module docstring longer than this many lines is an essay: its derivation belongs in docs/
MODULE_LINES = 12
#: words that tell the history of the code rather than what it is
HISTORY = re.compile(
    r"issue #?\d+|\(issue|\bsession\b|\bas before\b|\bno longer\b|\bpreviously\b|\bformerly\b"
    r"|\bused to be\b|\bthe old code\b|\bnow (?:uses|takes|is|gives|returns)\b",
    re.IGNORECASE,
)


def public(name: str) -> bool:
    return not name.startswith("_")


def returns_value(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    """Whether the function returns something: an annotation other than None, or a `return x`
    in its own body (not in nested functions)."""
    if fn.returns is not None:
        return not (isinstance(fn.returns, ast.Constant) and fn.returns.value is None)
    stack = list(fn.body)
    while stack:
        node = stack.pop()
        if isinstance(node, ast.Return) and node.value is not None:
            return True
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            stack.extend(ast.iter_child_nodes(node))
    return False


def arguments(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> list[str]:
    a = fn.args
    names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
    names += [x.arg for x in (a.vararg, a.kwarg) if x is not None]
    return [n for n in names if n not in ("self", "cls")]


def decorated(fn: ast.AST, *names: str) -> bool:
    return any(
        (isinstance(d, ast.Name) and d.id in names)
        or (isinstance(d, ast.Attribute) and d.attr in names)
        for d in getattr(fn, "decorator_list", [])
    )


def problems(source: str, where: str) -> list[str]:
    """Every rule of the module docstring broken by `source`, one line each."""
    tree = ast.parse(source)
    out = []
    doc = ast.get_docstring(tree)
    if not doc:
        out.append(f"{where}: no module docstring")
    elif len(doc.splitlines()) > MODULE_LINES:
        out.append(f"{where}: module docstring of {len(doc.splitlines())} lines (derivations go "
                   f"to docs/, at most {MODULE_LINES} lines here)")  # fmt: skip
    for line_no, line in enumerate(source.splitlines(), start=1):
        if HISTORY.search(line):
            out.append(f"{where}:{line_no}: history words: {line.strip()[:80]}")

    def visit(body: list[ast.stmt], prefix: str) -> None:
        for node in body:
            if isinstance(node, ast.ClassDef) and public(node.name):
                if not ast.get_docstring(node):
                    out.append(f"{where}: class {prefix}{node.name} has no docstring")
                visit(node.body, f"{prefix}{node.name}.")
            elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and public(node.name):
                check_function(node, f"{prefix}{node.name}")

    def check_function(fn: ast.FunctionDef | ast.AsyncFunctionDef, name: str) -> None:
        text = ast.get_docstring(fn)
        if not text:
            out.append(f"{where}: {name} has no docstring")
            return
        if decorated(fn, "property", "cached_property", "setter", "overload"):
            return
        one_liner = len(text.strip().splitlines()) == 1
        if arguments(fn) and "Parameters\n---" not in text and not one_liner:
            out.append(f"{where}: {name} takes arguments but its docstring has no Parameters")
        if (
            returns_value(fn)
            and "Returns\n---" not in text
            and "Yields\n---" not in text
            and (not one_liner)
        ):
            out.append(f"{where}: {name} returns a value but its docstring has no Returns")

    visit(tree.body, "")
    return out


def modules() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


@pytest.mark.parametrize("path", modules(), ids=lambda p: str(p.relative_to(ROOT)))
def test_docstrings(path):
    bad = problems(path.read_text(), str(path.relative_to(ROOT)))
    assert not bad, "\n".join(bad)


def test_the_checks_can_fail():
    essay = '"""' + "line\n" * (MODULE_LINES + 2) + '"""\n'
    assert "module docstring of" in problems(essay, "m")[0]
    assert problems("def f(x):\n    return x\n", "m") == [
        "m: no module docstring", "m: f has no docstring"
    ]  # fmt: skip
    two_lines = '"""M."""\ndef f(x):\n    """What f is.\n\n    Why.\n    """\n    return x\n'
    assert problems(two_lines, "m") == [
        "m: f takes arguments but its docstring has no Parameters",
        "m: f returns a value but its docstring has no Returns",
    ]
    full = (
        '"""M."""\ndef f(x):\n    """What f is.\n\n    Parameters\n    ----------\n    x : int\n'
        '        A number.\n\n    Returns\n    -------\n    int\n    """\n    return x\n'
    )
    assert problems(full, "m") == []
    assert problems('"""M."""\nclass C:\n    pass\n', "m") == ["m: class C has no docstring"]
    assert problems('"""M."""\n# as before, see issue #5\n', "m")[0].startswith("m:2: history")
    assert problems('"""M."""\ndef _private(x):\n    return x\n', "m") == []
