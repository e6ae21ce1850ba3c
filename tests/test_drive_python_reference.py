"""leadscrew.simulate against the independent NumPy implementation of the smooth
drive models (tests/helpers/drive_python.py, written from
docs/physics/drive_models.md).

Tolerance. Both sides are integrations, so they can only agree to their global
errors, which for these drives are far above rtol (the slip accelerates and
the lightly damped modes amplify local errors: for the nut-driven flexible_nut
scene cvode_bdf at rtol 1e-10 is off by 4e-6 relative in the normal force at
0.2 s). The global error of each side is therefore measured, not assumed, per
channel as the largest difference over the output times:
    e_cpp = max|C(rtol 1e-10) - C(rtol 1e-12)|   (cvode_bdf)
    e_py  = max|P(rtol 1e-11) - P(rtol 1e-12)|   (LSODA; over-estimates P(1e-12)'s error)
and C(1e-10) and P(1e-12) must agree within 3 (e_cpp + e_py) + 1e-10 max|channel|
(the last term: roundoff and atol). LSODA's error is not proportional to its
rtol (between 1e-10 and 1e-11 it can stall), so its estimate takes the decade
below. Both estimates must be small (<= 2e-5 max|channel|), so the bound cannot
silently grow: a wrong term in either model (a factor, a sign, a missing k'(a)
force) shows as a difference that does not shrink with the tolerances and fails.
Measured: the differences use at most half of the bound (mostly a third: C(1e-10)
against the far more accurate P(1e-12) differs by e_cpp).
"""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers.drive_python import DriveEquations, PythonJamming, simulate_python
from helpers.scenes import THESIS_THREAD, thesis_scene

ARCTAN = {"law": "arctan_velocity", "mu": 0.3, "k_v": 1e3}
BISTOP = {"axial": 1e-4, "contact": "bistop"}
CUBIC = {"axial": 1e-4, "contact": "cubic"}
SPEED = {"drive_torque": None, "axial_force": -10.0,
         "drive_speed": {"type": "sine", "amplitude": 20.0, "omega": 30.0, "offset": -5.0}}

# (id, t_end, scene changes): every concept x drive, no play / bistop / cubic,
# left hand, flank angle with two starts, speed control, drive_end support,
# initial play position and speed, overrides.
CASES = [
    ("rigid-screw-noplay", 0.2, dict(concept="rigid")),
    ("rigid-nut-bistop", 0.1, dict(concept="rigid", drive="nut", backlash=BISTOP)),
    ("rigid-screw-cubic-speed", 0.1, dict(concept="rigid", backlash=CUBIC, loads=SPEED)),
    ("flexnut-screw-cubic", 0.1, dict(concept="flexible_nut", backlash=CUBIC)),
    ("flexnut-nut-noplay-flank", 0.1, dict(
        concept="flexible_nut", drive="nut",
        thread={**THESIS_THREAD, "pitch": 1e-3, "starts": 2, "flank_angle": math.radians(30)})),
    ("flexnut-screw-noplay-speed", 0.05, dict(concept="flexible_nut", loads=SPEED)),
    ("flex-screw-noplay-left", 0.1, dict(concept="flexible",
                                         thread={**THESIS_THREAD, "hand": "left"})),
    ("flex-screw-bistop-driveend", 0.1, dict(
        concept="flexible", backlash=BISTOP, screw={"support": "drive_end"},
        initial={"play_position": 3e-5, "rotor_speed": 2.0})),
    ("flex-nut-cubic-left-flank", 0.1, dict(
        concept="flexible", drive="nut", backlash=CUBIC,
        thread={**THESIS_THREAD, "hand": "left", "flank_angle": math.radians(30)})),
    ("flex-nut-bistop-overrides", 0.1, dict(
        concept="flexible", drive="nut",
        backlash={"axial": 1e-4, "contact": "bistop", "exponent": 2.2, "stiffness": 1e8,
                  "damping": 1e3, "penetration": 1e-5},
        overrides={"damping_ratio": 0.1, "nut_torsional_damping": 1e-3})),
]

CHANNELS = ["u_load", "v_load", "phi_drive", "omega_drive", "normal_force", "friction_force",
            "slip_velocity", "drive_torque", "work_drive", "work_axial", "friction_loss",
            "damping_loss", "contact_loss", "kinetic", "elastic"]


def scene_of(changes):
    return ls.Scene.from_dict(thesis_scene(**{"friction": ARCTAN, **changes}))


@pytest.mark.parametrize("t_end, changes", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_simulate_agrees_with_independent_numpy_model(t_end, changes):
    scene = scene_of(changes)
    t = np.linspace(0.0, t_end, 21)
    cpp = ls.simulate(scene, t_end, integrator="cvode_bdf", rtol=1e-10, atol=1e-14, t_eval=t)
    cpp_fine = ls.simulate(scene, t_end, integrator="cvode_bdf", rtol=1e-12, atol=1e-15,
                           t_eval=t)
    py = simulate_python(scene, t_end, t, method="LSODA", rtol=1e-12, atol=1e-16)
    py_coarse = simulate_python(scene, t_end, t, method="LSODA", rtol=1e-11, atol=1e-15)
    for name in CHANNELS:
        scale = max(np.max(np.abs(cpp_fine[name])), 1e-300)
        e_cpp = np.max(np.abs(cpp[name] - cpp_fine[name]))
        e_py = np.max(np.abs(py[name] - py_coarse[name]))
        assert e_cpp <= 2e-5 * scale and e_py <= 2e-5 * scale, (name, e_cpp, e_py, scale)
        bound = 3.0 * (e_cpp + e_py) + 1e-10 * scale
        difference = np.abs(cpp[name] - py[name])
        worst = int(np.argmax(difference))
        assert difference[worst] <= bound, (
            f"{name} at t = {t[worst]}: C++ {cpp[name][worst]!r}, NumPy {py[name][worst]!r}, "
            f"bound {bound:.3g} (e_cpp {e_cpp:.3g}, e_py {e_py:.3g})")
    # the independent model's own energy account closes
    work = np.max(np.abs(py["work_drive"])) + np.max(np.abs(py["work_axial"]))
    assert np.max(np.abs(py["energy_residual"])) <= 1e-8 * work


@pytest.mark.parametrize("changes", [c[2] for c in CASES], ids=[c[0] for c in CASES])
def test_model_assembly_matches_the_document(changes):
    """Masses, spring stiffnesses at a_0 and damping c = 2 zeta sqrt(k m_max)
    (or the overrides) as the document states them, against the C++ model."""
    scene = scene_of(changes)
    eq = DriveEquations(scene)
    model = scene.model()
    assert sorted(model.coordinate_names) == sorted(eq.names)
    for name, mass in zip(model.coordinate_names, model.mass):
        assert eq.mass[eq.names.index(name)] == pytest.approx(mass, rel=1e-14), name
    mine = {s[0]: s for s in eq.springs}
    assert sorted(mine) == sorted(s["name"] for s in model.springs)
    for spring in model.springs:
        _, _, _, k0, c, _ = mine[spring["name"]]
        assert k0 == pytest.approx(spring["stiffness"], rel=1e-14), spring["name"]
        assert c == pytest.approx(spring["damping"], rel=1e-14), spring["name"]


def jam_scene(load):
    """Nut-driven rigid drive with rotor 1e-6 kg m^2: Delta_+ < 0 above 2.04 kg
    (docs/physics/rigid_drive.md section 11); with k_V = 1e3 the regularized
    paradox starts once (2/pi) mu' atan(k_V gamma) exceeds
    grad(e) M^-1 W_N / |grad(e) M^-1 W_T|."""
    return scene_of(dict(drive="nut", load={"mass": load}, rotor={"inertia": 1e-6}))


def test_both_models_jam_where_the_regularized_paradox_starts():
    t = np.linspace(0.0, 0.05, 11)
    scene = jam_scene(3.0)
    with pytest.raises(PythonJamming) as python_jam:
        simulate_python(scene, 0.3, method="LSODA", rtol=1e-11, atol=1e-15)
    with pytest.raises(ls.JammingError) as cpp_jam:
        ls.simulate(scene, 0.3, integrator="cvode_bdf", rtol=1e-12, atol=1e-15)
    onset = python_jam.value.time
    # the onset is a root of the margin, the same at every tolerance ...
    with pytest.raises(PythonJamming) as coarse:
        simulate_python(scene, 0.3, method="LSODA", rtol=1e-9, atol=1e-14)
    assert coarse.value.time == pytest.approx(onset, rel=1e-8)
    # ... and the C++ raises no earlier than it (it stops at the first step past it)
    assert onset - 1e-9 <= cpp_jam.value.time <= onset + 1e-3
    # up to the onset the trajectories agree
    cpp = ls.simulate(scene, 0.05, integrator="cvode_bdf", rtol=1e-12, atol=1e-15, t_eval=t)
    py = simulate_python(scene, 0.05, t, method="LSODA", rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(py["u_load"], cpp["u_load"], rtol=1e-8, atol=1e-15)
    # a lighter load does not jam in either
    light = jam_scene(1.5)
    ends = [simulate_python(light, 0.3, [0.3], method="LSODA", rtol=1e-11,
                            atol=1e-15)["u_load"][-1],
            ls.simulate(light, 0.3, integrator="cvode_bdf", rtol=1e-11, atol=1e-15,
                        t_eval=[0.3])["u_load"][-1]]
    assert ends[0] == pytest.approx(ends[1], rel=1e-7)


def test_out_of_scope_formulations_are_refused():
    with pytest.raises(ValueError, match="arctan_velocity"):
        DriveEquations(ls.Scene.from_dict(thesis_scene()))
    with pytest.raises(ValueError, match="bistop"):
        DriveEquations(scene_of(dict(backlash={"axial": 1e-4, "contact": "exact"})))
