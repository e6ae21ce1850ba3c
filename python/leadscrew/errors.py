"""Exceptions raised by leadscrew."""

from ._core import JammingError, NoEquilibriumError, NutOffScrewError, SimulationError

__all__ = ["SimulationError", "JammingError", "NutOffScrewError", "NoEquilibriumError",
           "StudyWarning"]

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
