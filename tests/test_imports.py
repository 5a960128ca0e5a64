"""What a command or a workflow job loads: only what it uses.  `rotbeam simulate` without
--plot or --uncertainty loads neither matplotlib (0.35 s) nor scipy.stats (0.5 s), numba (0.6 s,
and its compiled kernels) loads only with a time-stepped classification, and a workflow script
that draws nothing does not load matplotlib, nor one that only simulates pandas (0.2 s of each
job's start-up); each check runs in a fresh Python and has a
positive control that loads the module, so that it can fail."""

from __future__ import annotations

import ast
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("matplotlib", "scipy.stats", "numba")


def loaded_after(code: str, heavy: tuple[str, ...] = HEAVY) -> list[str]:
    """Which of `heavy` a fresh Python has in sys.modules after running `code`."""
    probe = (
        f"{code}\nimport json, sys\nprint(json.dumps([m for m in {heavy!r} if m in sys.modules]))"
    )
    p = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, cwd=ROOT,
                       timeout=300)  # fmt: skip
    assert p.returncode == 0, p.stderr[-2000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


def simulate(*flags: str) -> str:
    argv = ["simulate", "--omega0", "5", "--fd", "2", "--N", "6", "--json", *flags]
    return f"from rotbeam.cli import main\nmain({argv!r})"


def test_simulate_loads_neither_matplotlib_nor_scipy_stats(tmp_path):
    assert loaded_after(simulate()) == []
    # the controls: --plot draws (matplotlib), a Sobol design needs scipy.stats
    assert "matplotlib" in loaded_after(simulate("--plot", str(tmp_path / "a.png")))
    spread = ("--uncertainty", "gamma=0.039+-0.008", "--uq-method", "sobol", "--uq-samples", "2")
    assert "scipy.stats" in loaded_after(simulate(*spread))


def test_numba_loads_with_a_classification_only(tmp_path):
    """`rotbeam --help` and a scene with a stable periodic state do not load numba; a scene
    without one, whose response is classified by the compiled stepper, does."""
    assert "numba" not in loaded_after(cli_main(["--help"]))
    assert "numba" not in loaded_after(simulate())
    scene = tmp_path / "s.yaml"
    scene.write_text(
        "drive: {omega0: 5, f_d: 2}\n"
        "numerics: {N: 4, start: rest, max_periods: 2, extrapolate: false}\n"
    )
    argv = ["simulate", "--scene", str(scene), "--json", "--response-N", "4",
            "--response-periods", "2"]  # fmt: skip
    assert "numba" in loaded_after(cli_main(argv))


def cli_main(argv: list[str]) -> str:
    """Code that runs `rotbeam argv` and goes on when it exits."""
    return f"from rotbeam.cli import main\ntry:\n    main({argv!r})\nexcept SystemExit:\n    pass"


def script_rules() -> dict[str, bool]:
    """workflow script stem -> whether its rule writes a figure (.png or .pdf)."""
    out = {}
    for smk in (ROOT / "workflow" / "rules").glob("*.smk"):
        for block in re.split(r"^rule ", smk.read_text(), flags=re.M)[1:]:
            m = re.search(r"script:\s*\n\s*\"\.\./scripts/(\w+)\.py\"", block)
            if m:
                out[m.group(1)] = out.get(m.group(1), False) or bool(
                    re.search(r"\.(png|pdf)\"", block)
                )
    return out


def imports_of(script: Path) -> str:
    """The script's import statements, at any depth (what it loads before it works)."""
    tree = ast.parse(script.read_text())
    nodes = [n for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))]
    return "\n".join(ast.unparse(n) for n in nodes)


RULES = script_rules()


@pytest.mark.parametrize("stem", sorted(s for s, draws in RULES.items() if not draws))
def test_workflow_script_that_draws_nothing_loads_no_matplotlib(stem):
    assert "matplotlib" not in loaded_after(
        imports_of(ROOT / "workflow" / "scripts" / f"{stem}.py")
    )


def test_the_script_check_sees_a_drawing_script():
    drawing = sorted(s for s, draws in RULES.items() if draws)
    assert "fig3" in drawing and len(drawing) >= 10
    assert "matplotlib" in loaded_after(imports_of(ROOT / "workflow" / "scripts" / "fig3.py"))


#: the workflow's simulation scripts: they run sweeps and write records (`write_records`)
SIMULATING = ("sweep_line", "sweep_boundary_lines", "sweep_grid_column", "sweep_convergence",
              "repro_fig7_variant", "scene_series")  # fmt: skip

#: one short line, as the sweep scripts run them (a record per point), then written
LINE = """
from rotbeam.model.params import Effects
from rotbeam.paper.studies import line_columns, run_line
from rotbeam.report.io import write_records
from rotbeam.solve.numerics import Numerics
spec = {"beam": {}, "omega0": 5.0, "amplitude": 1.0, "c_max": 1.0}
rows = run_line(spec, [1.0, 2.0], Effects(), Numerics(N=6))
write_records(rows, line_columns(True), PATH)
"""


@pytest.mark.parametrize("stem", SIMULATING)
def test_workflow_script_that_simulates_loads_no_pandas(stem):
    code = imports_of(ROOT / "workflow" / "scripts" / f"{stem}.py")
    assert loaded_after(code, ("pandas",)) == []


def test_a_sweep_line_runs_and_is_written_without_pandas(tmp_path):
    path = tmp_path / "line.csv"
    assert loaded_after(LINE.replace("PATH", repr(str(path))), ("pandas",)) == []
    assert path.read_text().startswith("c_max_target,omega0,f_d,")
    assert len(path.read_text().splitlines()) == 3
    # the control: the table of the same line loads it
    table = "from rotbeam.runs.sweeps import scan_line\nfrom rotbeam.model.params import Beam\n"
    assert loaded_after(table + "scan_line(Beam(), 5.0, [1.0])", ("pandas",)) == ["pandas"]
