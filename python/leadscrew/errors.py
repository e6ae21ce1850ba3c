"""Exceptions raised by leadscrew."""

from ._core import JammingError, SimulationError

__all__ = ["SimulationError", "JammingError"]

SimulationError.__doc__ = """A solver failed during a simulation.

Attributes:
    time: simulated time [s] at which it failed.
    reason: what failed (solver flag name, step size underflow, LCP failure, ...).
"""
JammingError.__doc__ = """A self-locking drive jams dynamically (Painleve paradox).

No consistent flank-contact mode exists. Attributes as SimulationError.
"""
