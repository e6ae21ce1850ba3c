"""A result whose channels a test may change: the fuzz checker's tests feed
it hand-made violations (tests/test_fuzz.py, tests/test_train_invariants.py)."""

import numpy as np

__all__ = ["FakeResult"]


class FakeResult:
    """A result with channels that can be changed (from a real one)."""

    def __init__(self, result, **changes):
        self.t = np.array(result.t, dtype=float)
        self.channels = list(result.channels)
        self.events = list(result.events)
        self.integrator = result.integrator
        self.friction = result.friction
        self.data = {name: np.array(result[name], dtype=float) for name in self.channels}
        for name, value in changes.items():
            if name in ("t", "events", "integrator"):
                setattr(self, name, value)
            else:
                self.data[name] = value

    def __getitem__(self, name):
        return self.data[name]
