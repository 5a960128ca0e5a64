"""The command line's flags, generated from the parameter registry, and what turns them into a
scene: one line for a bad value, naming the flag, the value and what is allowed."""

from __future__ import annotations

import argparse
import math
import re
from pathlib import Path
from typing import Any

from ..config.errors import RotbeamInputError
from ..config.parameters import SECTIONS, check_value, help_text, param

EXIT_USAGE = 2

#: flag names that are not `--` + the field's name with hyphens
FLAG_NAMES = {
    ("drive", "f_d"): "--fd",
    ("response", "periods"): "--response-periods",
    ("response", "N"): "--response-N",
    ("modes", "count"): "--k",
}


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors (exit status 2) and negative numbers read as values."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        # values like -2.5e1, -1e-5, -inf are values, not flags (argparse only knows -2, -2.5)
        self._negative_number_matcher = re.compile(
            r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE
        )

    def error(self, message: str) -> None:
        """Exit with status 2 and one line on stderr (pointing to --help for unknown flags).

        Parameters
        ----------
        message : str
            argparse's message.

        Raises
        ------
        SystemExit
            Always, with status EXIT_USAGE.
        """
        if message.startswith("unrecognized arguments"):
            message += f"; allowed: see `{self.prog} --help`"
        self.exit(EXIT_USAGE, f"rotbeam: error: {message}\n")


def finite(text: str) -> float:
    """A finite real number from a flag's text (an argparse `type`).

    Parameters
    ----------
    text : str
        The flag's value.

    Returns
    -------
    float

    Raises
    ------
    argparse.ArgumentTypeError
        If the text is not a number, or not finite.
    """
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(v):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return v


def integer(text: str) -> int:
    """An integer from a flag's text (an argparse `type`).

    Parameters
    ----------
    text : str
        The flag's value.

    Returns
    -------
    int

    Raises
    ------
    argparse.ArgumentTypeError
        If the text is not an integer.
    """
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None


def flag_name(section: str, name: str) -> str:
    """The flag of a registry field: `--` and its name with hyphens, or FLAG_NAMES'.

    Parameters
    ----------
    section : str
        The registry section (beam, drive, effects, numerics, ...).
    name : str
        The field's name.

    Returns
    -------
    str
        E.g. "--omega0", "--fd".
    """
    return FLAG_NAMES.get((section, name), "--" + name.replace("_", "-"))


def dest(section: str, name: str) -> str:
    """Where argparse keeps a registry field's value.

    Parameters
    ----------
    section : str
        The registry section.
    name : str
        The field's name.

    Returns
    -------
    str
        The attribute of the parsed namespace, "<section>__<name>".
    """
    return f"{section}__{name}"


#: scene fields a command cannot do without (for the drives that read them): their help says
#: so instead of showing the registry's default, which the Python API uses
REQUIRED = {
    ("drive", "omega0"): "required for a sine or harmonics drive, here or in --scene; a "
    "profile or a move has its own speeds; a finite number",
    ("drive", "f_d"): "required for a periodic drive, here or in --scene; a move has none; a "
    "number > 0",
}


def add_field(p: argparse.ArgumentParser, section: str, name: str, **kwargs: Any) -> None:
    """One flag for the registry field section.name: its type, help (unit, default, range);
    default None (unset: the scene file's value or the registry's default).

    Parameters
    ----------
    p : argparse.ArgumentParser
        The parser (or argument group) the flag is added to.
    section : str
        The registry section.
    name : str
        The field's name.
    **kwargs
        Passed to `add_argument`.
    """
    entry = param(section, name)
    flag = flag_name(section, name)
    common = {"dest": dest(section, name), "default": None,
              "help": kwargs.pop("help", None) or help_text(section, name)}  # fmt: skip
    if entry.kind == "bool":
        p.add_argument(flag, action=argparse.BooleanOptionalAction, **common, **kwargs)
    elif entry.kind == "choice":
        p.add_argument(flag, metavar="{" + ",".join(entry.choices) + "}", **common, **kwargs)
    else:
        kind = integer if entry.kind == "int" else finite
        p.add_argument(flag, type=kind, **common, **kwargs)
    p.set_defaults(_fields=[*(p.get_default("_fields") or []), (section, name)])


def add_section(p: argparse.ArgumentParser, section: str, skip: tuple[str, ...] = ()) -> None:
    """A flag for every field of a scene section but `skip`, in a group of its own.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser.
    section : str
        The scene section (beam, drive, numerics).
    skip : tuple of str
        Fields that get no flag.
    """
    group = p.add_argument_group(f"{section} (scene section; a --scene file's values unless set)")
    for name, entry in SECTIONS[section].items():
        if name not in skip and entry.kind != "data":  # structured: `add_drive_flags`
            extra = {}
            if (section, name) in REQUIRED:
                unit = f" [{entry.unit}]" if entry.unit else ""
                extra["help"] = f"{entry.help}{unit} ({REQUIRED[section, name]})"
            add_field(group, section, name, **extra)  # type: ignore[arg-type]


def add_drive_flags(p: argparse.ArgumentParser, move: bool = True) -> None:
    """--harmonics, --profile and (for simulate) --move: drives beyond the sine.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser.
    move : bool
        Whether the command takes a single move.
    """
    p.add_argument(
        "--harmonics",
        help="Omega_0 + sum_k a_k sin(2 pi k f_d t + phase_k) instead of --amplitude, as "
        "k:a_k:phase_k[,...], e.g. 1:1.0:0,3:0.5:0.7 (rad/s, rad)",
    )
    p.add_argument(
        "--profile",
        help="one period of sampled speed: a CSV file with columns phase in [0, 1) and omega "
        "[rad/s], repeated at --fd",
    )
    if move:
        p.add_argument(
            "--move",
            help="a single move: a CSV file with columns t [s] and omega [rad/s]; the beam "
            "starts at rest in the static state of its first speed (see --move-start)",
        )


def harmonics_flag(text: str) -> list[dict[str, float]]:
    """The harmonics of a --harmonics flag.

    Parameters
    ----------
    text : str
        k:amplitude[:phase][,...], e.g. "1:1.0:0,3:0.5:0.7" (rad/s, rad).

    Returns
    -------
    list of dict
        A scene file's harmonics list.
    """
    out = []
    for part in filter(None, (q.strip() for q in text.split(","))):
        fields = part.split(":")
        try:
            if len(fields) not in (2, 3):
                raise ValueError
            k, a = int(fields[0]), finite(fields[1])
            phase = finite(fields[2]) if len(fields) == 3 else 0.0
        except (ValueError, argparse.ArgumentTypeError):
            raise RotbeamInputError(
                f"argument --harmonics: {part!r}; allowed: k:amplitude[:phase], e.g. 3:0.5:0.7"
            ) from None
        out.append({"k": k, "amplitude": a, "phase": phase})
    return out


def add_scene_flags(
    p: argparse.ArgumentParser, drive_frequency: bool = True, auto_effects: bool = True
) -> None:
    """--scene, every beam, drive and numerics field, --effects and --json.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser.
    drive_frequency : bool
        Whether the command takes --fd and --move (`rotbeam critical` does not: it finds f_d*;
        nor does `rotbeam sweep`: it runs a line of them).
    auto_effects : bool
        Whether --effects takes auto[:TOL] (an effect budget at one drive frequency).
    """
    p.add_argument("--scene", help="YAML scene file (sections beam, drive, effects, numerics)")
    for section in ("beam", "drive", "numerics"):
        add_section(p, section, skip=() if drive_frequency or section != "drive" else ("f_d",))
    add_drive_flags(p, move=drive_frequency)
    auto = (
        "; or auto[:TOL]: those whose share of RMS is >= TOL (default 0.001), from "
        "`rotbeam effects`" + ("" if drive_frequency else " at the linear estimate of f_d*")
    )
    p.add_argument("--effects", help="comma list of effects switched on, e.g. centrifugal,euler"
                   + (auto if auto_effects else ""))  # fmt: skip
    p.add_argument("--json", action="store_true", help="print one JSON object")


def given(args: argparse.Namespace) -> dict[str, str]:
    """`section.name` -> flag of every registry field set on the command line.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags.

    Returns
    -------
    dict
        E.g. {"drive.omega0": "--omega0"}.
    """
    return {f"{s}.{n}": flag_name(s, n) for s, n in getattr(args, "_fields", [])
            if getattr(args, dest(s, n)) is not None}  # fmt: skip


def option(args: argparse.Namespace, section: str, name: str) -> Any:
    """A command option's value, checked against the registry (its default when unset).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags.
    section : str
        The registry section (e.g. verdict, critical, response).
    name : str
        The field's name.

    Returns
    -------
    object
        The checked value, in the field's unit.

    Raises
    ------
    RotbeamInputError
        If the value is outside the field's range.
    """
    value = getattr(args, dest(section, name))
    return check_value(section, name, param(section, name).default if value is None else value)


def scene_values(args: argparse.Namespace) -> dict[str, dict[str, Any]]:
    """The scene fields set by flags, by section.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags.

    Returns
    -------
    dict
        Section -> {field: value}, only fields whose flag was given.
    """
    out: dict[str, dict[str, Any]] = {}
    for s, n in getattr(args, "_fields", []):
        value = getattr(args, dest(s, n))
        if value is not None and s in SECTIONS:
            out.setdefault(s, {})[n] = value
    return out


def named_flag(message: str, args: argparse.Namespace) -> str:
    """`message` prefixed with `argument --flag:` when it is about a field a flag set.

    Parameters
    ----------
    message : str
        A `RotbeamInputError`'s message, starting with the key it is about.
    args : argparse.Namespace
        The parsed flags.

    Returns
    -------
    str
        The message, naming the flag where one set the value.
    """
    for key, flag in given(args).items():
        if message.startswith(key) and not message[len(key) : len(key) + 1].isalnum():
            return f"argument {flag}: {message}"
    if message.startswith("effects") and getattr(args, "effects", None) is not None:
        return f"argument --effects: {message}"
    return message


def scene_request(args: argparse.Namespace, needs: tuple[str, ...] = ("omega0", "f_d")) -> tuple:
    """The scene of the command line: its --scene file, overridden by the flags.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed flags (`add_scene_flags`, optionally `add_uncertainty_flags`).
    needs : tuple of str
        Drive fields the command cannot do without (from the file or a flag).

    Returns
    -------
    scene : Scene
        The scene (at the means of its uncertain inputs).
    auto_tol : float or None
        TOL of `effects: auto` (flag or file; an explicit --effects list wins), None without.
    inputs : dict
        Uncertain inputs, name -> (mean, sd).

    Raises
    ------
    RotbeamInputError
        If the scene file, a flag or the uncertainty is not allowed, or a needed drive field is
        missing.
    """
    from ..config.scenefile import auto_tol, load_scene_file, scene_sections, split_auto
    from ..model.drives import DRIVE_FIELDS
    from ..model.params import Effects
    from ..runs.scene import build_scene, drive_kind

    raw = dict(load_scene_file(args.scene)) if args.scene else {}
    section = raw.pop("uncertainty", None)
    raw, file_tol = split_auto(raw)
    spec = scene_sections(raw)
    flags = scene_values(args)
    for s, values in flags.items():
        spec.setdefault(s, {}).update(values)
    drive = spec.setdefault("drive", {})
    _drive_flags(args, drive, flags.get("drive", {}))
    kind = drive_kind(drive)
    needs = tuple(k for k in needs if k in DRIVE_FIELDS[kind])
    tol = None
    text = args.effects or ""
    if text == "auto" or text.startswith("auto:"):
        tol = auto_tol(text, "argument --effects")
    elif args.effects is not None:
        spec["effects"] = vars(Effects.from_list(args.effects)).copy()
    else:
        tol = file_tol
    _check_values(spec)  # a bad value is named before a missing one
    for key in needs:
        if key not in spec.get("drive", {}):
            what = {"omega0": "a finite number, rad/s", "f_d": "a number > 0, Hz"}[key]
            raise RotbeamInputError(
                f"drive.{key} is missing: give {flag_name('drive', key)} ({what}) or drive.{key} "
                f"in the --scene file"
            )
    scene = build_scene(spec, Path(args.scene).parent if args.scene else ".")
    inputs = {}
    if hasattr(args, "uncertainty"):
        from ..analysis.uncertainty import at_means, read_inputs

        inputs = read_inputs(section, args.uncertainty, f"scene file {args.scene!r}")
        scene = at_means(scene, inputs)
    return scene, tol, inputs


def _check_values(spec: dict[str, dict[str, Any]]) -> None:
    """Check every scalar field a scene spec sets against the registry (one line naming the
    first bad one), before its missing fields are asked for."""
    for section, values in spec.items():
        for name, value in values.items():
            if param(section, name).kind != "data":
                check_value(section, name, value)


#: the flags that set a drive's kind by a structured value, and how each reads its text into the
#: scene key of its name (a file is relative to where the command runs)
KIND_FLAGS = {
    "harmonics": harmonics_flag,
    "profile": lambda text: str(Path(text).resolve()),
    "move": lambda text: str(Path(text).resolve()),
}


def _drive_flags(args: argparse.Namespace, drive: dict[str, Any], flagged: dict) -> None:
    """Put --harmonics, --profile and --move into the drive section.  A flag's kind replaces
    the --scene file's: the file's keys that the flag's kind does not read give way (a flag's
    own values stay, and are refused if the kind does not read them)."""
    from ..model.drives import DRIVE_FIELDS, kind_of

    given = [k for k in KIND_FLAGS if getattr(args, k, None)]
    if not given:
        return
    if len(given) > 1:
        raise RotbeamInputError(
            f"--{' and --'.join(given)} given together; allowed: one of --harmonics, --profile, "
            f"--move"
        )
    key = given[0]
    reads = DRIVE_FIELDS[kind_of({key: True})]
    for name in SECTIONS["drive"]:
        if name not in reads and name not in flagged:
            drive.pop(name, None)
    drive[key] = KIND_FLAGS[key](getattr(args, key))


def add_uncertainty_flags(p: argparse.ArgumentParser) -> None:
    """--uncertainty, --uq-method, --uq-samples.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser.
    """
    p.add_argument("--uncertainty", help="inputs' normal spreads, e.g. "
                   "\"gamma=0.039+-0.008,E=1.22e6+-0.05e6\" (beam fields, omega0, amplitude; "
                   "adds to a scene file's uncertainty section)")  # fmt: skip
    p.add_argument("--uq-method", default="linear", choices=("linear", "sobol"),
                   help="linear (1 + k runs, default) or sobol (--uq-samples runs at a Sobol "
                   "design)")  # fmt: skip
    p.add_argument("--uq-samples", type=integer, default=32,
                   help="Sobol runs, a power of two (default 32)")  # fmt: skip


def add_criterion_flag(p: argparse.ArgumentParser) -> None:
    """--criterion: the observable whose Delta RMS the verdict and the f_d* search read.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser.
    """
    p.add_argument("--criterion", metavar="NAME", default="y_m",
                   help="judge Delta RMS of this observable: y_m (default, the paper's), tip, "
                   "root_moment, root_stress or tip_acceleration (the linear estimate of f_d* "
                   "stays the first mode's)")  # fmt: skip


def criterion_request(args: argparse.Namespace, inputs: dict) -> str:
    """The --criterion asked for, checked; an uncertainty propagates y_m's numbers only.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed flags (`add_criterion_flag`).
    inputs : dict
        The uncertainty's inputs (`scene_request`); empty without one.

    Returns
    -------
    str
        The observable's name.

    Raises
    ------
    RotbeamInputError
        One line for a name that is not an observable (naming the allowed ones), or for a
        criterion other than y_m beside an uncertainty.
    """
    from ..runs.observables import criterion_name

    name = criterion_name(args.criterion)
    if name != "y_m" and inputs:
        raise RotbeamInputError(
            f"--criterion {name} does not combine with an uncertainty (it propagates y_m's "
            "Delta RMS only); allowed there: --criterion y_m"
        )
    return name


def check_plot_path(path: str | None) -> None:
    """Check a --plot path's suffix (.png, .pdf, .svg) before any work.

    Parameters
    ----------
    path : str or None
        The --plot value; None or empty: nothing to check.

    Raises
    ------
    RotbeamInputError
        If the suffix is not one of PLOT_SUFFIXES.
    """
    if path:
        from ..config.checks import check_plot_suffix

        check_plot_suffix(path)
