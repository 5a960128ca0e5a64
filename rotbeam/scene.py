"""One scene: a beam, a drive, the effects and the numerics; dynamic and quasi-static responses.

A scene file is YAML with optional sections `beam`, `drive`, `effects`, `numerics` whose keys are
the fields of `Beam`, `Drive`, `Effects` and `Numerics`; unknown keys are errors.
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Callable
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from .criterion import delta_rms, rms
from .elastica import DiscreteElastica
from .integrate import Numerics, SteadyState, steady_state
from .params import Beam, Dimensionless, Drive, Effects, RotbeamInputError, drive_groups
from .quasistatic import quasistatic_series


class _Loader(yaml.SafeLoader):
    """SafeLoader that also reads 1e6 and 2.0e6 as floats (YAML 1.1 wants 1.0e+6)."""


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(
        r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
        |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
        |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
        |[-+]?\.(?:inf|Inf|INF)
        |\.(?:nan|NaN|NAN))$""",
        re.X,
    ),
    list("-+0123456789."),
)


def load_yaml(text: str):
    """YAML with scientific notation read as numbers."""
    return yaml.load(text, Loader=_Loader)


SECTIONS = {"beam": Beam, "drive": Drive, "effects": Effects, "numerics": Numerics}


@dataclass(frozen=True)
class Scene:
    beam: Beam = Beam()
    drive: Drive = Drive()
    effects: Effects = Effects()
    numerics: Numerics = Numerics()

    @property
    def dimensionless(self) -> Dimensionless:
        return Dimensionless.from_physical(self.beam, self.drive, self.effects)


def build_scene(spec: dict[str, Any] | None = None) -> Scene:
    """Scene from a nested dict like the YAML file; names the offending key on error."""
    spec = spec or {}
    if not isinstance(spec, dict):
        raise RotbeamInputError(f"a scene must be a mapping of sections, got {type(spec).__name__}")
    unknown = set(spec) - set(SECTIONS)
    if unknown:
        raise RotbeamInputError(
            f"unknown scene section(s) {sorted(unknown)}; allowed: {', '.join(SECTIONS)}"
        )
    parts = {}
    for name, cls in SECTIONS.items():
        values = spec.get(name) or {}
        if not isinstance(values, dict):
            raise RotbeamInputError(f"scene section {name!r} must be a mapping, got {values!r}")
        allowed = {f.name for f in fields(cls)}
        bad = set(values) - allowed
        if bad:
            raise RotbeamInputError(
                f"unknown key(s) {sorted(bad)} in {name!r}; allowed: {', '.join(sorted(allowed))}"
            )
        try:
            parts[name] = cls(**values)
        except TypeError as exc:  # pragma: no cover - guarded by the key check above
            raise RotbeamInputError(f"{name}: {exc}") from None
    return Scene(**parts)


def load_scene_file(path: str | Path) -> dict[str, Any]:
    path = Path(path)
    if not path.is_file():
        raise RotbeamInputError(f"scene file {str(path)!r} does not exist")
    try:
        data = load_yaml(path.read_text())
    except yaml.YAMLError as exc:
        raise RotbeamInputError(f"scene file {str(path)!r} is not valid YAML: {exc}") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise RotbeamInputError(f"scene file {str(path)!r} must hold a mapping of sections")
    return data


@dataclass
class SceneResult:
    """Dynamic and quasi-static responses of one scene over the same RMS window."""

    scene: Scene
    dynamic: SteadyState
    tau: np.ndarray
    y_dynamic: np.ndarray
    y_quasistatic: np.ndarray
    theta_quasistatic: np.ndarray
    rms_dynamic: float
    rms_quasistatic: float
    delta_rms: float
    seconds: float

    @property
    def converged(self) -> bool:
        return self.dynamic.converged

    def summary(self) -> dict[str, Any]:
        beam, drive = self.scene.beam, self.scene.drive
        out: dict[str, Any] = {
            "rms_dynamic": self.rms_dynamic,
            "rms_quasistatic": self.rms_quasistatic,
            "delta_rms": self.delta_rms,
            "converged": self.converged,
            "status": self.dynamic.status,
            "message": self.dynamic.message,
            "periods": self.dynamic.periods,
            "transient_bound": self.dynamic.transient,
            "nfev": self.dynamic.nfev,
            "f_n_hz": beam.f_n,
            "omega0": drive.omega0,
            "amplitude": drive.amplitude,
            "f_d": drive.f_d,
            "N": self.scene.numerics.N,
            "method": self.scene.numerics.method,
            "effects": ",".join(self.scene.effects.active()),
            "seconds": self.seconds,
        }
        out.update(drive_groups(beam, drive))
        out.update({k: v for k, v in beam.derived().items() if k in ("G", "delta", "eta", "zeta")})
        return out

    def time_series(self) -> dict[str, np.ndarray]:
        T = self.scene.beam.T
        return {
            "tau": self.tau,
            "t_s": self.tau * T,
            "y_m_dynamic": self.y_dynamic,
            "y_m_quasistatic": self.y_quasistatic,
        }


def quasistatic_midspan(
    dl: Dimensionless, N: int, taus: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    model = DiscreteElastica(N, dl.hub_ratio, dl.eta, dl.effects)
    theta = quasistatic_series(model, dl, taus)
    return theta, np.atleast_1d(model.grid.midspan(theta))


def simulate(
    scene: Scene,
    progress: Callable[[int, float], None] | None = None,
    guess: np.ndarray | None = None,
) -> SceneResult:
    """Dynamic steady state and quasi-static response sampled at the same instants.

    `guess` seeds the periodic collocation (the previous point's orbit along a sweep).
    """
    t0 = time.perf_counter()
    dl = scene.dimensionless
    num = scene.numerics
    # quasi-static first: it is cheap, sets the response scale and the tolerances' size
    m = num.samples_per_period
    taus_one = np.arange(m) / m * dl.period
    th_qs1, y_qs1 = quasistatic_midspan(dl, num.N, taus_one)
    scale = float(np.max(np.abs(th_qs1))) if th_qs1.size else 0.0
    dyn = steady_state(dl, num, progress=progress, response_scale=scale or None, guess=guess)
    # the quasi-static response has the drive's period: reuse the one-period solve when the
    # window's instants fall on its phases (they do, but for a failed run's last sample)
    phase = (dyn.tau / dl.period) % 1.0 * m
    idx = np.rint(phase).astype(int) % m
    if np.allclose(phase, np.rint(phase), atol=1e-6):
        theta_qs, y_qs = th_qs1[:, idx], np.atleast_1d(y_qs1)[idx]
    else:
        theta_qs, y_qs = quasistatic_midspan(dl, num.N, dyn.tau)
    r_dyn = rms(dyn.y_m)
    r_qs = rms(y_qs)
    if not math.isfinite(r_dyn):
        r_dyn = float("nan")
    return SceneResult(
        scene=scene,
        dynamic=dyn,
        tau=dyn.tau,
        y_dynamic=dyn.y_m,
        y_quasistatic=y_qs,
        theta_quasistatic=theta_qs,
        rms_dynamic=r_dyn,
        rms_quasistatic=r_qs,
        delta_rms=delta_rms(r_dyn, r_qs),
        seconds=time.perf_counter() - t0,
    )
