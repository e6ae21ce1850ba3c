"""Export a drive as an FMI 2.0 co-simulation FMU.

:func:`export_fmu` writes one file that Simulink, Dymola, OpenModelica,
Adams, Simcenter Amesim or FMPy import: the scene's core spec
(:meth:`leadscrew.Scene.to_core_toml`) in its ``resources/``, the package's
generic binary (``binaries/linux64/``: SUNDIALS and the C++ runtime linked
statically, glibc's functions taken at versions up to 2.28, so that it
loads on any x86-64 Linux with glibc >= 2.28 (Debian 10, Ubuntu 20.04,
RHEL 8) and needs neither Python nor this package) and a ``modelDescription.xml`` written from
the core's table of the drive's variables (``_core.cosim_variables``):

- inputs: the drive's, ``drive_torque`` [N.m] (a torque-controlled drive),
  ``motor_voltage`` [V] (a DC motor, scene section ``motor``) or
  ``drive_speed`` [rad/s] (a speed-controlled drive), and ``axial_force``
  [N]. A torque, a voltage and the force are held over each communication
  step (no input interpolation); a prescribed speed is not stepped (a step
  is an infinite acceleration): it ramps linearly from the speed at the
  step's start to the new value at its end, then holds it (the outputs at
  the step's end are the ramp's), and a speed set before the first step is
  the one the drive starts at. Their start values are the scene's loads at
  t = 0. An input the importer never sets
  follows the scene's load (a constant, sine or table: the FMU then runs as
  :func:`leadscrew.simulate`); from the first value the importer sets, it
  takes the importer's values;
- outputs ``u_load``, ``v_load``, ``phi_drive``, ``omega_drive``,
  ``normal_force``, ``friction_force``, ``stick`` (Boolean),
  ``friction_loss``, with a DC motor ``motor_current`` [A], and where the
  torque is no input (a DC motor, a speed-controlled drive)
  ``drive_torque`` [N.m], the torque the motor supplies; then every channel
  the scene's elements have (``stop_force`` [N] with end stops, a load
  spring's force, a DC motor's energies, the train's stage losses), as
  :func:`leadscrew.simulate`'s result names them;
- parameters that may be set before the initialization ends: the friction
  law's (``mu``, ...), the masses and inertias, for a flexible concept the
  springs' stiffness overrides (0: from the geometry), and a DC motor's
  resistance, inductance, constants and current limit.

Events and stick/slip are located exactly inside each step. A step that
ends past the screw's end, or any step after a failure, is refused with
``fmi2Error`` and a message to the importer's logger naming the cause.
"""

from __future__ import annotations

import datetime
import math
import os
import uuid
import zipfile
from typing import Dict, List, Optional
from xml.sax.saxutils import quoteattr

from . import _core
from .files import writing

__all__ = ["export_fmu", "MODEL_IDENTIFIER"]

#: The FMU's model identifier: the name of its binary in ``binaries/linux64/``.
MODEL_IDENTIFIER = "leadscrew_drive"

# SI base-unit exponents of the units the variables use (FMI's BaseUnit).
_BASE_UNITS: Dict[str, Dict[str, int]] = {
    "m": {"m": 1}, "m/s": {"m": 1, "s": -1}, "rad": {"rad": 1}, "rad/s": {"rad": 1, "s": -1},
    "N": {"kg": 1, "m": 1, "s": -2}, "N.m": {"kg": 1, "m": 2, "s": -2},
    "J": {"kg": 1, "m": 2, "s": -2}, "kg": {"kg": 1}, "kg.m2": {"kg": 1, "m": 2},
    "N/m": {"kg": 1, "s": -2}, "N.m/rad": {"kg": 1, "m": 2, "s": -2, "rad": -1},
    "s/m": {"s": 1, "m": -1}, "1/m": {"m": -1}, "N.s/m": {"kg": 1, "s": -1},
    "s": {"s": 1},
    "V": {"kg": 1, "m": 2, "s": -3, "A": -1}, "A": {"A": 1},
    "Ohm": {"kg": 1, "m": 2, "s": -3, "A": -2}, "H": {"kg": 1, "m": 2, "s": -2, "A": -2},
    "N.m/A": {"kg": 1, "m": 2, "s": -2, "A": -1},
    "V.s/rad": {"kg": 1, "m": 2, "s": -2, "A": -1, "rad": -1},
}


# Display units an engineer reads these quantities in (FMI 2.0 DisplayUnit:
# display value = factor * SI value): the variables stay SI, an importer
# offers these beside them.
_DISPLAY_UNITS: Dict[str, List[tuple]] = {
    "m": [("mm", 1e3)], "m/s": [("mm/s", 1e3)], "rad": [("deg", 180.0 / math.pi)],
    "rad/s": [("rpm", 30.0 / math.pi)], "N.m": [("N.mm", 1e3)],
}


def _binary() -> str:
    from . import _shipped

    return _shipped("lib", "leadscrew_fmu.so", directory=False)


def _number(value: float) -> str:
    return repr(float(value))


def _model_description(variables: List[dict], name: str, guid: str,
                      stop_time: float = 1.0, step: float = 1e-3) -> str:
    """The ``modelDescription.xml`` text of a drive's FMU.

    Args:
        variables: ``_core.cosim_variables(parameters)``.
        name: the model's name (the scene's).
        guid: the FMU's GUID.
        stop_time: the default experiment's stop time [s].
        step: the default communication step [s].

    Returns:
        The XML text (UTF-8).
    """
    units = sorted({v["unit"] for v in variables if v["unit"]})
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<fmiModelDescription fmiVersion="2.0" modelName={quoteattr(name)} '
             f'guid={quoteattr(guid)} description="a lead-screw drive (leadscrew)" '
             f'generationTool="leadscrew" generationDateAndTime='
             f'"{datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")}" '
             f'variableNamingConvention="flat" numberOfEventIndicators="0">',
             f'  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" '
             'canHandleVariableCommunicationStepSize="true" canInterpolateInputs="false" '
             'canBeInstantiatedOnlyOncePerProcess="false" canGetAndSetFMUstate="false" '
             'canSerializeFMUstate="false" providesDirectionalDerivative="false" '
             'needsExecutionTool="false"/>',
             "  <UnitDefinitions>"]
    for unit in units:
        base = _BASE_UNITS.get(unit)
        if base:
            exponents = " ".join(f'{k}="{e}"' for k, e in base.items())
            display = "".join(f'<DisplayUnit name={quoteattr(name)} factor="{_number(factor)}"/>'
                              for name, factor in _DISPLAY_UNITS.get(unit, []))
            lines.append(f"    <Unit name={quoteattr(unit)}><BaseUnit {exponents}/>{display}"
                         "</Unit>")
        else:
            lines.append(f"    <Unit name={quoteattr(unit)}/>")
    lines += ["  </UnitDefinitions>",
              "  <LogCategories>",
              '    <Category name="logStatusError" description="a refused call or a failed '
              'step, with its cause"/>',
              "  </LogCategories>",
              f'  <DefaultExperiment startTime="0.0" stopTime="{_number(stop_time)}" '
              f'stepSize="{_number(step)}"/>',
              "  <ModelVariables>"]
    outputs = []
    for index, v in enumerate(variables, start=1):
        kind = v["kind"]
        attributes = (f'name={quoteattr(v["name"])} valueReference="{v["reference"]}" '
                      f'description={quoteattr(v["description"])} causality="{kind}"')
        if kind == "input":
            attributes += ' variability="continuous"'
        elif kind == "parameter":
            attributes += ' variability="fixed" initial="exact"'
        else:
            attributes += f' variability="{"discrete" if v["boolean"] else "continuous"}"'
            outputs.append(index)
        unit = f' unit={quoteattr(v["unit"])}' if v["unit"] else ""
        start = f' start="{_number(v["start"])}"' if kind != "output" else ""
        element = "Boolean" if v["boolean"] else f"Real{unit}"
        lines.append(f"    <!-- {index} -->")
        lines.append(f"    <ScalarVariable {attributes}><{element}{start}/></ScalarVariable>")
    lines += ["  </ModelVariables>", "  <ModelStructure>", "    <Outputs>"]
    lines += [f'      <Unknown index="{i}"/>' for i in outputs]
    lines += ["    </Outputs>", "    <InitialUnknowns>"]
    lines += [f'      <Unknown index="{i}"/>' for i in outputs]
    lines += ["    </InitialUnknowns>", "  </ModelStructure>", "</fmiModelDescription>", ""]
    return "\n".join(lines)


def _positive_time(name: str, value) -> float:
    """``value`` [s] (a number or a unit string) as a finite float > 0."""
    from .units import to_si

    seconds = to_si(name, value, "s")
    try:
        seconds = float(seconds)
    except (TypeError, ValueError):
        seconds = float("nan")
    if not (math.isfinite(seconds) and seconds > 0.0):
        raise ValueError(f"{name} = {value!r} is invalid: must be a finite number > 0 [s]")
    return seconds


def _fmu_path(path: "str | os.PathLike[str]", name: Optional[str]) -> str:
    """The file an FMU is written to: ``path``, or ``path/NAME.fmu`` where
    ``path`` is a directory (or ends with a separator).

    Raises:
        ValueError: a file that does not end in ``.fmu`` (importers pick an
            FMU by its suffix), or a directory without ``name``.
    """
    path = os.fspath(path)
    if os.path.isdir(path) or path.endswith(("/", os.sep)):
        if not name:
            raise ValueError(f"path = {path!r} is a directory: give name, the model's name "
                             "(the FMU is written to DIRECTORY/NAME.fmu), or a .fmu file")
        return os.path.join(path, f"{name}.fmu")
    if not path.endswith(".fmu"):
        raise ValueError(f"path = {path!r} is invalid: an FMU's file name ends in .fmu "
                         f"(e.g. {os.path.splitext(path)[0]}.fmu), or give a directory")
    return path


def export_fmu(scene, path: "str | os.PathLike[str]", name: Optional[str] = None,
               stop_time: float = 1.0, step: float = 1e-3, **options) -> str:
    """Write the scene as an FMI 2.0 co-simulation FMU.

    Args:
        scene: a :class:`leadscrew.Scene`.
        path: the ``.fmu`` file to write, or a directory (the FMU is then
            ``path/NAME.fmu``).
        name: the model's name (default: the file's stem; required with a
            directory).
        stop_time: the default experiment's stop time [s].
        step: the default experiment's communication step [s].
        **options: the run's options as :meth:`leadscrew.Scene.to_core_toml`
            takes them (``rtol``, ``atol``, ``integrator``, ...).

    Returns:
        The path written.

    Raises:
        ValueError: a file name that does not end in ``.fmu``, a directory
            without ``name``, a Python callable load (no FMU can carry it), a derived value out
            of range, an unknown option, an option
            the FMU's stepper refuses (``integrator="moreau"``, an
            integrator that does not fit the friction law), or a stop time
            or step that is not a finite number > 0 (step <= stop time).
        FileNotFoundError: the package was installed without the FMU binary.
        leadscrew.WriteError: ``path`` cannot be written (nothing is left
            there: the FMU is written whole or not at all).
    """
    from .scene import Scene

    if not isinstance(scene, Scene):
        raise ValueError(f"scene = {scene!r} is invalid: must be a leadscrew.Scene")
    try:
        spec = scene.to_core_toml(**options)
    except ValueError as error:
        if "callable" in str(error):
            raise ValueError(f"the scene cannot be exported as an FMU: {error}; an FMU runs "
                             f"without Python, so its loads must be constants, sines or "
                             f"tables") from None
        raise
    stop_time = _positive_time("stop_time", stop_time)
    step = _positive_time("step", step)
    if step > stop_time:
        raise ValueError(f"step = {step!r} is invalid: must be <= stop_time = {stop_time!r} s "
                         "(the default experiment's communication step)")
    # What the FMU will refuse at its initialization is refused here: the
    # same core reads the spec and builds the same stepper.
    parameters, run_options = _core.read_core_spec(spec)
    _core.DriveStepper(_core.DriveModel(parameters), **run_options)
    variables = _core.cosim_variables(scene.model().parameters)
    path = _fmu_path(path, name)
    name = name or os.path.splitext(os.path.basename(path))[0]
    guid = "{" + str(uuid.uuid5(uuid.NAMESPACE_URL, "leadscrew:" + name + spec)) + "}"
    xml = _model_description(variables, name, guid, stop_time, step)
    binary = _binary()
    with writing(path) as temporary, \
            zipfile.ZipFile(temporary, "w", compression=zipfile.ZIP_DEFLATED) as fmu:
        fmu.writestr("modelDescription.xml", xml)
        fmu.write(binary, f"binaries/linux64/{MODEL_IDENTIFIER}.so")
        fmu.writestr("resources/core.toml", spec)
        fmu.writestr("resources/guid", guid + "\n")
    return path
