"""A drive with a DC motor started at rest in static equilibrium
(``initial.state = "equilibrium"``, issue 32): at rest there is no back-EMF,
so the armature's steady current is i = U(0) / R, clamped by the driver's
current_limit, and its torque k_t i holds the drive like a drive torque
(docs/physics/dc_motor.md). Against the closed forms: the current, the
thread force of tests/helpers/static_equilibrium.py, the power-screw holding
band (no equilibrium outside it: NoEquilibriumError), the inductance's
current starting steady instead of rising as U / R (1 - e^(-t R / L)); on
both schemes, every run checked step by step by
tests/helpers/result_invariants.py."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers.result_invariants import check_result, failed
from helpers.scenes import thesis_scene
from helpers.static_equilibrium import thread_force

R, KT = 2.0, 0.05  # [Ohm], [N m/A] (= k_e in SI)
L = 1e-3  # [H]: L / R = 0.5 ms
U = 3.0  # [V]: the steady current at rest U / R = 1.5 A, its torque 0.075 N m
F = 40.0  # [N]: the holding band of the self-locking thesis thread about +-0.1 N m
T_END = 10 * L / R
DT, INERTIA = 1e-5, 1e-5  # [s]: Moreau-Jean's step; [kg m^2]: the thesis rotor's


def dc_scene(voltage=U, axial_force=F, state="equilibrium", friction=None, **motor):
    """The rigid thesis drive with a DC motor instead of the drive torque."""
    section = {"type": "dc", "voltage": voltage, "resistance": R, "inductance": L,
               "torque_constant": KT, **motor}
    d = thesis_scene(loads={"axial_force": axial_force}, motor=section,
                     initial={"state": state})
    d["loads"].pop("drive_torque")
    if friction:
        d["friction"] = friction
    return ls.Scene.from_dict(d)


def holding_band(scene):
    """The torques [N m] the stuck rigid drive holds under F (thesis eq. 3.5-3.8)."""
    from leadscrew.studies import static_holding_band

    return static_holding_band(scene, F)


def run(scene, integrator, t_end=T_END):
    """A run with every step and its independent check."""
    options = {"integrator": "moreau", "dt": DT} if integrator == "moreau" else {}
    result = ls.simulate(scene, t_end, t_eval="steps", **options)
    report = check_result(result, scene.to_dict(), {"t_end": t_end, **options})
    assert not failed(report), report
    return result


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
@pytest.mark.parametrize("inductance", [L, 0.0])
@pytest.mark.parametrize("limit, current", [(None, U / R), (0.5, 0.5)])
def test_the_drive_starts_at_rest_held_by_the_steady_current(integrator, inductance, limit,
                                                             current):
    motor = {"inductance": inductance, **({"current_limit": limit} if limit else {})}
    scene = dc_scene(**motor)
    result = run(scene, integrator)
    assert result.integrator == integrator
    # i = U / R at rest (or the limit) at every row, from t = 0 on.
    np.testing.assert_allclose(result["motor_current"], current, rtol=1e-12)
    np.testing.assert_allclose(result["drive_torque"], KT * current, rtol=1e-12)
    torque = KT * current
    # The thread holds the motor's torque and the load: |(N, T)| closed form.
    diameter = scene.to_dict()["thread"]["mean_diameter"]
    thread = math.hypot(result["normal_force"][-1], result["friction_force"][-1])
    assert thread == pytest.approx(thread_force(torque, F, diameter), rel=1e-9)
    start = scene.initial_state()
    assert math.hypot(start["normal_force"], start["friction_force"]) == pytest.approx(
        thread_force(torque, F, diameter), rel=1e-12)
    # At rest: the event-driven scheme exactly, Moreau-Jean to the round-off
    # of one step's impulse k_t i dt on the rotor's inertia.
    scale = torque * DT / INERTIA if integrator == "moreau" else 0.0
    assert np.max(np.abs(result["omega_drive"])) <= 1e-12 * scale
    assert np.max(np.abs(result["v_load"])) <= 1e-12 * scale
    assert np.all(result["stick"][1:] == 1.0)
    # The energy account starts at 0 with the magnetic energy L i^2 / 2
    # already stored, and the driver puts out R i at rest.
    assert result["energy_residual"][0] == 0.0
    assert result["magnetic_energy"][0] == pytest.approx(0.5 * inductance * current**2,
                                                         rel=1e-12)
    np.testing.assert_allclose(result["motor_voltage"][1:], R * current, rtol=1e-12)
    if inductance > 0.0 and limit and integrator == "event_driven":
        # The limiter holds from t = 0: no event reaches it.
        assert not any("current limit" in e.kind for e in result.events)


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
def test_with_inductance_the_current_starts_steady_not_at_zero(integrator):
    """The relaxed start's current rises as U / R (1 - e^(-t R / L)) (the
    driver switched on at t = 0); in equilibrium it is U / R from the start."""
    equilibrium = run(dc_scene(), integrator)
    relaxed = run(dc_scene(state="relaxed"), integrator)
    tau = L / R
    np.testing.assert_allclose(equilibrium["motor_current"], U / R, rtol=1e-12)
    rising = U / R * (1.0 - np.exp(-relaxed.t / tau))
    # (Moreau-Jean integrates the armature exactly over each step.)
    np.testing.assert_allclose(relaxed["motor_current"], rising, rtol=1e-6, atol=1e-9 * U / R)
    early = relaxed.t <= tau
    assert np.count_nonzero(early) > 2
    assert np.all(relaxed["motor_current"][early] <= (1 - math.exp(-1)) * U / R * (1 + 1e-6))


@pytest.mark.parametrize("sign", [1, -1])
def test_an_equilibrium_exists_iff_the_motor_torque_lies_in_the_holding_band(sign):
    low, high = holding_band(dc_scene())
    assert low < 0.0 < high  # self-locking
    edge = high if sign > 0 else low
    for share in (0.98, 0.5):
        dc_scene(voltage=share * edge * R / KT).initial_state()  # holds
    with pytest.raises(ls.NoEquilibriumError,
                       match=r"invalid for the loads at t = 0 \(drive torque .* N\*m \(the "
                             r"motor's k_t i at rest\).*no static equilibrium exists"):
        dc_scene(voltage=1.02 * edge * R / KT).initial_state()
    with pytest.raises(ls.NoEquilibriumError, match="friction cone"):
        ls.simulate(dc_scene(voltage=1.02 * edge * R / KT), T_END)
    # The driver's limit clamps the current: beyond the band's voltage, a
    # limit inside it holds.
    limited = dc_scene(voltage=2 * edge * R / KT, current_limit=0.9 * abs(edge) / KT)
    result = run(limited, "event_driven")
    np.testing.assert_allclose(result["motor_current"], sign * 0.9 * abs(edge) / KT, rtol=1e-12)


def test_a_thread_that_is_not_self_locking_needs_the_motor_to_hold():
    """mu' < tan(alpha): the load back-drives the thread without a torque;
    the motor's steady torque inside the (then one-signed) band holds it."""
    friction = {"law": "coulomb", "mu": 0.005}
    low, high = holding_band(dc_scene(friction=friction))
    assert 0.0 < low < high
    with pytest.raises(ls.NoEquilibriumError, match="no static equilibrium exists"):
        dc_scene(voltage=0.0, friction=friction).initial_state()
    voltage = 0.5 * (low + high) * R / KT
    for integrator in ("event_driven", "moreau"):
        result = run(dc_scene(voltage=voltage, friction=friction), integrator)
        np.testing.assert_allclose(result["motor_current"], voltage / R, rtol=1e-12)
        assert np.all(result["stick"][1:] == 1.0)
