"""Whether a progress bar is drawn: one rule for :func:`leadscrew.simulate`,
every study and the command line."""

from __future__ import annotations

import sys

import numpy as np

__all__ = ["shown"]


def _watched() -> bool:
    """Someone watches the bar: standard error is a terminal, or the code
    runs in a Jupyter kernel (whose bar is a widget, not text in a log)."""
    stream = sys.stderr
    if stream is not None and hasattr(stream, "isatty") and stream.isatty():
        return True
    # A kernel's shell, not the module: ipykernel imported by another
    # library (a notebook runner in the same process) watches nothing.
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None
    return getattr(shell, "kernel", None) is not None


def shown(progress) -> bool:
    """Check a ``progress`` option and say whether its bar is drawn.

    Args:
        progress: True or False (numpy's bool too); nothing else, so that
            ``"false"``, ``"no"`` or 0 are refused alike everywhere rather
            than taken for true or false.

    Returns:
        True where ``progress`` is True and someone watches (standard error
        a terminal, or a Jupyter kernel): a bar drawn into a log file or a
        pipe is only noise there.

    Raises:
        ValueError: ``progress`` is not a bool.
    """
    if isinstance(progress, np.ndarray) and progress.shape == ():
        progress = progress[()]
    if not isinstance(progress, (bool, np.bool_)):
        raise ValueError(f"progress = {progress!r} is invalid: must be True or False "
                         "(a bar where standard error is a terminal)")
    return bool(progress) and _watched()
