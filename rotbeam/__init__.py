"""rotbeam: is a quasi-static model good enough for a cantilevered beam on a rotating disk?

The public API: the scene (`Beam`, `Drive`, `Effects`, `Numerics`, `Scene`, `load_scene`,
`build_scene`), its answers (`simulate`, `judge`, `critical`, `effect_budget`, `modes`), the
atlas of the phase plane (`atlas`, `Atlas`, `plot_atlas`), motion design (`design_move`,
`MoveDesign`) and `__version__`.  The names load their modules on first use, so
`import rotbeam` is quick.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version

# the one version is pyproject.toml's, read from the installed package's metadata
try:
    __version__ = version("rotbeam")
except PackageNotFoundError:  # not installed: the source tree on PYTHONPATH only
    __version__ = "0+unknown"

#: public name -> the module that defines it
_HOMES = {
    "Beam": "rotbeam.model.params",
    "Drive": "rotbeam.model.params",
    "Effects": "rotbeam.model.params",
    "Numerics": "rotbeam.solve.numerics",
    "Scene": "rotbeam.runs.scene",
    "SceneResult": "rotbeam.runs.scene",
    "build_scene": "rotbeam.runs.scene",
    "load_scene": "rotbeam.runs.scene",
    "simulate": "rotbeam.runs.scene",
    "judge": "rotbeam.analysis.verdict",
    "Verdict": "rotbeam.analysis.verdict",
    "critical": "rotbeam.analysis.verdict",
    "Critical": "rotbeam.analysis.verdict",
    "effect_budget": "rotbeam.analysis.effect_budget",
    "EffectBudget": "rotbeam.analysis.effect_budget",
    "modes": "rotbeam.model.modes",
    "atlas": "rotbeam.analysis.atlas",
    "Atlas": "rotbeam.analysis.atlas",
    "plot_atlas": "rotbeam.report.atlas_figure",
    "design_move": "rotbeam.analysis.move_design",
    "MoveDesign": "rotbeam.analysis.move_design",
    "RotbeamInputError": "rotbeam.config.errors",
}

__all__ = ["__version__", *_HOMES]


def __getattr__(name: str):
    """The public name `name`, imported from its module on first use."""
    if name not in _HOMES:
        raise AttributeError(f"module 'rotbeam' has no attribute {name!r}")
    value = getattr(import_module(_HOMES[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(__all__)
