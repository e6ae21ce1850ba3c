"""What a scene's inputs give: the core's derivation, model and parameters.

``_derivation`` asks the core for the masses, inertias, rigidities and
stiffnesses (``_core.derive_drive``, every quantity checked), ``_model``
assembles the core's model, ``_core_parameters`` the parameters it takes.
A quantity out of range raises ``ValueError`` naming the scene's inputs that
made it so (``_blamed``, which asks the core again with inputs set back).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Dict, Optional

from . import _core
from .excitation import checked_callable
from .scene_loads import _DEFAULT_DRIVE_TORQUE, _DEFAULT_ROTOR_SPEED, _make_excitation
from .scene_schema import OPTIONAL, SCHEMA, Field, _element_sections, _friction_values
from .thread import Thread

__all__: list = []  # the scene's internals: Scene.derived() and Scene.model() use them


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
            if f.default is None and f"{section}.{key}" not in _REFERENCE_VALUES:
                continue  # (a required field of a section with no reference: the motor's)
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
    p.nut_preload = data["nut"]["preload"]
    p.nut_preload_stiffness = data["nut"]["preload_stiffness"]
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
    for key in ("base_acceleration", "base_angular_acceleration", "transverse_slip_velocity"):
        if key in loads:
            setattr(p, key, _make_excitation(loads[key], key))
    motor = data.get("motor")
    if motor is not None:  # (without a type: a torque-driven rotor's friction only)
        p.motor_friction_torque = motor["friction_torque"]
    if motor is not None and motor.get("type") == "dc":
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
    gear = data.get("gear")
    if gear is not None:
        p.gear = gear["type"]
        p.gear_ratio = gear["ratio"]
        if gear["type"] == "lossy":
            p.gear_efficiency = gear["efficiency"]
            p.gear_efficiency_backdrive = gear.get("efficiency_backdrive", gear["efficiency"])
        elif gear["type"] == "worm":
            p.gear_lead_angle = gear["lead_angle"]
            p.gear_mu = gear["mu"]
            p.gear_mu_static = gear.get("mu_static", -1.0)
            p.gear_flank_angle = gear.get("flank_angle", p.gear_flank_angle)
    # The elements' own sections (the end stops, ...), as the scene has them:
    # the core declares, checks and reads them (element_section.hpp).
    p.sections = {section["name"]: data[section["name"]] for section in _element_sections()
                  if section["name"] in data}
    init = data["initial"]
    # (A speed-controlled drive starts at drive_speed(0): the core takes that.)
    p.rotor_angle, p.rotor_speed, p.play_position = (
        init["rotor_angle"], init.get("rotor_speed", _DEFAULT_ROTOR_SPEED), init["play_position"])
    p.initial_state = init["state"]
    return p
