"""The studies of the paper as plain data built from the workflow config (no snakemake here).

A *line* is one sweep: a beam, a mean speed Omega_0 and a list (or an f_0-relative scan) of
drive frequencies (a job of its own, or run with the other lines of its Fig. 7 grid column or of
Fig. B.8 in one job).  A *series* is one scene whose time series is kept.  Ids are readable and
carry the values that define them, so that an output path names its parameters.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from ..config.errors import RotbeamInputError
from ..config.scenefile import load_yaml
from ..config.schema import (
    coerce_numbers,
    describe_allowed,
    g,
    json_numbers,
    key_name,
    schema_error_message,
    subschema,
)
from ..model.params import Beam, Effects, fd_for_emax, omega0_for_cmax

REF = "ref"  #: the beam id of the reference beam's lines


def beam_id(beam: dict[str, float]) -> str:
    """The readable id of a grid beam, from the values that define it.

    Parameters
    ----------
    beam : dict
        The beam's `Beam` fields (SI): E, L and h are read.

    Returns
    -------
    str
        "E<E>_L<L>_hL<h/L>", e.g. "E100000_L0.0001_hL0.05".
    """
    return f"E{g(beam['E'])}_L{g(beam['L'])}_hL{g(beam['h'] / beam['L'])}"


DAMPING = ("gamma", "eta", "zeta")  #: what a grid beam keeps of the reference beam's damping
GEOMETRY = ("R", "delta")  #: what it keeps of the reference beam's position: R or L/R


def grid_beam(
    ref: dict[str, float], E: float, L: float, h_over_L: float,
    damping: str = "gamma", geometry: str = "R", zeta: float | None = None,
) -> dict[str, float]:  # fmt: skip
    """One beam of a Fig. 7 grid: E, L, h = h_over_L L and the reference beam's b/h and rho.

    Parameters
    ----------
    ref : dict
        The reference beam's `Beam` fields (SI).
    E : float
        Young's modulus [Pa].
    L : float
        Length [m].
    h_over_L : float
        Slenderness h/L (dimensionless).
    damping : str
        What the beam keeps of the reference beam's damping: "gamma" (its gamma), "eta"
        (gamma scaled so that eta, the damping of the dimensionless equations, is the
        reference's) or "zeta" (gamma scaled so that zeta = eta / (2 beta_1^2) is `zeta`).
    geometry : str
        What it keeps of the reference beam's position: "R" (its R) or "delta" (R scaled with L
        so that L/R is the reference's).
    zeta : float or None
        The damping ratio (dimensionless) of damping "zeta"; None: the reference beam's (which
        then equals damping "eta").

    Returns
    -------
    dict
        The beam's `Beam` fields (SI).

    Raises
    ------
    RotbeamInputError
        For an unknown damping or geometry, or a beam `Beam` refuses.
    """
    if damping not in DAMPING:
        raise RotbeamInputError(f"damping = {damping!r}: must be one of {', '.join(DAMPING)}")
    if geometry not in GEOMETRY:
        raise RotbeamInputError(f"geometry = {geometry!r}: must be one of {', '.join(GEOMETRY)}")
    h = h_over_L * L
    beam = dict(ref, E=float(E), L=float(L), h=float(h), b=float(ref["b"] / ref["h"] * h))
    if geometry == "delta":
        beam["R"] = float(ref["R"] / ref["L"] * L)
    rb, b0 = Beam(**ref), Beam(**{**beam, "gamma": 1.0})  # b0.eta: eta per unit gamma
    if damping == "eta":
        beam["gamma"] = float(rb.eta / b0.eta)
    elif damping == "zeta":
        beam["gamma"] = float((rb.zeta if zeta is None else zeta) / b0.zeta)
    return beam


def variant_tag(damping: str, geometry: str, zeta: float | None = None) -> str:
    """The name of a (damping, geometry) hypothesis, e.g. "eta-delta" or "zeta0.017-R".

    Parameters
    ----------
    damping : str
        "gamma", "eta" or "zeta" (`grid_beam`).
    geometry : str
        "R" or "delta".
    zeta : float or None
        The damping ratio of damping "zeta", written into the name when given.

    Returns
    -------
    str
        "<damping>-<geometry>".
    """
    d = f"zeta{g(zeta)}" if damping == "zeta" and zeta is not None else damping
    return f"{d}-{geometry}"


def fig7_beams(config: dict[str, Any]) -> dict[str, dict[str, float]]:
    """The Fig. 7 grid of beams: E x L x h/L, each a `grid_beam` of the reference beam.

    The beams keep b/h and rho of the reference beam, and its gamma or eta or zeta
    (``fig7.damping``) and its R or L/R (``fig7.geometry``).

    Parameters
    ----------
    config : dict
        The workflow config (sections ``beam`` and ``fig7``).

    Returns
    -------
    dict
        {beam id: the beam's `Beam` fields (SI)}.  The ids of the default (gamma, R) grid carry
        no tag; the others end in _<damping>-<geometry>.
    """
    f7 = config["fig7"]
    damping, geometry = f7.get("damping", "gamma"), f7.get("geometry", "R")
    zeta = f7.get("zeta")
    default = (damping, geometry) == ("gamma", "R")
    tag = "" if default else "_" + variant_tag(damping, geometry, zeta)
    return _grid(config["beam"], f7, damping, geometry, zeta, prefix="", tag=tag)


def _grid(ref, spec, damping, geometry, zeta, prefix, tag) -> dict[str, dict[str, float]]:
    out = {}
    for E in spec["E"]:
        for L in spec["L"]:
            for hl in spec["h_over_L"]:
                beam = grid_beam(ref, E, L, hl, damping, geometry, zeta)
                out[prefix + beam_id(beam) + tag] = beam
    return out


def repro_fig7_variants(config: dict[str, Any]) -> dict[str, dict[str, dict[str, float]]]:
    """The damping x geometry hypotheses of the Fig. 7 study, each with its small grid of beams.

    Parameters
    ----------
    config : dict
        The workflow config (sections ``beam`` and ``reproduction.fig7``).

    Returns
    -------
    dict
        {tag "<damping>-<geometry>": {beam id: the beam's `Beam` fields}}; the ids start with
        "r7_", so that they never meet the paper grid's files.  Empty without the section.
    """
    rc = config.get("reproduction", {}).get("fig7")
    if not rc:
        return {}
    out = {}
    for damping in rc["damping"]:
        for geometry in rc["geometry"]:
            zeta = rc.get("zeta") if damping == "zeta" else None
            tag = variant_tag(damping, geometry, zeta)
            out[tag] = _grid(config["beam"], rc, damping, geometry, zeta, "r7_", "_" + tag)
    return out


def run_grid_lines(
    beams: dict[str, dict[str, float]], spec: dict[str, Any], amplitude: float, effects: Effects,
    numerics, log: Callable[[str], None] | None = None,
) -> dict[str, list]:  # fmt: skip
    """Every boundary line of a grid, run in this process.

    The workflow runs one job per (E, L) column of the grid, or per hypothesis, instead of one
    per line: a job's start-up, 0.3 s of imports, costs about as much as a small line.

    Parameters
    ----------
    beams : dict
        {beam id: the beam's `Beam` fields (SI)}.
    spec : dict
        The grid's config section: ``c_max`` (the lines) and the scan ``lo``, ``hi``,
        ``points`` (fractions of f_0).
    amplitude : float
        Drive amplitude a [rad/s].
    effects : Effects
        The model's effects.
    numerics : Numerics
        The solver settings.
    log : callable or None
        Receives progress messages.

    Returns
    -------
    dict
        {beam id: the records of its lines, one after the other (`run_line`), key
        ``c_max_target`` naming the line}.
    """
    out = {}
    for bid, beam in beams.items():
        lines, _ = boundary_lines(beam, spec["c_max"], spec, amplitude)
        out[bid] = []
        for lid, ls in lines.items():
            if log:
                log(f"{bid} {lid}")
            out[bid] += run_line(ls, scan_frequencies(ls), effects, numerics, log)
    return out


def run_line(spec: dict[str, Any], f_ds: list[float], effects: Effects, numerics,
             log: Callable[[str], None] | None = None):  # fmt: skip
    """One sweep line at its drive frequencies (`rotbeam.runs.sweeps.scan_line`).

    Parameters
    ----------
    spec : dict
        A line of `lines_from_config`, `boundary_lines` or `convergence_lines`: beam,
        omega0 [rad/s], amplitude [rad/s] and, for a boundary line, c_max.
    f_ds : list of float
        Drive frequencies [Hz] (`scan_frequencies`).
    effects : Effects
        The model's effects.
    numerics : Numerics
        The solver settings.
    log : callable or None
        Receives progress messages.

    Returns
    -------
    list of dict
        A record per point (`rotbeam.runs.sweeps.COLUMNS`), with ``c_max_target`` when the
        line belongs to a C_max (`line_columns`).
    """
    from ..runs.sweeps import line_sweep

    line = line_sweep(Beam(**spec["beam"]), spec["omega0"], f_ds, amplitude=spec["amplitude"],
                      effects=effects, numerics=numerics, log=log)  # fmt: skip
    if "c_max" in spec:
        return [{"c_max_target": spec["c_max"], **row} for row in line.records]
    return line.records


def line_columns(boundary: bool, *extra: str) -> list[str]:
    """The columns of a file of `run_line` records: ``c_max_target`` first on a boundary line,
    then `rotbeam.runs.sweeps.COLUMNS`, then `extra`.

    Parameters
    ----------
    boundary : bool
        Whether the lines belong to a C_max.
    *extra : str
        Columns the caller adds (e.g. the beam id).

    Returns
    -------
    list of str
        The header.
    """
    from ..runs.sweeps import COLUMNS

    return (["c_max_target"] if boundary else []) + list(COLUMNS) + list(extra)


def grid_columns(
    beams: dict[str, dict[str, float]],
) -> tuple[dict[str, dict[str, dict[str, float]]], list[str]]:
    """A grid's beams by (E, L) column, for one sweep job per column (its beams differ in h/L).

    Parameters
    ----------
    beams : dict
        {beam id: the beam's `Beam` fields}, ids as `fig7_beams` makes them.

    Returns
    -------
    columns : dict
        {column id "E<E>_L<L>": {beam id: beam}}.
    tails : list of str
        The beam ids after their column id ("_hL0.05", ...; with the grid's tag if it has
        one), the same in every column.

    Raises
    ------
    ValueError
        When a beam id does not start with its column id, or the columns differ in their tails.
    """
    columns: dict[str, dict[str, dict[str, float]]] = {}
    for bid, beam in beams.items():
        column = f"E{g(beam['E'])}_L{g(beam['L'])}"
        if not bid.startswith(column + "_"):
            raise ValueError(f"grid beam id {bid!r} does not start with its column {column!r}")
        columns.setdefault(column, {})[bid] = beam
    tails = {c: [bid[len(c) :] for bid in col] for c, col in columns.items()}
    first = next(iter(tails.values()), [])
    for c, t in tails.items():
        if t != first:
            raise ValueError(f"grid column {c}: beams {t}, another column {first}")
    return columns, first


def check_config(
    config: dict[str, Any], schema: dict | None = None, scene_dir: str | Path = "config"
) -> None:
    """The checks of the workflow config that the JSON schema cannot express.

    NaN and inf pass its bounds; scan ranges must not be empty or reversed; every beam (the
    reference, the Fig. 7 grid, each reproduction grid) must be one `Beam` accepts, with the
    clamp off the axis; effects and numerics must parse; every user scene must be one
    `build_scene` accepts.

    Parameters
    ----------
    config : dict
        The workflow config.
    schema : dict or None
        The workflow's config schema, which words the allowed range of a non-finite value.
    scene_dir : str or Path
        The folder the user scenes' drive files start from.

    Raises
    ------
    RotbeamInputError
        At the first check that fails; the message is one line naming the key, its value and
        what is allowed.
    """
    for path, v in json_numbers(config):
        if not math.isfinite(v):
            allowed = describe_allowed(subschema(schema, path) if schema else None, schema)
            raise RotbeamInputError(f"{key_name(path)} = {v!r}: must be {allowed}")
    try:
        Beam(**config["beam"])
    except TypeError as exc:
        raise RotbeamInputError(f"config beam: {exc}") from None
    for name in ("fig4", "boundary", "fig7", "c_hypotheses"):
        if name not in config:
            continue
        lo, hi = config[name]["lo"], config[name]["hi"]
        if not lo < hi:
            raise RotbeamInputError(
                f"{name}.lo = {lo!r}, {name}.hi = {hi!r}: the scan range is empty or reversed; "
                f"must be lo < hi (fractions of f_0)"
            )
    nl = config.get("nonlinear")
    if nl is not None and not nl["f_lo"] < nl["f_hi"]:
        raise RotbeamInputError(
            f"nonlinear.f_lo = {nl['f_lo']!r}, nonlinear.f_hi = {nl['f_hi']!r}: the range is "
            f"empty or reversed; must be f_lo < f_hi"
        )
    f3 = config["fig3"]
    if not f3["f_d_min"] < f3["f_d_max"]:
        raise RotbeamInputError(
            f"fig3.f_d_min = {f3['f_d_min']!r}, fig3.f_d_max = {f3['f_d_max']!r}: the range is "
            f"empty or reversed; must be f_d_min < f_d_max"
        )
    R = config["beam"]["R"]
    geometry = config["fig7"].get("geometry", "R")
    for i, L in enumerate(config["fig7"]["L"] if geometry == "R" else []):
        if not L < R:
            raise RotbeamInputError(
                f"fig7.L[{i}] = {L!r}: must be < beam.R = {R!r} m (every Fig. 7 beam keeps the "
                f"reference R, and its clamp must sit off the axis)"
            )
    grids = {"fig7": fig7_beams(config)}
    for tag, beams in repro_fig7_variants(config).items():
        grids[f"reproduction.fig7 ({tag})"] = beams
    for where, beams in grids.items():
        for bid, beam in beams.items():
            try:
                Beam(**beam)
            except RotbeamInputError as exc:
                raise RotbeamInputError(f"{where} beam {bid}: {exc}") from None
    from ..runs.sweeps import numerics_from_config

    Effects.from_list(config["effects"])
    numerics_from_config(config.get("numerics"))
    if config.get("user_scenes"):
        from ..analysis.scenes import build_scenes

        build_scenes(config["user_scenes"], scene_dir)
    if config.get("move_designs"):
        from ..analysis.move_design import design_spec

        for i, spec in enumerate(config["move_designs"]):
            try:
                design_spec(spec, scene_dir)
            except RotbeamInputError as exc:
                raise RotbeamInputError(f"move_designs[{i}].{exc}") from None


def validate_config(
    config: dict[str, Any],
    schema_path: str | Path,
    schema_validate: Callable[[dict[str, Any]], None] | None = None,
    scene_dir: str | Path | None = None,
) -> dict[str, Any]:
    """The workflow's config check: numbers given as strings become numbers, then the JSON
    schema, then `check_config`.

    Parameters
    ----------
    config : dict
        The workflow config.
    schema_path : str or Path
        The config schema (YAML).
    schema_validate : callable or None
        Validates a config against the schema (snakemake.utils.validate in the workflow);
        None: jsonschema's Draft 2020-12 validator.
    scene_dir : str, Path or None
        The folder the user scenes' drive files start from; None: `config/` beside the
        schema's `workflow/` folder (the workflow's config folder).

    Returns
    -------
    dict
        The coerced config.

    Raises
    ------
    RotbeamInputError
        With one line naming the key, the value and what is allowed.
    """

    root = load_yaml(Path(schema_path).read_text())
    config = coerce_numbers(config)
    if schema_validate is None:
        import jsonschema

        def schema_validate(c: dict[str, Any]) -> None:
            jsonschema.Draft202012Validator(root).validate(c)

    try:
        schema_validate(config)
    except Exception as exc:  # jsonschema's, or snakemake's WorkflowError wrapping it
        err = next(
            (
                e
                for e in (exc, exc.__cause__, exc.__context__)
                if e is not None and hasattr(e, "validator") and hasattr(e, "absolute_path")
            ),
            None,
        )
        if err is None:
            raise RotbeamInputError(" ".join(str(exc).split())) from None
        raise RotbeamInputError(schema_error_message(err, root)) from None
    check_config(config, root, scene_dir or Path(schema_path).resolve().parents[2] / "config")
    return config


def boundary_lines(
    beam: dict[str, float], c_max: list[float], scan: dict, amplitude: float
) -> tuple[dict[str, dict[str, Any]], list[float]]:
    """The boundary lines of one beam, one per C_max.

    Parameters
    ----------
    beam : dict
        The beam's `Beam` fields (SI).
    c_max : list of float
        The lines' C_max (dimensionless).
    scan : dict
        The f_0-relative scan: ``lo``, ``hi``, ``points``.
    amplitude : float
        Drive amplitude a [rad/s].

    Returns
    -------
    lines : dict
        {line id "cmax<C_max>": its spec (beam, omega0, amplitude, c_max, scan)}.
    skipped : list of float
        The C_max below G a^2 (Omega_0 < 0), left out.
    """
    b = Beam(**beam)
    lines, skipped = {}, []
    for c in c_max:
        w0 = omega0_for_cmax(b, c, amplitude)
        if w0 < 0:
            skipped.append(c)
            continue
        lines[f"cmax{g(c)}"] = {
            "beam": beam, "omega0": w0, "amplitude": amplitude, "c_max": float(c),
            "scan": {"lo": scan["lo"], "hi": scan["hi"], "points": scan["points"]},
        }  # fmt: skip
    return lines, skipped


def lines_from_config(config: dict[str, Any]) -> dict[tuple[str, str], dict[str, Any]]:
    """Every sweep line of the workflow but Fig. B.8's (`convergence_lines`).

    Fig. 3's line, Fig. 4's lines, the reference beam's boundary lines and those of every Fig. 7
    beam.

    Parameters
    ----------
    config : dict
        The workflow config.

    Returns
    -------
    dict
        {(beam id, line id): the line's spec}; the reference beam's id is `REF`.
    """
    a = float(config["amplitude"])
    ref = config["beam"]
    out: dict[tuple[str, str], dict[str, Any]] = {}
    f3 = config["fig3"]
    out[(REF, "fig3")] = {
        "beam": ref, "omega0": f3["omega0"], "amplitude": a,
        "f_d": np.linspace(f3["f_d_min"], f3["f_d_max"], f3["points"]).round(10).tolist(),
    }  # fmt: skip
    f4 = config["fig4"]
    for w in f4["omega0"]:
        out[(REF, f"fig4_w{g(w)}")] = {
            "beam": ref, "omega0": float(w), "amplitude": a,
            "scan": {"lo": f4["lo"], "hi": f4["hi"], "points": f4["points"]},
        }  # fmt: skip
    lines, _ = boundary_lines(ref, config["boundary"]["c_max"], config["boundary"], a)
    out.update({(REF, k): v for k, v in lines.items()})
    f7 = config["fig7"]
    for bid, beam in fig7_beams(config).items():
        lines, _ = boundary_lines(beam, f7["c_max"], f7, a)
        out.update({(bid, k): v for k, v in lines.items()})
    return out


def convergence_lines(config: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """The grid-convergence lines of Fig. B.8 (App. C).

    The reference beam at each Omega_0 and the config's drive frequencies on a grid of N
    intervals, N outer and Omega_0 inner (the row order of Fig. B.8's table).

    Parameters
    ----------
    config : dict
        The workflow config (sections ``beam``, ``amplitude``, ``convergence``).

    Returns
    -------
    dict
        {line id "conv_N<N>_w<Omega_0>": the line's spec, with its N}.
    """
    a = float(config["amplitude"])
    cv = config["convergence"]
    out = {}
    for N in cv["N"]:
        for w in cv["omega0"]:
            out[f"conv_N{N}_w{g(w)}"] = {
                "beam": config["beam"], "omega0": float(w), "amplitude": a, "N": int(N),
                "f_d": [float(f) for f in cv["f_d"]],
            }  # fmt: skip
    return out


def run_convergence_lines(
    lines: dict[str, dict[str, Any]], effects: Effects, numerics: dict[str, Any],
    log: Callable[[str], None] | None = None,
):  # fmt: skip
    """Every grid-convergence line, run in this process: one job for all.

    A line is 0.01-0.6 s of work, most of them less than a job's start-up.  Each line studies
    the raw grid: the config's numerics with the line's N and no Richardson extrapolation.  The
    study is of the RMS, so an orbit's |mu|max is resolved as far as its stability verdict needs
    (floquet_tol = VERDICT_ONLY): at N = 80 the resolution to 1e-5 costs 2.4 s of the study's 4.3 s.

    Parameters
    ----------
    lines : dict
        The lines of `convergence_lines`.
    effects : Effects
        The model's effects.
    numerics : dict
        The config's ``numerics`` section.
    log : callable or None
        Receives progress messages.

    Returns
    -------
    list of dict
        The lines' records (`run_line`), in the order of `lines`.
    """
    from ..runs.sweeps import numerics_from_config
    from ..solve.floquet import VERDICT_ONLY

    records = []
    for lid, spec in lines.items():
        f_ds = scan_frequencies(spec)
        if log:
            log(f"line {lid}: {len(f_ds)} points")
        num = numerics_from_config(
            {**numerics, "N": spec["N"], "extrapolate": False, "floquet_tol": VERDICT_ONLY}
        )
        records += run_line(spec, f_ds, effects, num, log)
    return records


def series_from_config(config: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """The single scenes whose time series are kept (Fig. 3b,c; Fig. 5b,c).

    Parameters
    ----------
    config : dict
        The workflow config (sections ``beam``, ``amplitude``, ``fig3``, ``fig5``).

    Returns
    -------
    dict
        {series id ("fig3", "fig5_E<E_max>"): its spec (beam, omega0 [rad/s], f_d [Hz],
        amplitude, periods; Fig. 5's also c_max and e_max)}.
    """
    a = float(config["amplitude"])
    ref = config["beam"]
    b = Beam(**ref)
    f3 = config["fig3"]
    out = {
        "fig3": {"beam": ref, "omega0": f3["omega0"], "f_d": f3["series_f_d"], "amplitude": a,
                 "periods": f3["series_periods"]},
    }  # fmt: skip
    f5 = config["fig5"]
    w0 = omega0_for_cmax(b, f5["c_max"], a)
    for e in f5["e_max"]:
        out[f"fig5_E{g(e)}"] = {
            "beam": ref, "omega0": w0, "f_d": fd_for_emax(b, e, a), "amplitude": a,
            "periods": f5["periods"], "c_max": f5["c_max"], "e_max": float(e),
        }  # fmt: skip
    return out


def scan_frequencies(spec: dict[str, Any]) -> list[float]:
    """The drive frequencies of a line: its explicit list, or its f_0-relative scan.

    Parameters
    ----------
    spec : dict
        A line spec with ``f_d`` (a list [Hz]) or ``scan`` (``lo``, ``hi``, ``points``,
        fractions of f_0, the linear first frequency at Omega_0 + a).

    Returns
    -------
    list of float
        The drive frequencies [Hz]; non-finite ones are left out.
    """
    if "f_d" in spec:
        return [float(f) for f in spec["f_d"]]
    from ..runs.sweeps import boundary_scan_frequencies

    s = spec["scan"]
    f = boundary_scan_frequencies(
        Beam(**spec["beam"]), spec["omega0"], s["lo"], s["hi"], s["points"], spec["amplitude"]
    )
    return [float(x) for x in f if math.isfinite(x)]
