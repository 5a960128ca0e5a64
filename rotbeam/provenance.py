"""Which rotbeam code a workflow script runs, and one hash of exactly that code.

Snakemake tracks a rule's script but not the package modules the script imports.  The workflow
derives them here instead of listing them by hand (hand-written lists drift): every ``rotbeam``
module a script imports, transitively, counting imports inside functions and relative imports,
and the ``__init__`` of every package on the way (importing a module runs them).  The hash is of
the normalised code (``ast.dump`` without docstrings), so that a comment, docstring or layout
edit changes nothing and a change to what runs changes it.  Pure Python: no snakemake here.
"""

from __future__ import annotations

import ast
import hashlib
from functools import lru_cache
from pathlib import Path


def _module_file(name: str, root: Path) -> Path | None:
    """The file of module ``name`` (dotted) under ``root`` (the directory holding the package)."""
    base = root.joinpath(*name.split("."))
    for path in (base / "__init__.py", base.with_suffix(".py")):
        if path.is_file():
            return path
    return None


def _module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _with_parents(name: str) -> list[str]:
    """``a.b.c`` -> ``a``, ``a.b``, ``a.b.c``: importing a module imports its packages first."""
    parts = name.split(".")
    return [".".join(parts[: k + 1]) for k in range(len(parts))]


def _read(path: Path, package: str | None) -> tuple[frozenset[str], str]:
    """(the modules ``path`` may import, its normalised code), worked out once per content of
    the file: a workflow parse asks for the same modules once per rule."""
    return _read_cached(path.read_bytes(), str(path), package)


@lru_cache(maxsize=1024)
def _read_cached(source: bytes, filename: str, package: str | None) -> tuple[frozenset[str], str]:
    tree = ast.parse(source, filename=filename)
    imports = frozenset(_imported_names(tree, package))
    return imports, ast.dump(_strip_docstrings(tree), include_attributes=False)


def _imported_names(tree: ast.Module, package: str | None) -> set[str]:
    """Dotted names of every module an ``import`` anywhere in ``tree`` may load (``from m import
    x`` counts ``m`` and ``m.x``: ``x`` may be a submodule).  ``package`` resolves relative
    imports (None for a script outside the package: relative imports there are not ours)."""
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                if package is None:
                    continue
                parts = package.split(".")
                if node.level - 1 >= len(parts):
                    continue  # beyond the top of the package: not rotbeam code
                stem = ".".join(parts[: len(parts) - node.level + 1])
                base = f"{stem}.{node.module}" if node.module else stem
            else:
                base = node.module or ""
            names.add(base)
            names.update(f"{base}.{alias.name}" for alias in node.names if alias.name != "*")
    return names


def code_dependencies(script: str | Path, package_dir: str | Path) -> list[Path]:
    """Every module file of the package in ``package_dir`` that ``script`` imports, transitively
    (sorted; the script itself is not included: Snakemake tracks it).

    Imports inside functions and relative imports count, and so does the ``__init__`` of every
    package on the way.

    Parameters
    ----------
    script : str or Path
        The workflow script.
    package_dir : str or Path
        The package's directory (e.g. ``rotbeam/``); only its modules are followed.

    Returns
    -------
    list of Path
        The module files, resolved and sorted.
    """
    package_dir = Path(package_dir).resolve()
    root = package_dir.parent
    top = package_dir.name
    found: set[Path] = set()
    files: dict[str, Path | None] = {}  # dotted name -> its file, looked up once per call
    todo: list[tuple[Path, str | None]] = [(Path(script).resolve(), None)]
    while todo:
        path, package = todo.pop()
        for name in _read(path, package)[0]:
            if name.split(".")[0] != top:
                continue
            for dotted in _with_parents(name):
                if dotted not in files:
                    files[dotted] = _module_file(dotted, root)
                module = files[dotted]
                if module is None or module in found:
                    continue
                found.add(module)
                todo.append((module, _package_of(module, root)))
    return sorted(found)


def _strip_docstrings(tree: ast.Module) -> ast.Module:
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if (
                body
                and isinstance(body[0], ast.Expr)
                and isinstance(body[0].value, ast.Constant)
                and isinstance(body[0].value.value, str)
            ):
                node.body = body[1:] or [ast.Pass()]
    return tree


def _package_of(module: Path, root: Path) -> str:
    """The package a module's relative imports start from."""
    own = _module_name(module, root)
    return own if module.name == "__init__.py" else own.rpartition(".")[0]


def normalised_code(path: str | Path, root: str | Path) -> str:
    """The code of module ``path`` (under ``root``) without comments, docstrings or positions:
    what a run depends on.

    Parameters
    ----------
    path : str or Path
        The module file.
    root : str or Path
        The directory holding the package (resolves the module's relative imports).

    Returns
    -------
    str
        ``ast.dump`` of the module without docstrings or positions.
    """
    path = Path(path).resolve()
    return _read(path, _package_of(path, Path(root).resolve()))[1]


def code_hash(files: list[Path], root: str | Path) -> str:
    """SHA-256 over the normalised code of ``files``, each keyed by its path under ``root`` (so
    that the same code in another checkout hashes the same).  The dump depends on the Python
    version's ``ast``: a new Python reruns everything once, which it may deserve anyway.

    Parameters
    ----------
    files : list of Path
        The module files (`code_dependencies`), each under ``root``.
    root : str or Path
        The directory holding the package.

    Returns
    -------
    str
        The first 16 hexadecimal digits of the digest.
    """
    digest = hashlib.sha256()
    for path in sorted(files):
        digest.update(Path(path).resolve().relative_to(Path(root).resolve()).as_posix().encode())
        digest.update(b"\0")
        digest.update(normalised_code(path, root).encode())
        digest.update(b"\0")
    return digest.hexdigest()[:16]


def code_version(script: str | Path, package_dir: str | Path) -> tuple[list[Path], str]:
    """The package modules ``script`` runs and the hash of their normalised code.

    Parameters
    ----------
    script : str or Path
        The workflow script.
    package_dir : str or Path
        The package's directory (e.g. ``rotbeam/``).

    Returns
    -------
    files : list of Path
        The module files (`code_dependencies`).
    hash : str
        Their `code_hash`: it changes when what runs changes, not with a comment or docstring.
    """
    files = code_dependencies(script, package_dir)
    return files, code_hash(files, Path(package_dir).resolve().parent)
