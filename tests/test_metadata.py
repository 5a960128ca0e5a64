"""What a person adopting rotbeam reads besides the code: one version everywhere it is written
(pyproject.toml is the source; the installed metadata, `rotbeam.__version__`, CITATION.cff and
CHANGELOG.md follow it), the licence files the metadata names, and a line in config/README.md
for every key of config/config.yaml."""

import importlib.metadata
import re
from pathlib import Path

import pytest
import yaml

import rotbeam

ROOT = Path(__file__).resolve().parents[1]


def pyproject() -> dict:
    tomllib = pytest.importorskip("tomllib")  # Python >= 3.11
    return tomllib.loads((ROOT / "pyproject.toml").read_text())


def citation() -> dict:
    return yaml.safe_load((ROOT / "CITATION.cff").read_text())


def test_version_is_the_installed_metadata():
    assert rotbeam.__version__ != "0+unknown", "rotbeam is not installed: pip install -e ."
    assert rotbeam.__version__ == importlib.metadata.version("rotbeam")


def test_version_is_pyproject_version():
    # the installed metadata is written at install time: after a bump, pip install -e . again
    assert rotbeam.__version__ == pyproject()["project"]["version"]


def test_citation_names_this_version_and_licence():
    cff = citation()
    assert cff["cff-version"] == "1.2.0"
    assert cff["title"] == "rotbeam"
    assert str(cff["version"]) == rotbeam.__version__
    assert cff["license"] == pyproject()["project"]["license"]
    # the paper it reproduces, as a reference (not as the preferred citation of the software)
    assert "preferred-citation" not in cff
    titles = [r["title"] for r in cff["references"]]
    assert any(t.startswith("Dynamic versus quasi-static response") for t in titles), titles


def test_changelog_has_a_section_for_this_version():
    text = (ROOT / "CHANGELOG.md").read_text()
    assert "## [Unreleased]" in text
    assert re.search(rf"^## \[{re.escape(rotbeam.__version__)}\] - \d{{4}}-\d\d-\d\d$", text, re.M)


def test_licence_files_exist_and_are_named_in_the_metadata():
    project = pyproject()["project"]
    assert (ROOT / "LICENSE").read_text().startswith("BSD 3-Clause License")
    for pattern in project["license-files"]:
        assert sorted(ROOT.glob(pattern)), f"license-files {pattern!r} matches no file"
    # the SciPy code adapted in rotbeam/solve/trbdf2.py comes with SciPy's licence
    scipy_licence = (ROOT / "LICENSES" / "scipy.txt").read_text()
    assert scipy_licence.startswith(
        "Copyright (c) 2001-2002 Enthought, Inc. 2003, SciPy Developers."
    )
    assert "LICENSES/scipy.txt" in (ROOT / "LICENSE").read_text()


def test_every_config_key_has_a_line_in_config_readme():
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    readme = (ROOT / "config" / "README.md").read_text()
    # a top-level key heads a row of a table
    rows = set(re.findall(r"^\| `([^`]+)` \|", readme, re.M))
    missing = [key for key in config if key not in rows]
    assert not missing, f"config/README.md has no row for {missing}"
    # a key of a section is named in its row, or in a table of its own
    named = set(re.findall(r"`([^`\s]+)`", readme))
    missing = [
        f"{section}.{key}"
        for section, value in config.items()
        if isinstance(value, dict)
        for key in value
        if key not in named
    ]
    assert not missing, f"config/README.md does not name {missing}"


def test_command_line_version_is_the_package_version():
    """`python -m rotbeam --version` prints the installed version (and `python -m rotbeam` runs
    the command line)."""
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-m", "rotbeam", "--version"], capture_output=True,
                         text=True, timeout=60, check=False)  # fmt: skip
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["rotbeam", rotbeam.__version__], out.stdout
