"""simulate's default output (t_eval None): a long run's integrator steps
sampled down to about DEFAULT_ROWS, every event's rows and the last time
kept, the values the integrator's own; t_eval="steps" keeps every step."""

import numpy as np
import pytest

import leadscrew as ls
from leadscrew.simulation import DEFAULT_ROWS, _sampled


def _rows_of(every, sampled):
    """The rows of ``every`` (times) that ``sampled`` kept: an event's two
    rows at one time are consecutive."""
    rows = np.searchsorted(every, sampled, side="left")
    for i in range(1, len(rows)):
        if sampled[i] == sampled[i - 1]:
            rows[i] = rows[i - 1] + 1
    return rows


def test_a_default_seat_adjuster_second_keeps_at_most_5000_rows():
    scene = ls.scenes.load("seat_adjuster")
    default = ls.simulate(scene, 1.0)
    assert len(default.t) <= 5000 and default._sampled
    assert default.t[0] == 0.0 and default.t[-1] == 1.0
    every = ls.simulate(scene, 1.0, t_eval="steps")
    assert len(every.t) > 20_000 and not every._sampled  # every step of the run
    assert default.events == every.events
    # The sample of one run: rows of its own, unchanged.
    sampled = _sampled(every)
    assert len(sampled.t) == len(default.t)
    assert len(sampled.t) <= DEFAULT_ROWS + 2 * len(sampled.events) + 2
    rows = _rows_of(every.t, sampled.t)
    np.testing.assert_array_equal(every.t[rows], sampled.t)
    for name in ("u_load", "stop_force", "motor_current", "energy_residual"):
        np.testing.assert_array_equal(every[name][rows], sampled[name])
    # Both ends, and each event's rows (before and after it).
    assert sampled.t[0] == 0.0 and sampled.t[-1] == 1.0
    assert sampled.events == every.events and sampled.stats == every.stats
    for event in every.events:
        assert np.count_nonzero(sampled.t == event.time) == np.count_nonzero(every.t == event.time)
    # Evenly spread: for each of DEFAULT_ROWS even times the first step at
    # or after it is kept.
    first = np.searchsorted(every.t, np.linspace(0.0, 1.0, DEFAULT_ROWS), side="left")
    assert set(first.tolist()) <= set(rows.tolist())


def test_a_short_run_keeps_every_step_and_a_block_is_sampled_alike():
    scene = ls.scenes.load("default")
    short = ls.simulate(scene, 0.05)
    assert len(short.t) <= DEFAULT_ROWS
    np.testing.assert_array_equal(short.t, ls.simulate(scene, 0.05, t_eval="steps").t)
    block = ls.FrictionBlock(mass=1.0, mu=0.3, g=10.0, force=ls.Sine(6.0, 4 * np.pi))
    every = ls.simulate(block, 20.0, integrator="moreau", dt=1e-3, t_eval="steps")
    assert len(every.t) > 20_000 >= 10 * len(ls.simulate(block, 20.0, integrator="moreau",
                                                         dt=1e-3).t)
    sampled = _sampled(every)
    np.testing.assert_array_equal(every["u"][_rows_of(every.t, sampled.t)], sampled["u"])


@pytest.mark.parametrize("t_eval", ["step", "all", ""])
def test_t_eval_takes_steps_and_no_other_word(t_eval):
    with pytest.raises(ValueError, match=r"t_eval = .* is invalid: must be a sequence of times "
                                         r"\[s\] in \[0, t_end\], or \"steps\""):
        ls.simulate(ls.scenes.load("default"), 0.05, t_eval=t_eval)
