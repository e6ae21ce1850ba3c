"""What the commands write: figures, tables with units, summaries.

The run's figures' titles (``_title``; the figures are
:meth:`leadscrew.Result.plot`'s) and time series
(CSV with a row of units, or Parquet with each field's unit), the output
directory (checked before anything runs, created only once there is something
to write), and a study's output: the failed rows counted (``_failures``),
its summary as JSON (NaN and infinities as null, with the units) and as
text for the terminal.
"""

from __future__ import annotations

import importlib.util
import math
import numbers
import os
from pathlib import Path
from typing import Any, Dict, Tuple

from .cli_parser import StudyFailed, UsageError
from .errors import WriteError
from .files import writing

__all__: list = []  # the command line's internals: leadscrew.cli.main is the entry point


def _title(name: str, scene) -> str:
    """A figure's title: the scene's name and what runs (not the Scene's
    repr): ``default: rigid concept, screw driven, coulomb friction, mu = 0.3``."""
    data = scene.to_dict()
    backlash = data.get("backlash")
    play = f", {backlash['axial'] * 1e3:g} mm play ({backlash['contact']})" if backlash else ""
    return (f"{name}: {data['concept']} concept, {data['drive']} driven, "
            f"{data['friction']['law']} friction, mu = {data['friction']['mu']:g}{play}")


# The suffixes of the files the commands write: an -o that ends in one is a
# file's name given where the output directory is meant.
_FILE_SUFFIXES = (".csv", ".parquet", ".png", ".json", ".toml", ".fmu", ".pdf", ".svg")


def _check_output_dir(path: str) -> None:
    """Refuse an output directory that cannot be created, without creating it.

    Commands check this before they simulate and create the directory only
    once there is something to write, so that a failed command leaves nothing.

    Raises:
        UsageError: ``path`` or its first existing ancestor is no directory
            (a file given where a directory is meant, or a file's name).
        leadscrew.WriteError: that directory is not writable (exit 1, as
            any other write that fails; nothing is written).
    """
    out = Path(path)
    # The first existing ancestor (bounded by the path's depth).
    existing = next((p for p in (out, *out.absolute().parents) if p.exists()), None)
    if existing is None or not existing.is_dir():
        raise UsageError(f"-o {path}: cannot create the output directory "
                         f"({existing} is not a directory)")
    if out.suffix.lower() in _FILE_SUFFIXES:
        # (-o names a directory: drive.csv/ would hold drive.csv/drive.csv)
        raise UsageError(f"-o {path}: -o takes the output directory, not a file's name "
                         f"(its files are named after the scene: give e.g. -o {out.parent / out.stem})")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise WriteError(existing, PermissionError(
            "the directory is not writable" if existing == out else
            f"the directory to create {out} in is not writable"))


def _output_dir(path: str) -> Path:
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise WriteError(out, error) from None
    return out


def _output_file(out: Path, name: str, suffix: str) -> Path:
    """``out/name.suffix``: the suffix appended, never replacing a dotted
    part of the name (``drive_v1.2`` gives ``drive_v1.2.csv``)."""
    return out / f"{name}.{suffix}"


def _summary(name: str, what: str, result, t_end: float) -> str:
    """The run's line: ``what`` ran (the Scene's repr, or "core spec")."""
    stats = result.stats
    return (f"{name}: {what}, t_end = {t_end:g} s, {result.friction}/{result.integrator}: "
            f"{len(result.events)} events, {stats['steps']} steps, "
            f"{stats['wall_time'] * 1e3:.3g} ms; u_load(t_end) = {result['u_load'][-1] * 1e3:.6g} mm")


def _write_series(result, out: Path, name: str, fmt: str) -> Path:
    """Write the time series with the unit of every column.

    CSV: the row of names, then a row of units (SI, ``""`` for the flag
    ``stick``), then the data (pandas reads the data with
    ``read_csv(path, skiprows=[1])``, names and units with ``header=[0, 1]``).
    Parquet: each field's metadata ``unit``, and the frame's
    ``attrs["units"]`` (which ``pandas.read_parquet`` restores).
    """
    frame = result.to_frame()
    units = frame.attrs["units"]
    path = _output_file(out, name, fmt)
    if fmt == "parquet":
        import pyarrow as pa

        schema = pa.Schema.from_pandas(frame, preserve_index=False)
        schema = pa.schema([field.with_metadata({"unit": units[field.name]})
                            for field in schema], metadata=schema.metadata)
        with writing(path) as temporary:
            frame.to_parquet(temporary, index=False, schema=schema)
    else:
        _write_csv(frame, path, units)
    return path


def _write_csv(frame, path: Path, units: Dict[str, str], index: bool = False) -> None:
    """Write a frame as CSV: the row of names, a row of units (``units`` by
    column, ``""`` where it has none: a label, a flag, the index), then the
    data (``pandas.read_csv(path, skiprows=[1])`` reads the data, with
    ``header=[0, 1]`` names and units)."""
    import csv

    names = [str(column) for column in frame.columns]
    unit_row = [str(units.get(column, "")) for column in frame.columns]
    if index:
        names.insert(0, "" if frame.index.name is None else str(frame.index.name))
        unit_row.insert(0, "")
    with writing(path) as temporary, open(temporary, "w", encoding="utf-8", newline="") as stream:
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow(names)
        writer.writerow(unit_row)
        frame.to_csv(stream, index=index, header=False, lineterminator="\n")


def _save_figure(figure, path: Path, dpi: int = 110) -> None:
    """Write a figure to ``path`` whole or not at all."""
    with writing(path) as temporary:
        figure.savefig(temporary, dpi=dpi)


def _require_parquet(fmt: str) -> None:
    if fmt == "parquet" and importlib.util.find_spec("pyarrow") is None:
        raise UsageError("--format parquet needs pyarrow, which is not installed "
                         "(pip install pyarrow), or use --format csv")


#: Columns in which a study reports the failure of a case (None: it ran).
_FAILURE_COLUMNS = ("error", "failure")


def _failure_message(value: Any) -> str:
    """A failure cell as one line ("" where the case ran: None, NaN, "")."""
    import pandas as pd

    if value is None or (pd.api.types.is_scalar(value) and pd.isna(value)):
        return ""
    return " ".join(str(value).split())


def _failures(frame) -> Tuple[int, str]:
    """How many rows of a study's frame failed, and the first message.

    A row failed if one of its columns ``error`` or ``failure`` (work_precision)
    holds a message.
    """
    columns = [c for c in _FAILURE_COLUMNS if c in frame.columns]
    count, first = 0, ""
    for values in zip(*(frame[c].tolist() for c in columns)):
        messages = [m for m in map(_failure_message, values) if m]
        if messages:
            count += 1
            first = first or messages[0]
    return count, first


def _json_value(value: Any) -> Any:
    """A summary value as JSON data: NaN becomes null (not a number), an
    infinity the string "inf" or "-inf" (a breakaway no voltage reaches, a
    thread that never back-drives: a value, not a missing one; JSON has no
    infinity)."""
    import numpy as np

    if isinstance(value, np.generic):
        value = value.item()
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        number = float(value)
        if math.isinf(number):
            return "inf" if number > 0 else "-inf"
        return number if math.isfinite(number) else None
    if isinstance(value, dict):
        return {str(k): _json_value(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)) or hasattr(value, "tolist"):
        return [_json_value(v) for v in (value.tolist() if hasattr(value, "tolist") else value)]
    return str(value)


def _summary_json(summary: Dict[str, Any], frame) -> Dict[str, Any]:
    """A study's summary as JSON data (:func:`_json_value`), with ``"units"``:
    the SI unit of every entry the study gives one (its frame's
    ``attrs["summary_units"]``; ``"1"`` a ratio or count; labels and flags
    have none).

    Raises:
        StudyFailed: the summary has a key ``"units"`` of its own (it would
            be overwritten).
    """
    if "units" in summary:
        raise StudyFailed("the study's summary has a key 'units', which the summary file "
                          "keeps for the units of its entries")
    units = frame.attrs.get("summary_units") or {}
    data = _json_value(dict(summary))
    data["units"] = {str(key): str(units[key]) for key in summary if key in units}
    return data


def _summary_unit(key: str, frame) -> str:
    """The unit of a summary entry: the frame's ``attrs["summary_units"]``,
    which every study sets for its numbers; "" for ratios ("1") and for keys
    it leaves out (labels: booleans, strings)."""
    unit = (frame.attrs.get("summary_units") or {}).get(key)
    return "" if unit in (None, "", "1") else str(unit)


def _summary_text(value: Any, unit: str = "") -> str:
    """A summary value for the terminal (NaN stays visible), with its unit; an
    empty list is "none", without one."""
    import numpy as np

    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        text = str(int(value))
    elif isinstance(value, numbers.Real):
        text = f"{float(value):.6g}"
    elif isinstance(value, (list, tuple)) or hasattr(value, "tolist"):
        values = value.tolist() if hasattr(value, "tolist") else value
        if not values:  # an empty list has no value for a unit to follow ("undecided:  V")
            return "none"
        text = ", ".join(_summary_text(v) for v in values)
    else:
        return str(value)
    return f"{text} {unit}" if unit else text
