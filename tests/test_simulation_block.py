"""The friction benchmark of thesis section 3.2.6 through leadscrew.simulate:
exact Coulomb (event-driven, Moreau-Jean) and the arctan regularizations,
against the independent closed form in tests/helpers/block_reference.py."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers.block_reference import solve_block

MASS, MU, G, OMEGA = 1.0, 0.3, 10.0, 4 * math.pi
REGULARIZED_INTEGRATORS = ["cvode_bdf", "cvode_adams", "dopri5"]


def block(amplitude, **kwargs):
    return ls.FrictionBlock(MASS, MU, g=G, force=ls.Sine(amplitude, OMEGA), **kwargs)


@pytest.fixture(scope="module", params=[6.0, 4.0], ids=["V=6", "V=4"])
def case(request):
    amplitude = request.param
    reference = solve_block(MASS, MU, G, amplitude, OMEGA, t_end=2.0)
    result = ls.simulate(block(amplitude), 2.0, rtol=1e-12, atol=1e-14)
    return amplitude, reference, result


def test_event_driven_matches_closed_form(case):
    _, reference, result = case
    assert np.max(np.abs(result["u"] - reference.position(result.t))) <= 1e-9
    assert np.max(np.abs(result["v"] - reference.velocity(result.t))) <= 1e-8


def test_event_times_match_closed_form(case):
    _, reference, result = case
    assert len(result.events) == len(reference.events)
    for ours, theirs in zip(result.events, reference.events):
        assert abs(ours.time - theirs.time) <= 1e-10
        expected = {"stick->slip": "stick->slip", "slip->stick": "->stick",
                    "reversal": "slip"}[theirs.kind]
        assert expected in ours.kind


def test_invariants(case):
    _, _, result = case
    friction, normal = result["friction_force"], result["normal_force"]
    # Events are located to CVODE's root tolerance, 100 eps (|t| + |h|) ~ 1e-13 s:
    # at a stick exit the stick force has passed mu N by |dF/dt| * 1e-13 s at
    # most, and just before a slip->stick event the velocity has crossed zero
    # by |a| * 1e-13 s at most (|dF/dt| <= 50 N/s, |a| <= 10 m/s^2 here).
    root_time = 1e-13
    assert np.all(np.abs(friction) <= MU * normal + 50.0 * root_time)
    # Friction never does positive work: the dissipated energy never falls.
    assert np.all(np.diff(result["friction_loss"]) >= -1e-15)
    assert np.all(friction * result["v"] >= -MU * MASS * G * 10.0 * root_time)
    stick = result["stick"] == 1.0
    assert np.all(result["v"][stick] == 0.0)  # exactly, not approximately
    assert np.max(np.abs(result["energy_residual"])) <= 1e-9


def test_v4_has_stick_phases_and_v6_one():
    r4 = ls.simulate(block(4.0), 2.0)
    r6 = ls.simulate(block(6.0), 2.0)
    assert sum(e.kind.endswith("->stick") for e in r4.events) == 8
    assert sum(e.kind.endswith("->stick") for e in r6.events) == 0


def test_t_eval_output_and_frame():
    t = np.linspace(0, 2, 41)
    result = ls.simulate(block(6.0), 2.0, t_eval=t, rtol=1e-10, atol=1e-12)
    np.testing.assert_array_equal(result.t, t)
    reference = solve_block(MASS, MU, G, 6.0, OMEGA, t_end=2.0)
    np.testing.assert_allclose(result["u"], reference.position(t), atol=1e-8)
    frame = result.to_frame()
    assert list(frame.columns[:3]) == ["t", "u", "v"] and len(frame) == 41


def fitted_order(steps, errors):
    return np.polyfit(np.log(steps), np.log(errors), 1)[0]


def moreau_errors(amplitude, theta, dts):
    reference = solve_block(MASS, MU, G, amplitude, OMEGA, t_end=2.0)
    position, velocity = [], []
    for dt in dts:
        r = ls.simulate(block(amplitude), 2.0, integrator="moreau", dt=dt, theta=theta)
        position.append(np.max(np.abs(r["u"] - reference.position(r.t))))
        velocity.append(np.max(np.abs(r["v"] - reference.velocity(r.t))))
    return position, velocity


@pytest.mark.parametrize("amplitude", [6.0, 4.0])
def test_moreau_converges_at_first_order(amplitude):
    """theta = 1 (implicit Euler on the velocity level): exactly first order;
    theta = 1/2: at least first order (second order between events)."""
    dts = 2e-3 / 2.0 ** np.arange(5)
    position, velocity = moreau_errors(amplitude, 1.0, dts)
    assert 0.9 <= fitted_order(dts, position) <= 1.15
    assert 0.9 <= fitted_order(dts, velocity) <= 1.15
    position, velocity = moreau_errors(amplitude, 0.5, dts)
    assert fitted_order(dts, position) >= 0.9 and fitted_order(dts, velocity) >= 0.9
    r = ls.simulate(block(amplitude), 2.0, integrator="moreau", dt=1e-3)
    assert np.all(np.abs(r["friction_force"]) <= MU * MASS * G * (1 + 1e-12))
    assert np.all(np.diff(r["friction_loss"]) >= 0.0)
    assert np.all(r["v"][r["stick"] == 1.0] == 0.0)


def position_errors(friction, gains):
    reference = solve_block(MASS, MU, G, 6.0, OMEGA, t_end=2.0)
    errors = []
    for k_v in gains:
        r = ls.simulate(block(6.0), 2.0, friction=friction, k_v=k_v, rtol=1e-10, atol=1e-12)
        errors.append(np.max(np.abs(r["u"] - reference.position(r.t))))
    return errors


def test_velocity_regularization_converges_to_coulomb():
    """Eq. (3.16) tends to exact Coulomb; the position error falls like
    k_V^(-2/3) (the slip at each velocity zero lasts ~ k_V^(-1/3) longer)."""
    gains = (1.0, 10.0, 100.0, 1000.0, 1e4, 1e5)
    errors = position_errors("arctan_velocity", gains)
    assert all(b < a for a, b in zip(errors, errors[1:])), errors
    assert -0.75 <= fitted_order(gains[2:], errors[2:]) <= -0.55


def test_acceleration_regularization_error_falls_but_not_to_coulomb():
    """Eq. (3.15) puts the friction against the acceleration: as k_V grows the
    block no longer decelerates while |F| < mu m g, so the error falls (thesis
    Fig. 3.11) but levels off instead of vanishing."""
    errors = position_errors("arctan_acceleration", (1.0, 10.0, 100.0, 1000.0))
    assert all(b < a for a, b in zip(errors, errors[1:])), errors
    assert errors[-1] > 0.1


@pytest.mark.parametrize("integrator", REGULARIZED_INTEGRATORS)
def test_regularized_error_falls_with_tolerance(integrator):
    # Reference: the same regularized model at a tight tolerance.
    fine = ls.simulate(block(6.0), 2.0, friction="arctan_velocity", k_v=10.0,
                       integrator="cvode_bdf", rtol=1e-12, atol=1e-14,
                       t_eval=np.linspace(0, 2, 21))
    errors = []
    for rtol in (1e-4, 1e-6, 1e-8):
        r = ls.simulate(block(6.0), 2.0, friction="arctan_velocity", k_v=10.0,
                        integrator=integrator, rtol=rtol, atol=rtol * 1e-2,
                        t_eval=np.linspace(0, 2, 21))
        errors.append(np.max(np.abs(r["u"] - fine["u"])))
    assert errors[1] < errors[0] and errors[2] < errors[1], errors


@pytest.mark.parametrize("integrator", REGULARIZED_INTEGRATORS)
def test_regularized_invariants(integrator):
    r = ls.simulate(block(6.0), 2.0, friction="arctan_velocity", k_v=100.0,
                    integrator=integrator, rtol=1e-9, atol=1e-11)
    assert np.all(np.abs(r["friction_force"]) <= MU * MASS * G)
    assert np.all(r["friction_force"] * r["v"] >= 0.0)
    assert np.max(np.abs(r["energy_residual"])) < 1e-6


def test_callable_and_table_loads_agree_with_sine():
    t = np.linspace(0, 2, 4001)
    sine = ls.simulate(block(4.0), 2.0, t_eval=t)
    callable_force = ls.FrictionBlock(MASS, MU, g=G, force=lambda s: 4.0 * math.sin(OMEGA * s))
    r = ls.simulate(callable_force, 2.0, t_eval=t)
    np.testing.assert_allclose(r["u"], sine["u"], atol=1e-8)
    table = ls.FrictionBlock(MASS, MU, g=G, force=ls.Table([0, 1, 2], [0, 6, 0]))
    r = ls.simulate(table, 2.0)
    # |F| <= 3 N until t = 0.5 s: stuck; then slip; the table knot restarts the integrator.
    assert r.events[0].kind == "stick->slip+" and abs(r.events[0].time - 0.5) < 1e-10


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: ls.FrictionBlock(-1.0, 0.3), "mass"),
        (lambda: ls.FrictionBlock(1.0, -0.3), "mu"),
        (lambda: ls.FrictionBlock(1.0, 0.3, g=float("nan")), "g"),
        (lambda: ls.FrictionBlock(1.0, 0.3, force="strong"), "force"),
        (lambda: ls.simulate(block(6.0), 0.0), "t_end"),
        (lambda: ls.simulate(block(6.0), -1.0), "t_end"),
        (lambda: ls.simulate(block(6.0), 1.0, friction="viscous"), "friction"),
        (lambda: ls.simulate(block(6.0), 1.0, integrator="dopri5"), "integrator"),
        (lambda: ls.simulate(block(6.0), 1.0, friction="arctan_velocity", integrator="moreau"), "integrator"),
        (lambda: ls.simulate(block(6.0), 1.0, integrator="moreau", dt=-1e-3), "dt"),
        # 1 s of steps of 1 ms: 1000 steps, more than max_steps
        (lambda: ls.simulate(block(6.0), 1.0, integrator="moreau", dt=1e-3, max_steps=999),
         "needs 1000 steps, more than max_steps = 999"),
        (lambda: ls.simulate(block(6.0), 1.0, friction="arctan_velocity", integrator="dopri5",
                             max_order=3), "max_order = 3 is invalid: must be 0 for dopri5"),
        (lambda: ls.simulate(block(6.0), 1.0, friction="arctan_velocity", k_v=0.0), "k_v"),
        (lambda: ls.simulate(block(6.0), 1.0, t_eval=[0.5, 0.2]), "t_eval"),
        (lambda: ls.Sine(float("inf"), 1.0), "amplitude"),
        (lambda: ls.Table([0, 0], [1, 2]), "times"),
    ],
)
def test_bad_input_raises_value_error(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_unknown_names_list_the_allowed_values():
    with pytest.raises(ValueError, match='"coulomb", "arctan_velocity", "arctan_acceleration"'):
        ls.simulate(block(6.0), 1.0, friction="viscous")
    with pytest.raises(ValueError, match='"event_driven", "moreau"'):
        ls.simulate(block(6.0), 1.0, integrator="dopri5")


def test_callable_errors_propagate():
    def broken(t):
        raise RuntimeError("sensor failure")

    with pytest.raises(RuntimeError, match="sensor failure"):
        ls.simulate(ls.FrictionBlock(1.0, 0.3, force=broken), 1.0)
    with pytest.raises(ls.SimulationError, match="nan"):
        ls.simulate(ls.FrictionBlock(1.0, 0.3, force=lambda t: float("nan")), 1.0,
                    friction="arctan_velocity")


def test_friction_block_takes_unit_strings():
    given = ls.FrictionBlock("1 kg", "0.3", g="10 m/s^2", force=ls.Sine("6 N", "2 Hz"),
                             initial_position="5 mm", initial_velocity="-2 mm/s")
    plain = ls.FrictionBlock(1.0, 0.3, g=10.0, force=ls.Sine(6.0, 4 * math.pi),
                             initial_position=0.005, initial_velocity=-0.002)
    assert (given.mass, given.mu, given.g) == (plain.mass, plain.mu, plain.g)
    np.testing.assert_array_equal(ls.simulate(given, 0.5)["u"], ls.simulate(plain, 0.5)["u"])
    assert ls.FrictionBlock(1.0, 0.3, force="-2 N").force(0.0) == -2.0
    import pickle

    again = pickle.loads(pickle.dumps(given))
    assert repr(again) == repr(given)


@pytest.mark.parametrize("call, message", [
    (lambda: ls.FrictionBlock("1 m", 0.3), 'mass = "1 m" is invalid: "1 m" is not a mass (kg)'),
    (lambda: ls.FrictionBlock(1.0, None), "mu = None is invalid: must be a number"),
    (lambda: ls.FrictionBlock(1.0, 0.3, g="9.81 m/s"), 'g = "9.81 m/s" is invalid'),
    (lambda: ls.FrictionBlock(1.0, 0.3, force="6 N*m"),
     'force = "6 N*m" is invalid: "6 N*m" is not a force (N)'),
    (lambda: ls.FrictionBlock(1.0, 0.3, force=ls.Sine("6 N*m", 1.0)),
     "force = Sine(amplitude='6.0 N*m', omega=1.0, phase=0.0, offset='0.0 N*m') is invalid: its "
     "values are a torque (N*m), not a force (N)"),
    (lambda: ls.FrictionBlock(1.0, 0.3, force=ls.Constant("2 rad/s")), "force = Constant("),
    (lambda: ls.FrictionBlock(1.0, 0.3, initial_velocity="1 rad/s"),
     'initial_velocity = "1 rad/s" is invalid'),
])
def test_friction_block_names_a_bad_parameter(call, message):
    with pytest.raises(ValueError) as info:
        call()
    assert str(info.value).startswith(message), str(info.value)


def test_a_mistyped_option_is_refused_naming_it_and_both_lists():
    """A keyword that is neither simulate()'s nor any friction law's
    parameter names the closest option and what simulate and the law take;
    another law's parameter is the law's error (the core's)."""
    with pytest.raises(ValueError, match=r"^rtool = 1e-06 is invalid: simulate\(\) has no option "
                                         r"'rtool' and the friction law 'coulomb' no parameter "
                                         r"'rtool' \(did you mean 'rtol'\?\); simulate takes "
                                         r"friction, integrator, rtol, .*, the law mu, "
                                         r"mu_static$"):
        ls.simulate(block(6.0), 0.1, rtool=1e-6)
    with pytest.raises(ValueError, match=r"sigma0 is invalid for the friction law \"coulomb\""):
        ls.simulate(block(6.0), 0.1, sigma0=1e5)


@pytest.mark.parametrize("options, message", [
    ({"friction": "arctan_velocity", "dt": 1e-3},
     r"^dt = 0.001 is invalid with integrator 'cvode_bdf' \(the default here\): dt is taken by "
     r"moreau only"),
    ({"integrator": "event_driven", "dt": 1e-3},
     r"^dt = 0.001 is invalid with integrator 'event_driven': dt is taken by moreau only"),
    ({"friction": "arctan_velocity", "theta": 0.5},
     r"^theta = 0.5 is invalid with integrator 'cvode_bdf' \(the default here\)"),
    ({"integrator": "moreau", "rtol": 1e-6}, r"^rtol = 1e-06 is invalid with integrator "
                                             r"'moreau': moreau is a fixed-step scheme"),
    ({"integrator": "moreau", "max_order": 2}, r"^max_order = 2 is invalid with integrator "
                                               r"'moreau'"),
])
def test_options_the_integrator_would_ignore_are_refused(options, message):
    with pytest.raises(ValueError, match=message):
        ls.simulate(block(6.0), 0.1, **options)
    # left out, or None, they are not
    left_out = {key: (None if key not in ("friction", "integrator") else value)
                for key, value in options.items()}
    ls.simulate(block(6.0), 1.0, t_eval=[1.0], **left_out)


def test_dt_left_to_the_default_integrator_runs_moreau_jean():
    """Coulomb's block runs event-driven by default; dt (Moreau-Jean's step)
    given without an integrator runs Moreau-Jean with it."""
    result = ls.simulate(block(6.0), 2.0, dt=1e-3, t_eval=[1.0, 2.0])
    assert result.integrator == "moreau"
    explicit = ls.simulate(block(6.0), 2.0, integrator="moreau", dt=1e-3, t_eval=[1.0, 2.0])
    np.testing.assert_array_equal(result["v"], explicit["v"])


def test_simulate_passes_the_core_its_arguments_in_the_bindings_order():
    # simulate calls the core's simulate_block and simulate_drive by position
    # (faster than by keyword): their order must be the bindings', name for name.
    import re

    from leadscrew import _core
    from leadscrew.simulation import _BLOCK_CALL, _DRIVE_CALL

    for function, order in ((_core.simulate_block, _BLOCK_CALL),
                            (_core.simulate_drive, _DRIVE_CALL)):
        signature = function.__doc__.split("\n")[0]
        names = re.findall(r"(\w+): ", signature[signature.index("(") + 1:])
        assert tuple(names) == order
    # and each option reaches the core as given: a wrong rtol is named
    block = ls.FrictionBlock(1.0, 0.3, 10.0, 1.0)
    with pytest.raises(ValueError, match="rtol"):
        ls.simulate(block, 0.1, rtol=-1.0)
    with pytest.raises(ValueError, match="atol"):
        ls.simulate(block, 0.1, atol=-1.0)
    with pytest.raises(ValueError, match="theta"):
        ls.simulate(block, 0.1, integrator="moreau", theta=2.0)
