"""Candidate mechanisms for the paper's critical-frequency constant c, run through our model.

Each named `Hypothesis` changes one thing in how RMS_dyn, RMS_QS, Delta RMS or f_0 are obtained;
`c_for_hypothesis` gives the c of f_d* = c f_0 it yields at every Delta RMS threshold, `grid_c`
the same under the paper's first-grid-point rule, and `study_table` the long table of the
workflow rule ``c_hypotheses``.  The options, the method and the verdict: docs/c_hypotheses.md.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd
from scipy.interpolate import PchipInterpolator

from ..config.checks import check_positive, check_threshold
from ..config.errors import RotbeamInputError
from ..model.criterion import critical_from_scan, rms
from ..model.modes import modes, resonance_frequency_hz
from ..model.params import Beam, Dimensionless, Drive, Effects, omega0_for_cmax
from ..model.surrogate import southwell_frequency_hz
from .c_response import dynamic_response, hypothesis_quasistatic_midspan, midspan_measure
from .printed import printed_per_threshold, read_claims

THRESHOLDS = (0.05, 0.07, 0.10, 0.12)  #: the Delta RMS thresholds of App. D
_CLAIMS = read_claims()[1]
PAPER_C = printed_per_threshold(_CLAIMS, "c_")  #: App. D: threshold -> printed c
PAPER_C_ERR = float(_CLAIMS.loc[_CLAIMS["id"] == "c_0.10", "tolerance"].iloc[0])  #: its +-
F_N_PRINTED = 6.37  #: Hz, Sec. 5
QS_SCALE = "qs_scale_"  #: prefix of the calibration hypotheses, e.g. qs_scale_1.05


@dataclass(frozen=True)
class Hypothesis:
    """One candidate mechanism: options that say how RMS_dyn, RMS_QS, Delta RMS and f_0 are made.

    The defaults are ours; a hypothesis changes one or two of them.  What each option stands
    for in the paper's pipeline: docs/c_hypotheses.md ("What a hypothesis can change").

    Attributes
    ----------
    description : str
        The hypothesis in words (the study table's description column).
    model : tuple of str
        Printed misprints of the dynamic model (`rotbeam.paper.printed_model.MISPRINTS`);
        empty: ours.
    qs : str
        Quasi-static answer: "discrete" (the model on grid N) or "continuum" (Richardson limit
        of the static problem on N = 80 and 160).
    s_dyn : float or None
        Arclength, as a fraction of L, where the dynamic y_m is read (the quasi-static y_m is
        read at 1/2); None: node N/2 counted from the clamp as node 1, s = (N/2 - 1)/N.
    N_dyn : int or None
        Grid intervals of the dynamic model (None: those of the quasi-static answer).
    measure : str
        "y" (rotating frame), "lab" (frame turning uniformly at Omega_0) or "chord"
        (deflection normal to the clamp-tip chord).
    dynamics : str
        "periodic" (collocated orbit), "steps" / "steps_rest" (the integrator's own output
        steps, from the orbit or from rest) or "rest" (time stepping from rest).
    window : tuple
        Runs from rest: ("periods", k), ("seconds", t) or ("last", k).
    t_end_tau : float
        Runs from rest: the least run length, dimensionless (units of T).
    method : str
        `scipy.integrate.solve_ivp` method of time-stepped runs, or "TRBDF2".
    rtol, atol : float
        Its tolerances.
    f0 : str
        Definition of f_0: "linear_max", "linear_mean", "southwell_flap",
        "southwell_inplane", "fn_printed" or "peak" (`f0_for`).
    zeta : float or None
        Damping ratio (dimensionless) the beam's gamma is scaled to; None: the beam's own.
    denominator : str
        "dyn" (Eq. Delta_RMS) or "qs" (RMS_QS in the denominator).
    mean : str
        "keep" or "remove" (the mean of y_m removed before the RMS).
    qs_scale : float
        Factor (dimensionless) on RMS_QS: the calibration.
    coriolis_ny : bool
        Coriolis on with the printed +2 I y_t of n_y, modelled as eta -> eta + 2 lam0.
    N : int or None
        Grid intervals (None: the scan's N).
    step_periods : int
        Dynamics "steps": periods stepped from the orbit (the last 2 sampled).
    """

    description: str = "ours: collocated orbit N, quasi-static on the same grid, y at s = 1/2"
    model: tuple[str, ...] = ()  #: printed misprints of the dynamic model (PrintedElastica)
    qs: str = "discrete"
    s_dyn: float = 0.5
    N_dyn: int | None = None
    measure: str = "y"
    dynamics: str = "periodic"
    window: tuple = ("last", 1)
    t_end_tau: float = 0.0  #: time-stepped runs: at least this long (dimensionless)
    method: str = "Radau"
    rtol: float = 1e-6
    atol: float = 1e-9
    f0: str = "linear_max"
    zeta: float | None = None
    denominator: str = "dyn"
    mean: str = "keep"
    qs_scale: float = 1.0
    coriolis_ny: bool = False
    N: int | None = None  #: grid (None: the numerics' N)
    step_periods: int = 3  #: dynamics "steps": periods stepped from the orbit (last 2 sampled)


_PRINTED = "printed appendix: dynamic model with {}, quasi-static continuum"

HYPOTHESES: dict[str, Hypothesis] = {
    "ours": Hypothesis(),
    "continuum_qs": Hypothesis(
        "discrete dynamic model N beside a continuum quasi-static answer", qs="continuum"
    ),
    "printed_bracket": Hypothesis(
        _PRINTED.format("the tension bracket"), model=("bracket",), qs="continuum"
    ),
    "printed_U3": Hypothesis(
        _PRINTED.format("the last column of 3s in U"), model=("U3",), qs="continuum"
    ),
    "printed_symS": Hypothesis(
        _PRINTED.format("the symmetric S~"), model=("symS",), qs="continuum"
    ),
    "printed_Kds": Hypothesis(_PRINTED.format("K with 1/ds"), model=("Kds",), qs="continuum"),
    "printed_U3_symS": Hypothesis(
        _PRINTED.format("U3 and symmetric S~ (the plausible slips)"),
        model=("U3", "symS"),
        qs="continuum",
    ),
    "printed_all_but_K": Hypothesis(
        _PRINTED.format("bracket, U3, symmetric S~"),
        model=("bracket", "U3", "symS"),
        qs="continuum",
    ),
    "printed_ny_coriolis": Hypothesis(
        "Coriolis on with the printed +2 I y_t of n_y (extra damping 2 lam0), QS continuum",
        qs="continuum",
        coriolis_ny=True,
    ),
    "ym_node_matlab": Hypothesis(
        "dynamic y_m at node N/2 counted from the clamp as node 1 (s = (N/2 - 1)/N), QS at s = 1/2",
        s_dyn=None,
        qs="continuum",
    ),
    "ym_39_intervals": Hypothesis(
        "'N = 40 nodes' as 39 intervals, dynamic y_m at node 20 from "
        "the clamp as node 1 (s = 19/39), QS at s = 1/2",
        s_dyn=19 / 39,
        N_dyn=39,
        qs="continuum",
    ),
    "ym_lab_frame": Hypothesis(
        "y_m in a frame turning uniformly at Omega_0 (the drive's "
        "rigid oscillation included), dynamic and QS",
        measure="lab",
    ),
    "ym_normal_to_chord": Hypothesis(
        "midspan deflection normal to the clamp-tip chord", measure="chord"
    ),
    "rest_10_periods": Hypothesis(
        "from rest, RMS over the first 10 drive periods", dynamics="rest", window=("periods", 10)
    ),
    "rest_20_periods": Hypothesis(
        "from rest, RMS over the first 20 drive periods", dynamics="rest", window=("periods", 20)
    ),
    "rest_5_s": Hypothesis(
        "from rest, RMS over the first 5 s", dynamics="rest", window=("seconds", 5.0)
    ),
    "rest_10_s": Hypothesis(
        "from rest, RMS over the first 10 s", dynamics="rest", window=("seconds", 10.0)
    ),
    "f0_linear_mean": Hypothesis("f_0 linear at Omega_0 (not Omega_0 + a)", f0="linear_mean"),
    "f0_southwell_flap": Hypothesis(
        "f_0 by Eq. Southwell with the flapwise S_1", f0="southwell_flap"
    ),
    "f0_southwell_inplane": Hypothesis(
        "f_0 by Eq. Southwell with the in-plane S_1", f0="southwell_inplane"
    ),
    "f0_fn_printed": Hypothesis(
        "f_0 with f_n = 6.37 Hz (printed) in place of 6.52 Hz", f0="fn_printed"
    ),
    "f0_peak": Hypothesis("f_0 = peak of the dynamic RMS scan (nonlinear, a = 1)", f0="peak"),
    "zeta_0.017": Hypothesis("damping zeta = 0.017 (App. E) instead of 0.020", zeta=0.017),
    "mean_removed": Hypothesis("RMS of y_m with its mean removed", mean="remove"),
    "qs_denominator": Hypothesis("Delta RMS with RMS_QS in the denominator", denominator="qs"),
    "ode_steps_trbdf2_1e-3": Hypothesis(
        "RMS_dyn over the integrator's own output steps (ode23tb returns its steps, Refine 1), "
        "TR-BDF2 at rtol 1e-3, atol 1e-6, last 2 of 3 periods from the orbit; QS uniform",
        dynamics="steps",
        method="TRBDF2",
        rtol=1e-3,
        atol=1e-6,
        qs="continuum",
    ),
    "ode_steps_trbdf2_1e-4": Hypothesis(
        "as ode_steps_trbdf2_1e-3 at rtol 1e-4",
        dynamics="steps",
        method="TRBDF2",
        rtol=1e-4,
        atol=1e-6,
        qs="continuum",
    ),
    "ode_steps_trbdf2_1e-3_from_rest": Hypothesis(
        "RMS_dyn over TR-BDF2's own steps (rtol 1e-3, atol 1e-6) over the last period of a run "
        "from rest of 2 ln(1000)/eta; QS uniform",
        dynamics="steps_rest",
        method="TRBDF2",
        rtol=1e-3,
        atol=1e-6,
        qs="continuum",
        t_end_tau=2 * math.log(1000.0) / Beam().eta,
    ),
    "trbdf2_loose": Hypothesis(
        "TR-BDF2 (ode23tb's method) from rest at rtol 1e-3, atol 1e-6, "
        "RMS over the last period of 2 ln(1000)/eta",
        dynamics="rest",
        method="TRBDF2",
        rtol=1e-3,
        atol=1e-6,
        window=("last", 1),
        t_end_tau=2 * math.log(1000.0) / Beam().eta,
    ),
}


def hypothesis(name: str | Hypothesis) -> Hypothesis:
    """The hypothesis a name stands for.

    Parameters
    ----------
    name : str or Hypothesis
        A key of `HYPOTHESES`, or ``qs_scale_<k>`` (the calibration: RMS_QS multiplied by a
        number k > 0, e.g. ``qs_scale_1.05``); a `Hypothesis` is returned as it is.

    Returns
    -------
    Hypothesis
        The registered (or calibration) hypothesis.

    Raises
    ------
    RotbeamInputError
        For an unknown name, or a ``qs_scale_<k>`` whose k is not a number > 0.
    """
    if isinstance(name, Hypothesis):
        return name
    if name.startswith(QS_SCALE):
        try:
            k = check_positive(name, float(name[len(QS_SCALE) :]))
        except ValueError:
            raise RotbeamInputError(
                f"hypothesis {name!r}: {QS_SCALE}<k> needs a number k > 0, e.g. {QS_SCALE}1.05"
            ) from None
        return Hypothesis(f"RMS_QS multiplied by {k:g}", qs_scale=k)
    if name not in HYPOTHESES:
        raise RotbeamInputError(
            f"hypothesis {name!r}: unknown; allowed: {', '.join(HYPOTHESES)} or {QS_SCALE}<k>"
        )
    return HYPOTHESES[name]


@dataclass(frozen=True)
class ScanSpec:
    """The lines a hypothesis is run on, and how each is scanned.

    A line is the Omega_0 of one C_max (`omega0_for_cmax`), scanned at
    f_d = f_0 linspace(lo, hi, points) with f_0 ours (linear, at Omega_0 + a).

    Attributes
    ----------
    c_max : tuple of float
        The lines' maximal centrifugal numbers C_max (dimensionless, > 0; at least one).
    N : int
        Grid intervals, 4 to 2000.
    lo, hi : float
        The scan's ends as fractions of f_0 (dimensionless), 0 < lo < hi <= 3.
    points : int
        Scan points per line, 3 to 1000.
    samples : int
        Samples per drive period, 8 to 4096.
    amplitude : float
        Drive amplitude a [rad/s], > 0.

    Raises
    ------
    RotbeamInputError
        When a field is outside its range.
    """

    c_max: tuple[float, ...] = (1.0,)
    N: int = 40
    lo: float = 0.15
    hi: float = 0.5
    points: int = 15
    samples: int = 32
    amplitude: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "c_max", tuple(float(c) for c in self.c_max))
        if not self.c_max:
            raise RotbeamInputError("c_max = []: needs at least one C_max line")
        for c in self.c_max:
            check_positive("c_max", c)
        for name, lo, hi in (("N", 4, 2000), ("points", 3, 1000), ("samples", 8, 4096)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
                raise RotbeamInputError(f"{name} = {v!r}: must be an integer in [{lo}, {hi}]")
        check_positive("amplitude", self.amplitude)
        if not 0 < check_positive("lo", self.lo) < check_positive("hi", self.hi) <= 3:
            raise RotbeamInputError(
                f"lo = {self.lo!r}, hi = {self.hi!r}: must be 0 < lo < hi <= 3 (fractions of f_0)"
            )


@dataclass(frozen=True)
class GridRule:
    """The paper's first-grid-point rule on a coarse scan.

    f_d* is the first point of the scan f_d = k step (unit "Hz") or f_d = k step f_0 (unit
    "f0", f_0 ours), k = 1, 2, ..., at or above the line's Delta RMS root.  It needs no new
    simulation: `grid_c` applies it to the roots of a `c_for_hypothesis` result.

    Attributes
    ----------
    step : float
        The scan's step, > 0: in Hz for unit "Hz", a fraction of f_0 (dimensionless) for "f0".
    unit : str
        "Hz" or "f0".

    Raises
    ------
    RotbeamInputError
        For a step that is not > 0 or another unit.
    """

    step: float
    unit: str = "Hz"

    def __post_init__(self) -> None:
        check_positive("grid step", self.step)
        if self.unit not in ("Hz", "f0"):
            raise RotbeamInputError(f"grid unit = {self.unit!r}: must be 'Hz' or 'f0'")

    @property
    def label(self) -> str:
        """The rule's name in the study table, e.g. ``grid_0.5Hz`` or ``grid_0.05f0``."""
        return f"grid_{self.step:g}{self.unit}"

    def point_above(self, root_hz: float, f_ref: float) -> float:
        """The first grid point at or above a root.

        Parameters
        ----------
        root_hz : float
            The line's Delta RMS root f_d* [Hz].
        f_ref : float
            The line's f_0, ours [Hz]: the step of unit "f0" is `step` f_ref.

        Returns
        -------
        float
            The grid point [Hz]; a root less than 1e-9 steps above a grid point counts as on it.
        """
        h = self.step if self.unit == "Hz" else self.step * f_ref
        return math.ceil(root_hz / h - 1e-9) * h


# --- one scene, one line ---------------------------------------------------------------------
def _beam_for(beam: Beam, h: Hypothesis) -> Beam:
    if h.zeta is None:
        return beam
    return replace(beam, gamma=beam.gamma * h.zeta / beam.zeta)


def _rms(y: np.ndarray, mean: str) -> float:
    """RMS of y (Eq. RMS), with its mean removed first when `mean` is "remove"."""
    y = np.asarray(y, float)
    return rms(y - y.mean() if mean == "remove" else y)


def scene_delta(
    h: Hypothesis | str,
    beam: Beam,
    omega0: float,
    f_d: float,
    scan: ScanSpec = ScanSpec(),
    state: dict | None = None,
) -> dict:
    """RMS_dyn, RMS_QS and Delta RMS of one scene under one hypothesis.

    Parameters
    ----------
    h : Hypothesis or str
        The hypothesis, or its name (`hypothesis`).
    beam : Beam
        The beam (SI); its gamma is rescaled when the hypothesis sets ``zeta``.
    omega0 : float
        Mean rotation rate Omega_0 [rad/s].
    f_d : float
        Drive frequency [Hz].
    scan : ScanSpec
        Grid N, samples per period and drive amplitude a.
    state : dict or None
        Carries the orbit from one f_d to the next along a line (updated in place); None: a
        fresh start.

    Returns
    -------
    dict
        ``rms_dynamic`` and ``rms_quasistatic`` (RMS of y_m in units of L, dimensionless; the
        latter times ``qs_scale``), ``delta_rms`` (dimensionless), ``f_d`` [Hz], ``omega0``
        [rad/s] and ``samples`` (the number of dynamic samples).

    Raises
    ------
    RotbeamInputError
        For an unknown hypothesis name.
    RuntimeError
        When no periodic orbit is found or time stepping fails.
    """
    h = hypothesis(h)
    state = {} if state is None else state
    beam = _beam_for(beam, h)
    N, m = h.N or scan.N, scan.samples
    drive = Drive(omega0=omega0, amplitude=scan.amplitude, f_d=f_d)
    dl = Dimensionless.from_physical(beam, drive, Effects())
    run = dynamic_response(h, dl, h.N_dyn or N, m, state, beam.T)
    return {**_readout(h, dl, N, m, *run), "f_d": f_d, "omega0": omega0}


#: Hypothesis fields that change only what is read from the dynamic response (or, zeta, the
#: beam it runs on): hypotheses that differ in these alone share one dynamic run a line
#: (`_line_dynamics`)
READOUT_FIELDS = ("description", "qs", "s_dyn", "N_dyn", "measure", "f0", "zeta",
                  "denominator", "mean", "qs_scale", "N")  # fmt: skip


def _readout(h: Hypothesis, dl: Dimensionless, N: int, m: int, grid, theta, taus) -> dict:
    """RMS_dyn, RMS_QS, Delta RMS and the sample count of one scene's dynamic response under a
    hypothesis (`scene_delta` without the run)."""
    s_dyn = h.s_dyn if h.s_dyn is not None else (grid.N // 2 - 1) / grid.N
    y_dyn = midspan_measure(grid, theta, s_dyn, h.measure, dl, taus)
    if h.dynamics in ("steps", "steps_rest"):  # QS on a uniform grid of one period
        taus = np.arange(m) / m * dl.period
    y_qs = hypothesis_quasistatic_midspan(h, dl, N, taus)
    r_dyn, r_qs = _rms(y_dyn, h.mean), h.qs_scale * _rms(y_qs, h.mean)
    den = r_dyn if h.denominator == "dyn" else r_qs
    return {"rms_dynamic": r_dyn, "rms_quasistatic": r_qs, "delta_rms": abs(r_dyn - r_qs) / den,
            "samples": int(np.size(y_dyn))}  # fmt: skip


@functools.lru_cache(maxsize=64)
def _line_dynamics(
    dynamics: Hypothesis,
    beam: Beam,
    omega0: float,
    fds: tuple[float, ...],
    N: int,
    m: int,
    amplitude: float,
) -> tuple:
    """(dl, grid, theta, taus) at every f_d of a line, each orbit continued from the one before;
    computed once a process for all hypotheses that share `dynamics` (READOUT_FIELDS reset)."""
    state: dict = {}
    out = []
    for f_d in fds:
        dl = Dimensionless.from_physical(beam, Drive(omega0, amplitude, f_d), Effects())
        out.append((dl, *dynamic_response(dynamics, dl, N, m, state, beam.T)))
    return tuple(out)


def _peak_frequency_hz(beam: Beam, omega0: float, scan: ScanSpec) -> float:
    """Peak of our dynamic RMS on f_lin [0.9, 1.15] (11 points, PCHIP on 401)."""
    f_lin = resonance_frequency_hz(beam, abs(omega0) + scan.amplitude)
    fs = f_lin * np.linspace(0.9, 1.15, 11)
    st: dict = {}
    r = [scene_delta(Hypothesis(), beam, omega0, f, scan, st)["rms_dynamic"] for f in fs]
    j = min(max(int(np.argmax(r)), 1), len(fs) - 2)
    fine = np.linspace(fs[j - 1], fs[j + 1], 401)
    return float(fine[np.argmax(PchipInterpolator(fs, r)(fine))])


def f0_for(h: Hypothesis, beam: Beam, omega0: float, scan: ScanSpec = ScanSpec()) -> float:
    """f_0 of one line as the hypothesis defines it.

    Parameters
    ----------
    h : Hypothesis
        Its ``f0`` names the definition: "linear_max" (ours: linearised in-plane frequency at
        Omega_0 + a), "linear_mean" (at Omega_0), "southwell_flap" / "southwell_inplane"
        (Eq. Southwell at Omega_0 + a), "fn_printed" (ours shifted to f_n = 6.37 Hz) or "peak"
        (peak of our dynamic RMS scan).
    beam : Beam
        The beam (SI).
    omega0 : float
        Mean rotation rate Omega_0 [rad/s].
    scan : ScanSpec
        Drive amplitude a, and for "peak" the grid and samples of the scan.

    Returns
    -------
    float
        f_0 [Hz].

    Raises
    ------
    RotbeamInputError
        For an unknown ``f0``.
    """
    a = scan.amplitude
    if h.f0 == "linear_max":
        return resonance_frequency_hz(beam, abs(omega0) + a)
    if h.f0 == "linear_mean":
        return float(modes(beam, abs(omega0), 1, 80)[0])
    if h.f0 in ("southwell_flap", "southwell_inplane"):
        return southwell_frequency_hz(beam, abs(omega0) + a, softening=h.f0 == "southwell_inplane")
    if h.f0 == "fn_printed":
        f0 = resonance_frequency_hz(beam, abs(omega0) + a)
        return math.sqrt(f0 * f0 - beam.f_n**2 + F_N_PRINTED**2)
    if h.f0 == "peak":
        return _peak_frequency_hz(beam, omega0, scan)
    raise RotbeamInputError(f"f0 = {h.f0!r}: unknown f_0 definition")


def line_scan(h: Hypothesis | str, beam: Beam, c_max: float, scan: ScanSpec = ScanSpec()) -> dict:
    """Delta RMS along one line: f_d = f_0 linspace(lo, hi, points), f_0 ours, at C_max's Omega_0.

    Parameters
    ----------
    h : Hypothesis or str
        The hypothesis, or its name.
    beam : Beam
        The beam (SI).
    c_max : float
        The line's maximal centrifugal number C_max (dimensionless, > 0).
    scan : ScanSpec
        The scan and its numerics.

    Returns
    -------
    dict
        ``c_max``; ``omega0`` [rad/s]; ``f_ref``, f_0 ours [Hz], which sets the scan; ``f_d``
        [Hz], ``delta``, ``rms_dynamic`` and ``rms_quasistatic`` (arrays, one entry per f_d);
        ``f0`` [Hz], f_0 as the hypothesis defines it.

    Raises
    ------
    RotbeamInputError
        For an unknown hypothesis or a C_max that is not > 0.
    """
    h = hypothesis(h)
    omega0 = omega0_for_cmax(beam, c_max, scan.amplitude)
    f_ref = resonance_frequency_hz(beam, abs(omega0) + scan.amplitude)
    fds = f_ref * np.linspace(scan.lo, scan.hi, scan.points)
    hb, N, m = _beam_for(beam, h), h.N or scan.N, scan.samples
    dynamics = replace(h, **{k: getattr(Hypothesis(), k) for k in READOUT_FIELDS})
    runs = _line_dynamics(dynamics, hb, float(omega0), tuple(float(f) for f in fds),
                          h.N_dyn or N, m, scan.amplitude)  # fmt: skip
    rows = [_readout(h, dl, N, m, *run) for dl, *run in runs]
    return {"c_max": c_max, "omega0": omega0, "f_ref": f_ref, "f_d": fds,
            "delta": np.array([r["delta_rms"] for r in rows]),
            "rms_dynamic": np.array([r["rms_dynamic"] for r in rows]),
            "rms_quasistatic": np.array([r["rms_quasistatic"] for r in rows]),
            "f0": f0_for(h, _beam_for(beam, h), omega0, scan)}  # fmt: skip


# --- c over the lines ------------------------------------------------------------------------
def slope_fit(f0: Sequence[float], fd: Sequence[float]) -> tuple[float, float]:
    """Least-squares slope c of fd = c f0 through the origin, and its standard error.

    The fit of `rotbeam.analysis.boundary.fit_c`, on plain sequences.

    Parameters
    ----------
    f0 : sequence of float
        f_0 of each line [Hz].
    fd : sequence of float
        f_d* of each line [Hz].

    Returns
    -------
    c : float
        The slope (dimensionless); NaN with no line.
    c_err : float
        Its standard error; NaN with fewer than 2 lines.
    """
    f0, fd = np.asarray(f0, float), np.asarray(fd, float)
    if f0.size == 0:
        return math.nan, math.nan
    c = float(f0 @ fd / (f0 @ f0))
    if f0.size < 2:
        return c, math.nan
    resid = fd - c * f0
    return c, float(math.sqrt(resid @ resid / (f0.size - 1) / (f0 @ f0)))


def line_roots(lines: Sequence[dict], threshold: float, lo: float) -> tuple[list[dict], list[str]]:
    """The PCHIP root f_d* of each line at one threshold.

    Parameters
    ----------
    lines : sequence of dict
        `line_scan` results.
    threshold : float
        Delta RMS threshold (dimensionless).
    lo : float
        The scan's lower end as a fraction of f_0, quoted in the notes.

    Returns
    -------
    roots : list of dict
        One per line with a root: ``c_max``, ``root`` (f_d* [Hz]), ``f0`` and ``f_ref`` [Hz].
    notes : list of str
        One per line without a root: why, and Delta RMS at the first scanned point.
    """
    roots, notes = [], []
    for ln in lines:
        cr = critical_from_scan(ln["f_d"], ln["delta"], threshold)
        if cr["found"] and math.isfinite(cr["f_d_root"]):
            roots.append({"c_max": ln["c_max"], "root": cr["f_d_root"], "f0": ln["f0"],
                          "f_ref": ln["f_ref"]})  # fmt: skip
        else:
            notes.append(f"C_max {ln['c_max']:g}, threshold {threshold:g}: {cr.get('message')} "
                         f"(Delta RMS at f_d = {lo:g} f_0: {ln['delta'][0]:.3g})")  # fmt: skip
    return roots, notes


def c_for_hypothesis(
    name: str | Hypothesis,
    beam: Beam | None = None,
    scan: ScanSpec = ScanSpec(),
    thresholds: Iterable[float] = THRESHOLDS,
) -> dict:
    """c = f_d*/f_0 at every threshold for one hypothesis.

    On each line of `scan`, f_d* is the PCHIP root of Delta RMS; c is the least-squares slope
    of f_d* = c f_0 over the lines (`slope_fit`), f_0 as the hypothesis defines it.  A threshold
    not reached from below on a line (Delta RMS already above it at the lowest scanned f_d, or
    never reached) drops that line, with a note.

    Parameters
    ----------
    name : str or Hypothesis
        The hypothesis, or its name (`hypothesis`).
    beam : Beam or None
        The beam (SI); None: the reference beam.
    scan : ScanSpec
        The lines and their scan.
    thresholds : iterable of float
        Delta RMS thresholds, each in (0, 1).

    Returns
    -------
    dict
        ``name`` and ``description``; ``c`` and ``c_err``, {threshold: float} (NaN c with no
        line); ``per_line``, {threshold: [f_d*/f_0 of each line, NaN where dropped]};
        ``roots``, {threshold: the roots of `line_roots`}; ``notes``, a list of str; ``lines``,
        the `line_scan` results.

    Raises
    ------
    RotbeamInputError
        For an unknown hypothesis or a threshold outside (0, 1).
    """
    beam = beam or Beam()
    h = hypothesis(name)
    thresholds = [check_threshold(t) for t in thresholds]
    lines = [line_scan(h, beam, cm, scan) for cm in scan.c_max]
    out: dict = {"name": name if isinstance(name, str) else h.description,
                 "description": h.description, "c": {}, "c_err": {}, "per_line": {},
                 "roots": {}, "notes": [], "lines": lines}  # fmt: skip
    for th in thresholds:
        roots, notes = line_roots(lines, th, scan.lo)
        out["notes"] += notes
        out["roots"][th] = roots
        out["c"][th], out["c_err"][th] = slope_fit([r["f0"] for r in roots],
                                                   [r["root"] for r in roots])  # fmt: skip
        found = {r["c_max"]: r["root"] / r["f0"] for r in roots}
        out["per_line"][th] = [found.get(ln["c_max"], math.nan) for ln in lines]
    return out


def grid_c(result: dict, rule: GridRule) -> dict[float, tuple[float, float]]:
    """c of a `c_for_hypothesis` result under the first-grid-point rule (no new simulation).

    The first grid point at or above the PCHIP root is the first with Delta RMS >= threshold on
    the interpolant (PCHIP does not overshoot its data, and every scanned point below the root's
    bracket is below the threshold); grid points below the scan's lo are taken as below it too.

    Parameters
    ----------
    result : dict
        A `c_for_hypothesis` result (its ``roots`` are read).
    rule : GridRule
        The coarse scan.

    Returns
    -------
    dict
        {threshold: (c, c_err)}, as `slope_fit` gives them.
    """
    out = {}
    for th, roots in result["roots"].items():
        fds = [rule.point_above(r["root"], r["f_ref"]) for r in roots]
        out[th] = slope_fit([r["f0"] for r in roots], fds)
    return out


# --- the study's table -----------------------------------------------------------------------
def _rows(name: str, description: str, fits: dict, result: dict) -> list[dict]:
    """One row per threshold; `fits` {threshold: (c, c_err)}, lines_used from `result`."""
    return [
        {"hypothesis": name, "threshold": th, "c": c, "c_err": err,
         "c_paper": PAPER_C.get(round(th, 4), math.nan),
         "lines_used": len(result["roots"][th]), "description": description}
        for th, (c, err) in fits.items()
    ]  # fmt: skip


def _grid_description(description: str, rule: GridRule) -> str:
    unit = "Hz" if rule.unit == "Hz" else "f_0"
    return f"{description}; f_d* the first scan point f_d = k {rule.step:g} {unit} above the root"


def study_table(
    names: Sequence[str],
    beam: Beam,
    scan: ScanSpec,
    thresholds: Iterable[float] = THRESHOLDS,
    grid_rules: Sequence[GridRule] = (),
    grid_hypotheses: Sequence[str] = (),
    log: Callable[[str], None] = lambda msg: None,
) -> pd.DataFrame:
    """The c study's long table: every named hypothesis, and some under each grid rule.

    Every name is checked before the first simulation, and a hypothesis named in both `names`
    and `grid_hypotheses` runs once.

    Parameters
    ----------
    names : sequence of str
        Hypotheses tabled with c from the PCHIP root.
    beam : Beam
        The beam (SI).
    scan : ScanSpec
        The lines and their scan.
    thresholds : iterable of float
        Delta RMS thresholds, each in (0, 1).
    grid_rules : sequence of GridRule
        Coarse scans for the first-grid-point rule.
    grid_hypotheses : sequence of str
        Hypotheses also tabled under each of `grid_rules`, as "<hypothesis>+grid_<step><unit>".
    log : callable
        Receives one line per hypothesis: its c and notes.

    Returns
    -------
    pandas.DataFrame
        One row per (hypothesis, threshold): hypothesis, threshold, c, c_err, c_paper (the
        printed c; NaN at a threshold the paper does not print), lines_used (the lines with a
        root at that threshold), description.

    Raises
    ------
    RotbeamInputError
        For an unknown hypothesis name or a threshold outside (0, 1).
    """
    thresholds = [check_threshold(t) for t in thresholds]
    todo = list(dict.fromkeys([*names, *grid_hypotheses]))
    for name in todo:
        hypothesis(name)  # every name checked before the first simulation
    results = {}
    for name in todo:
        results[name] = r = c_for_hypothesis(name, beam, scan, thresholds)
        cs = ", ".join(f"{c:.4f}" for c in r["c"].values())
        log(f"{name}: c = {cs}" + (f"; {'; '.join(r['notes'])}" if r["notes"] else ""))
    rows = []
    for name in names:
        r = results[name]
        rows += _rows(name, r["description"], {t: (r["c"][t], r["c_err"][t]) for t in r["c"]}, r)
    for name in grid_hypotheses:
        r = results[name]
        for rule in grid_rules:
            desc = _grid_description(r["description"], rule)
            rows += _rows(f"{name}+{rule.label}", desc, grid_c(r, rule), r)
    return pd.DataFrame(rows)


@dataclass(frozen=True)
class Study:
    """The workflow's c study (config section ``c_hypotheses``), ready to run on a beam.

    Attributes
    ----------
    hypotheses : tuple of str
        Hypotheses tabled with c from the PCHIP root.
    scan : ScanSpec
        The lines and their scan.
    thresholds : tuple of float
        Delta RMS thresholds.
    grid_rules : tuple of GridRule
        Coarse scans for the first-grid-point rule.
    grid_hypotheses : tuple of str
        Hypotheses also tabled under each of `grid_rules`.
    """

    hypotheses: tuple[str, ...]
    scan: ScanSpec = ScanSpec()
    thresholds: tuple[float, ...] = THRESHOLDS
    grid_rules: tuple[GridRule, ...] = ()
    grid_hypotheses: tuple[str, ...] = ()

    def run(self, beam: Beam, log: Callable[[str], None] = lambda msg: None) -> pd.DataFrame:
        """The study's table for one beam (`study_table`).

        Parameters
        ----------
        beam : Beam
            The beam (SI).
        log : callable
            Receives one line per hypothesis.

        Returns
        -------
        pandas.DataFrame
            The long table of `study_table`.
        """
        return study_table(self.hypotheses, beam, self.scan, self.thresholds, self.grid_rules,
                           self.grid_hypotheses, log)  # fmt: skip

    def describe(self) -> str:
        """The setup in one line (lines, N, scan, samples, amplitude), for the study's Markdown."""
        s = self.scan
        lines = ", ".join(f"{c:g}" for c in s.c_max)
        return (f"C_max = {lines}; N = {s.N}; f_d = f_0 linspace({s.lo:g}, {s.hi:g}, {s.points}),"
                f" {s.samples} samples per period; a = {s.amplitude:g} rad/s")  # fmt: skip


def study_from_config(section: dict, amplitude: float = 1.0) -> Study:
    """The `Study` of the workflow config's ``c_hypotheses`` section.

    Parameters
    ----------
    section : dict
        The section: ``hypotheses``, ``c_max``, ``N``, ``lo``, ``hi``, ``points``, and
        optionally ``samples`` (default 32), ``thresholds`` (default `THRESHOLDS`) and ``grid``
        (``step_hz``, ``step_f0``, ``hypotheses``).
    amplitude : float
        Drive amplitude a [rad/s] (the config's ``amplitude``).

    Returns
    -------
    Study
        The study; its hypothesis names are checked when it runs.

    Raises
    ------
    RotbeamInputError
        When a value of the scan or a grid step is outside its range.
    """
    scan = ScanSpec(c_max=tuple(section["c_max"]), N=int(section["N"]), lo=section["lo"],
                    hi=section["hi"], points=int(section["points"]),
                    samples=int(section.get("samples", 32)), amplitude=amplitude)  # fmt: skip
    grid = section.get("grid", {})
    rules = [GridRule(float(s), "Hz") for s in grid.get("step_hz", [])]
    rules += [GridRule(float(s), "f0") for s in grid.get("step_f0", [])]
    return Study(tuple(section["hypotheses"]), scan,
                 tuple(float(t) for t in section.get("thresholds", THRESHOLDS)), tuple(rules),
                 tuple(grid.get("hypotheses", [])))  # fmt: skip
