"""Scenes: a lead-screw drive described section by section.

``Scene.from_dict(d)`` validates a nested dict against :data:`SCHEMA` (unknown
keys, missing required keys and out-of-range values raise ``ValueError``
naming the key path, e.g. ``backlash.axial``), fills the documented defaults,
and keeps only the sections the scene needs. ``Scene.to_dict()`` returns the
complete dict, which ``from_dict`` accepts again unchanged (defaults filled,
except the drive torque: without ``loads.drive_torque`` and
``loads.drive_speed`` the model applies 0 N*m, and the scene keeps the key
absent; likewise ``initial.rotor_speed``: 0, or drive_speed(0) for a
speed-controlled drive, which starts there and refuses another value; loads
given as :class:`~leadscrew.Constant`, :class:`~leadscrew.Sine`
or :class:`~leadscrew.Table` are kept as their ``{"type": ...}`` dicts).
``Scene.from_toml(path)`` and ``Scene.to_toml(path)`` read and write the same
structure as a TOML file.

Every value is SI (m, kg, s, N, N*m, Pa, rad). A numeric field may instead be
given as a string with a unit (``"1 mm"``, ``"210 GPa"``, ``"2 Hz"``, ``"30
deg"``), converted to the field's unit by :func:`leadscrew.units.to_si` (Hz is
cycles per second: ``"2 Hz"`` is 4 pi rad/s). :func:`describe_schema` prints
the documentation of every field with its unit and default.

The core derives the masses, inertias and stiffnesses from geometry and
material (``_core.derive_drive``, cpp/include/leadscrew/model/drive_geometry.hpp)
and checks them; the enumerations' names and the rule that the nut stays on
the screw are the core's as well. ``Scene.derived()`` and ``Scene.model()``
check what the inputs give: every mass, inertia, rigidity and stiffness
finite and positive, the lead angle within 1e-6 <= tan(alpha) <= 1e6 (the
core's ranges), every part's natural angular frequency on
its spring at most 1e12 rad/s, and the core's own checks of the assembled
model. A quantity out of range raises ``ValueError`` naming the input(s)
that made it so (those whose default, or for a required field the thesis
drive's value, ends the problem), the value and why, e.g. ``nut.outer_radius
= 1e+300 is invalid: with it the nut's mass (...) comes to inf kg: must be a
finite number > 0 (or set overrides.nut_mass)``.
"""

from __future__ import annotations

import functools
import json
import math
import numbers
import os
import sys
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any, Callable, Dict, Optional, Tuple

from . import _core
from .excitation import Constant, Sine, Table, check_load_unit, checked_callable
from .thread import Thread
from .units import to_si, what_it_takes

__all__ = ["Scene", "SCHEMA", "describe_schema"]


@dataclass(frozen=True)
class Field:
    """One scene field: its unit, default (None: required; ``OPTIONAL``: may be
    absent) and valid range."""

    doc: str
    unit: str = ""
    default: Any = None
    kind: str = "float"  # float, int, choice, load
    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    high_open: bool = False
    choices: Tuple[str, ...] = ()
    default_doc: str = ""  # the default in words, where it depends on other fields


OPTIONAL = object()  # the field may be absent (derived or unused)
# The names of the model's enumerations by key path (the core's lists).
_CHOICES = {path: tuple(names) for path, names in _core.scene_choices()}
POSITIVE = dict(low=0.0, low_open=True)
NONNEGATIVE = dict(low=0.0)
# Sane physical ranges of material data (beyond them a part is no solid the
# models describe, and the derived stiffnesses and masses leave what the
# integrators resolve).
MODULUS = dict(low=1e4, high=1e13)
DENSITY = dict(low=1.0, high=1e5)
_MODULUS_RANGE_DOC = (", in [1e4, 1e13] Pa: from soft foams and elastomers (about 1e5 Pa) "
                      "to beyond diamond (1.2e12 Pa)")
_DENSITY_RANGE_DOC = ", in [1, 1e5] kg/m^3: from aerogels to beyond osmium (22,590 kg/m^3)"

# The friction laws' parameters that every scene's friction section has (mu;
# k_v with its default even where the law takes none, as scenes have always
# carried it); the others are optional, each law checks its own.
_FRICTION_COMMON = ("mu", "k_v")


@functools.lru_cache(maxsize=None)
def _friction_registry() -> Tuple[dict, ...]:
    """The core's registry of friction laws (``_core.friction_laws()``),
    read once: it does not change while the module lives, and building it
    costs 40 us a call (twice a block's simulation, which takes 25 us)."""
    return tuple(_core.friction_laws())


def _friction_law_entry(name: str) -> Optional[dict]:
    """The registry's entry of the friction law ``name`` (None: no such law)."""
    return next((law for law in _friction_registry() if law["name"] == name), None)


def _friction_section() -> Dict[str, Field]:
    """The friction section from the core's registry of laws
    (``_core.friction_laws()``): the law, mu, k_v and every law's other
    parameters (optional; only the law that takes one accepts it)."""
    laws = _friction_registry()
    law_doc = "; ".join(f"'{law['name']}': {law['doc']}" for law in laws)
    section = {
        "law": Field(f"flank friction law: {law_doc}", "", "coulomb", kind="choice",
                     choices=tuple(law["name"] for law in laws)),
        "mu": Field("flank friction coefficient (the kinetic one where a law has a static one)",
                    "", None, **NONNEGATIVE),
        "k_v": Field("gain k_V of the arctan laws and of a set-valued law's regularization "
                     "with an ODE integrator (slip velocity in m/s, or slip acceleration in "
                     "m/s^2, times k_V; in s^2/m for 'arctan_acceleration')", "s/m", 1.0e4,
                     **POSITIVE),
    }
    for law in laws:
        for parameter in law["parameters"]:
            key = parameter["key"]
            if key in section:
                continue
            takers = [other["name"] for other in laws
                      if any(q["key"] == key for q in other["parameters"])]
            default = (f"default {parameter['default']:g}" if parameter["default"] is not None
                       else f"default friction.{parameter['default_from']}")
            section[key] = Field(f"{parameter['doc']} ({default}; laws "
                                 f"{', '.join(repr(t) for t in takers)})", parameter["unit"],
                                 OPTIONAL, low=parameter["low"], high=parameter["high"],
                                 low_open=parameter["low_open"],
                                 high_open=parameter["high_open"])
    return section


def _friction_values(friction: Dict[str, Any]) -> list:
    """The law's parameters of a checked friction section besides mu and k_v,
    as the core takes them ((key, value) pairs)."""
    return [(key, value) for key, value in friction.items()
            if key not in ("law",) + _FRICTION_COMMON]


def _check_friction(friction: Dict[str, Any]) -> None:
    """The friction section's parameters against its law: a parameter the law
    does not take is refused, and the law checks its own (mu_static >= mu)."""
    name = friction["law"]
    law = _friction_law_entry(name)
    takes = {parameter["key"] for parameter in law["parameters"]}
    for key, value in _friction_values(friction):
        if key not in takes:
            own = sorted(takes - set(_FRICTION_COMMON))
            _fail(f"friction.{key}", value,
                  f"absent with friction.law = {name!r}: that law takes "
                  + (", ".join(own) + " besides mu" if own else "mu alone")
                  + (" and k_v" if "k_v" in takes else ""))
    values = [("mu", friction["mu"])] + _friction_values(friction)
    if "k_v" in takes:
        values.append(("k_v", friction["k_v"]))
    _core.check_friction_law(name, values)


SCHEMA: Dict[str, Any] = {
    "concept": Field("model concept of thesis section 4.1: 'rigid' (4.1.1, one degree of "
                     "freedom without backlash), 'flexible_nut' (4.1.2), 'flexible' (4.1.3, "
                     "flexible screw and nut)", default="rigid", kind="choice",
                     choices=_CHOICES["concept"]),
    "drive": Field("which part the motor turns: 'screw' (axially fixed screw, the nut and "
                   "load translate, Fig. 3.2) or 'nut' (axially fixed nut, the screw and "
                   "load translate, Fig. 3.1)", default="screw", kind="choice",
                   choices=_CHOICES["drive"]),
    "thread": {
        "pitch": Field("axial distance between neighbouring flanks", "m", None, **POSITIVE),
        "mean_diameter": Field("mean (pitch) diameter d_m = 2 r_m; with the lead, 1e-6 <= "
                               "tan(alpha) = lead / (pi d_m) <= 1e6 (Scene.derived and "
                               "Scene.model check it: a flatter or steeper thread leaves "
                               "what the models resolve)", "m", None, **POSITIVE),
        "starts": Field("number of thread starts (lead = starts * pitch), 1 to 100 (lead "
                        "screws have up to about 16)", "", 1, kind="int", low=1, high=100),
        "flank_angle": Field("included thread angle beta: 0 square, 29 deg Acme, 30 deg ISO "
                             "trapezoidal", "rad", 0.0, low=0.0, high=math.pi, high_open=True),
        "hand": Field("thread hand", "", "right", kind="choice", choices=("right", "left")),
    },
    "friction": _friction_section(),
    "backlash": {
        "axial": Field("total axial clearance c_a of the thread (a relaxed start puts the nut at "
                       "initial.play_position, by default centred)", "m",
                       None, **NONNEGATIVE),
        "contact": Field("flank contact across the play: 'exact' (unilateral contacts, Newton "
                         "impacts), 'bistop' (Adams BISTOP penalty), 'cubic' (smooth cubic "
                         "penalty, cf. thesis Fig. 2.6)", "", "exact", kind="choice",
                         choices=_CHOICES["backlash.contact"]),
        "restitution": Field("Newton restitution coefficient of flank impacts ('exact')", "",
                             0.0, low=0.0, high=1.0),
        "stiffness": Field("contact stiffness k of 'bistop' in N/m^exponent (a string is "
                           "converted to that unit: \"1e7 N/mm^1.5\" for exponent 1.5) and of "
                           "'cubic' in N/m (default: the nut's axial stiffness E_M A_M / l_M, "
                           "for 'bistop' scaled to d_0^(1 - exponent) so that both give the "
                           "same force at the penetration d_0)", "N/m", OPTIONAL,
                           **POSITIVE),
        "exponent": Field("force exponent of 'bistop': F = k d^e, in [1, 10]", "", 1.5,
                          low=1.0, high=10.0),
        "damping": Field("maximum contact damping of 'bistop' and 'cubic' (default: "
                         "critical damping of the contact stiffness with the translating mass)",
                         "N*s/m", OPTIONAL, **NONNEGATIVE),
        "penetration": Field("penetration at which 'bistop' reaches full damping (default: "
                             "c_a / 100, at least 1e-7 m)", "m", OPTIONAL, **POSITIVE),
    },
    "screw": {
        "radius": Field("screw radius (solid cylinder)", "m", 10e-3, **POSITIVE),
        "length": Field("screw length between its supports", "m", 0.5, **POSITIVE),
        "youngs_modulus": Field("Young's modulus E_S" + _MODULUS_RANGE_DOC, "Pa", 210e9,
                                **MODULUS),
        "poisson": Field("Poisson's ratio nu_S (G = E / (2 (1 + nu)))", "", 0.3, low=-1.0,
                         high=0.5, low_open=True),
        "density": Field("density" + _DENSITY_RANGE_DOC, "kg/m^3", 7850.0, **DENSITY),
        "support": Field("axial support of a screw-driven screw: 'both_ends' (k = EA/a + "
                         "EA/(L - a), eq. 4.24) or 'drive_end' (k = EA/a); a is the nut's "
                         "distance from the drive end", "", "both_ends", kind="choice",
                         choices=_CHOICES["screw.support"]),
    },
    "nut": {
        "outer_radius": Field("outer radius of the nut (hollow cylinder; inner radius = screw "
                              "radius)", "m", 12e-3, **POSITIVE),
        "length": Field("nut length l_nM", "m", 20e-3, **POSITIVE),
        "youngs_modulus": Field("Young's modulus E_M" + _MODULUS_RANGE_DOC, "Pa", 2e9,
                                **MODULUS),
        "poisson": Field("Poisson's ratio nu_M", "", 0.3, low=-1.0, high=0.5, low_open=True),
        "density": Field("density" + _DENSITY_RANGE_DOC, "kg/m^3", 1400.0, **DENSITY),
        "position": Field("initial distance a_0 of the nut's centre from the screw's drive "
                          "end (drive='screw') or load end (drive='nut'), in (nut.length / 2, "
                          "screw.length - nut.length / 2) for both drives: the whole nut on the "
                          "screw. The model takes the nut's centre as the point where the "
                          "thread force enters the screw (screw segments a and L - a, eq. 4.24); "
                          "nut.length sets the nut's mass and stiffness, and a run of any "
                          "concept ends (SimulationError) where the nut's end reaches the "
                          "screw's", "m", 0.1, **POSITIVE),
    },
    "rotor": {
        "inertia": Field("rotor inertia about the screw axis", "kg*m^2", 1e-5, **POSITIVE),
    },
    "load": {
        "mass": Field("load mass carried by the translating part", "kg", 1.0, **NONNEGATIVE),
    },
    "overrides": {
        "screw_mass": Field("screw mass (default: density * volume)", "kg", OPTIONAL,
                            **POSITIVE),
        "screw_inertia": Field("screw polar inertia (default m r^2 / 2)", "kg*m^2", OPTIONAL,
                               **POSITIVE),
        "nut_mass": Field("nut mass (default: density * volume)", "kg", OPTIONAL, **POSITIVE),
        "nut_inertia": Field("nut polar inertia (default m (r_o^2 + r_i^2) / 2)", "kg*m^2",
                             OPTIONAL, **POSITIVE),
        "screw_axial_stiffness": Field("screw axial stiffness (replaces eq. 4.24; then "
                                       "constant)", "N/m", OPTIONAL, **POSITIVE),
        "screw_torsional_stiffness": Field("screw torsional stiffness (replaces G I_p / a; "
                                           "then constant)", "N*m/rad", OPTIONAL, **POSITIVE),
        "nut_axial_stiffness": Field("nut axial stiffness (replaces E A / l, eq. 4.17)", "N/m",
                                     OPTIONAL, **POSITIVE),
        "nut_torsional_stiffness": Field("nut torsional stiffness (replaces G I_p / l)",
                                         "N*m/rad", OPTIONAL, **POSITIVE),
        "damping_ratio": Field("damping ratio zeta of every spring, c = 2 zeta sqrt(k m) with "
                               "m the larger mass (or inertia) of the two bodies it connects, "
                               "at most 10 (zeta > 1 is overdamped already; a larger one would "
                               "make damping time scales no integrator resolves: set the "
                               "damping coefficients below instead)", "", 0.05, low=0.0,
                               high=10.0),
        "screw_axial_damping": Field("screw axial damping", "N*s/m", OPTIONAL, **NONNEGATIVE),
        "screw_torsional_damping": Field("screw torsional damping", "N*m*s/rad", OPTIONAL,
                                         **NONNEGATIVE),
        "nut_axial_damping": Field("nut axial damping", "N*s/m", OPTIONAL, **NONNEGATIVE),
        "nut_torsional_damping": Field("nut torsional damping", "N*m*s/rad", OPTIONAL,
                                       **NONNEGATIVE),
    },
    "loads": {
        "drive_torque": Field("motor torque on the rotor about +x: a number, "
                              "{'type': 'sine'|'constant'|'table', ...} or an Excitation or "
                              "callable (default 0 unless drive_speed is given; the default is "
                              "applied in the model, not stored in the scene)", "N*m",
                              OPTIONAL, kind="load"),
        "drive_speed": Field("instead of drive_torque: a speed-controlled motor prescribing "
                             "the rotor's angular velocity; the torque it takes is reported",
                             "rad/s", OPTIONAL, kind="load"),
        "axial_force": Field("axial force on the load along +x", "N", 0.0, kind="load"),
    },
    # (Absent: no motor element; loads.drive_torque or loads.drive_speed drive the rotor.)
    "motor": {
        "type": Field("the motor driving the rotor instead of loads.drive_torque or "
                      "loads.drive_speed (exclusive with both): 'dc', a permanent-magnet DC "
                      "motor on the rotor (rotor.inertia is its inertia) with the armature "
                      "L di/dt = U_d - R i - k_e omega and the torque k_t i; its current i "
                      "starts at 0 (the driver switched on at t = 0)", "", None,
                      kind="choice", choices=("dc",)),
        "voltage": Field("the driver's voltage U(t): a number, {'type': "
                         "'sine'|'constant'|'table', ...} or an Excitation or callable",
                         "V", None, kind="load"),
        "resistance": Field("armature resistance R (terminal to terminal)", "ohm", None,
                            **POSITIVE),
        "inductance": Field("armature inductance L; 0 is the quasi-static limit, exact: "
                            "i = (U - k_e omega) / R without a state", "H", 0.0,
                            **NONNEGATIVE),
        "torque_constant": Field("torque constant k_t: the torque k_t i on the rotor",
                                 "N*m/A", None, **POSITIVE),
        "back_emf_constant": Field("back-EMF constant k_e (equal to k_t in SI for a real "
                                   "motor; where they differ the motor converts "
                                   "(k_t - k_e) i omega out of nothing, which work_drive "
                                   "books)", "V*s/rad", OPTIONAL,
                                   default_doc="motor.torque_constant", **POSITIVE),
        "current_limit": Field("the driver's current limit i_max: a voltage source with "
                               "current limiting, which where |i| reaches i_max and U(t) would "
                               "drive it further lowers its output to U_d = R i + k_e omega, "
                               "holding |i| = i_max (an event starts and ends the hold; "
                               "inductance 0: i clamped to +-i_max), and never puts out more "
                               "than U(t) (absent: no limit)", "A", OPTIONAL, **POSITIVE),
        "friction_torque": Field("the motor's own Coulomb friction torque: not modelled yet, "
                                 "must be 0 (a value is refused rather than approximated; "
                                 "put the motor's friction into friction.mu for now)", "N*m",
                                 0.0, **NONNEGATIVE),
    },
    "initial": {
        "rotor_angle": Field("rotor angle at t = 0", "rad", 0.0),
        "rotor_speed": Field("rotor angular velocity at t = 0; every body moves consistently "
                             "with the thread, springs relaxed (state 'relaxed'). A "
                             "speed-controlled drive (loads.drive_speed) starts at drive_speed(0): "
                             "leave rotor_speed out, or give that value (another one is refused)",
                             "rad/s", OPTIONAL, default_doc="0, or drive_speed(0) for a "
                             "speed-controlled drive"),
        "play_position": Field("axial position of the nut within the backlash, from its "
                               "centre (|value| <= axial / 2)", "m", 0.0),
        "state": Field("the state at t = 0: 'relaxed' (every spring relaxed, the nut at "
                       "play_position, every body turning with the thread at rotor_speed) or "
                       "'equilibrium' (at rest in static equilibrium under the loads at "
                       "t = 0: the springs deflected, the nut on the flank the loads press it "
                       "against, a penalty flank penetrated as far as its force takes, the "
                       "thread stuck with its friction force inside the static cone; "
                       "rotor_speed and play_position 0, a torque-controlled motor; "
                       "NoEquilibriumError where "
                       "the loads drive the thread. A regularized law, which carries no "
                       "friction at rest, starts from that state and slips from it; LuGre's "
                       "bristles start relaxed. "
                       "Scene.initial_state() gives the state)", "", "relaxed", kind="choice",
                       choices=_CHOICES["initial.state"]),
    },
}

# Sections that may be absent: then they take their defaults, except backlash
# (absent: a thread without play) and overrides.
_REQUIRED_SECTIONS = ("thread", "friction")
_OPTIONAL_SECTIONS = ("backlash", "motor")


def _fail(path: str, value: Any, allowed: str) -> None:
    raise ValueError(f"{path} = {value!r} is invalid: must be {allowed}")


def _range_text(f: Field) -> str:
    lo = "(" if f.low_open else "["
    hi = ")" if f.high_open else "]"
    number = "an integer" if f.kind == "int" else "a finite number"
    if f.low == -math.inf and f.high == math.inf:
        return number
    if f.high == math.inf:
        return f"{number} {'>' if f.low_open else '>='} {f.low:g}"
    return f"{number} in {lo}{f.low:g}, {f.high:g}{hi}"


_LOAD_TYPES = {"constant": ("value",), "sine": ("amplitude", "omega", "phase", "offset"),
               "table": ("times", "values")}
# Units of the entries of a load table; None: the unit of the load itself.
_LOAD_ENTRY_UNITS = {"value": None, "amplitude": None, "offset": None, "values": None,
                     "omega": "rad/s", "phase": "rad", "times": "s"}

# Fields whose unit depends on other fields of their section (checked after
# them; _field_unit says on which).
_UNIT_DEPENDS_ON = frozenset({("friction", "k_v"), ("backlash", "stiffness")})


def _power_text(exponent: float) -> str:
    """An exponent as unit text that parses back to the same float."""
    return str(int(exponent)) if float(exponent).is_integer() else repr(float(exponent))


def _field_unit(section: str, key: str, f: Field, values: Dict[str, Any]) -> str:
    """The unit of a field, given the (checked) values of its section: k_v is
    in s^2/m for 'arctan_acceleration', a 'bistop' stiffness in N/m^exponent."""
    if (section, key) == ("friction", "k_v") and values.get("law") == "arctan_acceleration":
        return "s^2/m"
    if (section, key) == ("backlash", "stiffness") and values.get("contact") == "bistop":
        exponent = values.get("exponent", SCHEMA["backlash"]["exponent"].default)
        return "N/m" if exponent == 1.0 else f"N/m^{_power_text(exponent)}"
    return f.unit


def _load_entry_to_si(path: str, key: str, entry: Any, unit: str):
    """An entry of a load table as float(s) in its unit: a number or a list of
    numbers, each a real number (not a bool) or a string with a unit.

    Raises:
        ValueError: naming ``path.key`` (or ``path.key[i]``), the value and
            what is allowed.
    """
    entry_unit = _LOAD_ENTRY_UNITS[key] or unit
    if key in ("times", "values"):
        items = entry.tolist() if hasattr(entry, "tolist") else entry
        if isinstance(items, (str, bytes, dict, set, frozenset)) or not isinstance(
                items, Iterable):
            _fail(f"{path}.{key}", entry, "a list of numbers" + (f" [{entry_unit}]" if entry_unit
                                                                  else ""))
        return [_load_number(f"{path}.{key}[{i}]", x, entry_unit) for i, x in enumerate(items)]
    return _load_number(f"{path}.{key}", entry, entry_unit)


def _load_number(path: str, value: Any, unit: str) -> float:
    """One number of a load table: a finite real number (numpy scalars too,
    not a bool) or a string with a unit, as float in ``unit``."""
    number = to_si(path, value, unit)
    finite = None if isinstance(number, bool) else _finite_float(number)
    if finite is None:
        shown = _Converted(value, number, unit) if isinstance(value, str) else value
        _fail(path, shown, what_it_takes(unit, "a finite number"))
    return finite


def _finite_float(value: Any) -> Optional[float]:
    """A real number as a finite float; None for anything else (NaN, inf, an
    int beyond the float range, no real number)."""
    if not isinstance(value, numbers.Real):
        return None
    try:
        number = float(value)
    except OverflowError:
        return None
    return number if math.isfinite(number) else None


def _excitation_spec(value: Any) -> Optional[Dict[str, Any]]:
    """The ``{type = ...}`` dict of a Constant, Sine or Table (None for
    anything else): a scene stores these loads as dicts, which compare equal
    by value and round-trip through TOML."""
    if isinstance(value, Constant):
        return {"type": "constant", "value": value.value}
    if isinstance(value, Sine):
        return {"type": "sine", "amplitude": value.amplitude, "omega": value.omega,
                "phase": value.phase, "offset": value.offset}
    if isinstance(value, Table):
        return {"type": "table", "times": value.times.tolist(), "values": value.values.tolist()}
    return None


def _check_load(path: str, value: Any, unit: str = ""):
    spec = _excitation_spec(value)
    if spec is not None:  # the core checked the object as it was built
        check_load_unit(path, value, unit)
        return spec
    if isinstance(value, _core.Excitation) or (callable(value) and not isinstance(value, dict)):
        return value
    value = to_si(path, value, unit)
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        number = _finite_float(value)
        if number is None:
            _fail(path, value, "finite")
        return number
    if isinstance(value, dict):
        kind = value.get("type")
        if not isinstance(kind, str) or kind not in _LOAD_TYPES:
            _fail(f"{path}.type", kind, "one of " + ", ".join(repr(k) for k in _LOAD_TYPES))
        allowed = _LOAD_TYPES[kind]
        for key in value:
            if key != "type" and key not in allowed:
                _fail(f"{path}.{key}", value[key],
                      f"absent: {kind!r} loads take {', '.join(allowed)}")
        out = {"type": kind}
        for key in allowed:
            if key in value:
                out[key] = _load_entry_to_si(path, key, value[key], unit)
            elif kind == "sine" and key in ("phase", "offset"):
                out[key] = 0.0
            else:
                raise ValueError(f"{path}.{key} is missing: a {kind!r} load needs "
                                 f"{', '.join(allowed)}")
        try:
            _make_excitation(out)
        except ValueError as error:
            raise ValueError(f"{path}: {error}") from None
        return out
    _fail(path, value, "a number, a dict with 'type' in constant/sine/table, an Excitation "
          "or a callable f(t)")


def _make_excitation(spec, key: str = ""):
    """An Excitation (or number, or checked callable) from a validated load
    value; ``key`` (of ``loads``) names a Python callable's load in its errors."""
    if isinstance(spec, dict):
        kind = spec["type"]
        if kind == "constant":
            return Constant(spec["value"])
        if kind == "sine":
            return Sine(spec["amplitude"], spec["omega"], spec["phase"], spec["offset"])
        return Table(spec["times"], spec["values"])
    if spec.__class__ is not float and callable(spec) and not isinstance(spec, _core.Excitation):
        return checked_callable(f"loads.{key}", spec, SCHEMA["loads"][key].unit)
    return spec


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


class _Converted:
    """A value given with a unit, shown in messages as given and converted."""

    def __init__(self, given: str, value: Any, unit: str):
        self.text = json.dumps(given) + (f" (= {value!r} {unit})".rstrip() if unit else "")

    def __repr__(self) -> str:
        return self.text


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
        allowed = "a number, a dict with 'type' in constant/sine/table, an Excitation or a callable"
    else:
        allowed = _range_text(f) + (f" [{f.unit}]" if f.unit else "")
    if f.default is None:
        hint = f"{path} is required; leave it out of Scene.replace to keep the scene's value"
    else:
        hint = (f"leave {path} out for its default {f.default!r}, or out of Scene.replace to "
                "keep the scene's value")
    _fail(path, None, f"{allowed} (None removes only an optional field: {hint})")


def _validate_section(path: str, schema: Dict[str, Field], given: Dict[str, Any]) -> Dict[str, Any]:
    if not isinstance(given, dict):
        _fail(path, given, "a table (dict) of fields")
    for key in given:
        if key not in schema:
            raise ValueError(f"{path}.{key} is not a known key; {path} takes "
                             f"{', '.join(schema)}")
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
            raise ValueError(f"{key} is not a known section; a scene has "
                             f"{', '.join(SCHEMA)}")


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


def _copy_tree(value: Any) -> Any:
    """A copy of a scene's nested dicts and lists. The leaves are numbers,
    strings, excitations (immutable) and user callables (shared, as
    copy.deepcopy shares functions), so this equals a deep copy at a fraction
    of its cost."""
    if isinstance(value, dict):
        return {key: _copy_tree(item) for key, item in value.items()}
    if isinstance(value, list):
        return [_copy_tree(item) for item in value]
    return value


class Scene:
    """A validated lead-screw drive description (immutable).

    Build it with :meth:`from_dict`; read it back with :meth:`to_dict` or
    item access (``scene["thread"]["pitch"]``).
    """

    def __init__(self, data: Dict[str, Any]):
        self._data = data
        # The core's model, built on the first model() call: a scene is
        # immutable and so is its model, and building it (the derivation,
        # the checks) was a third of a rigid drive's 60 us simulate call.
        self._model = None

    def __getstate__(self) -> Dict[str, Any]:
        # (Pickled without the core's model, which does not pickle: a scene
        # sent to a process pool builds its own.)
        return {"_data": self._data}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self.__init__(state["_data"])

    @classmethod
    def from_dict(cls, d: Dict[str, Any]) -> "Scene":
        """Validate a scene dict and fill its defaults.

        Args:
            d: nested dict with the sections of :data:`SCHEMA`.

        Returns:
            The scene.

        Raises:
            ValueError: unknown key, missing required key, None for a field
                that is not optional (it would not mean its default), or
                value out of range; the message names the key path, the value
                and what is allowed.
        """
        if not isinstance(d, dict):
            _fail("scene", d, "a dict of sections")
        _check_section_names(d)
        data: Dict[str, Any] = {}
        for key in SCHEMA:
            _validate_entry(key, d, data)
        _check_consistency(data)
        return cls(data)

    def to_dict(self) -> Dict[str, Any]:
        """The complete scene as a nested dict (a deep copy)."""
        return _copy_tree(self._data)

    @classmethod
    def from_toml(cls, path: "str | os.PathLike[str]") -> "Scene":
        """Read a scene file: TOML with the sections of :meth:`from_dict`.

        Values are SI numbers or strings with units (``pitch = "1 mm"``); see
        :mod:`leadscrew.units`.

        Args:
            path: the file.

        Returns:
            The scene.

        Raises:
            OSError: the file cannot be read.
            ValueError: ``path`` is a directory, the file is empty (or holds
                only comments), a TOML syntax error (the message gives the
                file, line and column) or an invalid scene (as
                :meth:`from_dict`: unknown key, missing section or key, wrong
                dimension, value out of range; the message gives the file and
                the key path).
        """
        if os.path.isdir(path):
            files = sorted(entry.name for entry in os.scandir(path)
                           if entry.name.endswith(".toml") and entry.is_file())
            hint = (f"; it holds {', '.join(files[:5])}{', ...' if len(files) > 5 else ''}"
                    if files else "; it holds no .toml file")
            raise ValueError(f"{os.fspath(path)}: is a directory, not a scene file (a TOML "
                             f"file){hint}")
        with open(path, "rb") as stream:
            raw = stream.read()
        return cls(_from_toml_text(raw, os.fspath(path))._data)

    def to_toml(self, path: "Optional[str | os.PathLike[str]]" = None) -> str:
        """The scene as TOML text: SI numbers, each commented with its unit.

        :meth:`from_toml` reads the file back to an equal scene (floats are
        written with ``repr``, which round-trips exactly). Loads given as
        :class:`~leadscrew.Constant`, :class:`~leadscrew.Sine` or
        :class:`~leadscrew.Table` are stored, and written, as their
        ``{type = ...}`` tables. An absent drive torque (the default 0) stays
        absent.

        Args:
            path: the file to write (UTF-8); None only returns the text.

        Returns:
            The TOML text.

        Raises:
            ValueError: a load is a Python callable or a bare C++ excitation,
                which a scene file cannot hold (the message names the key).
        """
        text = _to_toml_text(self._data)
        if path is not None:
            with open(path, "w", encoding="utf-8", newline="\n") as stream:
                stream.write(text)
        return text

    def to_core_toml(self, path: "Optional[str | os.PathLike[str]]" = None,
                     **options) -> str:
        """The scene's core spec: the drive as the C++ core runs it, in TOML,
        for the C API (``leadscrew.h``) and programs without Python.

        Every value is an SI number and every default and derived value
        explicit (masses, inertias, stiffnesses, damping, the loads as
        constant, sine or table), with the run's options (an ``[options]``
        table). One C++ writer and reader define the format
        (``cpp/include/leadscrew/model/core_spec.hpp``).

        Args:
            path: the file to write (UTF-8); None only returns the text.
            **options: the run's options as :func:`leadscrew.simulate` takes
                them (``integrator``, ``smooth_integrator``, ``rtol``,
                ``atol``, ``max_steps``, ``max_events``, ``max_step``,
                ``first_step``, ``bounce_threshold``, ``max_order``), with its
                defaults.

        Returns:
            The TOML text.

        Raises:
            ValueError: a load is a Python callable (no file can carry it),
                a derived value is out of range (as :meth:`model`), or an
                unknown option (naming it).
        """
        from .simulation import _run_options

        known = ("integrator", "smooth_integrator", "rtol", "atol", "max_steps", "max_events",
                 "max_step", "first_step", "bounce_threshold", "max_order")
        for name in options:
            if name not in known:
                raise ValueError(f"{name} = {options[name]!r} is invalid: to_core_toml takes "
                                 f"the options {', '.join(known)}")
        text = _core.write_core_spec(self.model().parameters, **_run_options(**options))
        if path is not None:
            with open(path, "w", encoding="utf-8", newline="\n") as stream:
                stream.write(text)
        return text

    def __getitem__(self, key: str):
        return _copy_tree(self._data[key])

    def __contains__(self, key: str) -> bool:
        return key in self._data

    def replace(self, **sections) -> "Scene":
        """A new scene with some fields changed: ``scene.replace(friction={"mu": 0.1})``
        merges into the named sections (``backlash=None`` removes the backlash;
        None for an optional field removes it, ``loads={"drive_torque": None}``;
        None for any other field is refused, as by :meth:`from_dict`: leave
        the key out to keep the scene's value).

        Raises:
            ValueError: as :meth:`from_dict`.
        """
        _check_section_names(sections)
        # Only the named sections are merged and checked again: the others are
        # valid already and shared with this scene (a Scene never mutates its
        # data; to_dict and item access return copies). The cross-section
        # checks run on the whole result.
        merged: Dict[str, Any] = dict(self._data)
        for key, value in sections.items():
            if value is None:
                merged.pop(key, None)
            elif isinstance(value, dict) and isinstance(merged.get(key), dict):
                merged[key] = {**merged[key], **value}
            else:
                merged[key] = value
        data: Dict[str, Any] = {}
        for key in SCHEMA:
            if key in sections:
                _validate_entry(key, merged, data)
            elif key in merged:
                data[key] = merged[key]
        _check_consistency(data)
        return Scene(data)

    def derived(self) -> Dict[str, Any]:
        """Derived parameters with every override applied.

        Returns:
            dict with masses [kg], inertias [kg*m^2], rigidities E A [N] and
            G I_p [N*m^2], stiffnesses [N/m, N*m/rad] (0 for a screw stiffness
            that follows the nut position) and, with backlash, the contact
            stiffness, damping and penetration defaults; each finite and
            in range.

        Raises:
            ValueError: a derived quantity is not finite, zero where it must
                be positive, or the lead angle out of range (tan(alpha) in
                [1e-6, 1e6]); the message names the input(s) that made it so
                (``nut.density = 5e-324 is invalid: with it the nut's mass
                (...) comes to 0.0 kg: must be a finite number > 0 (or set
                overrides.nut_mass)``).
        """
        return _derived(self._data)

    def model(self) -> "_core.DriveModel":
        """The assembled C++ model: coordinates, masses, springs, degrees of freedom.

        Raises:
            ValueError: a derived value is out of range (as :meth:`derived`,
                or as the core checks it, e.g. zero load mass on a flexible
                part, a spring's damping that is not finite); the message
                names the input(s) that made it so.
        """
        if self._model is None:
            self._model = _model(self._data)
        return self._model

    def initial_state(self) -> Dict[str, Any]:
        """The state the run starts from (``initial.state``), as the core computes it.

        Returns:
            dict with ``q`` and ``v``: coordinate name -> displacement from
            the reference configuration (springs relaxed, the nut at
            ``initial.play_position``) [m or rad] and velocity [m/s or
            rad/s]; ``play`` [m], the nut's place in the play (0 without
            backlash); ``normal_force`` and ``friction_force`` [N], the flank
            forces holding the loads at t = 0 (0 for a relaxed start);
            ``iterations``, Newton's (0 for a relaxed start).

        Raises:
            NoEquilibriumError: (a ValueError) ``initial.state`` is
                ``'equilibrium'`` and the loads at t = 0 drive the thread.
            ValueError: as :meth:`model`.
            SimulationError: the equilibrium's solve did not converge.
        """
        model = self.model()
        start = model.initial_state()
        names = model.coordinate_names
        return {"q": dict(zip(names, map(float, start["q"]))),
                "v": dict(zip(names, map(float, start["v"]))),
                "play": float(start["play"]), "normal_force": float(start["normal_force"]),
                "friction_force": float(start["friction_force"]),
                "iterations": int(start["iterations"])}

    @property
    def thread(self) -> Thread:
        return _thread(self._data)

    def __repr__(self) -> str:
        b = self._data.get("backlash")
        play = f", backlash {b['axial']:g} m {b['contact']}" if b else ""
        return (f"<Scene {self._data['concept']}, drive={self._data['drive']}, "
                f"{self._data['friction']['law']} mu={self._data['friction']['mu']:g}{play}>")

    def __eq__(self, other) -> bool:
        """Equal data, an absent drive torque counting as its default 0 (both
        build the same model). Loads given as Constant, Sine or Table objects
        are stored as their dicts and so compare by value; a bare C++
        Excitation or a callable compares by identity."""
        return isinstance(other, Scene) and _effective(self._data) == _effective(other._data)


# The drive torque of a scene that gives neither drive_torque nor drive_speed.
_DEFAULT_DRIVE_TORQUE = 0.0
# The initial rotor speed of a torque-driven scene that gives none.
_DEFAULT_ROTOR_SPEED = 0.0


def _effective(data: Dict[str, Any]) -> Dict[str, Any]:
    """The scene data with the defaults the model applies filled in (for
    comparing): the drive torque, and the initial rotor speed (that of a
    speed-controlled drive is drive_speed(0), whether given or not)."""
    loads, initial = data["loads"], data["initial"]
    if "drive_speed" in loads:
        initial = {k: v for k, v in initial.items() if k != "rotor_speed"}
    else:
        initial = {"rotor_speed": _DEFAULT_ROTOR_SPEED, **initial}
    if not ("drive_torque" in loads or "drive_speed" in loads):
        loads = {**loads, "drive_torque": _DEFAULT_DRIVE_TORQUE}
    return {**data, "loads": loads, "initial": initial}


def _check_rotor_speed(data: Dict[str, Any]) -> None:
    """A rotor speed given for a speed-controlled drive must be the speed the
    drive prescribes at t = 0 (the run starts there: another value would be
    overridden silently).

    Raises:
        ValueError: naming initial.rotor_speed, its value and drive_speed(0).
    """
    speed = data["initial"].get("rotor_speed")
    if speed is None or "drive_speed" not in data["loads"]:
        return
    load = _make_excitation(data["loads"]["drive_speed"], "drive_speed")
    prescribed = float(load if isinstance(load, numbers.Real) else load(0.0))
    # Round-off of the load's evaluation (a sine's offset + amplitude sin(phase)).
    if not math.isclose(speed, prescribed, rel_tol=1e-12, abs_tol=1e-12):
        _fail("initial.rotor_speed", speed,
              f"{prescribed!r} rad/s or absent: loads.drive_speed prescribes {prescribed!r} "
              "rad/s at t = 0, where a speed-controlled drive starts")


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


def _check_motor(data: Dict[str, Any]) -> None:
    """The motor section's rules across sections: exclusive with the drive
    loads, no equilibrium start, no friction torque yet.

    Raises:
        ValueError: naming the keys at fault and their values.
    """
    motor, loads = data["motor"], data["loads"]
    for key in ("drive_torque", "drive_speed"):
        if key in loads:
            raise ValueError(f"loads.{key} = {loads[key]!r} is invalid with motor.type = "
                             f"{motor['type']!r}: give either motor or loads.{key}, not both")
    if motor["friction_torque"] != 0.0:
        _fail("motor.friction_torque", motor["friction_torque"],
              "0 (the motor's own Coulomb friction is not modelled yet)")
    if data["initial"]["state"] == "equilibrium":
        raise ValueError("initial.state = 'equilibrium' is invalid with motor.type = "
                         f"{motor['type']!r}: the run starts with the current at 0 (use "
                         "'relaxed')")


def describe_schema() -> str:
    """The documentation of every scene field: key path, unit, default, meaning."""
    lines = []
    for key, entry in SCHEMA.items():
        items = [(key, entry)] if isinstance(entry, Field) else [
            (f"{key}.{k}", f) for k, f in entry.items()]
        for path, f in items:
            if f.default is None:
                default = "required"
            elif f.default_doc:
                default = f.default_doc
            elif f.default is OPTIONAL:
                default = "optional"
            else:
                default = repr(f.default)
            unit = f" [{f.unit}]" if f.unit else ""
            lines.append(f"{path}{unit} (default {default}): {f.doc}")
    return "\n".join(lines)


# The scene's inputs of the derivation (_core.DriveGeometry's fields, named
# <section>_<key>): always present, and optional (None where absent).
_GEOMETRY_FIELDS = (("thread", ("pitch", "mean_diameter", "starts", "flank_angle")),
                    ("friction", ("mu",)),
                    ("screw", ("radius", "length", "density", "youngs_modulus", "poisson")),
                    ("nut", ("outer_radius", "length", "density", "youngs_modulus", "poisson")),
                    ("load", ("mass",)))
_OPTIONAL_GEOMETRY_FIELDS = (("backlash", ("stiffness", "damping", "penetration")),
                             ("overrides", ("screw_mass", "screw_inertia", "nut_mass",
                                            "nut_inertia", "screw_axial_stiffness",
                                            "screw_torsional_stiffness", "nut_axial_stiffness",
                                            "nut_torsional_stiffness")))


def _geometry(data: Dict[str, Any]) -> "_core.DriveGeometry":
    """The core's DriveGeometry of a (checked) scene."""
    g = _core.DriveGeometry()
    g.drive = data["drive"]
    for section, keys in _GEOMETRY_FIELDS:
        values = data[section]
        for key in keys:
            setattr(g, f"{section}_{key}", values[key])
    backlash = data.get("backlash")
    if backlash is not None:
        g.backlash_contact = backlash["contact"]
        g.backlash_axial, g.backlash_exponent = backlash["axial"], backlash["exponent"]
    for section, keys in _OPTIONAL_GEOMETRY_FIELDS:
        values = data.get(section) or {}
        for key in keys:
            setattr(g, f"{section}_{key}", values.get(key))
    return g


def _derivation(data: Dict[str, Any]) -> "_core.DerivedQuantities":
    """The core's derivation of the scene's masses, inertias, rigidities and
    stiffnesses (``_core.derive_drive``: thesis eq. 4.17, 4.18, 4.24,
    overrides applied), every quantity in its range.

    Raises:
        ValueError: a quantity is out of its range (the core's verdict), naming
            the inputs that made it so (see :func:`_blamed`), e.g.
            ``nut.density = 5e-324 is invalid: with it the nut's mass (...)
            comes to 0.0 kg: must be a finite number > 0 (or set
            overrides.nut_mass)``.
    """
    derivation = _core.derive_drive(_geometry(data))
    key = derivation.problem
    if key is None:
        return derivation
    quantity = _QUANTITY[key]
    value = derivation.quantities[key]

    def still_bad(changed: Dict[str, Any]) -> bool:
        value = _quantity_values(changed).get(key)
        return value is not None and quantity.problem(value) is not None

    hint = f" (or set {quantity.override})" if quantity.override else ""
    unit = f" {quantity.unit}" if quantity.unit else ""
    raise _blamed(data, still_bad, f"{quantity.text} comes to {value!r}{unit}: must be "
                                   f"{quantity.problem(value)}{hint}")


def _derived(data: Dict[str, Any]) -> Dict[str, Any]:
    """Scene.derived(): the checked derivation's values (:func:`_derivation`)."""
    return _derivation(data).derived


@dataclass(frozen=True)
class _Quantity:
    """A quantity the core derives and checks (``_core.derived_quantities()``):
    its key (in derived() or tan_lead_angle, effective_mu), its text for
    messages, unit and the override that replaces it."""

    key: str
    text: str
    unit: str
    override: str = ""

    def problem(self, value: float) -> Optional[str]:
        """None if ``value`` is in the core's range of the quantity, else what it must be."""
        return _core.derived_quantity_problem(self.key, value)


_QUANTITIES = tuple(_Quantity(q["key"], q["text"], q["unit"], q["override"])
                    for q in _core.derived_quantities())
_QUANTITY = {q.key: q for q in _QUANTITIES}


def _quantity_values(data: Dict[str, Any]) -> Dict[str, float]:
    """Every quantity the core derives from ``data``, unchecked."""
    return _core.derive_drive(_geometry(data)).quantities


def _in_range(values: Dict[str, float], thread: Dict[str, float]) -> bool:
    """Whether every quantity of ``values`` and ``thread`` (tan_lead_angle,
    effective_mu) is in its range: the core's verdict on them all at once."""
    return _core.first_derived_problem(list({**thread, **values}.items())) is None


def _model(data: Dict[str, Any]) -> "_core.DriveModel":
    """The core's model of a scene, its springs checked (``_core.spring_frequency_problem``).

    A ValueError of the core that names an internal quantity (a spring's
    damping, a part's mass) names the scene's inputs that made it so instead
    (see :func:`_blamed`); one that names a key of the scene stays as it is.
    """
    derivation = _derivation(data)  # ValueError naming the inputs itself
    try:
        model = _core.DriveModel(_core_parameters(data, derivation))
    except ValueError as error:
        message = str(error)
        name, _, rest = message.partition(" = ")
        if name in _FIELD_PATHS:  # the core names a key of the scene itself
            raise
        value, _, why = rest.partition(" is invalid: ")
        raise _blamed(data, _model_is_bad, f"the model's {name} comes to {value}: {why}" if why
                      else f"the model cannot be built: {message}") from None
    # A part too stiff for its mass (the core's rule, sqrt(k / m) <= 1e12 rad/s).
    why = _core.spring_frequency_problem(model)
    if why is not None:
        raise _blamed(data, _model_is_bad, why)
    return model


def _model_is_bad(data: Dict[str, Any]) -> bool:
    """Whether the scene ``data`` has no model (:func:`_model`'s checks)."""
    try:
        derivation = _derivation(data)
        model = _core.DriveModel(_core_parameters(data, derivation))
    except ValueError:
        return True
    return _core.spring_frequency_problem(model) is not None


# The key paths of the numeric fields, and the value each is set back to
# when _blamed asks whether it made a quantity go wrong: its default, absent
# for an optional one (derived again), or for a required one the thesis's
# Table 5.1 drive's (pitch 1 mm, d_m 20 mm, mu 0.3; play 0.1 mm).
_FIELD_PATHS = frozenset(f"{section}.{key}" for section, entry in SCHEMA.items()
                         if isinstance(entry, dict) for key in entry)
_ABSENT = object()
_REFERENCE_VALUES = {"thread.pitch": 1e-3, "thread.mean_diameter": 20e-3, "friction.mu": 0.3,
                     "backlash.axial": 1e-4}


def _reference_value(section: str, key: str, f: Field) -> Any:
    if f.default is OPTIONAL:
        return _ABSENT
    if f.default is None:
        return _REFERENCE_VALUES[f"{section}.{key}"]
    return f.default


def _changed(data: Dict[str, Any], paths) -> Dict[str, Any]:
    """``data`` with the fields ``paths`` set back to their reference values."""
    out = dict(data)
    for path in paths:
        section, key = path.split(".")
        values = out[section] = dict(out[section])
        value = _reference_value(section, key, SCHEMA[section][key])
        if value is _ABSENT:
            values.pop(key, None)
        else:
            values[key] = value
    return out


def _blamed(data: Dict[str, Any], still_bad: Callable[[Dict[str, Any]], bool],
            why: str) -> ValueError:
    """The ValueError for a problem ``why`` of a scene's derived quantities,
    naming the inputs that caused it.

    An input caused it if setting it back to its reference value (default,
    absent, or the thesis drive's for a required field) ends the problem
    (``still_bad`` false). If no single input does, the smallest set found
    by setting all back and then restoring one by one while the problem
    stays away is named (together); if even setting all back leaves it, all
    numeric inputs that differ from their references are named.
    """
    candidates = []
    for section, entry in SCHEMA.items():
        if isinstance(entry, Field) or section not in data:
            continue
        for key, f in entry.items():
            if f.kind not in ("float", "int") or key not in data[section]:
                continue
            if data[section][key] != _reference_value(section, key, f):
                candidates.append(f"{section}.{key}")
    culprits = [path for path in candidates if not still_bad(_changed(data, [path]))]
    together = not culprits
    if together:
        culprits = list(candidates)
        if not still_bad(_changed(data, culprits)):
            for path in list(culprits):
                fewer = [p for p in culprits if p != path]
                if not still_bad(_changed(data, fewer)):
                    culprits = fewer
    shown = [f"{path} = {_field_value(data, path)!r}" for path in culprits] or ["the scene"]
    if len(shown) == 1:
        return ValueError(f"{shown[0]} is invalid: with it {why}")
    joined = (" and " if together else " or ").join(shown)
    verb = "are invalid together" if together else "is invalid"
    return ValueError(f"{joined} {verb}: with {'them' if together else 'it'} {why}")


def _field_value(data: Dict[str, Any], path: str) -> Any:
    section, key = path.split(".")
    return data[section][key]


def _thread(data: Dict[str, Any]) -> Thread:
    t = data["thread"]
    return Thread._validated(t["pitch"], t["mean_diameter"], t["starts"], t["flank_angle"],
                        t["hand"])


def _core_parameters(data: Dict[str, Any],
                     derivation: "_core.DerivedQuantities") -> "_core.DriveParameters":
    """The core's parameters of a scene, ``derivation`` its derived values
    (:func:`_derivation`)."""
    p = _core.DriveParameters()
    p.concept = data["concept"]
    p.drive = data["drive"]
    p.thread = _thread(data)
    f = data["friction"]
    p.friction, p.mu, p.k_v = f["law"], f["mu"], f["k_v"]
    p.friction_values = _friction_values(f)
    derivation.apply_to(p)  # masses, inertias, stiffnesses, the contact's values
    backlash = data.get("backlash")
    if backlash is not None:
        p.backlash = backlash["contact"]
        p.clearance = backlash["axial"]
        p.restitution = backlash["restitution"]
        p.contact_exponent = backlash["exponent"]
    p.rotor_inertia = data["rotor"]["inertia"]
    p.load_mass = data["load"]["mass"]
    p.screw_length = data["screw"]["length"]
    p.nut_position = data["nut"]["position"]
    p.nut_length = data["nut"]["length"]
    p.support = data["screw"]["support"]
    over = data["overrides"]
    p.damping_ratio = over["damping_ratio"]
    for key in ("screw_axial_damping", "screw_torsional_damping", "nut_axial_damping",
                "nut_torsional_damping"):
        setattr(p, key, over.get(key, -1.0))
    loads = data["loads"]
    given = "drive_speed" if "drive_speed" in loads else "drive_torque"
    p.speed_controlled = given == "drive_speed"
    for key in (given, "axial_force"):
        setattr(p, key, _make_excitation(loads.get(key, _DEFAULT_DRIVE_TORQUE), key))
    motor = data.get("motor")
    if motor is not None:
        p.dc_motor = True
        voltage = motor["voltage"]
        p.motor_voltage = (checked_callable("motor.voltage", voltage, "V")
                           if voltage.__class__ is not float and callable(voltage)
                           and not isinstance(voltage, _core.Excitation)
                           else _make_excitation(voltage))
        p.motor_resistance = motor["resistance"]
        p.motor_inductance = motor["inductance"]
        p.motor_torque_constant = motor["torque_constant"]
        p.motor_back_emf_constant = motor.get("back_emf_constant", -1.0)
        p.motor_current_limit = motor.get("current_limit", 0.0)
    init = data["initial"]
    # (A speed-controlled drive starts at drive_speed(0): the core takes that.)
    p.rotor_angle, p.rotor_speed, p.play_position = (
        init["rotor_angle"], init.get("rotor_speed", _DEFAULT_ROTOR_SPEED), init["play_position"])
    p.initial_state = init["state"]
    return p



# --- scene files (TOML) ---------------------------------------------------

_TOML_HEADER = ("# leadscrew scene (read it with leadscrew.Scene.from_toml).\n"
                "# Numbers are SI, in the unit noted after '#'; strings with units such as\n"
                "# \"1 mm\", \"210 GPa\" or \"2 Hz\" (= 4 pi rad/s) are accepted as well.\n")


def _toml_parser():
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - exercised on Python < 3.11 only
        import tomli as tomllib
    return tomllib


def _from_toml_text(raw: bytes, source: str) -> Scene:
    """A scene from the bytes of a TOML file; ``source`` names it in messages."""
    tomllib = _toml_parser()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        raise ValueError(f"{source}: not a UTF-8 text file ({error})") from None
    try:
        d = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{source}: TOML syntax error: {error}") from None
    if not d:
        what = "is empty" if not text.strip() else "holds no keys (only comments)"
        raise ValueError(f"{source}: the file {what}: a scene file needs at least the "
                         f"sections {', '.join(f'[{k}]' for k in _REQUIRED_SECTIONS)} "
                         "(leadscrew.scene.describe_schema() lists every field)")
    try:
        return Scene.from_dict(d)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None


def _toml_value(path: str, value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        number = float(value)
        if not math.isfinite(number):
            _fail(path, value, "finite to be written to TOML")
        return repr(number)
    if isinstance(value, str):
        return json.dumps(value)  # JSON's escapes are a subset of TOML's basic strings
    if isinstance(value, (list, tuple)) or hasattr(value, "tolist"):
        items = value.tolist() if hasattr(value, "tolist") else value
        return "[" + ", ".join(_toml_value(f"{path}[{i}]", x) for i, x in enumerate(items)) + "]"
    raise ValueError(f"{path} = {value!r} cannot be written to TOML: a scene file holds "
                     "numbers, strings and lists")


def _load_table(path: str, value: Any) -> Any:
    """A load as a TOML value: a number or a {type = ...} table."""
    if isinstance(value, dict) or (isinstance(value, numbers.Real)
                                   and not isinstance(value, bool)):
        return value
    raise ValueError(f"{path} = {value!r} cannot be written to TOML: a load in a scene file "
                     "is a number or a table {type = \"constant\" | \"sine\" | \"table\", ...}")


def _unit_comment(unit: str) -> str:
    return f"  # {unit}" if unit else ""


def _to_toml_text(data: Dict[str, Any]) -> str:
    lines = [_TOML_HEADER]
    for key, entry in SCHEMA.items():
        if isinstance(entry, Field) and key in data:
            lines.append(f"{key} = {_toml_value(key, data[key])}")
    for section, schema in SCHEMA.items():
        if isinstance(schema, Field) or section not in data:
            continue
        values = data[section]
        lines += ["", f"[{section}]"]
        tables = []
        for key, f in schema.items():
            if key not in values:
                continue
            path = f"{section}.{key}"
            unit = _field_unit(section, key, f, values)
            value = _load_table(path, values[key]) if f.kind == "load" else values[key]
            if isinstance(value, dict):
                tables.append((path, value, unit))
            else:
                lines.append(f"{key} = {_toml_value(path, value)}{_unit_comment(unit)}")
        for path, table, unit in tables:
            lines += ["", f"[{path}]"]
            for key, value in table.items():
                entry_unit = "" if key == "type" else (_LOAD_ENTRY_UNITS[key] or unit)
                lines.append(f"{key} = {_toml_value(f'{path}.{key}', value)}"
                             f"{_unit_comment(entry_unit)}")
    return "\n".join(lines) + "\n"
