"""Sphinx configuration of rotbeam's documentation: the Markdown pages of docs/ (myst-parser),
the API reference from the numpydoc docstrings (autodoc + numpydoc) and the furo theme.

The tutorial is the scripts in examples/, which sphinx-gallery runs during the build (their
figures and printed output go into the pages it writes to docs/tutorial/).

Build it strictly (what .ci/run does): sphinx-build -W --keep-going -b html docs docs/_build/html
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

from sphinx.util import logging

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))  # the source tree, also when rotbeam is not installed

import rotbeam  # noqa: E402

project = "rotbeam"
author = "rotbeam contributors"
copyright = "rotbeam contributors, BSD-3-Clause"
version = release = rotbeam.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
# `name` in a docstring is a cross-reference where the name is documented, code otherwise
default_role = "py:obj"
exclude_patterns = ["_build"]

# Markdown pages: anchors for headings down to ### so that links such as
# model.md#axial-stretching-extension resolve (GitHub's slugs)
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]

# API reference: autodoc documents the members, numpydoc renders the sections
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_default_options = {"members": True, "show-inheritance": True}
numpydoc_show_class_members = False  # autodoc's :members: lists them once
numpydoc_class_members_toctree = False

# the tutorial: every script of examples/ is run (in file-name order) and its figures drawn, on
# every build (also when the script is unchanged: the package under it may not be); a script that
# fails fails the build
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "tutorial",
    "filename_pattern": r"\.py$",
    "within_subsection_order": "FileNameSortKey",
    "abort_on_example_error": True,
    "run_stale_examples": True,
    "download_all_examples": False,
    "remove_config_comments": True,
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "show_memory": False,
}

html_theme = "furo"
html_title = f"rotbeam {release}"
html_static_path: list[str] = []

#: the core packages whose every module the API reference (api.rst) documents
CORE = ("config", "model", "solve", "runs", "analysis", "report", "bench")


def _check_api_page(app) -> None:
    """Warn (so the strict build fails) when api.rst misses a public name or a core module."""
    logger = logging.getLogger("rotbeam.docs")
    text = (DOCS / "api.rst").read_text()
    documented = set(re.findall(r"^\.\. auto\w+:: ([\w.]+)", text, re.M))
    left_out = set(re.findall(r"^- ``(rotbeam\.[\w.]+)``$", text, re.M))
    for name in rotbeam.__all__:
        if name != "__version__" and f"rotbeam.{name}" not in documented:
            logger.warning(f"api.rst does not document the public name rotbeam.{name}")
    for package in CORE:
        for path in sorted((ROOT / "rotbeam" / package).glob("*.py")):
            if path.stem == "__init__":
                continue
            module = f"rotbeam.{package}.{path.stem}"
            if module not in documented and module not in left_out:
                logger.warning(f"api.rst does not document the core module {module}")


def _plain_pipes(app, what, name, obj, options, lines) -> None:
    """Docstrings write |x| for an absolute value (plain text, as the code reads it); in
    reStructuredText a bar starts a substitution, so every bar is escaped."""
    for i, line in enumerate(lines):
        lines[i] = line.replace("|", r"\|")


def setup(app):
    app.connect("builder-inited", _check_api_page)
    app.connect("autodoc-process-docstring", _plain_pipes, priority=400)
