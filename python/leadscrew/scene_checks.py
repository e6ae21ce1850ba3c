"""The checks of a scene: each field, each section and the rules across sections.

``_validate_entry`` checks one top-level entry of a raw scene dict against
:data:`~leadscrew.scene_schema.SCHEMA` (unknown keys, missing required ones,
None, units and ranges, each ``ValueError`` naming the key path, the value
and what is allowed); ``_check_consistency`` then checks what sections say
together (the friction law's parameters, the drive loads or the motor, the
nut on the screw, the play position, an equilibrium start).
"""

from __future__ import annotations

import math
import numbers
from typing import Any, Dict, Optional

from . import _core
from ._hints import did_you_mean
from .scene_loads import _DEFAULT_ROTOR_SPEED, _check_load, _check_rotor_speed
from .scene_schema import (OPTIONAL, SCHEMA, _OPTIONAL_SECTIONS, _REQUIRED_SECTIONS,
                           _UNIT_DEPENDS_ON, Field, _check_friction, _Converted,
                           _element_sections, _fail, _field_unit, _range_text)
from .scene_schema import _SMALLEST_GEAR_RATIO, DC_MOTOR_FIELDS
from .units import to_si

__all__: list = []  # the scene's internals: leadscrew.Scene is the public face


def _check_field(path: str, f: Field, value: Any, unit: Optional[str] = None,
                 name: Optional[str] = None):
    """A field's value checked and converted to ``unit`` (default: the
    field's); ``name`` says what it measures in unit messages."""
    unit = f.unit if unit is None else unit
    if f.kind == "choice":
        if value not in f.choices:
            _fail(path, value, "one of " + ", ".join(repr(c) for c in f.choices))
        return value
    if f.kind == "load":
        return _check_load(path, value, unit)
    given = value
    value = to_si(path, value, unit, name)
    shown = _Converted(given, value, unit) if isinstance(given, str) else value
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        _fail(path, shown, "a number" if f.kind == "float" else "an integer")
    if f.kind == "int":
        if not (isinstance(value, numbers.Integral)
                or (math.isfinite(value) and int(value) == value)):
            _fail(path, shown, _range_text(f))
        value = int(value)
    else:
        try:
            value = float(value)
        except OverflowError:  # an int beyond the float range
            _fail(path, shown, _range_text(f))
    above = value > f.low if f.low_open else value >= f.low
    below = value < f.high if f.high_open else value <= f.high
    if not ((f.kind == "int" or math.isfinite(value)) and above and below):
        _fail(path, shown, _range_text(f) + (f" [{unit}]" if unit and shown is not value else ""))
    return value


def _refuse_none(path: str, f: Field) -> None:
    """None for a field that is not optional: refused (it would take the
    schema's default silently, also in :meth:`Scene.replace`, whose scene
    may hold another value).

    Raises:
        ValueError: naming the key path, what the field takes and its default.
    """
    if f.kind == "choice":
        allowed = "one of " + ", ".join(repr(c) for c in f.choices)
    elif f.kind == "load":
        allowed = ("a number, a dict with 'type' in constant/sine/table/random/measured, an "
                   "Excitation or a callable")
    else:
        allowed = _range_text(f) + (f" [{f.unit}]" if f.unit else "")
    if f.default is None:
        hint = f"{path} is required; leave it out of Scene.replace to keep the scene's value"
    else:
        hint = (f"leave {path} out for its default {f.default!r}, or out of Scene.replace to "
                "keep the scene's value")
    _fail(path, None, f"{allowed} (None removes only an optional field: {hint})")


# Keys of planned physics not implemented yet: refused with what is
# supported instead, not as unknown keys.
_NOT_IMPLEMENTED: Dict[str, str] = {}


def _validate_section(path: str, schema: Dict[str, Field], given: Dict[str, Any]) -> Dict[str, Any]:
    if not isinstance(given, dict):
        _fail(path, given, "a table (dict) of fields")
    for key in given:
        if f"{path}.{key}" in _NOT_IMPLEMENTED:
            raise ValueError(f"{path}.{key} = {given[key]!r} is not supported: "
                             f"{_NOT_IMPLEMENTED[f'{path}.{key}']}")
        if key not in schema:
            raise ValueError(f"{path}.{key} is not a known key{did_you_mean(key, schema)}; "
                             f"{path} takes {', '.join(schema)}")
    out = {}
    # A field whose unit depends on others is checked after them.
    for key in sorted(schema, key=lambda k: (path, k) in _UNIT_DEPENDS_ON):
        f = schema[key]
        sub = f"{path}.{key}"
        if key in given and given[key] is None and f.default is not OPTIONAL:
            _refuse_none(sub, f)
        if key in given and given[key] is not None:
            unit = _field_unit(path, key, f, out)
            bistop = unit != f.unit and (path, key) == ("backlash", "stiffness")
            try:
                out[key] = _check_field(sub, f, given[key], unit,
                                        "a 'bistop' contact stiffness" if bistop else None)
            except ValueError as error:
                if not bistop:
                    raise
                raise ValueError(f"{error} (a 'bistop' stiffness is in N/m^exponent, here "
                                 f"backlash.exponent = {out['exponent']!r})") from None
        elif f.default is None:
            raise ValueError(f"{sub} is missing: {f.doc}" + (f" [{f.unit}]" if f.unit else ""))
        elif f.default is not OPTIONAL:
            out[key] = f.default
    return {key: out[key] for key in schema if key in out}


def _check_section_names(d: Dict[str, Any]) -> None:
    for key in d:
        if key not in SCHEMA:
            raise ValueError(f"{key} is not a known section{did_you_mean(key, SCHEMA)}; "
                             f"a scene has {', '.join(SCHEMA)}")


def _validate_entry(key: str, given: Dict[str, Any], data: Dict[str, Any]) -> None:
    """Check the top-level entry ``key`` of the raw scene ``given`` into ``data``
    (a field, a required or optional section, or a section of defaults)."""
    entry = SCHEMA[key]
    if isinstance(entry, Field):
        data[key] = _check_field(key, entry, given[key]) if key in given else entry.default
        return
    if key not in given:
        if key in _REQUIRED_SECTIONS:
            raise ValueError(f"{key} is missing: a scene needs the sections "
                             f"{', '.join(_REQUIRED_SECTIONS)}")
        if key in _OPTIONAL_SECTIONS:
            return
    data[key] = _validate_section(key, entry, given.get(key, {}))


def _check_consistency(data: Dict[str, Any]) -> None:
    _check_friction(data["friction"])
    loads = data["loads"]
    if "drive_torque" in loads and "drive_speed" in loads:
        raise ValueError("loads.drive_speed = {!r} is invalid: give either loads.drive_torque "
                         "or loads.drive_speed, not both".format(loads["drive_speed"]))
    # Without either the drive torque is 0, applied by _core_parameters: it is
    # not stored, so replace(loads={"drive_speed": w}) switches to speed.
    if "motor" in data:
        _check_motor(data)
    if "gear" in data:
        _check_gear(data["gear"])
    _check_element_sections(data)
    if "simulation" in data:
        _check_simulation(data)
    if data["nut"]["outer_radius"] <= data["screw"]["radius"]:
        _fail("nut.outer_radius", data["nut"]["outer_radius"],
              f"> screw.radius = {data['screw']['radius']:g}")
    # Both drives: the whole nut on the screw (the core's rule, which
    # DriveModel checks alike; a run of any concept ends where the nut's
    # end reaches the screw's).
    _core.check_nut_on_screw(data["drive"], data["nut"]["position"], data["nut"]["length"],
                             data["screw"]["length"])
    _check_rotor_speed(data)
    play = data["initial"]["play_position"]
    backlash = data.get("backlash")
    half = backlash["axial"] / 2 if backlash else 0.0
    if abs(play) > half:
        _fail("initial.play_position", play, f"within +-backlash.axial / 2 = +-{half:g}"
              + (f" (backlash.axial = {backlash['axial']!r})" if backlash else " (no backlash)"))
    if data["initial"]["state"] == "equilibrium":
        # The core checks the same (DriveModel); here the scene names it first.
        equilibrium = " is invalid with initial.state = 'equilibrium': "
        if "drive_speed" in loads:
            raise ValueError("initial.state = 'equilibrium' is invalid with loads.drive_speed: "
                             "the static equilibrium needs a torque-controlled motor "
                             "(loads.drive_torque)")
        if data["initial"].get("rotor_speed", _DEFAULT_ROTOR_SPEED) != 0.0:
            raise ValueError(f"initial.rotor_speed = {data['initial']['rotor_speed']!r}"
                             f"{equilibrium}must be 0 (the drive starts at rest)")
        if play != 0.0:
            raise ValueError(f"initial.play_position = {play!r}{equilibrium}must be 0 (the "
                             "equilibrium puts the nut on the flank the loads press it "
                             "against)")


def _check_simulation(data: Dict[str, Any]) -> None:
    """The ``[simulation]`` section's options together, by simulate's rules
    (:func:`leadscrew.simulation.unused_option`): with an ``integrator``
    stored, no option that integrator would ignore (``rtol`` with
    ``'moreau'``, ``dt`` with another, ``smooth_integrator`` but with
    ``'event_driven'``), and ``bounce_threshold`` only with an exact
    backlash; without an ``integrator``, no two options that no integrator
    takes together (``dt`` with ``rtol``: :func:`option_conflict`), which
    every run would refuse. Whether the integrator fits the scene's law and play is
    checked where it runs (:func:`leadscrew.simulate` lists those that do).

    Raises:
        ValueError: naming ``simulation.<key>``, its value and which
            integrator or scene takes it.
    """
    from .simulation import _shown, option_conflict, unused_option  # (it imports the scene)

    options = data["simulation"]
    integrator = options.get("integrator")
    if "smooth_integrator" in options and integrator not in (None, "event_driven"):
        _fail("simulation.smooth_integrator", options["smooth_integrator"],
              f"absent with simulation.integrator = {integrator!r}: only 'event_driven' takes "
              "one (the method between its events)")
    given = {name: options.get(name) for name in ("rtol", "atol", "dt", "theta", "max_order",
                                                  "max_step", "first_step", "bounce_threshold")}
    if integrator is None:  # (the scene's default integrator is known when it runs)
        conflict = option_conflict(given, spell=lambda name: f"simulation.{name}")
        if conflict is not None:  # (no integrator takes both: a run would refuse it)
            raise ValueError(conflict)
        given = {"bounce_threshold": given["bounce_threshold"]}
    unused = unused_option(integrator or "", given, data)
    if unused is not None:
        name, of_scene, why = unused
        where = "for this scene" if of_scene else f"with simulation.integrator = {integrator!r}"
        raise ValueError(f"simulation.{name} = {_shown(given[name])} is invalid {where}: {why}")


def _check_gear(gear: Dict[str, Any]) -> None:
    """The gear section's rules: a nonzero ratio, each type's own fields
    (the efficiencies for 'lossy', the worm's for 'worm'; their ranges and
    where a lossy or worm stage runs are the core's checks).

    Raises:
        ValueError: naming the key at fault, its value and the valid range.
    """
    ratio = gear["ratio"]
    if abs(ratio) < _SMALLEST_GEAR_RATIO:
        _fail("gear.ratio", ratio, f"in [{_SMALLEST_GEAR_RATIO:g}, {1 / _SMALLEST_GEAR_RATIO:g}] "
              f"or in [-{1 / _SMALLEST_GEAR_RATIO:g}, -{_SMALLEST_GEAR_RATIO:g}] (rotor turns per "
              "turn of the driven part; < 0 a reversing stage)")
    kind = gear["type"]
    fields = {"lossy": ("efficiency", "efficiency_backdrive"),
              "worm": ("lead_angle", "mu", "mu_static", "flank_angle")}
    required = {"lossy": ("efficiency",), "worm": ("lead_angle", "mu")}
    for key in ("efficiency", "efficiency_backdrive", "lead_angle", "mu", "mu_static",
                "flank_angle"):
        if key in gear and key not in fields.get(kind, ()):
            owner = "lossy" if key.startswith("efficiency") else "worm"
            _fail(f"gear.{key}", gear[key], f"absent with gear.type = {kind!r} (a field of "
                  f"gear.type = {owner!r})")
    for key in required.get(kind, ()):
        if key not in gear:
            raise ValueError(f"gear.{key} is missing: gear.type = {kind!r} needs it")


def _check_motor(data: Dict[str, Any]) -> None:
    """The motor section's rules across sections. A DC motor (type 'dc'):
    its required fields, exclusive with the drive loads (an equilibrium
    start holds the drive with its steady current at rest: the core's).
    Without a type: the friction_torque of a rotor driven by
    loads.drive_torque (issue 33), none of a DC motor's fields.

    Raises:
        ValueError: naming the keys at fault and their values.
    """
    motor, loads = data["motor"], data["loads"]
    if "type" not in motor:
        for key in DC_MOTOR_FIELDS:
            if key in motor:
                raise ValueError(
                    f"motor.type is missing: motor.{key} = {motor[key]!r} is a DC motor's "
                    "(motor.type = 'dc'); without a type the section gives only the "
                    "friction_torque of a rotor driven by loads.drive_torque")
        return
    section = SCHEMA["motor"]
    for key in section:
        if section[key].required_with and key not in motor:
            f = section[key]
            raise ValueError(f"motor.{key} is missing: {f.doc}" + (f" [{f.unit}]" if f.unit else ""))
    # (the DC motor's default inductance, in the section's order)
    data["motor"] = motor = {key: motor.get(key, 0.0 if key == "inductance" else None)
                             for key in section if key in motor or key == "inductance"}
    for key in ("drive_torque", "drive_speed"):
        if key in loads:
            raise ValueError(f"loads.{key} = {loads[key]!r} is invalid with motor.type = "
                             f"{motor['type']!r}: give either motor or loads.{key}, not both")


def _check_element_sections(data: Dict[str, Any]) -> None:
    """The elements' own sections (the end stops, ...): each one's rules
    across its fields and the other sections, as the core declares them
    (``_core.check_element_section``; its fields' ranges are checked already).

    Raises:
        ValueError: naming the keys at fault, their values and what is allowed.
    """
    present = [section["name"] for section in _element_sections() if section["name"] in data]
    if not present:
        return
    # What the sections' rules read of the others.
    context = _core.DriveParameters()
    context.concept, context.drive = data["concept"], data["drive"]
    context.initial_state = data["initial"]["state"]
    context.friction = data["friction"]["law"]
    if data.get("backlash"):
        context.backlash = data["backlash"]["contact"]
        context.clearance = data["backlash"]["axial"]
    if "gear" in data:
        context.gear = data["gear"]["type"]
    if "motor" in data:
        context.dc_motor = data["motor"].get("type") == "dc"
        context.motor_friction_torque = data["motor"]["friction_torque"]
    for name in present:
        _core.check_element_section(name, data[name], context)
