"""Exceptions raised by leadscrew."""

import os

from ._core import JammingError, NoEquilibriumError, NutOffScrewError, SimulationError

__all__ = ["SimulationError", "JammingError", "NutOffScrewError", "NoEquilibriumError",
           "StudyWarning", "WriteError"]

SimulationError.__doc__ = """A solver failed during a simulation.

Attributes:
    time: simulated time [s] at which it failed.
    reason: what failed (solver flag name, step size underflow, LCP failure, ...).
"""
JammingError.__doc__ = """A self-locking drive jams dynamically (Painleve paradox).

No consistent flank-contact mode exists. Attributes as SimulationError.
"""
NutOffScrewError.__doc__ = """The nut ran off the screw: its end reached the screw's end.

The run ends there (beyond it the thread no longer holds the nut); the
end of a drive's travel, not a solver's failure. Attributes as
SimulationError (``time``: when the nut's end reached the screw's).
"""
NoEquilibriumError.__doc__ = """A start in static equilibrium (``initial.state =
'equilibrium'``) that the loads at t = 0 do not admit: holding them at rest
takes a flank friction force beyond the friction cone (the loads drive the
thread). A ValueError; the message gives the loads and the forces.
"""


class StudyWarning(RuntimeWarning):
    """A study returned a result that needs a reader's attention: cases that
    failed (their rows carry the message and decide nothing), or a verdict
    that rests on an assumption its evaluations contradict."""


class WriteError(OSError):
    """A file could not be written (no space left on device, a file size
    limit, a directory that is not writable, ...). Nothing is left at the
    path: leadscrew writes each file whole or not at all
    (:mod:`leadscrew.files`); a file already there is unchanged.

    Attributes:
        filename: the path that was to be written.
        strerror: the cause, as the operating system gave it.
    """

    def __init__(self, path, cause: BaseException):
        strerror = getattr(cause, "strerror", None) or str(cause)
        super().__init__(getattr(cause, "errno", None), strerror, os.fspath(path))

    def __str__(self) -> str:
        return f"cannot write {self.filename}: {self.strerror}"
