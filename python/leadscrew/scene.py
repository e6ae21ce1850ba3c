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

This module holds the :class:`Scene` class; its parts are modules of their
own: the fields (:mod:`leadscrew.scene_schema`: :data:`SCHEMA`,
:func:`describe_schema`), the loads and initial-state rules
(:mod:`leadscrew.scene_loads`), the checks of fields, sections and the rules
across them (:mod:`leadscrew.scene_checks`), the derivation and the core's
model (:mod:`leadscrew.scene_derived`) and the TOML files
(:mod:`leadscrew.scene_files`).
"""

from __future__ import annotations

import os
from typing import Any, Dict, Optional

from . import _core
from .files import write_text
from .scene_checks import _check_consistency, _check_section_names, _validate_entry
from .scene_derived import _derived, _model, _thread
# (Re-exported: the tests and the package's modules import them from here.)
from .scene_derived import _QUANTITIES, _geometry, _in_range  # noqa: F401
from .scene_files import _from_toml_text, _to_toml_text, _toml_parser  # noqa: F401
from .scene_loads import _DEFAULT_DRIVE_TORQUE, _effective  # noqa: F401
from .scene_schema import (DENSITY, MODULUS, NONNEGATIVE, OPTIONAL,  # noqa: F401
                           POSITIVE, SCHEMA, Field, _fail, _friction_law_entry,
                           _friction_registry, describe_schema)
from .thread import Thread

__all__ = ["Scene", "SCHEMA", "describe_schema"]


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


def _validated(d: Any) -> Dict[str, Any]:
    """A scene dict checked against :data:`SCHEMA`, its defaults filled
    (:meth:`Scene.from_dict`)."""
    if not isinstance(d, dict):
        _fail("scene", d, "a dict of sections")
    _check_section_names(d)
    data: Dict[str, Any] = {}
    for key in SCHEMA:
        _validate_entry(key, d, data)
    _check_consistency(data)
    return data


class Scene:
    """A validated lead-screw drive description (immutable).

    Build it with ``Scene(d)`` or :meth:`from_dict` (the same: both
    validate ``d``); read it back with :meth:`to_dict` or item access
    (``scene["thread"]["pitch"]``).
    """

    def __init__(self, data: Dict[str, Any]):
        """Validate a scene dict and fill its defaults (:meth:`from_dict`).

        Raises:
            ValueError: as :meth:`from_dict`.
        """
        # (Scene(d) once stored d unvalidated, and failed later with a
        # KeyError on a section it left out.)
        self._set(_validated(data))

    def _set(self, data: Dict[str, Any]) -> None:
        self._data = data
        # The core's model, built on the first model() call: a scene is
        # immutable and so is its model, and building it (the derivation,
        # the checks) was a third of a rigid drive's 60 us simulate call.
        self._model = None

    @classmethod
    def _from_validated(cls, data: Dict[str, Any]) -> "Scene":
        """A scene of data that is already validated (no second check)."""
        scene = cls.__new__(cls)
        scene._set(data)
        return scene

    def __getstate__(self) -> Dict[str, Any]:
        # (Pickled without the core's model, which does not pickle: a scene
        # sent to a process pool builds its own.)
        return {"_data": self._data}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self._set(state["_data"])

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
        return cls._from_validated(_validated(d))

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
            leadscrew.WriteError: ``path`` cannot be written (nothing is left
                there).
        """
        text = _to_toml_text(self._data)
        if path is not None:
            write_text(path, text)
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
                defaults; each left out takes the scene's own where its
                ``[simulation]`` section stores one.

        Returns:
            The TOML text.

        Raises:
            ValueError: a load is a Python callable (no file can carry it),
                a derived value is out of range (as :meth:`model`), or an
                unknown option (naming it).
            leadscrew.WriteError: ``path`` cannot be written (nothing is left
                there).
        """
        from .simulation import _run_options, _stored_option_errors, scene_options

        known = ("integrator", "smooth_integrator", "rtol", "atol", "max_steps", "max_events",
                 "max_step", "first_step", "bounce_threshold", "max_order")
        for name in options:
            if name not in known:
                raise ValueError(f"{name} = {options[name]!r} is invalid: to_core_toml takes "
                                 f"the options {', '.join(known)}")
        # The scene's [simulation] options where these leave one out (a core
        # spec has no Moreau-Jean step: the scene's dt and theta stay out).
        options, stored = scene_options(self, options)
        options = {name: value for name, value in options.items()
                   if name in known and value is not None}
        with _stored_option_errors(stored):
            text = _core.write_core_spec(self.model().parameters, **_run_options(**options))
        if path is not None:
            write_text(path, text)
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
        return Scene._from_validated(data)

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
