"""Run a core spec: the file ``leadscrew scene resolve`` and
:meth:`leadscrew.Scene.to_core_toml` write (the drive as the C++ core runs
it, every value SI and explicit, with its run's options), as the C API and
the FMU read it."""

from __future__ import annotations

import os
from typing import Optional, Sequence, Union

from . import _core

__all__ = ["FORMAT", "is_core_spec", "simulate_core_spec"]

#: The value of a core spec's ``format`` key.
FORMAT = "leadscrew-core-spec"


def is_core_spec(text: str) -> bool:
    """Whether TOML ``text`` is a core spec (its ``format`` key says so), not
    a scene file."""
    from .scene_files import _toml_parser

    try:
        return _toml_parser().loads(text).get("format") == FORMAT
    except Exception:  # not TOML at all: the scene reader says why
        return False


def simulate_core_spec(spec: Union[str, "os.PathLike[str]"], t_end: float,
                       t_eval: Union[None, str, Sequence[float]] = None,
                       progress: bool = False):
    """Simulate the drive of a core spec with the run options it carries.

    Args:
        spec: the spec's TOML text, or the path of its file.
        t_end: end time [s], > 0.
        t_eval: as :func:`leadscrew.simulate`'s: output times [s],
            ``"steps"`` (every step and event) or None (the steps sampled).
        progress: a progress bar (as :func:`leadscrew.simulate`'s).

    Returns:
        A :class:`leadscrew.Result`.

    Raises:
        ValueError: not a core spec, or one the core refuses (naming the key
            and the value), or a bad ``t_end`` or ``t_eval``.
        OSError: the file cannot be read.
        SimulationError: the run failed.
    """
    from .simulation import (_drive_arguments, _drive_call, _run_core, _sampled,
                             _t_eval_list)

    text = spec if isinstance(spec, str) and "\n" in spec else None
    if text is None:
        with open(spec, encoding="utf-8") as stream:
            text = stream.read()
    if not is_core_spec(text):
        raise ValueError(f"spec = {os.fspath(spec) if text is not spec else '<text>'!r} is "
                         f"invalid: a core spec has format = {FORMAT!r} (leadscrew scene "
                         "resolve writes one)")
    parameters, options = _core.read_core_spec(text)
    arguments = _drive_arguments(
        t_end, options["integrator"] or None, options["smooth_integrator"] or None,
        options["rtol"], options["atol"], None, None, _t_eval_list(t_eval),
        options["max_steps"], options["max_events"], options["max_step"] or None,
        options["first_step"] or None, options["bounce_threshold"], options["max_order"] or None)
    arguments["drive"] = _core.DriveModel(parameters)
    result = _run_core(_core.simulate_drive, _drive_call, arguments, progress)
    return _sampled(result) if t_eval is None else result
