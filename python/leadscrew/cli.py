"""Command line interface: ``leadscrew run | check | study | demo``.

::

    leadscrew run SCENE [-o DIR] [--t-end T] [--integrator NAME] [--format csv|parquet]
    leadscrew check [SCENE]
    leadscrew study NAME SCENE [-o DIR] [KEY=VALUE ...]
    leadscrew demo [-o DIR]

SCENE is a TOML scene file (see :meth:`leadscrew.Scene.from_toml`) or the name
of a shipped scene (:func:`leadscrew.scenes.available`). Errors print one line
to stderr and exit with 2 for usage and validation errors (bad arguments, an
invalid or unreadable scene file, an integrator that does not fit) and 1 for
failures while running (simulation errors, a study that fails);
``--debug`` shows the traceback instead.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import inspect
import math
import os
import sys
import time
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

from . import thread as _thread

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


def _load_scene(arg: str):
    """A Scene from a file path or a shipped scene's name, and a short name for outputs."""
    from . import scenes
    from .scene import Scene

    path = Path(arg)
    if path.is_file():
        return Scene.from_toml(path), path.stem
    shipped = scenes.available()
    stem = arg[:-5] if arg.endswith(".toml") else arg
    if stem in shipped and os.sep not in arg and "/" not in arg:
        return scenes.load(stem), stem
    raise UsageError(f"scene {arg!r}: no such file, and not a shipped scene "
                     f"({', '.join(shipped)})")


def _rigid_equivalent(scene) -> Tuple[float, float]:
    """Rotating inertia J and translating mass m of the scene's rigid model."""
    rigid = scene.replace(concept="rigid", backlash=None, initial={"play_position": 0.0})
    mass = rigid.model().mass
    return float(mass[0]), float(mass[1])


# --- check ----------------------------------------------------------------------


def _print_thread_verdicts(t, mu: float, flank_angle: float, hand: str = "right") -> None:
    tan_a = math.tan(t.lead_angle)
    print(f"thread: lead {t.lead * 1e3:.4g} mm, mean diameter {t.mean_diameter * 1e3:.4g} mm, "
          f"lead angle {math.degrees(t.lead_angle):.4f} deg, flank angle "
          f"{math.degrees(flank_angle):g} deg, {hand}-hand")
    print(f"friction: mu = {mu:g}, mu' = {t.effective_mu(mu):.6g}; "
          f"bounds tan(alpha) = {tan_a:.6g} < mu' < cot(alpha) = {1.0 / tan_a:.6g}")
    print(f"self-locking (holds under pure axial load): {'yes' if _thread.is_self_locking(t, mu) else 'no'}")
    print(f"drivable by a pure torque:                 {'yes' if _thread.is_drivable(t, mu) else 'no'}")
    print(f"efficiency forward {_thread.efficiency(t, mu):.6g}, "
          f"back-driving {_thread.efficiency(t, mu, backdrive=True):.6g}")


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
    tan_a = math.tan(t.lead_angle)
    cot_a = 1.0 / tan_a
    r = 0.5 * t.mean_diameter
    mu_e = t.effective_mu(mu)
    J, m = rotating_inertia, translating_mass
    lhs1, rhs1 = m * r * r * tan_a * (mu_e - tan_a), J * (1.0 + mu_e * tan_a)
    lhs2, rhs2 = J * cot_a * (mu_e - cot_a), m * r * r * (1.0 + mu_e * cot_a)
    mass1 = J * (1.0 + mu_e * tan_a) / (r * r * tan_a * (mu_e - tan_a)) if mu_e > tan_a else math.inf
    inertia2 = (m * r * r * (1.0 + mu_e * cot_a) / (cot_a * (mu_e - cot_a)) if mu_e > cot_a
                else math.inf)
    return dict(lhs1=lhs1, rhs1=rhs1, jams1=lhs1 >= rhs1, lhs2=lhs2, rhs2=rhs2,
                jams2=lhs2 >= rhs2, mass1=mass1, inertia2=inertia2)


_DERIVED_UNITS = {
    "screw_mass": "kg", "nut_mass": "kg", "screw_inertia": "kg*m^2", "nut_inertia": "kg*m^2",
    "screw_axial_rigidity": "N (E A)", "screw_torsional_rigidity": "N*m^2 (G I_p)",
    "nut_axial_stiffness": "N/m", "nut_torsional_stiffness": "N*m/rad",
    "screw_axial_stiffness": "N/m", "screw_torsional_stiffness": "N*m/rad",
    "contact_stiffness": "N/m^e", "contact_damping": "N*s/m", "contact_penetration": "m",
}


def _check_scene(arg: str) -> int:
    scene, name = _load_scene(arg)
    d = scene.to_dict()
    print(f"scene {name}: valid, {scene!r}")
    _print_thread_verdicts(scene.thread, d["friction"]["mu"], d["thread"]["flank_angle"],
                           d["thread"]["hand"])
    J, m = _rigid_equivalent(scene)
    rotating, translating = (("rotor + screw", "nut + load") if d["drive"] == "screw"
                             else ("rotor + nut", "screw + load"))
    other = m - d["load"]["mass"]
    print(f"rigid drive: J = {rotating} = {J:.6g} kg*m^2, m = {translating} = {m:.6g} kg"
          + ("" if d["concept"] == "rigid" else f" (rigid equivalent of the {d['concept']} model)"))
    jm = jamming_margins(scene.thread, d["friction"]["mu"], J, m)
    print("dynamic jamming (Painleve paradox, rigid drive):")
    print(f"  m r^2 tan a (mu' - tan a) = {jm['lhs1']:.6g} >= J (1 + mu' tan a) = {jm['rhs1']:.6g}: "
          f"{'YES, jams' if jm['jams1'] else 'no'}"
          + (f" (jams from m = {jm['mass1']:.6g} kg, load mass {jm['mass1'] - other:.6g} kg)"
             if math.isfinite(jm["mass1"]) else " (mu' <= tan a: never)"))
    print(f"  J cot a (mu' - cot a) = {jm['lhs2']:.6g} >= m r^2 (1 + mu' cot a) = {jm['rhs2']:.6g}: "
          f"{'YES, jams' if jm['jams2'] else 'no'}"
          + (f" (jams from J = {jm['inertia2']:.6g} kg*m^2)" if math.isfinite(jm["inertia2"])
             else " (mu' <= cot a: never)"))
    print("derived:")
    for key, value in scene.derived().items():
        note = (" (follows the nut position, eq. 4.24)" if value == 0.0
                and key in ("screw_axial_stiffness", "screw_torsional_stiffness") else "")
        print(f"  {key} = {value:.6g} {_DERIVED_UNITS.get(key, '')}{note}")
    springs = scene.model().springs
    if springs:
        print(f"springs of the {d['concept']} model (at the start):")
        for spring in springs:
            print(f"  {spring['name']}: stiffness {spring['stiffness']:.6g}, "
                  f"damping {spring['damping']:.6g}")
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
    _print_thread_verdicts(t, mu, flank)
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


def _output_dir(path: str) -> Path:
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise UsageError(f"-o {path}: cannot create the output directory ({error.strerror})") from None
    return out


def _simulate(scene, t_end: float = DEFAULT_T_END, points: int = DEFAULT_POINTS, **options):
    """Simulate with the command line's checks; options with value None are left out."""
    import numpy as np

    from .simulation import simulate

    if not (math.isfinite(t_end) and t_end > 0):
        raise UsageError(f"--t-end {t_end:g} is invalid: must be a time > 0 [s]")
    if points < 0 or points == 1:
        raise UsageError(f"--points {points} is invalid: must be 0 (every step) or >= 2")
    t_eval = np.linspace(0.0, t_end, points) if points else None
    options = {k: v for k, v in options.items() if v is not None}
    return simulate(scene, t_end, t_eval=t_eval, **options)


def _summary(name: str, scene, result, t_end: float) -> str:
    stats = result.stats
    return (f"{name}: {scene!r}, t_end = {t_end:g} s, {result.friction}/{result.integrator}: "
            f"{len(result.events)} events, {stats['steps']} steps, "
            f"{stats['wall_time'] * 1e3:.3g} ms; u_load(t_end) = {result['u_load'][-1] * 1e3:.6g} mm")


def _write_series(result, path_stem: Path, fmt: str) -> Path:
    frame = result.to_frame()
    if fmt == "parquet":
        path = path_stem.with_suffix(".parquet")
        frame.to_parquet(path, index=False)
    else:
        path = path_stem.with_suffix(".csv")
        frame.to_csv(path, index=False)
    return path


def _require_parquet(fmt: str) -> None:
    if fmt == "parquet" and importlib.util.find_spec("pyarrow") is None:
        raise UsageError("--format parquet needs pyarrow, which is not installed "
                         "(pip install pyarrow), or use --format csv")


def _run(args: argparse.Namespace) -> int:
    _require_parquet(args.format)
    scene, name = _load_scene(args.scene)
    out = _output_dir(args.output)
    result = _simulate(scene, args.t_end, args.points, integrator=args.integrator,
                       rtol=args.rtol, atol=args.atol, dt=args.dt)
    print(_summary(name, scene, result, args.t_end))
    series = _write_series(result, out / name, args.format)
    figure = out / f"{name}.png"
    _plot_time_series(result, f"{name}: {scene!r}").savefig(figure, dpi=110)
    print(f"wrote {series}")
    print(f"wrote {figure}")
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
    written = [_write_series(result, out / name, "csv")]
    figures = ((f"{name}.png", _plot_time_series), (f"{name}_energy.png", _plot_energy))
    for filename, plot in figures:
        plot(result, f"{name}: {scene!r}").savefig(out / filename, dpi=110)
        written.append(out / filename)
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


def _import_studies():
    try:
        return importlib.import_module(".studies", __package__)
    except ImportError as error:
        raise StudyFailed(f"the studies module leadscrew.studies cannot be imported: {error}") from None


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
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):  # builtins without a signature: let the call decide
        signature = None
    if signature is not None:
        parameters = list(signature.parameters.values())
        takes_any = any(p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters)
        names = [p.name for p in parameters[1:]
                 if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
        unknown = [k for k in options if k not in names]
        if unknown and not takes_any:
            raise UsageError(f"study {args.name!r} has no option {unknown[0]!r}; it takes "
                             f"{', '.join(names) or 'no options'}")
    scene, scene_name = _load_scene(args.scene)
    out = _output_dir(args.output)
    start = time.perf_counter()
    frame = function(scene, **options)
    elapsed = time.perf_counter() - start
    if not hasattr(frame, "to_csv"):
        raise StudyFailed(f"study {args.name!r} returned {type(frame).__name__}, not a DataFrame")
    path = out / f"{args.name}_{scene_name}.csv"
    default_index = type(frame.index).__name__ == "RangeIndex" and frame.index.name is None
    # Columns holding arrays (time series per row) do not fit a CSV cell.
    arrays = [c for c in frame.columns
              if frame[c].map(lambda v: hasattr(v, "__len__") and not isinstance(v, str)).any()]
    frame.drop(columns=arrays).to_csv(path, index=not default_index)
    print(f"{args.name} on {scene_name}: {len(frame)} rows in {elapsed:.3g} s")
    if arrays:
        print(f"left out of the CSV (a time series per row): {', '.join(map(str, arrays))}")
    print(f"wrote {path}")
    return 0


# --- parser -----------------------------------------------------------------------


def _add_simulation_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--t-end", type=float, default=DEFAULT_T_END,
                        help=f"simulated time [s] (default {DEFAULT_T_END:g})")
    parser.add_argument("--integrator", default=None,
                        help="integrator (default: the scene's; event_driven, moreau, "
                             "cvode_bdf, cvode_adams, dopri5, ...)")
    parser.add_argument("--rtol", type=float, default=None, help="relative tolerance")
    parser.add_argument("--atol", type=float, default=None, help="absolute tolerance")
    parser.add_argument("--dt", type=float, default=None, help="fixed step of 'moreau' [s]")
    parser.add_argument("--points", type=int, default=DEFAULT_POINTS,
                        help=f"output points, evenly spaced over [0, t_end] (default "
                             f"{DEFAULT_POINTS}); 0 writes every integrator step and event")


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="leadscrew", description="Lead-screw drive simulator. SCENE is a TOML "
                     "scene file or the name of a shipped scene (default, thesis_table_5_1, "
                     "position_holding).")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
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

    study = command("study", help="run a design study of leadscrew.studies, write its table")
    study.add_argument("name", metavar="NAME", help="the study (leadscrew.studies.STUDIES)")
    study.add_argument("scene", metavar="SCENE")
    study.add_argument("options", metavar="KEY=VALUE", nargs="*",
                       help="options of the study, values in TOML syntax or comma-separated "
                            "lists, e.g. frequencies=5,10,20 progress=false")
    study.add_argument("-o", "--output", default=".", help="output directory (default .)")
    study.set_defaults(func=_study)

    demo = command("demo", help="simulate the default scene and write its figures")
    demo.add_argument("-o", "--output", default="leadscrew-demo",
                      help="output directory (default leadscrew-demo)")
    demo.set_defaults(func=_demo)
    return parser


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
        args = _parser().parse_args(argv)
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
