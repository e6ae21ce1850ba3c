"""Command line interface: ``leadscrew run | check | study | scene | export-fmu | list | demo``.

::

    leadscrew run SCENE [-o DIR] [--t-end T] [--integrator NAME] [--format csv|parquet]
                  [--rtol R] [--atol A] [--dt DT] [--theta THETA] [--points N]
    leadscrew check [SCENE]
    leadscrew study NAME SCENE [-o DIR] [KEY=VALUE ...]
    leadscrew scene resolve SCENE [-o FILE]
    leadscrew scene copy NAME [PATH]
    leadscrew export-fmu SCENE [-o FILE.fmu | DIR]
    leadscrew list
    leadscrew demo [-o DIR]
    leadscrew --version

SCENE is a TOML scene file (see :meth:`leadscrew.Scene.from_toml`) or the name
of a shipped scene (:func:`leadscrew.scenes.available`); ``run`` also takes
the core spec ``scene resolve`` writes (:mod:`leadscrew.core_spec`). Errors print one line
to stderr and exit with 2 for usage and validation errors (bad arguments, an
invalid or unreadable scene file, an integrator that does not fit, an option
the integrator would ignore: ``--dt``/``--theta`` without ``moreau``,
``--rtol``/``--atol`` with it) and 1 for failures while running (simulation
errors, a file that cannot be written, a study that raises or whose every
case failed; some failed cases:
exit 0 with a warning on stderr); ``--debug`` shows the traceback instead.
A Python warning (a profile not verified against its source) is a one-line
note on stderr, ``leadscrew: note: ...``.
Arguments are checked before anything is simulated, and the output
directory is created only once there is something to write; every file is
written whole or not at all (:mod:`leadscrew.files`).
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import warnings
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

from . import _core
from . import thread as _thread
from .cli_output import (_check_output_dir, _output_dir, _output_file, _require_parquet,
                         _save_figure, _summary, _title, _write_series)
from .cli_parser import DEFAULT_POINTS, DEFAULT_T_END, UsageError, _load_scene, _parse
from .cli_catalog import _list, _scene_copy
from .cli_study import _study
from .core_spec import is_core_spec, simulate_core_spec
from .files import write_text
# (Re-exported: the tests import them from here.)
from .cli_output import _failures, _summary_text  # noqa: F401
from .cli_parser import StudyFailed  # noqa: F401
from .cli_study import _option_value  # noqa: F401

__all__ = ["main"]


def _rigid_equivalent(scene) -> Tuple[float, float]:
    """Rotating inertia J and translating mass m of the scene's rigid model."""
    # (The stops play no part in the masses; exact ones would be refused on
    # the rigid concept.)
    rigid = scene.replace(concept="rigid", backlash=None, end_stops=None,
                          initial={"play_position": 0.0})
    mass = rigid.model().mass
    return float(mass[0]), float(mass[1])


# --- check ----------------------------------------------------------------------


def _self_locking_lines(t, mu: float, mu_static: Optional[float]) -> List[str]:
    """Self-locking at rest (with mu_static, the stick limit) and in motion
    (with mu): a thread whose static friction holds the load may still run
    down once moving."""
    def answer(value: float) -> str:
        return "yes" if _thread.is_self_locking(t, value) else "no"

    if mu_static is None or mu_static == mu:
        return [f"self-locking (holds under pure axial load): {answer(mu)}"]
    return [f"self-locking at rest (mu_static = {mu_static:g}, mu_static' = "
            f"{t.effective_mu(mu_static):.6g}): {answer(mu_static)}",
            f"self-locking in motion (mu = {mu:g}; a slipping thread keeps slipping "
            f"under the load if no): {answer(mu)}"]


def _thread_verdicts(t, mu: float, flank_angle: float, hand: str = "right",
                     mu_static: Optional[float] = None) -> List[str]:
    """The closed-form verdicts on a thread, as lines of text (mu_static:
    the scene's static coefficient, None where it equals mu)."""
    tan_a = math.tan(t.lead_angle)
    return [
        f"thread: lead {t.lead * 1e3:.4g} mm, mean diameter {t.mean_diameter * 1e3:.4g} mm, "
        f"lead angle {math.degrees(t.lead_angle):.4f} deg, flank angle "
        f"{math.degrees(flank_angle):g} deg, {hand}-hand",
        f"friction: mu = {mu:g}, mu' = {t.effective_mu(mu):.6g}; "
        f"bounds tan(alpha) = {tan_a:.6g} < mu' < cot(alpha) = {1.0 / tan_a:.6g}",
        *_self_locking_lines(t, mu, mu_static),
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
    "contact_stiffness": "N/m", "contact_damping": "N*s/m", "contact_penetration": "m",
}


def _lift_off_report(scene, d: Dict[str, Any], preload: float) -> List[str]:
    """A preloaded nut with penalty play on a flexible concept: where half A
    lifts off (docs/physics/preloaded_nut.md, "Lift-off")."""
    from .studies.preload import lift_off_spring_force

    lift_off = lift_off_spring_force(scene)
    if lift_off is None:
        return []
    spring, penetration = lift_off
    return [f"lift-off: half A leaves its flank where the spring carries P + k_p d_0 = "
            f"{spring:.6g} N (d_0 = {penetration:.6g} m, the flank's penetration at P); "
            f"beyond, the spring's {d['nut']['preload_stiffness']:.6g} N/m alone until the "
            f"play {d['backlash']['axial']:.6g} m is taken up"]


def _drive_train_report(scene, d: Dict[str, Any]) -> List[str]:
    """The drive train's elements in ``check``: the preloaded nut's efficiency,
    the DC motor's stall and no-load values (behind the gear stage), the end
    stops (docs/physics/)."""
    lines = []
    mu = d["friction"]["mu"]
    preload = d["nut"].get("preload", 0.0)
    force = scene.model().parameters.axial_force(0.0)
    if preload > 0.0:
        at = abs(force) if force != 0.0 else preload
        eta = float(_core.preloaded_efficiency_array(scene.thread, mu, at, [preload])[0])
        lines.append(f"preloaded split nut: P = {preload:.6g} N; efficiency raising "
                     f"{at:.6g} N {eta:.6g} (without the preload "
                     f"{_thread.efficiency(scene.thread, mu):.6g})")
        lines.extend(_lift_off_report(scene, d, preload))
    if "gear" in d:
        lines.append(f"gear stage: {d['gear']['type']}, n = {d['gear']['ratio']:g} (the rotor "
                     "turns n times per turn of the driven part)")
    train = scene.model().train_friction
    if train is not None and train["stage"]:
        static = ("" if train["efficiency_static"] == train["efficiency"] and
                  train["efficiency_backdrive_static"] == train["efficiency_backdrive"] else
                  f" (at breakaway {train['efficiency_static']:.6g}, "
                  f"{train['efficiency_backdrive_static']:.6g})")
        lines.append(f"  efficiency {train['efficiency']:.6g} rotor -> driven part, "
                     f"{train['efficiency_backdrive']:.6g} back{static}; self-locking: "
                     + ("yes (it holds the driven side with a free rotor)"
                        if train["self_locking"] else "no"))
    if train is not None and train["motor_friction_torque"] > 0.0:
        lines.append(f"motor friction: {train['motor_friction_torque']:.6g} N*m on the rotor")
    from .studies import motor as _motor  # (the studies' closed forms: pandas, on demand)

    voltage = _motor.constant_voltage(scene)
    if voltage is not None:
        motor = d["motor"]
        stall = _motor.stall_from_rest(scene, voltage)
        k_e = motor.get("back_emf_constant", motor["torque_constant"])
        lines.append(f"DC motor at {voltage:g} V: stall current {stall['current']:.6g} A, stall "
                     f"torque {stall['torque']:.6g} N*m, no-load speed {abs(voltage) / k_e:.6g} "
                     f"rad/s; stall load from rest (rigid drive, plain nut) {stall['load']:.6g} N")
    stops = d.get("end_stops")
    if stops:
        where = ", ".join(f"{side} {stops[side]:.6g} m" for side in ("lower", "upper")
                          if side in stops)
        lines.append(f"end stops: {where} (from the load's start), contact {stops['contact']}"
                     + (f", stiffness {stops['stiffness']:.6g} N/m, damping "
                        f"{stops['damping']:.6g} N*s/m" if stops["contact"] == "penalty" else
                        f", restitution {stops['restitution']:.6g}"))
    lines.extend(_element_sections_report(d))
    return lines


def _element_sections_report(d: Dict[str, Any]) -> List[str]:
    """A line per element section of the core's registry the scene has (a
    load spring, ...), each field with its unit; the end stops have their
    own line above."""
    from .scene_schema import SCHEMA, _element_sections

    lines = []
    for section in _element_sections():
        name = section["name"]
        if name == "end_stops" or not d.get(name):
            continue
        fields = ", ".join(
            f"{key} {value:.6g}" + (f" {SCHEMA[name][key].unit}" if SCHEMA[name][key].unit else "")
            if isinstance(value, (int, float)) else f"{key} {value}"
            for key, value in d[name].items())
        lines.append(f"{name}: {fields}")
    return lines


def _scene_report(name: str, scene) -> List[str]:
    """What ``check SCENE`` prints, computed whole before anything is printed."""
    d = scene.to_dict()
    lines = [f"scene {name}: valid, {scene!r}"]
    if d.get("simulation"):  # the run's options stored with the scene
        # (refused here as `leadscrew run` at its default t_end refuses them:
        # the same rules, in the same place)
        from .studies._batch import check_simulate_options

        check_simulate_options(scene, {}, DEFAULT_T_END)
        lines.append("run options ([simulation], simulate's defaults for this scene): "
                     + ", ".join(f"{key} = {value!r}" for key, value in d["simulation"].items()))
    lines += _thread_verdicts(scene.thread, d["friction"]["mu"], d["thread"]["flank_angle"],
                              d["thread"]["hand"], d["friction"].get("mu_static"))
    lines += _drive_train_report(scene, d)
    J, m = _rigid_equivalent(scene)
    rotating, translating = (("rotor + screw", "nut + load") if d["drive"] == "screw"
                             else ("rotor + nut", "screw + load"))
    if "gear" in d:  # the rotor reflected through the stage (docs/physics/gear.md)
        rotating = f"n^2 rotor (n = {d['gear']['ratio']:g}) + " + rotating.split(" + ")[1]
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
    contact = (d.get("backlash") or {}).get("contact", "exact")
    for key, value in scene.derived().items():
        if key.startswith("contact_") and contact == "exact":
            continue  # a penalty flank's, which an exact contact has not
        note = (" (follows the nut position, eq. 4.24)" if value == 0.0
                and key in ("screw_axial_stiffness", "screw_torsional_stiffness") else "")
        unit = _DERIVED_UNITS.get(key, "")
        if key == "contact_stiffness":  # F = k d^e: N/m^e for bistop, N/m for cubic
            unit = f"N/m^{d['backlash']['exponent']:g}" if contact == "bistop" else "N/m"
        lines.append(f"  {key} = {value:.6g} {unit}{note}")
    springs = scene.model().springs
    if springs:
        lines.append(f"springs of the {d['concept']} model (at the start):")
        for spring in springs:
            torsion = "torsion" in spring["name"]
            lines.append(f"  {spring['name']}: stiffness {spring['stiffness']:.6g} "
                         f"{'N*m/rad' if torsion else 'N/m'}, damping {spring['damping']:.6g} "
                         f"{'N*m*s/rad' if torsion else 'N*s/m'}")
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


def _check_sampling(t_end: float, points: int) -> None:
    if not (math.isfinite(t_end) and t_end > 0):
        raise UsageError(f"--t-end {t_end:g} is invalid: must be a time > 0 [s]")
    if points < 0 or points == 1:
        raise UsageError(f"--points {points} is invalid: must be 0 (every step) or >= 2")


def _check_integrator_options(scene, args: argparse.Namespace) -> None:
    """Refuse options the integrator that runs would ignore.

    ``--dt`` and ``--theta`` are parameters of the fixed-step ``moreau``
    scheme only; ``--rtol`` and ``--atol`` of the others only. Without
    ``--integrator`` an option names its scheme, as in leadscrew.simulate:
    ``--dt`` runs ``moreau`` where it fits the scene,
    ``--rtol`` on a scene whose default is ``moreau`` the first adaptive
    integrator that fits (``integrator_taking``); refused only where none
    that fits takes it.

    Raises:
        UsageError: naming the option, its value and the integrator.
    """
    from . import _core
    from .simulation import (check_integrator_name, integrator_taking, option_conflict,
                             unused_option)

    allowed = list(_core.drive_integrators(scene.model().parameters))
    if args.integrator is not None:
        check_integrator_name(args.integrator, shown=f"--integrator {args.integrator}",
                              fitting=allowed)
    given = {"rtol": args.rtol, "atol": args.atol, "dt": args.dt, "theta": args.theta}
    stored = scene["simulation"].get("integrator") if "simulation" in scene else None
    if args.integrator is not None:
        integrator, which = args.integrator, f"--integrator {args.integrator}"
    elif stored is not None:  # the scene's own (its [simulation] section)
        integrator, which = stored, f"the scene's integrator {stored} (simulation.integrator)"
    else:  # the scene's default: the first of the integrators that fit it
        conflict = option_conflict(given, spell=lambda name: f"--{name}", equals=" ")
        if conflict is not None:
            raise UsageError(conflict)
        integrator = integrator_taking(allowed, given, scene)
        which = f"the scene's default integrator {integrator}"
    # The rules of leadscrew.simulate, in the command line's spelling.
    unused = unused_option(integrator, given, scene, spell=lambda name: f"--{name}",
                           moreau_only=allowed == ["moreau"])
    if unused is not None:
        name, _, why = unused
        raise UsageError(f"--{name} {given[name]:g} is invalid with {which}: {why}")


def _simulate(scene, t_end: float = DEFAULT_T_END, points: int = DEFAULT_POINTS, **options):
    """Simulate (the caller checked t_end and points); options with value None
    are left out."""
    from .simulation import simulate

    options = {k: v for k, v in options.items() if v is not None}
    # A progress bar where someone watches (a terminal); Ctrl-C stops the
    # run either way.
    return simulate(scene, t_end, t_eval=_t_eval(t_end, points), progress=sys.stderr.isatty(),
                    **options)


def _core_spec_text(args: argparse.Namespace) -> Optional[str]:
    """SCENE's text where it is a core spec (``leadscrew scene resolve``'s
    output), else None.

    Raises:
        UsageError: an option of the run given with a core spec, which
            carries its run's options (its [options] table).
    """
    path = Path(args.scene)
    if not path.is_file():
        return None
    text = path.read_text(encoding="utf-8", errors="replace")
    if not is_core_spec(text):
        return None
    given = [f"--{k.replace('_', '-')}" for k in ("integrator", "rtol", "atol", "dt", "theta",
                                                  "max_steps") if getattr(args, k) is not None]
    if given:
        raise UsageError(f"{', '.join(given)} with the core spec {args.scene} is invalid: a core "
                         "spec carries its run's options (its [options] table: edit them there, "
                         "or run the scene file)")
    return text


def _t_eval(t_end: float, points: int):
    """The output times of ``--points`` (0: every step and event)."""
    import numpy as np

    return np.linspace(0.0, t_end, points) if points else "steps"


def _run(args: argparse.Namespace) -> int:
    # Every argument is checked before anything runs or is created.
    _require_parquet(args.format)
    _check_sampling(args.t_end, args.points)
    _check_output_dir(args.output)
    spec = _core_spec_text(args)
    if spec is not None:  # what scene resolve writes: the run's options its own
        name = Path(args.scene).stem
        result = simulate_core_spec(spec, args.t_end, _t_eval(args.t_end, args.points),
                                    progress=sys.stderr.isatty())
        summary, title = _summary(name, "core spec", result, args.t_end), f"{name}: core spec"
    else:
        scene, name, _ = _load_scene(args.scene)
        _check_integrator_options(scene, args)
        result = _simulate(scene, args.t_end, args.points, integrator=args.integrator,
                           rtol=args.rtol, atol=args.atol, dt=args.dt, theta=args.theta,
                           max_steps=args.max_steps)
        summary, title = _summary(name, repr(scene), result, args.t_end), _title(name, scene)
    out = _output_dir(args.output)
    print(summary)
    series = _write_series(result, out, name, args.format)
    figure = _output_file(out, name, "png")
    _save_figure(result.plot("time_series", title), figure)
    print(f"wrote {series}")
    print(f"wrote {figure}")
    return 0


def _scene_command(args: argparse.Namespace) -> int:
    """``leadscrew scene resolve SCENE [-o FILE]``: the scene's core spec
    (:meth:`leadscrew.Scene.to_core_toml`), the input of the C API, to FILE
    or standard output."""
    if args.action == "copy":
        if args.output is not None:
            raise UsageError(f"scene copy takes PATH, not -o (leadscrew scene copy {args.scene} "
                             f"{args.output})")
        return _scene_copy(args)
    if args.path is not None:
        raise UsageError(f"scene resolve writes to -o FILE, not to PATH {args.path!r}")
    scene, _, source = _load_scene(args.scene)
    try:
        text = scene.to_core_toml()
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None
    if args.output in (None, "-"):
        sys.stdout.write(text)
    else:
        write_text(args.output, text)
        print(f"wrote {args.output}")
    return 0


def _export_fmu(args: argparse.Namespace) -> int:
    """``leadscrew export-fmu SCENE [-o FILE.fmu | DIR]``: the scene as an FMI
    2.0 co-simulation FMU (:func:`leadscrew.fmi.export_fmu`), by default
    ``./NAME.fmu``."""
    from . import fmi

    scene, name, source = _load_scene(args.scene)
    output = args.output or "."
    try:
        fmi._fmu_path(output, name)
    except ValueError:
        raise UsageError(f"-o {output}: an FMU's file name ends in .fmu (e.g. "
                         f"{os.path.splitext(output)[0]}.fmu), or give a directory") from None
    try:
        written = fmi.export_fmu(scene, output, name=name)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None
    print(f"wrote {written}")
    return 0


def _demo(args: argparse.Namespace) -> int:
    from . import scenes

    name = "default"
    scene = scenes.load(name)
    out = _output_dir(args.output)
    print(f"leadscrew demo: the shipped scene {name!r} ({scenes.path(name)})")
    _check_scene(name)
    result = _simulate(scene)
    print(_summary(name, repr(scene), result, DEFAULT_T_END))
    written = [_write_series(result, out, name, "csv")]
    for filename, kind in ((name, "time_series"), (f"{name}_energy", "energy")):
        written.append(_output_file(out, filename, "png"))
        _save_figure(result.plot(kind, _title(name, scene)), written[-1])
    for path in written:
        print(f"wrote {path}")
    return 0


#: Each command's function, by the name the parser gives it (``args.command``).
_COMMANDS = {"run": _run, "check": _check, "study": _study, "scene": _scene_command,
             "export-fmu": _export_fmu, "demo": _demo, "list": _list}


def _is_input_error(error: BaseException) -> bool:
    """Bad arguments or an invalid or unreadable scene (exit code 2)."""
    from .errors import SimulationError

    from .errors import WriteError

    # (A file that could not be written is a failure while running: exit 1.)
    return (isinstance(error, (ValueError, OSError))
            and not isinstance(error, (SimulationError, WriteError)))


def _note_text(message, category) -> str:
    """A warning as the command line's one-line note (the warnings module's
    own shows the file, the line and the source line that warned, which say
    nothing to someone running a command): a ProfileWarning as
    ``leadscrew: note: profile ... is not verified ...``, any other with its
    category's name."""
    from .profiles import ProfileWarning

    text = " ".join(str(message).split())
    if not issubclass(category, ProfileWarning):
        text = f"{category.__name__}: {text}"
    return f"leadscrew: note: {text}"


def _run_command(args) -> int:
    """Run a command with its warnings as notes on stderr, printed when it
    ends; dropped where it ends in an input error (exit 2: nothing ran, and a
    note about the scene, e.g. its unverified profile, printed before the
    error misled a user who had mistyped a profile's name).

    Raises:
        the command's exception, the notes printed first unless it is an
        input error.
    """
    notes: List[str] = []
    with warnings.catch_warnings():  # (each warning once, as a note)
        warnings.simplefilter("default")
        warnings.showwarning = (lambda message, category, *_, **__:
                                notes.append(_note_text(message, category)))
        try:
            code = _COMMANDS[args.command](args)
        except Exception as error:
            if not _is_input_error(error):
                _print_notes(notes)
            raise
    _print_notes(notes)
    return code


def _print_notes(notes: List[str]) -> None:
    for note in notes:
        print(note, file=sys.stderr)


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
        if debug:
            return _COMMANDS[args.command](args)
        return _run_command(args)
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
