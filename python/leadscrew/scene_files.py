"""Scene files: a scene read from and written to TOML.

``_from_toml_text`` reads the bytes of a scene file (``Scene.from_toml``,
``leadscrew.scenes``), ``_to_toml_text`` writes a scene's data as TOML, each
SI number commented with its unit (``Scene.to_toml``).
"""

from __future__ import annotations

import json
import math
import numbers
import os
import sys
from typing import TYPE_CHECKING, Any, Dict

from .scene_loads import load_entry_unit
from .scene_schema import _REQUIRED_SECTIONS, SCHEMA, Field, _fail, _field_unit

if TYPE_CHECKING:
    from .scene import Scene

__all__: list = []  # the scene's internals: Scene.from_toml and Scene.to_toml use them


_TOML_HEADER = ("# leadscrew scene (read it with leadscrew.Scene.from_toml).\n"
                "# Numbers are SI, in the unit noted after '#'; strings with units such as\n"
                "# \"1 mm\", \"210 GPa\" or \"2 Hz\" (= 4 pi rad/s) are accepted as well.\n")


def _toml_parser():
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - exercised on Python < 3.11 only
        import tomli as tomllib
    return tomllib


def _from_toml_text(raw: bytes, source: str) -> "Scene":
    """A scene from the bytes of a TOML file; ``source`` names it in messages."""
    from .scene import Scene  # (leadscrew.scene imports this module)

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
    _records_beside(d, os.path.dirname(os.path.abspath(source)))
    try:
        return Scene.from_dict(d)
    except ValueError as error:
        raise ValueError(f"{source}: {error}") from None


def _records_beside(d: Dict[str, Any], directory: str) -> None:
    """A measured load's relative ``file`` in a scene file is the file's
    neighbour: the path is made relative to the scene file's directory (in
    place; anything else is left for the checks)."""
    loads = d.get("loads") if isinstance(d.get("loads"), dict) else {}
    motor = d.get("motor") if isinstance(d.get("motor"), dict) else {}
    for load in [*loads.values(), motor.get("voltage")]:
        if isinstance(load, dict) and load.get("type") == "measured" and \
                isinstance(load.get("file"), str) and not os.path.isabs(load["file"]):
            load["file"] = os.path.join(directory, load["file"])


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
                entry_unit = "" if key == "type" else load_entry_unit(key, unit)
                lines.append(f"{key} = {_toml_value(f'{path}.{key}', value)}"
                             f"{_unit_comment(entry_unit)}")
    return "\n".join(lines) + "\n"
