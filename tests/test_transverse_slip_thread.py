"""The thread under transverse flank slip (issue 34, item 3): the closed form's
input, the flank's stick-force ratio q (tests/helpers/transverse_slip_reference.py),
against the package's thread model; the drive's 2-D flank cone
(tests/test_transverse_slip_drive.py) is refused by name where not
implemented."""

import math

import pytest

import leadscrew as ls
from helpers.transverse_slip_reference import (creep_speed, thread_flank_ratio,
                                               thread_load_creep_speed)

THREADS = [ls.Thread("4 mm", "16 mm"), ls.Thread("2 mm", "10 mm", flank_angle="30 deg"),
           ls.Thread("12 mm", "12 mm", starts=2, hand="left")]


@pytest.mark.parametrize("thread", THREADS, ids=["tr16x4", "m10x2", "steep_left"])
@pytest.mark.parametrize("mu", [0.1, 0.3])
def test_the_flank_ratio_is_one_at_the_threads_raise_and_lower_torques(thread, mu):
    """q reaches the cone (1) exactly at the thread package's raise and lower
    torques: the stick forces' ratio has the package's conventions."""
    force = 250.0
    args = (thread.lead_angle, thread.mean_radius, thread.effective_mu(mu), thread.hand_sign)
    raising = ls.thread.raise_torque(thread, mu, force)
    if math.isfinite(raising):
        assert thread_flank_ratio(thread.hand_sign * raising, force, *args) == pytest.approx(
            1.0, rel=1e-12)
    lowering = ls.thread.lower_torque(thread, mu, force)
    assert thread_flank_ratio(-thread.hand_sign * lowering, force, *args) == pytest.approx(
        1.0, rel=1e-12)


@pytest.mark.parametrize("thread", THREADS, ids=["tr16x4", "m10x2", "steep_left"])
@pytest.mark.parametrize("mu", [0.05, 0.1, 0.3])
def test_free_rotor_ratio_is_tan_alpha_over_mu(thread, mu):
    """Free rotor: q = tan(alpha)/mu', below 1 exactly where the package calls
    the thread self-locking, and the load's creep is the block's along the
    helix times sin(alpha)."""
    mu_eff = thread.effective_mu(mu)
    q = thread_flank_ratio(0.0, 100.0, thread.lead_angle, thread.mean_radius, mu_eff,
                           thread.hand_sign)
    assert q == pytest.approx(math.tan(thread.lead_angle) / mu_eff, rel=1e-12)
    assert (q < 1.0) == ls.thread.is_self_locking(thread, mu)
    if q < 1.0:
        helix = creep_speed(q, 1.0, 1.0, 1e-3)
        assert thread_load_creep_speed(-100.0, thread.lead_angle, mu_eff, 1e-3) == pytest.approx(
            -math.sin(thread.lead_angle) * helix, rel=1e-12)


def test_transverse_slip_on_a_flexible_drive_is_refused_by_name():
    """The drive's cone runs on the rigid concept, and on the flexible ones
    on Moreau-Jean (tests/test_transverse_slip_drive.py, its play:
    test_transverse_slip_drive_play_motor.py); the shipped flexible scene
    with play on the event-driven scheme is refused naming the key, the
    obstacle and what is supported, as is a gear stage on Moreau-Jean."""
    scene = ls.scenes.load("position_holding")
    scene = scene.replace(loads={"transverse_slip_velocity": ls.Sine(1e-3, 60.0)})
    with pytest.raises(ValueError, match=r"loads\.transverse_slip_velocity = .* is invalid "
                                         r"with concept = \"flexible\" and integrator = "
                                         r"\"event_driven\" .*: the flank's 2-D friction cone "
                                         r"is implemented without play"):
        ls.simulate(scene, 0.01, integrator="event_driven")
    staged = scene.replace(gear={"type": "lossy", "ratio": 3.0, "efficiency": 0.7,
                                 "efficiency_backdrive": 0.4})
    with pytest.raises(ValueError, match=r"is invalid with gear.type = \"lossy\""):
        ls.simulate(staged, 0.01, integrator="moreau")
