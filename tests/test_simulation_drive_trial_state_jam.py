"""A jam at an integrator's trial state is no jam of the drive (issue 31,
reproduction 6): a flexible LuGre drive, not Painleve-like by its masses,
raised JammingError at t = 1e-4 s on rk_dopri5 at every rtol, where cvode_bdf,
ARKODE's dopri5 and rk_verner6 agree. The first step's last stage (h = 1e-4
s, far off the trajectory on the stiff bristles) left the flank no
consistent normal force; a right-hand side's jam is now a refused state
(core/errors.hpp: JammingAtState), which every integrator retries with a
shorter step and raises only where shorter steps meet it too."""

import numpy as np
import pytest

import leadscrew as ls

SCENE = {"concept": "flexible", "thread": {"pitch": 0.009, "mean_diameter": 0.008},
         "friction": {"law": "lugre", "mu": 0.3, "sigma0": 3000000.0}, "load": {"mass": 0.2},
         "loads": {"axial_force": 60.0}}
T_END = 0.01


@pytest.fixture(scope="module")
def reference():
    """cvode_bdf at rtol 1e-11 (converged: the integrators at rtol 1e-11
    agree to 2e-8 of max |omega_drive| and u_load(t_end), to 2e-6 at the
    default rtol 1e-8)."""
    return ls.simulate(ls.Scene.from_dict(SCENE), T_END, integrator="cvode_bdf", rtol=1e-11,
                       atol=1e-14)


@pytest.mark.parametrize("rtol, atol", [(None, None), (1e-11, 1e-14)])
def test_rk_dopri5_answers_what_the_other_integrators_answer(reference, rtol, atol):
    r = ls.simulate(ls.Scene.from_dict(SCENE), T_END, integrator="rk_dopri5", rtol=rtol,
                    atol=atol)
    for channel in ("omega_drive", "v_load"):
        assert np.max(np.abs(r[channel])) == pytest.approx(
            np.max(np.abs(reference[channel])), rel=2e-5)
    assert r["u_load"][-1] == pytest.approx(reference["u_load"][-1], rel=2e-5)
    # (the numbers: max |omega_drive| 1.845 rad/s, u_load 1.8162e-05 m)
    assert np.max(np.abs(r["omega_drive"])) == pytest.approx(1.845, abs=5e-4)
    assert r["u_load"][-1] == pytest.approx(1.8162e-05, abs=5e-10)

