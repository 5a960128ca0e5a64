"""Numerics: everything numerical that changes a result (defaults and ranges from the registry,
rotbeam.config.parameters)."""

from __future__ import annotations

from dataclasses import dataclass

from ..config.errors import RotbeamInputError
from ..config.parameters import SECTIONS, check_fields, default

METHODS = SECTIONS["numerics"]["method"].choices
JACOBIANS = SECTIONS["numerics"]["jacobian"].choices
STARTS = SECTIONS["numerics"]["start"].choices


def _d(name: str):
    return default("numerics", name)


@dataclass(frozen=True)
class Numerics:
    """Everything numerical that changes a result (help texts in the registry)."""

    N: int = _d("N")  #: grid intervals
    method: str = _d("method")  #: scipy solve_ivp method, or TRBDF2
    rtol: float = _d("rtol")  #: time stepper's relative tolerance (transients; see `steady`)
    ss_tol: float = _d("ss_tol")  #: steady-state tolerance (relative remaining transient)
    rms_periods: int = _d("rms_periods")  #: whole drive periods in the RMS window
    samples_per_period: int = _d("samples_per_period")
    max_periods: int = _d("max_periods")  #: give up after this many periods
    max_tau: float = _d("max_tau")  #: ... or after this much dimensionless time
    max_seconds: float = _d("max_seconds")  #: ... or after this much wall time
    start: str = _d("start")  #: initial state: "periodic", "linear", "quasistatic" or "rest"
    tail_tol: float = _d("tail_tol")  #: harmonic tail of the periodic (collocation) start
    #: the reported |mu|max stands to this (the Floquet step ladder's spread,
    #: rotbeam.solve.certify.reported_multipliers); 1 leaves it at what the stability verdict
    #: and the monodromy certificate needed
    floquet_tol: float = _d("floquet_tol")
    integrate: bool = _d("integrate")  #: verify the collocated orbit by time stepping
    #: "monodromy": an attracting orbit whose defect-based offset is small is accepted without
    #: the verification period; "time": always one period of time stepping (rotbeam.solve.steady)
    certify: str = _d("certify")
    jacobian: str = _d("jacobian")  #: "exact" (analytic) or "fd" (the stepper's differences)
    extrapolate: bool = _d("extrapolate")  #: Richardson from N and N // 2 (rotbeam.runs)
    model: str = _d("model")  #: "elastica" (the full discrete model) or "modal" (its modes)
    modes: int = _d("modes")  #: how many modes the modal model keeps

    def __post_init__(self) -> None:
        check_fields(self, "numerics")
        if self.extrapolate and self.N < 6:
            raise RotbeamInputError(
                f"numerics.N must be >= 6 with extrapolate (coarse grid N // 2), got {self.N}"
            )
        if self.model == "modal" and self.modes > self.N - 1:
            raise RotbeamInputError(
                f"numerics.modes = {self.modes}: allowed 1 to N - 1 = {self.N - 1} (numerics.N)"
            )
