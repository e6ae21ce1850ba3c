"""The command line's arguments: the parser, the SCENE argument and the commands' errors.

``_parse`` reads the command line (``study``'s KEY=VALUE options anywhere
after SCENE), ``_load_scene`` turns a SCENE argument (a TOML file or a
shipped scene's name) into a checked scene. A command's mistakes raise
:class:`UsageError` (exit code 2), a study that cannot run
:class:`StudyFailed` (exit code 1); :func:`leadscrew.cli.main` runs the
command and turns them into one line and the exit code.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Any, List, Tuple

from . import __version__, scenes
from ._hints import did_you_mean

__all__ = ["UsageError", "StudyFailed"]


DEFAULT_T_END = 1.0  # s
DEFAULT_POINTS = 2001


class UsageError(ValueError):
    """A command line mistake: exit code 2."""


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (and exit code 2, as argparse's own)."""

    def error(self, message: str):
        raise UsageError(f"{message} (see '{self.prog} --help')")


class StudyFailed(Exception):
    """A study cannot run (exit code 1)."""


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
            raise UsageError(f"scene {arg!r}: no such file, and not a shipped scene"
                             f"{did_you_mean(stem, shipped)} ({', '.join(shipped)})")
        scene, name, source = scenes.load(stem), stem, stem
    # Scene validation covers each value; the derived ones (masses,
    # stiffnesses) and the thread are checked when the model is assembled.
    try:
        scene.model()
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None
    return scene, name, source


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
                             "(default 1e6 per simulated second, at least 1e6)")
    parser.add_argument("--points", type=int, default=DEFAULT_POINTS,
                        help=f"output points, evenly spaced over [0, t_end] (default "
                             f"{DEFAULT_POINTS}); 0 writes every integrator step and event")


def _parser() -> argparse.ArgumentParser:
    # (the shipped scenes listed from the package: a list written here fell
    # behind the scenes shipped)
    parser = _Parser(prog="leadscrew", description="Lead-screw drive simulator. SCENE is a TOML "
                     "scene file or the name of a shipped scene ("
                     + ", ".join(scenes.available()) + ").")
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
    run.add_argument("scene", metavar="SCENE",
                     help="a scene file, a shipped scene's name, or a core spec that 'leadscrew "
                          "scene resolve' wrote (it carries its run's options)")
    run.add_argument("-o", "--output", default=".", help="output directory (default .)")
    run.add_argument("--format", choices=("csv", "parquet"), default="csv",
                     help="time series format (parquet needs pyarrow)")
    _add_simulation_options(run)

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
        epilog="examples: leadscrew study efficiency_vs_mu thesis_table_5_1 mu=0.1,0.2,0.3 "
        "loads=10,50 progress=false -o out; leadscrew study work_precision default t_end=0.5 "
        "(error against run time of the scene's default set of configurations, "
        "leadscrew.studies.default_configurations; or your own as a TOML list: "
        "configurations='[{integrator = \"event_driven\", rtol = 1e-6}, {integrator = "
        "\"moreau\", dt = 1e-4}]')")
    study.add_argument("name", metavar="NAME", help="the study (leadscrew.studies.STUDIES)")
    study.add_argument("scene", metavar="SCENE")
    study.add_argument("options", metavar="KEY=VALUE", nargs="*",
                       help="options of the study, values in TOML syntax or comma-separated "
                            "lists, e.g. frequencies=5,10,20 progress=false (before or after "
                            "-o DIR)")
    study.add_argument("-o", "--output", default=".", help="output directory (default .)")

    scene = command("scene", help="scene tools: 'resolve' writes the core spec (every value "
                    "SI and explicit) that the C API reads and 'leadscrew run' takes; 'copy' "
                    "copies a shipped scene (with its comments) to a file to edit",
                    epilog="examples: leadscrew scene resolve default -o core.toml; "
                    "leadscrew scene copy seat_adjuster my_seat.toml")
    scene.add_argument("action", choices=("resolve", "copy"), metavar="{resolve,copy}",
                       help="resolve: write SCENE's core spec (Scene.to_core_toml); copy: "
                            "write the shipped scene SCENE to PATH")
    scene.add_argument("scene", metavar="SCENE")
    scene.add_argument("path", metavar="PATH", nargs="?", default=None,
                       help="copy: the file or directory to write (default ./SCENE.toml; "
                            "never overwritten)")
    scene.add_argument("-o", "--output", default=None,
                       help="resolve: the file to write (default: standard output)")

    command("list", help="list the shipped scenes, the studies, the friction laws and the vibration profiles")

    export = command("export-fmu", help="write SCENE as an FMI 2.0 co-simulation FMU",
                     epilog="example: leadscrew export-fmu default -o drive.fmu")
    export.add_argument("scene", metavar="SCENE")
    export.add_argument("-o", "--output", default=None,
                        help="the .fmu file to write, or a directory to write NAME.fmu "
                             "into (default: ./NAME.fmu, NAME the scene's name)")

    demo = command("demo", help="simulate the default scene and write its figures")
    demo.add_argument("-o", "--output", default="leadscrew-demo",
                      help="output directory (default leadscrew-demo)")
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
