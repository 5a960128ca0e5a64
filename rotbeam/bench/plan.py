"""The benchmark's plan: the scenes, the curves (integrator and steady-state strategy), the
tolerance ladder, the grids and budgets, and the plan's mapping to and from a config dict.

What the benchmark measures and why: docs/numerics.md, "What accuracy costs, and how to trade
it".
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace
from typing import Any

from ..config.errors import RotbeamInputError
from ..model.params import Beam
from ..solve.numerics import Numerics

#: (label, Omega_0 [rad/s], f_d [Hz]) of the benchmark's scenes on the reference beam
SCENES: tuple[tuple[str, float, float], ...] = (
    ("O5_f2", 5.0, 2.0),
    ("O5_f7", 5.0, 7.0),
    ("O5_f15", 5.0, 15.0),
    ("O100_f5", 100.0, 5.0),
    ("O100_f30", 100.0, 30.0),
)

TOLERANCES: tuple[float, ...] = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
DELTA_SCALE = 0.1  #: Delta RMS errors are relative to max(|Delta_ref|, this)


@dataclass(frozen=True)
class Curve:
    """One line of the work-precision figure: fixed numerics, tolerance knobs set to `tol`."""

    name: str
    label: str
    numerics: dict[str, Any]
    knobs: tuple[str, ...]  #: Numerics fields set to the tolerance of the ladder

    def numerics_at(self, N: int, tol: float) -> Numerics:
        """The curve's numerics at a grid and a rung of the tolerance ladder.

        Parameters
        ----------
        N : int
            Grid intervals.
        tol : float
            The tolerance, dimensionless, set on every knob of the curve.

        Returns
        -------
        Numerics
        """
        return Numerics(N=N, **self.numerics, **{k: tol for k in self.knobs})


CURVES: dict[str, Curve] = {
    c.name: c
    for c in (
        Curve(
            "baseline",
            "Radau, FD Jacobian, from rest (baseline)",
            {"method": "Radau", "jacobian": "fd", "start": "rest"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "radau_rest",
            "Radau, exact Jacobian, from rest",
            {"method": "Radau", "start": "rest"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "radau_qs",
            "Radau, from the quasi-static state",
            {"method": "Radau", "start": "quasistatic"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "trbdf2_qs",
            "TR-BDF2 (ode23tb), from the quasi-static state",
            {"method": "TRBDF2", "start": "quasistatic"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "bdf_qs",
            "BDF, from the quasi-static state",
            {"method": "BDF", "start": "quasistatic"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "lsoda_qs",
            "LSODA, from the quasi-static state",
            {"method": "LSODA", "start": "quasistatic"},
            ("rtol", "ss_tol"),
        ),
        Curve(
            "collocation",
            "periodic collocation only (no time stepping)",
            {"start": "periodic", "integrate": False},
            ("tail_tol",),
        ),
        Curve(
            "default",
            "periodic collocation, certified by its monodromy (default)",
            {"start": "periodic"},
            ("rtol", "ss_tol", "tail_tol"),
        ),
    )  # fmt: skip
}


@dataclass
class BenchPlan:
    """What to run.  `quick()` is the small plan the tests and the quick config use.

    Scenes are (label, Omega_0 [rad/s], f_d [Hz]) on `beam`; tolerances are dimensionless;
    `max_seconds` is wall time per run [s]; `target` and `accept` are relative errors of RMS(y_m).
    A plan out of range raises `RotbeamInputError` when it is made.
    """

    scenes: tuple[tuple[str, float, float], ...] = SCENES
    curves: tuple[str, ...] = tuple(CURVES)
    tolerances: tuple[float, ...] = TOLERANCES
    N: int = 40  #: grid of the method comparison
    grid: tuple[int, ...] = (10, 20, 40, 80)  #: grid study with the default curve
    grid_tol: float = 1e-3  #: tolerance of the grid study (the default's)
    ref_N: tuple[int, int, int] = (20, 40, 80)
    ref_tol: float = 1e-7
    max_seconds: float = 60.0  #: per run; a curve's ladder stops at its first failure
    target: float = 1e-3  #: RMS error at which speed-ups are compared
    accept: float = 5e-3  #: error that a default must keep (docs/numerics.md: 0.5 %)
    surrogate: bool = True
    beam: Beam = field(default_factory=Beam)

    def __post_init__(self) -> None:
        unknown = set(self.curves) - set(CURVES)
        if unknown:
            raise RotbeamInputError(
                f"bench curves {sorted(unknown)} unknown; allowed: {', '.join(CURVES)}"
            )
        for t in self.tolerances:
            if not (1e-12 <= t <= 0.1):
                raise RotbeamInputError(f"bench tolerance must be in [1e-12, 0.1], got {t!r}")
        if not (math.isfinite(self.max_seconds) and self.max_seconds > 0):
            raise RotbeamInputError(
                f"bench max_seconds must be a finite number > 0, got {self.max_seconds!r}"
            )
        if self.N not in self.ref_N or len(self.ref_N) != 3 or min(self.ref_N) < 3:
            raise RotbeamInputError(
                f"bench N = {self.N} must be one of ref_N = {self.ref_N} (three grids >= 3)"
            )

    @classmethod
    def quick(cls) -> BenchPlan:
        """The small plan: two scenes, five curves, two tolerances, grids N = 10 and 20."""
        return cls(
            scenes=(SCENES[0], SCENES[3]),
            curves=("baseline", "radau_qs", "trbdf2_qs", "collocation", "default"),
            tolerances=(1e-3, 1e-5),
            grid=(10, 20),
            ref_N=(10, 20, 40),
            ref_tol=1e-7,
            max_seconds=60.0,
        )


def plan_to_dict(plan: BenchPlan) -> dict[str, Any]:
    """The plan as a plain mapping (the beam as its fields), e.g. for a YAML or JSON file.

    Parameters
    ----------
    plan : BenchPlan
        The plan.

    Returns
    -------
    dict
        BenchPlan field -> value.
    """
    d = asdict(plan)
    d["beam"] = asdict(plan.beam)
    return d


OUTPUT_STEMS = ("work_precision",)


def plan_from_dict(spec: dict[str, Any] | None) -> BenchPlan:
    """BenchPlan from a config mapping (keys = BenchPlan fields; `quick: true` starts small).

    Parameters
    ----------
    spec : dict or None
        The config's `benchmark` section (or `rotbeam bench --config`); None: the full plan.

    Returns
    -------
    BenchPlan
        The full or quick plan with the given fields replaced.

    Raises
    ------
    RotbeamInputError
        If a key is not a BenchPlan field (`beam` excepted), a value has the wrong shape, or the
        plan is out of range.
    """
    spec = dict(spec or {})
    base = BenchPlan.quick() if spec.pop("quick", False) else BenchPlan()
    allowed = {f for f in asdict(base) if f != "beam"}
    unknown = set(spec) - allowed
    if unknown:
        raise RotbeamInputError(
            f"benchmark: unknown key(s) {sorted(unknown)}; allowed: {', '.join(sorted(allowed))}"
        )
    shapes = {"scenes": "a list of [label, Omega_0 rad/s, f_d Hz]", "curves": "a list of names",
              "tolerances": "a list of numbers in [1e-12, 0.1]", "grid": "a list of integers",
              "ref_N": "three integers >= 3"}  # fmt: skip
    for key, what in shapes.items():
        if key not in spec:
            continue
        try:
            if key == "scenes":
                spec[key] = tuple((str(s[0]), float(s[1]), float(s[2])) for s in spec[key])
            elif key in ("grid", "ref_N"):
                spec[key] = tuple(int(v) for v in spec[key])
            elif key == "tolerances":
                spec[key] = tuple(float(v) for v in spec[key])
            else:
                spec[key] = tuple(str(v) for v in spec[key])
        except (TypeError, ValueError, IndexError):
            raise RotbeamInputError(f"benchmark.{key} = {spec[key]!r}: must be {what}") from None
    return replace(base, **spec)
