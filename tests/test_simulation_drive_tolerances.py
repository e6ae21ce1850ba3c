"""Tolerances that cannot resolve a scene are refused, not certified (issue
31, reproduction 9): the self-locking position_holding drive at a loose
atol turned back and left its whole friction loss unbooked in an energy
account that passed its check (docs/physics/result_checks.md,
"energy_balance" and "Options refused before a run")."""

import numpy as np
import pytest

import leadscrew as ls
from leadscrew import scenes

T_END = 0.5


def holding_drive(**friction):
    """The shipped position_holding scene on the rigid concept: a static
    torque that only the self-locking thread holds, a 50 N sine shaking it,
    with the thesis's arctan law (arctan_velocity, k_v = 1e6 s/m, unless
    `friction` says otherwise: the scene ships exact Coulomb since issue 34,
    item 5, and its comments say how to set this law) and simulate's own
    tolerances (the scene's stored rtol 1e-6 dropped)."""
    scene = scenes.load("position_holding").replace(
        concept="rigid", simulation=None,
        friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e6})
    return scene.replace(friction={**scene["friction"], **friction}) if friction else scene


def slip_gradient(scene):
    """|W_T|, the slip velocity per unit of the velocities summed: the rigid
    drive with play has the rotor's r cos(alpha) and the load's sin(alpha)
    (slip = r cos(alpha) omega - sin(alpha) v_load; square thread)."""
    alpha = np.arctan(scene["thread"]["pitch"] / (np.pi * scene["thread"]["mean_diameter"]))
    return scene["thread"]["mean_diameter"] / 2 * np.cos(alpha) + np.sin(alpha)


@pytest.mark.parametrize("rtol, atol", [(1e-3, 1e-5), (1e-3, 3e-6), (1e-4, 1e-5)])
def test_an_atol_beyond_the_regularized_stick_band_is_refused(rtol, atol):
    """The issue's call: at rtol 1e-3, atol 1e-5 the rotor turned back (u_load
    -0.29 mm against -0.107 mm converged), a friction loss of 0.109 J
    against 1.4e-4 J, every check passing; at atol 3e-6 it turned back by
    200 rad. The velocities' atol through |W_T| spans the arctan law's stick
    band: k_v |W_T| atol = 0.26 and 0.078, beyond 0.05. Refused before the
    run, naming atol and the largest that resolves the band."""
    scene = holding_drive()
    largest = 0.05 / (scene["friction"]["k_v"] * slip_gradient(scene))
    assert atol > largest  # 1.93e-6
    with pytest.raises(ValueError, match=r"atol = [0-9.e-]+ is invalid with friction\.k_v = "
                                         r"1000000 s/m: .*use atol <= 1\.9"):
        ls.simulate(scene, T_END, rtol=rtol, atol=atol)


def test_within_the_band_the_drive_holds():
    """rtol 1e-3 with the default atol: the holding creep of the converged
    run (the default tolerances) to 2 % (the issue measured 1.4 %)."""
    scene = holding_drive()
    converged = ls.simulate(scene, T_END)
    loose = ls.simulate(scene, T_END, rtol=1e-3)
    assert loose["u_load"][-1] == pytest.approx(converged["u_load"][-1], rel=2e-2)
    assert loose["friction_loss"][-1] == pytest.approx(converged["friction_loss"][-1], rel=2e-2)


def test_an_energy_account_that_leaves_a_loss_unbooked_is_refused():
    """k_v = 1e4 s/m at rtol 1e-3, atol 1e-4 (inside the band): the run
    leaves 3 % of its largest energy flow E unbooked, 35 times its friction
    loss, where K (rtol E + atol G) allowed several E (the flank's penalty
    stiffness in G). At most 1 % of E is an account that resolved its
    scene; the run raises and says to tighten rtol/atol."""
    scene = holding_drive(k_v=1e4)
    unchecked = ls.simulate(scene, T_END, rtol=1e-3, atol=1e-4, check=False)
    names = ["work_drive", "work_axial", "friction_loss", "damping_loss", "contact_loss",
             "impact_loss", "kinetic", "elastic"]
    flow = np.max(sum(np.abs(unchecked[n]) for n in names))
    residual = np.max(np.abs(unchecked["energy_residual"]))
    assert residual > 0.02 * flow
    assert residual > 10 * unchecked["friction_loss"][-1]
    balance = unchecked.checks["energy_balance"]
    assert not balance["passed"] and balance["bound"] == pytest.approx(0.01 * flow, rel=1e-6)
    with pytest.raises(ls.SimulationError, match=r"'energy_balance'.*tighten rtol/atol"):
        ls.simulate(scene, T_END, rtol=1e-3, atol=1e-4)
