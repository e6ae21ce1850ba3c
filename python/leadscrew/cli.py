"""Command line interface: ``leadscrew run | check | study | demo``.

::

    leadscrew run SCENE [-o DIR] [--t-end T] [--integrator NAME] [--format csv|parquet]
                  [--rtol R] [--atol A] [--dt DT] [--theta THETA] [--points N]
    leadscrew check [SCENE]
    leadscrew study NAME SCENE [-o DIR] [KEY=VALUE ...]
    leadscrew demo [-o DIR]
    leadscrew --version

SCENE is a TOML scene file (see :meth:`leadscrew.Scene.from_toml`) or the name
of a shipped scene (:func:`leadscrew.scenes.available`). Errors print one line
to stderr and exit with 2 for usage and validation errors (bad arguments, an
invalid or unreadable scene file, an integrator that does not fit, an option
the integrator would ignore: ``--dt``/``--theta`` without ``moreau``,
``--rtol``/``--atol`` with it) and 1 for failures while running (simulation
errors, a study that raises or whose every case failed; some failed cases:
exit 0 with a warning on stderr); ``--debug`` shows the traceback instead.
Arguments are checked before anything is simulated, and the output
directory is created only once there is something to write.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import inspect
import json
import math
import numbers
import os
import re
import sys
import time
import warnings
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

from . import __version__
from . import _core
from . import thread as _thread
from .errors import StudyWarning

__all__ = ["main"]

DEFAULT_T_END = 1.0  # s
DEFAULT_POINTS = 2001


class UsageError(ValueError):
    """A command line mistake: exit code 2."""


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (and exit code 2, as argparse's own)."""

    def error(self, message: str):
        raise UsageError(f"{message} (see '{self.prog} --help')")


# --- scenes -------------------------------------------------------------------


def _load_scene(arg: str) -> Tuple[Any, str, str]:
    """A scene from a file path or a shipped scene's name, checked whole.

    Args:
        arg: the SCENE argument.

    Returns:
        ``(scene, name, source)``: the Scene, a short name for outputs (the
        file name without its last suffix, or the shipped name) and what
        messages call it (the path, or the shipped name).

    Raises:
        ValueError: no such file or shipped scene, or an invalid scene,
            including one whose model or thread cannot be built (e.g. zero
            load mass on a flexible nut); the message starts with the source.
        OSError: the file cannot be read.
    """
    from . import scenes
    from .scene import Scene

    path = Path(arg)
    shipped = scenes.available()
    stem = arg[:-5] if arg.endswith(".toml") else arg
    is_shipped = stem in shipped and os.sep not in arg and "/" not in arg
    # A directory is not a scene (Scene.from_toml says so), unless its name
    # is that of a shipped scene.
    if path.is_file() or (path.is_dir() and not is_shipped):
        scene, name, source = Scene.from_toml(path), path.stem, os.fspath(path)
    else:
        if not is_shipped:
            raise UsageError(f"scene {arg!r}: no such file, and not a shipped scene "
                             f"({', '.join(shipped)})")
        scene, name, source = scenes.load(stem), stem, stem
    # Scene validation covers each value; the derived ones (masses,
    # stiffnesses) and the thread are checked when the model is assembled.
    try:
        scene.model()
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None
    return scene, name, source


def _rigid_equivalent(scene) -> Tuple[float, float]:
    """Rotating inertia J and translating mass m of the scene's rigid model."""
    rigid = scene.replace(concept="rigid", backlash=None, initial={"play_position": 0.0})
    mass = rigid.model().mass
    return float(mass[0]), float(mass[1])


# --- check ----------------------------------------------------------------------


def _thread_verdicts(t, mu: float, flank_angle: float, hand: str = "right") -> List[str]:
    """The closed-form verdicts on a thread, as lines of text."""
    tan_a = math.tan(t.lead_angle)
    return [
        f"thread: lead {t.lead * 1e3:.4g} mm, mean diameter {t.mean_diameter * 1e3:.4g} mm, "
        f"lead angle {math.degrees(t.lead_angle):.4f} deg, flank angle "
        f"{math.degrees(flank_angle):g} deg, {hand}-hand",
        f"friction: mu = {mu:g}, mu' = {t.effective_mu(mu):.6g}; "
        f"bounds tan(alpha) = {tan_a:.6g} < mu' < cot(alpha) = {1.0 / tan_a:.6g}",
        "self-locking (holds under pure axial load): "
        f"{'yes' if _thread.is_self_locking(t, mu) else 'no'}",
        f"drivable by a pure torque:                 {'yes' if _thread.is_drivable(t, mu) else 'no'}",
        f"efficiency forward {_thread.efficiency(t, mu):.6g}, "
        f"back-driving {_thread.efficiency(t, mu, backdrive=True):.6g}",
    ]


def jamming_margins(t, mu: float, rotating_inertia: float, translating_mass: float) -> Dict[str, Any]:
    """The two dynamic jamming (Painleve) inequalities of the rigid drive.

    ``m r^2 tan a (mu' - tan a) >= J (1 + mu' tan a)`` (a self-locking drive jams
    when it is driven) and ``J cot a (mu' - cot a) >= m r^2 (1 + mu' cot a)`` (a
    drive that no torque can turn jams when back-driven); docs/physics/rigid_drive.md
    section 7.

    Args:
        t: the thread.
        mu: flank friction coefficient.
        rotating_inertia: J [kg*m^2].
        translating_mass: m [kg].

    Returns:
        dict with the four sides ``lhs1, rhs1, lhs2, rhs2`` [kg*m^2], the verdicts
        ``jams1, jams2``, and the critical ``mass1`` [kg] (translating mass at
        which the first holds; inf if mu' <= tan a) and ``inertia2`` [kg*m^2]
        (rotating inertia at which the second holds; inf if mu' <= cot a).
    """
    # The core's inequalities (model/drive_geometry.hpp), which its
    # JammingError reports as well, at the friction factor mu'.
    return _core.rigid_jamming_margins(t, t.effective_mu(mu), rotating_inertia,
                                       translating_mass)


_DERIVED_UNITS = {
    "screw_mass": "kg", "nut_mass": "kg", "screw_inertia": "kg*m^2", "nut_inertia": "kg*m^2",
    "screw_axial_rigidity": "N (E A)", "screw_torsional_rigidity": "N*m^2 (G I_p)",
    "nut_axial_stiffness": "N/m", "nut_torsional_stiffness": "N*m/rad",
    "screw_axial_stiffness": "N/m", "screw_torsional_stiffness": "N*m/rad",
    "contact_stiffness": "N/m^e", "contact_damping": "N*s/m", "contact_penetration": "m",
}


def _scene_report(name: str, scene) -> List[str]:
    """What ``check SCENE`` prints, computed whole before anything is printed."""
    d = scene.to_dict()
    lines = [f"scene {name}: valid, {scene!r}"]
    lines += _thread_verdicts(scene.thread, d["friction"]["mu"], d["thread"]["flank_angle"],
                              d["thread"]["hand"])
    J, m = _rigid_equivalent(scene)
    rotating, translating = (("rotor + screw", "nut + load") if d["drive"] == "screw"
                             else ("rotor + nut", "screw + load"))
    other = m - d["load"]["mass"]
    lines.append(f"rigid drive: J = {rotating} = {J:.6g} kg*m^2, m = {translating} = {m:.6g} kg"
                 + ("" if d["concept"] == "rigid"
                    else f" (rigid equivalent of the {d['concept']} model)"))
    jm = jamming_margins(scene.thread, d["friction"]["mu"], J, m)
    lines.append("dynamic jamming (Painleve paradox, rigid drive):")
    lines.append(f"  m r^2 tan a (mu' - tan a) = {jm['lhs1']:.6g} >= J (1 + mu' tan a) = "
                 f"{jm['rhs1']:.6g}: {'YES, jams' if jm['jams1'] else 'no'}"
                 + (f" (jams from m = {jm['mass1']:.6g} kg, load mass {jm['mass1'] - other:.6g} kg)"
                    if math.isfinite(jm["mass1"]) else " (mu' <= tan a: never)"))
    lines.append(f"  J cot a (mu' - cot a) = {jm['lhs2']:.6g} >= m r^2 (1 + mu' cot a) = "
                 f"{jm['rhs2']:.6g}: {'YES, jams' if jm['jams2'] else 'no'}"
                 + (f" (jams from J = {jm['inertia2']:.6g} kg*m^2)" if math.isfinite(jm["inertia2"])
                    else " (mu' <= cot a: never)"))
    lines.append("derived:")
    for key, value in scene.derived().items():
        note = (" (follows the nut position, eq. 4.24)" if value == 0.0
                and key in ("screw_axial_stiffness", "screw_torsional_stiffness") else "")
        lines.append(f"  {key} = {value:.6g} {_DERIVED_UNITS.get(key, '')}{note}")
    springs = scene.model().springs
    if springs:
        lines.append(f"springs of the {d['concept']} model (at the start):")
        for spring in springs:
            lines.append(f"  {spring['name']}: stiffness {spring['stiffness']:.6g}, "
                         f"damping {spring['damping']:.6g}")
    return lines


def _check_scene(arg: str) -> int:
    scene, name, source = _load_scene(arg)
    try:  # nothing is printed, "valid" least of all, before all of it is known
        lines = _scene_report(name, scene)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None
    print("\n".join(lines))
    return 0


def _check(args: argparse.Namespace) -> int:
    thread_options = ("pitch", "mean_diameter", "starts", "flank_angle_deg", "mu", "load")
    if args.scene is not None:
        given = [f"--{k.replace('_', '-')}" for k in thread_options if getattr(args, k) is not None]
        if given:
            raise UsageError(f"{', '.join(given)} apply without SCENE only (the scene file "
                             "holds the thread)")
        return _check_scene(args.scene)
    pitch = 1e-3 if args.pitch is None else args.pitch
    diameter = 20e-3 if args.mean_diameter is None else args.mean_diameter
    starts = 1 if args.starts is None else args.starts
    flank = 0.0 if args.flank_angle_deg is None else math.radians(args.flank_angle_deg)
    mu = 0.3 if args.mu is None else args.mu
    t = _thread.Thread(pitch, diameter, starts, flank)
    print("\n".join(_thread_verdicts(t, mu, flank)))
    if args.load is not None:
        print(f"torque to raise {args.load:g} N: {_thread.raise_torque(t, mu, args.load):.6g} N*m, "
              f"to lower: {_thread.lower_torque(t, mu, args.load):.6g} N*m")
    return 0


# --- run, demo ------------------------------------------------------------------


def _plot_time_series(result, title: str):
    """Load position, rotor speed, forces and drive torque over time (a Figure)."""
    from matplotlib.figure import Figure

    t = result.t
    figure = Figure(figsize=(8.0, 9.0), layout="constrained")
    axes = figure.subplots(4, 1, sharex=True)
    axes[0].plot(t, result["u_load"] * 1e3, color="C0")
    if "stick" in result and len(t) > 1:
        stick = result["stick"] > 0.5
        axes[0].fill_between(t, 0, 1, where=stick, transform=axes[0].get_xaxis_transform(),
                             color="0.85", step="mid", label="stick")
        if stick.any():
            axes[0].legend(loc="best")
    axes[0].set_ylabel("load position u [mm]")
    axes[1].plot(t, result["omega_drive"], color="C1")
    axes[1].set_ylabel("rotor speed [rad/s]")
    for name, label in (("axial_force", "axial load F"), ("normal_force", "flank normal N"),
                        ("friction_force", "flank friction T")):
        if name in result:
            axes[2].plot(t, result[name], label=label)
    axes[2].set_ylabel("force [N]")
    axes[2].legend(loc="best")
    axes[3].plot(t, result["drive_torque"] * 1e3, color="C3")
    axes[3].set_ylabel("drive torque [N*mm]")
    axes[3].set_xlabel("time t [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    figure.suptitle(title, fontsize="medium")
    return figure


def _plot_energy(result, title: str):
    """The energy account: work in, losses, stored energy, residual (a Figure)."""
    from matplotlib.figure import Figure

    t = result.t
    figure = Figure(figsize=(8.0, 6.0), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True)
    for name in ("work_drive", "work_axial", "friction_loss", "damping_loss", "contact_loss",
                 "impact_loss", "kinetic", "elastic"):
        if name in result and (result[name] != 0).any():
            top.plot(t, result[name], label=name)
    top.set_ylabel("energy [J]")
    top.legend(loc="best")
    bottom.plot(t, result["energy_residual"], color="k")
    bottom.set_ylabel("energy residual [J]")
    bottom.set_xlabel("time t [s]")
    for ax in (top, bottom):
        ax.grid(True, alpha=0.3)
    figure.suptitle(title, fontsize="medium")
    return figure


def _check_output_dir(path: str) -> None:
    """Refuse an output directory that cannot be created, without creating it.

    Commands check this before they simulate and create the directory only
    once there is something to write, so that a failed command leaves nothing.

    Raises:
        UsageError: ``path`` or its first existing ancestor is not a writable
            directory.
    """
    out = Path(path)
    # The first existing ancestor (bounded by the path's depth).
    existing = next((p for p in (out, *out.absolute().parents) if p.exists()), None)
    if existing is None or not existing.is_dir():
        raise UsageError(f"-o {path}: cannot create the output directory "
                         f"({existing} is not a directory)")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise UsageError(f"-o {path}: cannot create the output directory "
                         f"({existing} is not writable)")


def _output_dir(path: str) -> Path:
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise UsageError(f"-o {path}: cannot create the output directory ({error.strerror})") from None
    return out


def _output_file(out: Path, name: str, suffix: str) -> Path:
    """``out/name.suffix``: the suffix appended, never replacing a dotted
    part of the name (``drive_v1.2`` gives ``drive_v1.2.csv``)."""
    return out / f"{name}.{suffix}"


def _check_sampling(t_end: float, points: int) -> None:
    if not (math.isfinite(t_end) and t_end > 0):
        raise UsageError(f"--t-end {t_end:g} is invalid: must be a time > 0 [s]")
    if points < 0 or points == 1:
        raise UsageError(f"--points {points} is invalid: must be 0 (every step) or >= 2")


def _check_integrator_options(scene, args: argparse.Namespace) -> None:
    """Refuse options the integrator that runs would ignore.

    ``--dt`` and ``--theta`` are parameters of the fixed-step ``moreau``
    scheme only; ``--rtol`` and ``--atol`` of the others only.

    Raises:
        UsageError: naming the option, its value and the integrator.
    """
    from . import _core
    from .simulation import unused_option

    if args.integrator is not None:
        integrator, which = args.integrator, f"--integrator {args.integrator}"
    else:  # the scene's default: the first of the integrators that fit it
        integrator = _core.drive_integrators(scene.model().parameters)[0]
        which = f"the scene's default integrator {integrator}"
    given = {"rtol": args.rtol, "atol": args.atol, "dt": args.dt, "theta": args.theta}
    # The rules of leadscrew.simulate, in the command line's spelling.
    unused = unused_option(integrator, given, scene, spell=lambda name: f"--{name}")
    if unused is not None:
        name, _, why = unused
        raise UsageError(f"--{name} {given[name]:g} is invalid with {which}: {why}")


def _simulate(scene, t_end: float = DEFAULT_T_END, points: int = DEFAULT_POINTS, **options):
    """Simulate (the caller checked t_end and points); options with value None
    are left out."""
    import numpy as np

    from .simulation import simulate

    t_eval = np.linspace(0.0, t_end, points) if points else None
    options = {k: v for k, v in options.items() if v is not None}
    # A progress bar where someone watches (a terminal); Ctrl-C stops the
    # run either way.
    return simulate(scene, t_end, t_eval=t_eval, progress=sys.stderr.isatty(), **options)


def _summary(name: str, scene, result, t_end: float) -> str:
    stats = result.stats
    return (f"{name}: {scene!r}, t_end = {t_end:g} s, {result.friction}/{result.integrator}: "
            f"{len(result.events)} events, {stats['steps']} steps, "
            f"{stats['wall_time'] * 1e3:.3g} ms; u_load(t_end) = {result['u_load'][-1] * 1e3:.6g} mm")


def _write_series(result, out: Path, name: str, fmt: str) -> Path:
    """Write the time series with the unit of every column.

    CSV: the row of names, then a row of units (SI, ``""`` for the flag
    ``stick``), then the data (pandas reads the data with
    ``read_csv(path, skiprows=[1])``, names and units with ``header=[0, 1]``).
    Parquet: each field's metadata ``unit``, and the frame's
    ``attrs["units"]`` (which ``pandas.read_parquet`` restores).
    """
    frame = result.to_frame()
    units = frame.attrs["units"]
    path = _output_file(out, name, fmt)
    if fmt == "parquet":
        import pyarrow as pa

        schema = pa.Schema.from_pandas(frame, preserve_index=False)
        schema = pa.schema([field.with_metadata({"unit": units[field.name]})
                            for field in schema], metadata=schema.metadata)
        frame.to_parquet(path, index=False, schema=schema)
    else:
        _write_csv(frame, path, units)
    return path


def _write_csv(frame, path: Path, units: Dict[str, str], index: bool = False) -> None:
    """Write a frame as CSV: the row of names, a row of units (``units`` by
    column, ``""`` where it has none: a label, a flag, the index), then the
    data (``pandas.read_csv(path, skiprows=[1])`` reads the data, with
    ``header=[0, 1]`` names and units)."""
    import csv

    names = [str(column) for column in frame.columns]
    unit_row = [str(units.get(column, "")) for column in frame.columns]
    if index:
        names.insert(0, "" if frame.index.name is None else str(frame.index.name))
        unit_row.insert(0, "")
    with open(path, "w", encoding="utf-8", newline="") as stream:
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow(names)
        writer.writerow(unit_row)
        frame.to_csv(stream, index=index, header=False, lineterminator="\n")


def _require_parquet(fmt: str) -> None:
    if fmt == "parquet" and importlib.util.find_spec("pyarrow") is None:
        raise UsageError("--format parquet needs pyarrow, which is not installed "
                         "(pip install pyarrow), or use --format csv")


def _run(args: argparse.Namespace) -> int:
    # Every argument is checked before anything runs or is created.
    _require_parquet(args.format)
    _check_sampling(args.t_end, args.points)
    _check_output_dir(args.output)
    scene, name, _ = _load_scene(args.scene)
    _check_integrator_options(scene, args)
    result = _simulate(scene, args.t_end, args.points, integrator=args.integrator,
                       rtol=args.rtol, atol=args.atol, dt=args.dt, theta=args.theta,
                       max_steps=args.max_steps)
    out = _output_dir(args.output)
    print(_summary(name, scene, result, args.t_end))
    series = _write_series(result, out, name, args.format)
    figure = _output_file(out, name, "png")
    _plot_time_series(result, f"{name}: {scene!r}").savefig(figure, dpi=110)
    print(f"wrote {series}")
    print(f"wrote {figure}")
    return 0


def _scene_command(args: argparse.Namespace) -> int:
    """``leadscrew scene resolve SCENE [-o FILE]``: the scene's core spec
    (:meth:`leadscrew.Scene.to_core_toml`), the input of the C API, to FILE
    or standard output."""
    scene, _, source = _load_scene(args.scene)
    try:
        text = scene.to_core_toml()
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None
    if args.output in (None, "-"):
        sys.stdout.write(text)
    else:
        Path(args.output).write_text(text, encoding="utf-8")
        print(f"wrote {args.output}")
    return 0


def _export_fmu(args: argparse.Namespace) -> int:
    """``leadscrew export-fmu SCENE -o drive.fmu``: the scene as an FMI 2.0
    co-simulation FMU (:func:`leadscrew.fmi.export_fmu`)."""
    from . import fmi

    scene, name, source = _load_scene(args.scene)
    output = args.output or f"{name}.fmu"
    try:
        fmi.export_fmu(scene, output, name=name)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None
    print(f"wrote {output}")
    return 0


def _demo(args: argparse.Namespace) -> int:
    from . import scenes

    name = "default"
    scene = scenes.load(name)
    out = _output_dir(args.output)
    print(f"leadscrew demo: the shipped scene {name!r} ({scenes.path(name)})")
    _check_scene(name)
    result = _simulate(scene)
    print(_summary(name, scene, result, DEFAULT_T_END))
    written = [_write_series(result, out, name, "csv")]
    figures = ((name, _plot_time_series), (f"{name}_energy", _plot_energy))
    for filename, plot in figures:
        written.append(_output_file(out, filename, "png"))
        plot(result, f"{name}: {scene!r}").savefig(written[-1], dpi=110)
    for path in written:
        print(f"wrote {path}")
    return 0


# --- study ----------------------------------------------------------------------


class StudyFailed(Exception):
    """A study cannot run (exit code 1)."""


def _option_value(text: str) -> Any:
    """A study option's value: TOML syntax (numbers, true/false, lists, quoted
    strings); otherwise a comma-separated list of such values, or a bare string."""
    from .scene import _toml_parser

    tomllib = _toml_parser()

    def parse(item: str) -> Any:
        try:
            return tomllib.loads(f"v = {item}")["v"]
        except tomllib.TOMLDecodeError:
            return item.strip()

    value = parse(text)
    if isinstance(value, str) and value == text.strip() and "," in text:
        return [parse(item) for item in text.split(",")]
    return value


def _study_options(items: Sequence[str]) -> Dict[str, Any]:
    options: Dict[str, Any] = {}
    for item in items:
        key, sep, value = item.partition("=")
        key = key.strip().replace("-", "_")
        if not sep or not key.isidentifier():
            raise UsageError(f"study option {item!r} is invalid: write KEY=VALUE, e.g. "
                             "frequencies=5,10,20 or progress=false")
        options[key] = _option_value(value)
    return options


#: What a study's StudyWarning about its rows that raised says (studies/_common.py).
_RAISED_ROWS = r"\w+: \d+ of \d+ rows raised and decide nothing"


def _import_studies():
    try:
        return importlib.import_module(".studies", __package__)
    except ImportError as error:
        raise StudyFailed(f"the studies module leadscrew.studies cannot be imported: {error}") from None


#: Study parameters that take Python objects (an executor, matplotlib Axes, a
#: reference callable or Result): never from the command line.
_OBJECT_OPTIONS = frozenset({"executor", "ax", "reference"})

#: Type names an option's annotation may use for its value to come from text
#: (TOML numbers, booleans, strings, arrays, inline tables).
_TEXT_TYPES = frozenset({"Optional", "Union", "None", "NoneType", "float", "int", "str", "bool",
                         "Sequence", "List", "list", "Tuple", "tuple", "Dict", "dict",
                         "Mapping", "Any", "object"})


def _from_text(parameter: inspect.Parameter) -> bool:
    """Whether a study parameter's value can be written on the command line.

    Annotated: every type name in the annotation is a plain data type
    (numbers, strings, booleans, sequences, dicts). Not annotated: the
    default is such a value, or there is none (a required value).
    """
    if parameter.name in _OBJECT_OPTIONS:
        return False
    annotation = parameter.annotation
    if annotation is inspect.Parameter.empty:
        default = parameter.default
        return default is inspect.Parameter.empty or isinstance(
            default, (bool, int, float, str, list, tuple, dict))
    text = annotation if isinstance(annotation, str) else inspect.formatannotation(annotation)
    names = re.findall(r"[A-Za-z_][A-Za-z_0-9.]*", text)
    return all(name.rsplit(".", 1)[-1] in _TEXT_TYPES for name in names)


def _check_study_options(name: str, function, options: Dict[str, Any]) -> None:
    """Check the KEY=VALUE options against what the study takes.

    A study takes its own parameters (all but the first, the scene) and, if
    it passes ``**simulate_options`` on, :func:`leadscrew.simulate`'s
    keywords but ``model``, ``t_end`` and ``t_eval``.

    Raises:
        UsageError: an option the study does not take (listing those it
            does), one that takes a Python object (executor, ax, reference),
            or a required one not given (listing them).
    """
    from .simulation import _OPTIONS as simulate_options

    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):  # builtins without a signature: let the call decide
        return
    parameters = list(signature.parameters.values())[1:]
    own = {p.name: p for p in parameters if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}
    forwards = any(p.kind is p.VAR_KEYWORD for p in parameters)
    extra = ({k: v for k, v in simulate_options.items() if k not in own} if forwards else {})
    accepted = {**own, **extra}
    texts = [k for k, p in own.items() if _from_text(p)]
    takes = ", ".join(texts) or "no options"
    if extra:
        takes += " and leadscrew.simulate's " + ", ".join(k for k, p in extra.items()
                                                            if _from_text(p))
    for key in options:
        if key not in accepted:
            raise UsageError(f"study {name!r} has no option {key!r}; it takes {takes}")
        if not _from_text(accepted[key]):
            raise UsageError(f"study option {key} = {options[key]!r} is invalid: {key} takes a "
                             "Python object, which the command line cannot give (leave it out "
                             "for the default)")
    missing = [k for k, p in own.items() if p.default is p.empty and k not in options]
    objects = [k for k in missing if not _from_text(own[k])]
    if objects:
        raise UsageError(f"study {name!r} cannot run from the command line: it needs "
                         f"{', '.join(objects)}, a Python object")
    if missing:
        raise UsageError(f"study {name!r} needs {' '.join(k + '=...' for k in missing)} "
                         f"(KEY=VALUE after SCENE); it takes {takes}")


#: Columns in which a study reports the failure of a case (None: it ran).
_FAILURE_COLUMNS = ("error", "failure")


def _failure_message(value: Any) -> str:
    """A failure cell as one line ("" where the case ran: None, NaN, "")."""
    import pandas as pd

    if value is None or (pd.api.types.is_scalar(value) and pd.isna(value)):
        return ""
    return " ".join(str(value).split())


def _failures(frame) -> Tuple[int, str]:
    """How many rows of a study's frame failed, and the first message.

    A row failed if one of its columns ``error`` or ``failure`` (work_precision)
    holds a message.
    """
    columns = [c for c in _FAILURE_COLUMNS if c in frame.columns]
    count, first = 0, ""
    for values in zip(*(frame[c].tolist() for c in columns)):
        messages = [m for m in map(_failure_message, values) if m]
        if messages:
            count += 1
            first = first or messages[0]
    return count, first


def _json_value(value: Any) -> Any:
    """A summary value as JSON data: NaN and infinities become null."""
    import numpy as np

    if isinstance(value, np.generic):
        value = value.item()
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        number = float(value)
        return number if math.isfinite(number) else None
    if isinstance(value, dict):
        return {str(k): _json_value(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)) or hasattr(value, "tolist"):
        return [_json_value(v) for v in (value.tolist() if hasattr(value, "tolist") else value)]
    return str(value)


def _summary_json(summary: Dict[str, Any], frame) -> Dict[str, Any]:
    """A study's summary as JSON data (:func:`_json_value`), with ``"units"``:
    the SI unit of every entry the study gives one (its frame's
    ``attrs["summary_units"]``; ``"1"`` a ratio or count; labels and flags
    have none).

    Raises:
        StudyFailed: the summary has a key ``"units"`` of its own (it would
            be overwritten).
    """
    if "units" in summary:
        raise StudyFailed("the study's summary has a key 'units', which the summary file "
                          "keeps for the units of its entries")
    units = frame.attrs.get("summary_units") or {}
    data = _json_value(dict(summary))
    data["units"] = {str(key): str(units[key]) for key in summary if key in units}
    return data


def _summary_unit(key: str, frame) -> str:
    """The unit of a summary entry: the frame's ``attrs["summary_units"]``,
    which every study sets for its numbers; "" for ratios ("1") and for keys
    it leaves out (labels: booleans, strings)."""
    unit = (frame.attrs.get("summary_units") or {}).get(key)
    return "" if unit in (None, "", "1") else str(unit)


def _summary_text(value: Any, unit: str = "") -> str:
    """A summary value for the terminal (NaN stays visible), with its unit."""
    import numpy as np

    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        text = str(int(value))
    elif isinstance(value, numbers.Real):
        text = f"{float(value):.6g}"
    elif isinstance(value, (list, tuple)) or hasattr(value, "tolist"):
        text = ", ".join(_summary_text(v) for v in (value.tolist() if hasattr(value, "tolist")
                                                     else value))
    else:
        return str(value)
    return f"{text} {unit}" if unit else text


def _study(args: argparse.Namespace) -> int:
    studies = _import_studies()
    registry = getattr(studies, "STUDIES", None)
    if not hasattr(registry, "keys"):
        raise StudyFailed("leadscrew.studies has no STUDIES registry")
    if args.name not in registry:
        raise UsageError(f"study {args.name!r} is unknown; the studies are "
                         f"{', '.join(sorted(registry))}")
    function = registry[args.name]
    options = _study_options(args.options)
    _check_study_options(args.name, function, options)
    _check_output_dir(args.output)
    scene, scene_name, _ = _load_scene(args.scene)
    start = time.perf_counter()
    with warnings.catch_warnings():
        # The study's warning about its rows that raised: this command's own
        # (below, once the files are written) says the same.
        warnings.filterwarnings("ignore", message=_RAISED_ROWS, category=StudyWarning)
        frame = function(scene, **options)
    elapsed = time.perf_counter() - start
    if not hasattr(frame, "to_csv"):
        raise StudyFailed(f"study {args.name!r} returned {type(frame).__name__}, not a DataFrame")
    failed, first = _failures(frame)
    if failed and failed == len(frame):
        raise StudyFailed(f"study {args.name!r} on {scene_name}: all {failed} cases failed; "
                          f"the first: {first}")
    out = _output_dir(args.output)
    stem = f"{args.name}_{scene_name}"
    path = _output_file(out, stem, "csv")
    default_index = type(frame.index).__name__ == "RangeIndex" and frame.index.name is None
    # Columns holding arrays (time series per row) do not fit a CSV cell.
    arrays = [c for c in frame.columns
              if frame[c].map(lambda v: hasattr(v, "__len__") and not isinstance(v, str)).any()]
    _write_csv(frame.drop(columns=arrays), path, frame.attrs.get("units") or {},
               index=not default_index)
    written = [path]
    summary = frame.attrs.get("summary") or {}
    print(f"{args.name} on {scene_name}: {len(frame)} rows in {elapsed:.3g} s")
    if summary:
        print("summary:")
        for key, value in summary.items():
            print(f"  {key}: {_summary_text(value, _summary_unit(str(key), frame))}")
        written.append(_output_file(out, stem, "summary.json"))
        with open(written[-1], "w", encoding="utf-8") as stream:
            json.dump(_summary_json(summary, frame), stream, indent=2, allow_nan=False)
            stream.write("\n")
    # The study's figure (leadscrew.studies.PLOTS) beside its CSV, if it has one.
    save_figure = getattr(studies, "save_figure", None)
    figure = save_figure and save_figure(args.name, frame, _output_file(out, stem, "png"),
                                         f"{args.name} on {scene_name}")
    if figure:
        written.append(figure)
    if arrays:
        print(f"left out of the CSV (a time series per row): {', '.join(map(str, arrays))}")
    for path in written:
        print(f"wrote {path}")
    if failed:
        print(f"leadscrew: warning: {failed} of {len(frame)} cases failed: {first}",
              file=sys.stderr)
    return 0


# --- parser -----------------------------------------------------------------------


def _add_simulation_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--t-end", type=float, default=DEFAULT_T_END,
                        help=f"simulated time [s] (default {DEFAULT_T_END:g})")
    parser.add_argument("--integrator", default=None,
                        help="integrator (default: the scene's; event_driven, moreau, "
                             "cvode_bdf, cvode_adams, dopri5, ...)")
    parser.add_argument("--rtol", type=float, default=None,
                        help="relative tolerance (not with --integrator moreau)")
    parser.add_argument("--atol", type=float, default=None,
                        help="absolute tolerance [SI] (not with --integrator moreau)")
    parser.add_argument("--dt", type=float, default=None,
                        help="fixed step of --integrator moreau [s] (refused with the others)")
    parser.add_argument("--theta", type=float, default=None,
                        help="theta of --integrator moreau, in [0, 1] (default 0.5; refused "
                             "with the others)")
    parser.add_argument("--max-steps", type=int, default=None,
                        help="bound on integrator steps, Moreau's fixed steps t_end / dt too "
                             "(default 1000000; a lightly damped drive rattling in its play "
                             "may need more)")
    parser.add_argument("--points", type=int, default=DEFAULT_POINTS,
                        help=f"output points, evenly spaced over [0, t_end] (default "
                             f"{DEFAULT_POINTS}); 0 writes every integrator step and event")


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="leadscrew", description="Lead-screw drive simulator. SCENE is a TOML "
                     "scene file or the name of a shipped scene (default, thesis_table_5_1, "
                     "position_holding).")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    parser.add_argument("--version", action="version", version=f"leadscrew {__version__}",
                        help="print the version and exit")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def command(name: str, **kwargs) -> argparse.ArgumentParser:
        p = sub.add_parser(name, **kwargs)
        p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                       help="show tracebacks")
        return p

    run = command("run", help="simulate a scene, write its time series and a figure")
    run.add_argument("scene", metavar="SCENE")
    run.add_argument("-o", "--output", default=".", help="output directory (default .)")
    run.add_argument("--format", choices=("csv", "parquet"), default="csv",
                     help="time series format (parquet needs pyarrow)")
    _add_simulation_options(run)
    run.set_defaults(func=_run)

    check = command("check", help="validate a scene and print the closed-form verdicts "
                    "(without SCENE: a thread, default the thesis's Table 5.1 drive)")
    check.add_argument("scene", metavar="SCENE", nargs="?", default=None)
    check.add_argument("--pitch", type=float, default=None, help="pitch [m] (default 1e-3)")
    check.add_argument("--mean-diameter", type=float, default=None,
                       help="mean diameter [m] (default 20e-3)")
    check.add_argument("--starts", type=int, default=None, help="thread starts (default 1)")
    check.add_argument("--flank-angle-deg", type=float, default=None,
                       help="included flank angle [deg] (default 0)")
    check.add_argument("--mu", type=float, default=None,
                       help="flank friction coefficient (default 0.3)")
    check.add_argument("--load", type=float, default=None, help="axial load [N] for the torques")
    check.set_defaults(func=_check)

    study = command(
        "study", help="run a design study of leadscrew.studies, write its table",
        description="Run a study of leadscrew.studies on SCENE and write its table to "
        "DIR/NAME_SCENE.csv (a row of units under the column names). A study's scalar "
        "verdicts (its summary: position_holding, stick_slip, min_holding_preload, ...) are "
        "printed, one 'key: value unit' line each, and written to DIR/NAME_SCENE.summary.json "
        "(NaN and infinities as null; 'units' maps each number to its SI unit). Options are "
        "the study's parameters (values with a unit as strings: amplitude='20 N', "
        "frequencies='5 Hz,10 Hz') and, for studies that pass them on, leadscrew.simulate's "
        "keywords (integrator, max_steps, ...; not t_eval); executor, ax and reference take "
        "Python objects and cannot be given here. Exit codes: 0 success (also when some cases "
        "failed: a warning 'k of N cases failed: <first message>' goes to stderr and each "
        "row's error column says why), 1 when every case failed or the study failed while "
        "running, 2 for usage errors (unknown or missing options, an invalid scene or "
        "option value).",
        epilog="example: leadscrew study efficiency_vs_mu thesis_table_5_1 mu=0.1,0.2,0.3 "
        "loads=10,50 progress=false -o out")
    study.add_argument("name", metavar="NAME", help="the study (leadscrew.studies.STUDIES)")
    study.add_argument("scene", metavar="SCENE")
    study.add_argument("options", metavar="KEY=VALUE", nargs="*",
                       help="options of the study, values in TOML syntax or comma-separated "
                            "lists, e.g. frequencies=5,10,20 progress=false (before or after "
                            "-o DIR)")
    study.add_argument("-o", "--output", default=".", help="output directory (default .)")
    study.set_defaults(func=_study)

    scene = command("scene", help="scene tools: 'resolve' writes the core spec (every value "
                    "SI and explicit) that the C API reads",
                    epilog="example: leadscrew scene resolve default -o core.toml")
    scene.add_argument("action", choices=("resolve",), metavar="resolve",
                       help="write SCENE's core spec (Scene.to_core_toml)")
    scene.add_argument("scene", metavar="SCENE")
    scene.add_argument("-o", "--output", default=None,
                       help="the file to write (default: standard output)")
    scene.set_defaults(func=_scene_command)

    export = command("export-fmu", help="write SCENE as an FMI 2.0 co-simulation FMU",
                     epilog="example: leadscrew export-fmu default -o drive.fmu")
    export.add_argument("scene", metavar="SCENE")
    export.add_argument("-o", "--output", default=None,
                        help="the .fmu file to write (default: SCENE's name + .fmu)")
    export.set_defaults(func=_export_fmu)

    demo = command("demo", help="simulate the default scene and write its figures")
    demo.add_argument("-o", "--output", default="leadscrew-demo",
                      help="output directory (default leadscrew-demo)")
    demo.set_defaults(func=_demo)
    return parser


def _parse(argv: List[str]) -> argparse.Namespace:
    """The parsed command line. ``study``'s KEY=VALUE options may stand
    anywhere after SCENE, also after ``-o DIR`` (argparse alone takes a
    positional list in one piece and would refuse the rest).

    Raises:
        UsageError: an argument no command takes.
    """
    args, extra = _parser().parse_known_args(argv)
    if args.command == "study":
        options = [item for item in extra if not item.startswith("-")]
        args.options += options
        extra = [item for item in extra if item.startswith("-")]
    if extra:
        raise UsageError(f"unrecognized arguments: {' '.join(extra)} (see 'leadscrew "
                         f"{args.command} --help')")
    return args


def _is_input_error(error: BaseException) -> bool:
    """Bad arguments or an invalid or unreadable scene (exit code 2)."""
    from .errors import SimulationError

    return isinstance(error, (ValueError, OSError)) and not isinstance(error, SimulationError)


def main(argv: Optional[List[str]] = None) -> int:
    """Run the command line.

    Args:
        argv: the arguments (default ``sys.argv[1:]``).

    Returns:
        The exit code: 0 success, 2 usage or validation error, 1 failure while
        running.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    debug = "--debug" in argv
    try:
        args = _parse(argv)
        return args.func(args)
    except SystemExit as stop:  # --help
        return stop.code if isinstance(stop.code, int) else 0
    except KeyboardInterrupt:
        print("leadscrew: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader stopped early (leadscrew check | head)
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except Exception as error:  # one clear line unless --debug
        if debug:
            raise
        message = " ".join(str(error).split())
        if not _is_input_error(error):  # name what failed: JammingError at t = ...
            message = f"{type(error).__name__}{'' if message.startswith('at ') else ':'} {message}"
        print(f"leadscrew: error: {message}", file=sys.stderr)
        return 2 if _is_input_error(error) else 1


if __name__ == "__main__":
    sys.exit(main())
