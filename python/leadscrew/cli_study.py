"""The ``study`` command: a study of :mod:`leadscrew.studies` run from the command line.

``_study`` looks the study up in ``leadscrew.studies.STUDIES``, reads its
KEY=VALUE options (TOML syntax or comma-separated lists, ``_option_value``),
checks them against the study's signature (``_check_study_options``: its own
parameters and, where it passes them on, :func:`leadscrew.simulate`'s
keywords; never one that takes a Python object) before anything runs, runs
it and writes its table, summary and figure (:mod:`leadscrew.cli_output`).
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import json
import re
import sys
import time
import warnings
from typing import Any, Dict, Sequence

from .cli_output import (_check_output_dir, _failures, _output_dir, _output_file, _summary_json,
                         _summary_text, _summary_unit, _write_csv)
from .cli_parser import StudyFailed, UsageError, _load_scene
from .errors import StudyWarning
from ._hints import did_you_mean
from .files import write_text

__all__: list = []  # the command line's internals: leadscrew.cli.main is the entry point


_OPENING, _CLOSING = "[{(", "]})"


def _top_level_items(text: str) -> list:
    """``text`` split at the commas outside brackets, braces, parentheses
    and quotes (``1 mm,[2, 3]`` is two items)."""
    items, depth, quote, start = [], 0, "", 0
    for index, char in enumerate(text):
        if quote:
            quote = "" if char == quote else quote
        elif char in "\"'":
            quote = char
        elif char in _OPENING:
            depth += 1
        elif char in _CLOSING:
            depth -= 1
        elif char == "," and depth == 0:
            items.append(text[start:index])
            start = index + 1
    return items + [text[start:]]


def _option_value(text: str, key: str = "") -> Any:
    """A study option's value: TOML syntax (numbers, true/false, lists, quoted
    strings, inline tables); otherwise a comma-separated list of such values
    (split at the commas outside brackets and quotes), or a bare string.

    Raises:
        UsageError: a value that opens a TOML array or inline table (``[``,
            ``{``) but is not valid TOML (a shell that ate its quotes:
            ``{friction.mu=[uniform,0.08,0.12]}``), naming the option, the
            parser's reason and how to quote it.
    """
    from .scene_files import _toml_parser

    tomllib = _toml_parser()

    def parse(item: str) -> Any:
        try:
            return tomllib.loads(f"v = {item}")["v"]
        except tomllib.TOMLDecodeError:
            return item.strip()

    value = parse(text)
    if isinstance(value, str) and value == text.strip() and value[:1] in "[{" and value:
        try:
            tomllib.loads(f"v = {text}")
        except tomllib.TOMLDecodeError as error:
            raise UsageError(
                f"study option {key or 'value'}={text} is invalid: not a TOML "
                f"{'inline table' if value[0] == '{' else 'array'} ({error}); quote strings "
                f"inside it and the whole option for the shell, e.g. " + (
                    "'scatter={\"friction.mu\"=[\"uniform\", 0.08, 0.12]}'"
                    if key == "scatter" else "'frequencies=[\"5 Hz\", \"10 Hz\"]'")) from None
    if isinstance(value, str) and value == text.strip() and "," in text:
        return [parse(item) for item in _top_level_items(text)]
    return value


def _study_options(items: Sequence[str]) -> Dict[str, Any]:
    options: Dict[str, Any] = {}
    for item in items:
        key, sep, value = item.partition("=")
        key = key.strip().replace("-", "_")
        if not sep or not key.isidentifier():
            raise UsageError(f"study option {item!r} is invalid: write KEY=VALUE, e.g. "
                             "frequencies=5,10,20 or progress=false")
        if key in options:  # (a shell's brace expansion repeats it: scatter={a,b})
            raise UsageError(f"study option {key} is given twice ({key}={options[key]!r} and "
                             f"{item!r}); give it once (quote a value with commas and braces "
                             "for the shell: 'KEY={...}')")
        options[key] = _option_value(value, key)
    return options


#: What a study's StudyWarning about its rows that raised says (studies/_common.py).
_RAISED_ROWS = r"\w+: \d+ of \d+ rows raised and decide nothing"


def _import_studies():
    try:
        return importlib.import_module(".studies", __package__)
    except ImportError as error:
        raise StudyFailed(f"the studies module leadscrew.studies cannot be imported: {error}") from None


#: Study parameters that take Python objects (an executor, matplotlib Axes, a
#: reference callable or Result): never from the command line.
_OBJECT_OPTIONS = frozenset({"executor", "ax", "reference"})

#: Type names an option's annotation may use for its value to come from text
#: (TOML numbers, booleans, strings, arrays, inline tables).
_TEXT_TYPES = frozenset({"Optional", "Union", "None", "NoneType", "float", "int", "str", "bool",
                         "Sequence", "List", "list", "Tuple", "tuple", "Dict", "dict",
                         "Mapping", "Any", "object"})


def _from_text(parameter: inspect.Parameter) -> bool:
    """Whether a study parameter's value can be written on the command line.

    Annotated: every type name in the annotation is a plain data type
    (numbers, strings, booleans, sequences, dicts). Not annotated: the
    default is such a value, or there is none (a required value).
    """
    if parameter.name in _OBJECT_OPTIONS:
        return False
    annotation = parameter.annotation
    if annotation is inspect.Parameter.empty:
        default = parameter.default
        return default is inspect.Parameter.empty or isinstance(
            default, (bool, int, float, str, list, tuple, dict))
    text = annotation if isinstance(annotation, str) else inspect.formatannotation(annotation)
    names = re.findall(r"[A-Za-z_][A-Za-z_0-9.]*", text)
    return all(name.rsplit(".", 1)[-1] in _TEXT_TYPES for name in names)


def _check_study_options(name: str, function, options: Dict[str, Any]) -> None:
    """Check the KEY=VALUE options against what the study takes.

    A study takes its own parameters (all but the first, the scene) and, if
    it passes ``**simulate_options`` on, :func:`leadscrew.simulate`'s
    keywords but ``model``, ``t_end`` and ``t_eval``.

    Raises:
        UsageError: an option the study does not take (listing those it
            does), one that takes a Python object (executor, ax, reference),
            or a required one not given (listing them).
    """
    from .simulation import _OPTIONS as simulate_options

    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):  # builtins without a signature: let the call decide
        return
    parameters = list(signature.parameters.values())[1:]
    own = {p.name: p for p in parameters if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}
    forwards = any(p.kind is p.VAR_KEYWORD for p in parameters)
    extra = ({k: v for k, v in simulate_options.items() if k not in own} if forwards else {})
    accepted = {**own, **extra}
    texts = [k for k, p in own.items() if _from_text(p)]
    takes = ", ".join(texts) or "no options"
    if extra:
        takes += " and leadscrew.simulate's " + ", ".join(k for k, p in extra.items()
                                                            if _from_text(p))
    for key in options:
        if key not in accepted:
            raise UsageError(f"study {name!r} has no option {key!r}"
                             f"{did_you_mean(key, [k for k in accepted if _from_text(accepted[k])])}"
                             f"; it takes {takes}")
        if not _from_text(accepted[key]):
            raise UsageError(f"study option {key} = {options[key]!r} is invalid: {key} takes a "
                             "Python object, which the command line cannot give (leave it out "
                             "for the default)")
    missing = [k for k, p in own.items() if p.default is p.empty and k not in options]
    objects = [k for k in missing if not _from_text(own[k])]
    if objects:
        raise UsageError(f"study {name!r} cannot run from the command line: it needs "
                         f"{', '.join(objects)}, a Python object")
    if missing:
        raise UsageError(f"study {name!r} needs {' '.join(k + '=...' for k in missing)} "
                         f"(KEY=VALUE after SCENE); it takes {takes}")


def _study(args: argparse.Namespace) -> int:
    studies = _import_studies()
    registry = getattr(studies, "STUDIES", None)
    if not hasattr(registry, "keys"):
        raise StudyFailed("leadscrew.studies has no STUDIES registry")
    if args.name not in registry:
        raise UsageError(f"study {args.name!r} is unknown{did_you_mean(args.name, registry)}; "
                         f"the studies are "
                         f"{', '.join(sorted(registry))}")
    function = registry[args.name]
    options = _study_options(args.options)
    _check_study_options(args.name, function, options)
    _check_output_dir(args.output)
    scene, scene_name, _ = _load_scene(args.scene)
    start = time.perf_counter()
    with warnings.catch_warnings():
        # The study's warning about its rows that raised: this command's own
        # (below, once the files are written) says the same.
        warnings.filterwarnings("ignore", message=_RAISED_ROWS, category=StudyWarning)
        frame = function(scene, **options)
    elapsed = time.perf_counter() - start
    if not hasattr(frame, "to_csv"):
        raise StudyFailed(f"study {args.name!r} returned {type(frame).__name__}, not a DataFrame")
    failed, first = _failures(frame)
    if failed and failed == len(frame):
        raise StudyFailed(f"study {args.name!r} on {scene_name}: all {failed} cases failed; "
                          f"the first: {first}")
    out = _output_dir(args.output)
    stem = f"{args.name}_{scene_name}"
    path = _output_file(out, stem, "csv")
    default_index = type(frame.index).__name__ == "RangeIndex" and frame.index.name is None
    # Columns holding arrays (time series per row) do not fit a CSV cell.
    arrays = [c for c in frame.columns
              if frame[c].map(lambda v: hasattr(v, "__len__") and not isinstance(v, str)).any()]
    _write_csv(frame.drop(columns=arrays), path, frame.attrs.get("units") or {},
               index=not default_index)
    written = [path]
    summary = frame.attrs.get("summary") or {}
    print(f"{args.name} on {scene_name}: {len(frame)} rows in {elapsed:.3g} s")
    if summary:
        print("summary:")
        for key, value in summary.items():
            print(f"  {key}: {_summary_text(value, _summary_unit(str(key), frame))}")
        written.append(_output_file(out, stem, "summary.json"))
        write_text(written[-1], json.dumps(_summary_json(summary, frame), indent=2,
                                           allow_nan=False) + "\n")
    # The study's figure (leadscrew.studies.PLOTS) beside its CSV, if it has one.
    save_figure = getattr(studies, "save_figure", None)
    figure = save_figure and save_figure(args.name, frame, _output_file(out, stem, "png"),
                                         f"{args.name} on {scene_name}")
    if figure:
        written.append(figure)
    if arrays:
        print(f"left out of the CSV (a time series per row): {', '.join(map(str, arrays))}")
    for path in written:
        print(f"wrote {path}")
    if failed:
        print(f"leadscrew: warning: {failed} of {len(frame)} cases failed: {first}",
              file=sys.stderr)
    return 0
