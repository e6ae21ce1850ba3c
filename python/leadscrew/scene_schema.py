"""The scene's schema: every field of a scene with its unit, default and range.

:data:`SCHEMA` maps each section of a scene to its fields (:class:`Field`: the
documentation, unit, default and valid range of one key), the friction
section built from the core's registry of laws and the elements' own
sections (the end stops, ...) from the core's registry of sections
(``_core.element_sections()``); :func:`describe_schema`
prints them. The messages of a refused value (``_fail``, ``_range_text``,
``_Converted``) and the fields whose unit depends on others (``_field_unit``)
live here too, as every check of a scene uses them. The checks themselves are
in :mod:`leadscrew.scene_checks`, the loads in :mod:`leadscrew.scene_loads`.
"""

from __future__ import annotations

import copy
import functools
import json
import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

from . import _core

__all__ = ["Field", "OPTIONAL", "SCHEMA", "INTEGRATORS", "describe_schema", "friction_laws"]


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
    required_with: str = ""  # optional, but required where this holds (its check's)


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
# The gear stage's types (elements/train_friction.hpp) and the smallest
# |gear.ratio| (the core's, elements/gear.hpp).
_GEAR_TYPES = ("ideal", "lossy", "worm")
# What the train's friction stages (motor.friction_torque > 0, gear.type
# 'lossy' or 'worm') need and which schemes run them (check_train_friction,
# train_event_driven_obstacle in elements/build_drive.cpp).
_TRAIN_STAGE_RULE = (
    "initial.state = 'relaxed'; end stops, every play (backlash.contact 'exact', 'bistop' or "
    "'cubic') and a preloaded nut are allowed. With a torque (loads.drive_torque) or a DC "
    "motor Moreau-Jean (integrator = 'moreau') runs them on every concept and play with "
    "'coulomb', 'stribeck', 'arctan_velocity' and 'lugre' on the thread (a preloaded nut "
    "also lifting off with 'coulomb' or 'stribeck' without viscous), the "
    "event-driven scheme on the rigid concept without play with friction.law = 'coulomb' "
    "(mu_static too) outside the thread's Painleve regime and without a load spring or "
    "'arctan_velocity', and on the flexible concepts without play and with exact or penalty "
    "play ('exact', 'bistop', 'cubic') with friction.law = 'coulomb' (mu_static too), "
    "'stribeck' or 'arctan_velocity' (there with exact end stops, not beside exact play, "
    "and a preloaded nut too, lifting off too, 'stribeck' there without viscous; not on the "
    "rigid concept); where only "
    "Moreau-Jean fits, with mu_static, and off the rigid concept without play, it is the "
    "default. Behind a prescribed rotor speed "
    "(loads.drive_speed) the event-driven scheme runs them on every concept and play with "
    "every law, and Moreau-Jean, the default, where it runs the scene "
    "(docs/physics/gear.md, 'Friction stages')")
_SMALLEST_GEAR_RATIO = _core.smallest_gear_ratio
# The DC motor's fields: required, or given only, with motor.type = 'dc'
# (scene_checks._check_motor); without a type the section holds the
# friction_torque of a rotor driven by loads.drive_torque (issue 33).
_WITH_DC = "type 'dc'"
DC_MOTOR_FIELDS = ("voltage", "resistance", "inductance", "torque_constant",
                   "back_emf_constant", "current_limit")


@functools.lru_cache(maxsize=None)
def _friction_registry() -> Tuple[dict, ...]:
    """The core's registry of friction laws (``_core.friction_laws()``),
    read once: it does not change while the module lives, and building it
    costs 40 us a call (twice a block's simulation, which takes 25 us)."""
    return tuple(_core.friction_laws())


def friction_laws() -> List[dict]:
    """The friction laws of the registry, in its order.

    Returns:
        One dict per law: ``name``, ``doc`` (what it is), and its
        ``parameters``, each a dict with ``key``, ``unit`` (SI, ``""`` for a
        pure number), ``doc``, ``default`` (None: required or taken from
        ``default_from``, another key, as ``mu_static`` takes ``mu``) and its
        range. A scene's ``friction`` section takes the law's keys; a
        FrictionBlock's ``simulate`` takes them as keywords (its ``mu`` and
        ``mu_static`` belong to the block).
    """
    return copy.deepcopy(list(_friction_registry()))


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


@functools.lru_cache(maxsize=None)
def _element_sections() -> Tuple[dict, ...]:
    """The core's registry of the elements' own sections
    (``_core.element_sections()``: the end stops, ...), read once."""
    return tuple(_core.element_sections())


def _element_section(section: dict) -> Dict[str, Field]:
    """An element's section from its declaration in the core (its fields in
    order: doc, unit, default, optional or required, range, choices)."""
    defaults = {"required": None, "optional": OPTIONAL}
    return {field["key"]: Field(field["doc"], field["unit"],
                                defaults.get(field["presence"], field["default"]),
                                kind=field["kind"], low=field["low"], high=field["high"],
                                low_open=field["low_open"], high_open=field["high_open"],
                                choices=tuple(field["choices"]),
                                default_doc=field["default_doc"])
            for field in section["fields"]}


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
                         "penalty, cf. thesis Fig. 2.6); with friction.law 'coulomb' or "
                         "'stribeck' each runs on integrator 'event_driven' and 'moreau', the "
                         "penalty flanks with 'stribeck' also on the ODE integrators", "",
                         "exact", kind="choice",
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
        "preload": Field("preload P of a split nut: two nut halves sprung apart by a spring of "
                         "axial force P, each bearing on one flank (docs/physics/"
                         "preloaded_nut.md). 0: a plain nut. The half on the flank the axial "
                         "load presses at t = 0 carries the load plus P, the other P; both slip "
                         "together, so the torque to raise a load F is r_m [(F + P) "
                         "tan(alpha + rho') + P tan(rho' - alpha)]. Each half's flank takes the "
                         "friction law (every law), "
                         "on the integrators the law runs on (Moreau-Jean: every law but "
                         "'arctan_acceleration', with lift-off 'coulomb' and 'stribeck' without viscous "
                         "only), initial.state "
                         "'equilibrium' without lift-off; on concept 'rigid' (there it closes a "
                         "backlash: the thread without play, initial.play_position ignored) "
                         "and on the flexible concepts: without play; with "
                         "backlash.contact 'exact' closed by the preload (the thread without "
                         "play while half A bears on its flank; where the load on half B's "
                         "side would lift it off into the play, about P / cos^2(lead angle) "
                         "in stick, the run raises a SimulationError: not modelled); or with "
                         "backlash.contact 'bistop' or 'cubic': there half A is the nut "
                         "body on its penalty flank, which lifts off beyond the load the "
                         "preload holds, and the play comes back (the nut starts assembled, "
                         "initial.play_position ignored). At most 0.1 * the nut's axial "
                         "stiffness * nut.length (10 % axial strain of the nut body), and "
                         "with penalty play half A's flank penetration at P below half of "
                         "thread.pitch (the thread's depth)", "N", 0.0,
                         **NONNEGATIVE),
        "preload_stiffness": Field("rate of the split nut's spring (its axial stiffness "
                                   "between the halves; on the rigid concept the spring force "
                                   "stays P and the rate is reported, not simulated; with play "
                                   "on a flexible concept it carries the load beyond lift-off "
                                   "and must be > 0). 0: not given", "N/m", 0.0,
                                   **NONNEGATIVE),
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
                              "{'type': 'sine'|'constant'|'table'|'random'|'measured', ...} "
                              "or an Excitation or callable (default 0 unless drive_speed is given; the default is "
                              "applied in the model, not stored in the scene)", "N*m",
                              OPTIONAL, kind="load"),
        "drive_speed": Field("instead of drive_torque: a speed-controlled motor prescribing "
                             "the rotor's angular velocity; the torque it takes is reported",
                             "rad/s", OPTIONAL, kind="load"),
        "axial_force": Field("axial force on the load along +x", "N", 0.0, kind="load"),
        "base_acceleration": Field("the housing's axial acceleration along +x (vibration of "
                                   "the body the drive is mounted on): every translating body "
                                   "feels -m a, outputs stay relative to the housing; e.g. "
                                   "{'type': 'random', ...} (absent: at rest)", "m/s^2",
                                   OPTIONAL, kind="load"),
        "base_angular_acceleration": Field("the housing's angular acceleration about +x: every "
                                           "rotating body feels -J alpha (not with a gear "
                                           "stage; absent: at rest)", "rad/s^2", OPTIONAL,
                                           kind="load"),
        "transverse_slip_velocity": Field(
            "the nut's transverse slip on the flank, across the helix (an excitation: the "
            "flank's friction becomes the isotropic cone on the slip (helix, transverse)): "
            "friction.law 'coulomb' (mu_static too) or 'stribeck' on concept 'rigid' on "
            "event_driven or moreau and the flexible concepts on moreau (their default), "
            "'lugre' (2-D bristles) on every concept and scheme; without play or with penalty "
            "play, exact play on moreau; with a torque, a DC motor or a prescribed speed, an "
            "ideal gear, a base excitation, a load spring, end stops (exact ones on moreau, "
            "not with 'lugre'); no lossy or worm stage, motor friction or preloaded nut "
            "(docs/physics/transverse_slip.md; absent: none)", "m/s", OPTIONAL,
            kind="load"),
    },
    # (Absent: no motor element; loads.drive_torque or loads.drive_speed drive the rotor.)
    "motor": {
        "type": Field("the motor driving the rotor instead of loads.drive_torque or "
                      "loads.drive_speed (exclusive with both): 'dc', a permanent-magnet DC "
                      "motor on the rotor (rotor.inertia is its inertia) with the armature "
                      "L di/dt = U_d - R i - k_e omega and the torque k_t i; its current i "
                      "starts at 0 (the driver switched on at t = 0). Left out: the rotor is "
                      "driven by loads.drive_torque, and the section gives only its "
                      "friction_torque (the motor's bearing friction)", "", OPTIONAL,
                      kind="choice", choices=("dc",)),
        "voltage": Field("the driver's voltage U(t): a number, {'type': "
                         "'sine'|'constant'|'table'|'random'|'measured', ...} or an "
                         "Excitation or callable",
                         "V", OPTIONAL, kind="load", required_with=_WITH_DC),
        "resistance": Field("armature resistance R (terminal to terminal)", "ohm", OPTIONAL,
                            required_with=_WITH_DC, **POSITIVE),
        "inductance": Field("armature inductance L; 0 is the quasi-static limit, exact: "
                            "i = (U - k_e omega) / R without a state", "H", OPTIONAL,
                            default_doc="0 with type 'dc'", **NONNEGATIVE),
        "torque_constant": Field("torque constant k_t: the torque k_t i on the rotor",
                                 "N*m/A", OPTIONAL, required_with=_WITH_DC, **POSITIVE),
        "back_emf_constant": Field("back-EMF constant k_e (equal to k_t in SI for a real "
                                   "motor; where they differ the motor converts "
                                   "(k_t - k_e) i omega out of nothing, which work_drive "
                                   "books)", "V*s/rad", OPTIONAL,
                                   default_doc="motor.torque_constant", **POSITIVE),
        "current_limit": Field("the driver's current limit i_max: a voltage source with "
                               "current limiting, bounded by its supply |U_d| <= |U(t)|: "
                               "where |i| reaches i_max and U(t) would drive it further, it "
                               "puts out U_d = R i + k_e omega, holding |i| = i_max, as far as "
                               "the supply reaches; where the back-EMF asks for more (a load "
                               "driving the rotor) it saturates at -|U(t)| against the "
                               "current (+|U(t)| for a negative one) and the current passes "
                               "the limit, i = (U_d - k_e omega) / R at inductance 0 (events "
                               "start and end the hold and the saturation; "
                               "docs/physics/dc_motor.md) (absent: no limit)", "A", OPTIONAL,
                               **POSITIVE),
        "friction_torque": Field("the motor's own Coulomb friction torque T_c on the rotor: "
                                 "it opposes the rotor's slip with |T_c| and holds up to T_c "
                                 "at rest (one coefficient, no normal force); its loss is the "
                                 "channel motor_friction_loss [J]. 0: none (the drive runs "
                                 "bit-identically to a motor without the key). > 0 needs "
                                 + _TRAIN_STAGE_RULE + " (a rotor driven by "
                                 "loads.drive_torque takes it in a motor section without "
                                 "type: the bearing friction of a torque-driven rotor)",
                                 "N*m", 0.0, **NONNEGATIVE),
    },
    # (Absent: no gear stage; the rotor turns the driven part directly.)
    "gear": {
        "type": Field("the gear stage between the rotor and the driven part (the screw for "
                      "drive = 'screw', the nut for 'nut'; docs/physics/gear.md): 'ideal', a "
                      "kinematic ratio that stores and dissipates nothing: the driven part "
                      "feels the rotor's inertia as n^2 rotor.inertia and the motor's torque "
                      "T as n T (a DC motor's back-EMF is k_e n times the driven part's "
                      "speed); the channels phi_drive [rad], omega_drive [rad/s] and "
                      "drive_torque [N*m] and initial.rotor_angle / rotor_speed stay the "
                      "rotor's, loads.drive_torque and loads.drive_speed act on the rotor. "
                      "'lossy': the same ratio with Modelica's LossyGear losses (efficiency "
                      "where the power flows from the rotor to the driven part, "
                      "efficiency_backdrive where it flows back; stuck where the torques lie "
                      "within what the losses hold). 'worm': a worm pair with exact Coulomb "
                      "friction (lead_angle, mu, mu_static, flank_angle), the lossy law with "
                      "the efficiencies tan(lead_angle) / tan(lead_angle + rho') and "
                      "tan(lead_angle - rho') / tan(lead_angle), rho' = atan(mu / "
                      "cos(flank_angle / 2)) (self-locking where the second is <= 0). "
                      "'lossy' and 'worm' book their loss in the channel gear_loss [J] and "
                      "need " + _TRAIN_STAGE_RULE, "", "ideal",
                      kind="choice", choices=_GEAR_TYPES),
        "ratio": Field("gear ratio n: the rotor turns n times per turn of the driven part "
                       "(n > 1 a reduction); n < 0 is a reversing stage (the driven part "
                       "turns the other way); |n| in [1e-4, 1e4]", "", None,
                       low=-1.0 / _SMALLEST_GEAR_RATIO, high=1.0 / _SMALLEST_GEAR_RATIO),
        "efficiency": Field("type 'lossy' (required there): the efficiency eta where the "
                            "power flows from the rotor to the driven part (the driven part "
                            "gets eta n times the rotor's torque), in (0, 1]", "", OPTIONAL,
                            low=0.0, high=1.0, low_open=True),
        "efficiency_backdrive": Field("type 'lossy': the efficiency eta_b where the power "
                                      "flows from the driven part to the rotor (the rotor "
                                      "gets eta_b times the driven part's torque / n), at "
                                      "most 1; <= 0: the stage is self-locking (it holds "
                                      "whatever the driven side pushes, and lowering needs "
                                      "the motor to drive)", "", OPTIONAL,
                                      default_doc="gear.efficiency", high=1.0),
        "lead_angle": Field("type 'worm' (required there): the worm's lead angle gamma, in "
                            "(0, pi/2) (gamma + atan(mu_static / cos(flank_angle / 2)) below "
                            "pi/2: the worm can drive)", "rad", OPTIONAL, low=0.0,
                            high=math.pi / 2, low_open=True, high_open=True),
        "mu": Field("type 'worm' (required there): the worm flank's coefficient of "
                    "(kinetic) friction", "", OPTIONAL, **NONNEGATIVE),
        "mu_static": Field("type 'worm': its static coefficient at breakaway, at least mu",
                           "", OPTIONAL, default_doc="gear.mu", **NONNEGATIVE),
        "flank_angle": Field("type 'worm': the worm thread's included flank angle beta_w (as "
                             "thread.flank_angle: mu' = mu / cos(beta_w / 2)); 40 deg is the "
                             "standard 20 deg pressure angle", "rad", OPTIONAL,
                             default_doc="40 deg (0.6981 rad)", low=0.0, high=math.pi,
                             high_open=True),
    },
    # The elements' own sections (the core's registry, _core.element_sections():
    # the end stops, ...), each absent where the scene has no such element.
    **{section["name"]: _element_section(section) for section in _element_sections()},
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
                       "rotor_speed and play_position 0, a torque-controlled motor or a DC "
                       "motor, whose steady current at rest U(0) / R (within current_limit) "
                       "holds it; "
                       "NoEquilibriumError where "
                       "the loads drive the thread. A regularized law, which carries no "
                       "friction at rest, starts from that state and slips from it; LuGre's "
                       "bristles start relaxed. "
                       "Scene.initial_state() gives the state)", "", "relaxed", kind="choice",
                       choices=_CHOICES["initial.state"]),
    },
}

# The core's ranges of the run's options (simulation_checks.hpp: the loosest
# rtol and atol, the tightest atol; integrate::validate_options: the others'),
# which the scene's [simulation] section and simulate's keywords share.
LOOSEST_RTOL, LOOSEST_ATOL, TIGHTEST_ATOL = 1e-3, 1e-3, 1e-100
#: The integrators a run takes by name (``simulate``'s ``integrator``): the
#: ODE integrators of the core, the event-driven scheme and Moreau-Jean.
ODE_INTEGRATORS = tuple(_core.integrate.integrator_names())
INTEGRATORS = ODE_INTEGRATORS + ("event_driven", "moreau")


def _simulation_section() -> Dict[str, Field]:
    """The scene's ``[simulation]`` section: the run's options stored with
    the scene, which :func:`leadscrew.simulate` takes as its defaults for
    the scene (a keyword given overrides one). Every field is optional;
    absent, simulate's own default holds."""
    default = "simulate's default"
    return {
        "integrator": Field("the integrator that runs the scene (simulate's integrator): an ODE "
                            "integrator, 'event_driven' or 'moreau'; which fit the scene depends "
                            "on its friction law and play (leadscrew.simulate's docs), checked "
                            "when it runs", "", OPTIONAL, kind="choice", choices=INTEGRATORS,
                            default_doc=f"{default}, the first that fits the scene"),
        "smooth_integrator": Field("the ODE integrator inside 'event_driven'", "", OPTIONAL,
                                   kind="choice", choices=ODE_INTEGRATORS,
                                   default_doc=f"{default}: 'rk_verner6' on the rigid concept, "
                                               "'cvode_bdf' on the flexible ones"),
        "rtol": Field("relative tolerance of the ODE and event-driven integrators (not with "
                      "'moreau')", "", OPTIONAL, default_doc=f"{default} 1e-8", low=0.0,
                      high=LOOSEST_RTOL, low_open=True),
        "atol": Field("absolute tolerance of the ODE and event-driven integrators, on positions "
                      "in m and rad (not with 'moreau')", "", OPTIONAL,
                      default_doc=f"{default} 1e-10", low=TIGHTEST_ATOL, high=LOOSEST_ATOL),
        "dt": Field("fixed step of 'moreau' (only with it)", "s", OPTIONAL,
                    default_doc=f"{default}: 1e-4, shortened where the drive's stiffness needs "
                                "it", **POSITIVE),
        "theta": Field("theta of 'moreau' (only with it)", "", OPTIONAL,
                       default_doc=f"{default} 0.5", low=0.0, high=1.0),
        "max_steps": Field("bound on the integrator's steps", "", OPTIONAL, kind="int",
                           default_doc=f"{default}: 1e6 per simulated second, at least 1e6",
                           low=1),
        "max_events": Field("bound on the events (Zeno or chattering raise instead of "
                            "hanging)", "", OPTIONAL, kind="int",
                            default_doc=f"{default} 100000", low=0),
        "max_step": Field("largest step of the ODE integrators (0: unbounded; not with "
                          "'moreau')", "s", OPTIONAL, default_doc=f"{default} 0",
                          **NONNEGATIVE),
        "first_step": Field("first step of the ODE integrators (0: their choice; not with "
                            "'moreau')", "s", OPTIONAL, default_doc=f"{default} 0",
                            **NONNEGATIVE),
        "bounce_threshold": Field("a flank impact slower than this is plastic (an exact "
                                  "backlash, backlash.contact = 'exact', under 'event_driven' "
                                  "only)", "m/s", OPTIONAL, default_doc=f"{default} 1e-6",
                                  **NONNEGATIVE),
        "max_order": Field("highest order of the CVODE methods (0: the method's default; not "
                           "with 'moreau')", "", OPTIONAL, kind="int",
                           default_doc=f"{default} 0", low=0),
    }


SCHEMA["simulation"] = _simulation_section()

# Sections that may be absent: then they take their defaults, except backlash
# (absent: a thread without play) and overrides.
_REQUIRED_SECTIONS = ("thread", "friction")
_OPTIONAL_SECTIONS = ("backlash", "motor", "gear", "simulation",
                      *(section["name"] for section in _element_sections()))


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
    if f.low == -math.inf:
        return f"{number} {'<' if f.high_open else '<='} {f.high:g}"
    return f"{number} in {lo}{f.low:g}, {f.high:g}{hi}"


class _Converted:
    """A value given with a unit, shown in messages as given and converted."""

    def __init__(self, given: str, value: Any, unit: str):
        self.text = json.dumps(given) + (f" (= {value!r} {unit})".rstrip() if unit else "")

    def __repr__(self) -> str:
        return self.text


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


def describe_schema() -> str:
    """The documentation of every scene field, one line each: key path, unit,
    whether it is required or its default, its valid values (the range a
    number is checked against, or the names a choice takes), meaning."""
    lines = []
    for key, entry in SCHEMA.items():
        items = [(key, entry)] if isinstance(entry, Field) else [
            (f"{key}.{k}", f) for k, f in entry.items()]
        for path, f in items:
            if f.default is None:
                default = "required"
            elif f.required_with:
                default = f"required with {f.required_with}"
            elif f.default_doc:
                default = f"default {f.default_doc}"
            elif f.default is OPTIONAL:
                default = "optional"
            else:
                default = f"default {f.default!r}"
            if f.choices:
                valid = "one of " + ", ".join(map(repr, f.choices))
            elif f.kind in ("float", "int"):
                valid = _range_text(f)
            else:  # a load: a number, a table, a sine, a callable (see loads)
                valid = ""
            unit = f" [{f.unit}]" if f.unit else ""
            valid = f"; {valid}" if valid else ""
            lines.append(f"{path}{unit} ({default}{valid}): {f.doc}")
    return "\n".join(lines)
