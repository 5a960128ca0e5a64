"""results/README.md maps every file the workflow writes to the paper: each literal
``results/...`` path of the rules (workflow/rules/*.smk) matches one of its entries, whose
``{a,b}`` stands for a or b and ``{name}`` or ``*`` for one path segment or part of one."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def entry_pattern(entry: str) -> re.Pattern:
    """An entry of the README's table (`fig4/critical.csv`, `tables/table1.{csv,md}`,
    `sims/{beam}/lines.csv`, `series/*.csv`) as a regular expression of the paths it names."""
    out, pos = "", 0
    for m in re.finditer(r"\{([^}]*)\}|\*", entry):
        out += re.escape(entry[pos : m.start()])
        if m[0] == "*" or "," not in m[1]:
            out += r"[^/]+"
        else:
            out += "(?:" + "|".join(re.escape(x) for x in m[1].split(",")) + ")"
        pos = m.end()
    return re.compile(out + re.escape(entry[pos:]))


def readme_patterns(text: str) -> list[re.Pattern]:
    """The file entries of the table's first column."""
    cells = [line.split("|")[1] for line in text.splitlines() if line.startswith("| `")]
    return [entry_pattern(e) for cell in cells for e in re.findall(r"`([^`]+)`", cell)]


def rule_paths() -> set[str]:
    """Every literal results/ path (no wildcard) the rules name, relative to results/."""
    text = "".join(p.read_text() for p in (ROOT / "workflow" / "rules").glob("*.smk"))
    return {p for p in re.findall(r'"results/([^"{}]+)"', text)}


def unlisted(paths: set[str], text: str) -> list[str]:
    patterns = readme_patterns(text)
    return sorted(p for p in paths if not any(pat.fullmatch(p) for pat in patterns))


def test_every_file_the_rules_write_is_in_results_readme():
    paths = rule_paths()
    assert "reproduction/stretch.csv" in paths and len(paths) > 50
    assert unlisted(paths, (ROOT / "results" / "README.md").read_text()) == []


def test_the_check_can_fail():
    table = "| file | paper |\n| --- | --- |\n| `tables/table1.{csv,md}`, `series/*.csv` | x |\n"
    assert unlisted({"tables/table1.md", "series/fig3.csv"}, table) == []
    assert unlisted({"tables/table1.pdf", "scenes/scenes.csv"}, table) == [
        "scenes/scenes.csv",
        "tables/table1.pdf",
    ]
