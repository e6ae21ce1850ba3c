"""min_holding_preload: the design question that ends thesis section 5.2."""

import concurrent.futures
import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import leadscrew as ls  # noqa: E402
from helpers.scenes import thesis_scene  # noqa: E402
from leadscrew.studies.holding import min_holding_preload, plot_min_holding_preload  # noqa: E402

AMPLITUDE, FREQUENCY = 30.0, 20.0
EXCITATION = {"type": "sine", "amplitude": AMPLITUDE, "omega": 2 * math.pi * FREQUENCY}


def holding_scene(torque=5e-3, **changes):
    return ls.Scene.from_dict(thesis_scene(backlash={"axial": 2e-4},
                                           loads={"drive_torque": torque, "axial_force": 0.0},
                                           **changes))


def quasi_static_preload(torque, direction=-1.0, offset=0.0):
    """Closed form for the rigid drive: stuck, the load rests and the flank
    carries the applied force exactly, so the smallest force along the
    preload, P + direction offset - A, must keep the flank loaded and hold
    the torque with the power-screw torques (right hand: a positive torque
    moves the load along -x)."""
    thread = ls.Thread(1e-3, 20e-3)
    lowers = (torque > 0) == (direction < 0)
    per_newton = (ls.lower_torque if lowers else ls.raise_torque)(thread, 0.3, 1.0)
    return max(0.0, AMPLITUDE - direction * offset + abs(torque) / per_newton)


@pytest.fixture(scope="module")
def exact():
    return min_holding_preload(holding_scene(), EXCITATION, creep_limit=0.0, progress=False)


def test_zero_creep_limit_finds_the_closed_form(exact):
    s = exact.attrs["summary"]
    expected = quasi_static_preload(5e-3)
    assert s["quasi_static_preload"] == pytest.approx(expected, rel=1e-12)
    assert s["found"] and s["converged"]
    assert s["bracket_low"] < expected <= s["bracket_high"] * (1 + 1e-12)
    assert s["bracket_high"] - s["bracket_low"] <= 1e-3 * s["bracket_high"]
    assert s["min_preload"] == s["bracket_high"]
    # Every evaluated preload above the answer holds, every one below fails.
    ok = exact[exact["error"].isna()]
    assert (ok["holds"] == (ok["preload"] >= s["bracket_high"])).all()
    below = ok[ok["preload"] < AMPLITUDE]
    assert below["separated"].all()  # less preload than amplitude: the flank lets go
    holding = ok[ok["holds"]]
    assert (holding["creep_per_cycle"] == 0.0).all() and (holding["separations"] == 0).all()


def test_without_torque_the_amplitude_is_the_answer():
    frame = min_holding_preload(holding_scene(torque=0.0), ls.Sine(AMPLITUDE, EXCITATION["omega"]),
                                creep_limit=0.0, progress=False)
    s = frame.attrs["summary"]
    assert s["quasi_static_preload"] == AMPLITUDE
    assert s["bracket_low"] < AMPLITUDE <= s["bracket_high"] * (1 + 1e-12)


def test_reversed_preload_direction_raises_instead():
    frame = min_holding_preload(holding_scene(), EXCITATION, creep_limit=0.0, direction=1.0,
                                progress=False)
    s = frame.attrs["summary"]
    expected = quasi_static_preload(5e-3, direction=1.0)
    assert s["quasi_static_preload"] == pytest.approx(expected, rel=1e-12)
    assert s["bracket_low"] < expected <= s["bracket_high"] * (1 + 1e-12)


def test_a_creep_allowance_needs_less_preload(exact):
    """Slightly below the stick limit the drive slips a little near the force
    minimum; allowing 1 nm per cycle lowers the preload needed."""
    loose = min_holding_preload(holding_scene(), EXCITATION, creep_limit=1e-9, progress=False)
    s = loose.attrs["summary"]
    assert AMPLITUDE < s["min_preload"] < exact.attrs["summary"]["bracket_low"]
    held = loose[loose["holds"]]
    assert (np.abs(held["creep_per_cycle"]) <= 1e-9).all()
    assert (held["separations"] == 0).all()


def test_several_points_per_round_on_an_executor(exact):
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        frame = min_holding_preload(holding_scene(), EXCITATION, creep_limit=0.0,
                                    points_per_round=3, executor=pool, progress=False)
    s = frame.attrs["summary"]
    expected = quasi_static_preload(5e-3)
    assert s["bracket_low"] < expected <= s["bracket_high"] * (1 + 1e-12)
    assert s["iterations"] < exact.attrs["summary"]["iterations"]
    assert (frame.groupby("iteration").size().iloc[1:] == 3).all()


def test_iterations_are_bounded_and_unconverged_is_reported():
    frame = min_holding_preload(holding_scene(), EXCITATION, creep_limit=0.0, max_iterations=2,
                                progress=False)
    s = frame.attrs["summary"]
    assert s["iterations"] == 2 and not s["converged"] and s["found"]
    assert s["bracket_low"] < s["bracket_high"]


def test_an_upper_guess_that_fails_is_expanded():
    frame = min_holding_preload(holding_scene(), EXCITATION, creep_limit=0.0, upper=5.0,
                                tolerance=1e-2, progress=False)
    s = frame.attrs["summary"]
    assert list(frame["preload"][:5]) == [0.0, 5.0, 10.0, 20.0, 40.0]
    assert s["bracket_low"] < quasi_static_preload(5e-3) <= s["bracket_high"] * (1 + 1e-12)


@pytest.mark.parametrize("offset", [-10.0, 4.0])
def test_the_excitations_offset_adds_to_the_preload(offset):
    """An offset along the preload (direction -1: offset < 0) does part of
    its work, one against it needs more: the search and the closed form
    agree."""
    frame = min_holding_preload(holding_scene(), dict(EXCITATION, offset=offset),
                                creep_limit=0.0, progress=False)
    s = frame.attrs["summary"]
    expected = quasi_static_preload(5e-3, offset=offset)
    assert s["quasi_static_preload"] == pytest.approx(expected, rel=1e-12)
    assert s["found"] and s["converged"]
    # The search's first point is the closed form itself (half the default
    # upper end): exactly on the friction limit it may go either way.
    assert s["bracket_low"] <= expected <= s["bracket_high"] * (1 + 1e-12)


def test_an_offset_that_holds_alone_needs_no_preload():
    frame = min_holding_preload(holding_scene(torque=0.0), dict(EXCITATION, offset=-40.0),
                                creep_limit=0.0, progress=False)
    s = frame.attrs["summary"]
    assert s["quasi_static_preload"] == 0.0
    assert s["found"] and s["min_preload"] == 0.0  # the first evaluation, preload 0, holds
    assert frame["holds"].iloc[0] and frame["preload"].iloc[0] == 0.0


def test_columns_units_and_plot(exact):
    units = exact.attrs["units"]
    assert set(units) == set(exact.columns)
    assert units["preload"] == "N" and units["creep_per_cycle"] == "m"
    ax = plot_min_holding_preload(exact)
    assert ax.get_xlabel() == "static preload [N]"


def test_bad_scenes_and_arguments():
    with pytest.raises(ValueError, match="self-locking"):
        min_holding_preload(holding_scene(friction={"law": "coulomb", "mu": 0.01}), EXCITATION)
    with pytest.raises(ValueError, match="backlash"):
        min_holding_preload(ls.Scene.from_dict(thesis_scene(loads={"drive_torque": 0.0})),
                            EXCITATION)
    with pytest.raises(ValueError, match="excitation"):
        min_holding_preload(holding_scene(), ls.Constant(3.0))
    with pytest.raises(ValueError, match="excitation.omega is missing"):
        min_holding_preload(holding_scene(), {"type": "sine", "amplitude": 3.0})
    with pytest.raises(ValueError, match="direction"):
        min_holding_preload(holding_scene(), EXCITATION, direction=0.5)
    with pytest.raises(ValueError, match="creep_limit"):
        min_holding_preload(holding_scene(), EXCITATION, creep_limit=-1.0)
    with pytest.raises(ValueError, match="direction = True is invalid"):
        min_holding_preload(holding_scene(), EXCITATION, direction=True)
    # Checked once, before any case runs (not a row of errors per preload).
    for kwargs, match in [({"cycles": 0}, "cycles = 0 is invalid"),
                          ({"settle_cycles": -1}, "settle_cycles = -1 is invalid"),
                          ({"points_per_cycle": 2}, "points_per_cycle = 2 is invalid"),
                          ({"rtol": float("nan")}, "rtol = nan is invalid"),
                          ({"integrator": "euler"}, r"integrator = \"euler\" is invalid")]:
        with pytest.raises(ValueError, match=match):
            min_holding_preload(holding_scene(), EXCITATION, progress=False, **kwargs)
    with pytest.raises(TypeError, match="frequncy"):
        min_holding_preload(holding_scene(), EXCITATION, progress=False, frequncy=3.0)


def test_the_simulated_excitation_keeps_the_users_omega_bit_for_bit(monkeypatch):
    # 13.95 rad/s does not survive omega -> f -> omega (13.950000000000001).
    import leadscrew.studies.holding as holding
    omega = 13.95
    assert (omega / (2 * math.pi)) * 2 * math.pi != omega
    seen = []
    monkeypatch.setattr(holding, "cycle_response", lambda scene, *args, **kwargs: seen.append(
        scene["loads"]["axial_force"]["omega"]) or {})
    sine = {"amplitude": 30.0, "omega": omega, "phase": 0.0, "offset": 0.0}
    holding._preload_case(40.0, holding_scene(), sine, -1.0, 2, 1, 20, {})
    assert seen == [omega]


def test_every_number_of_the_summary_has_its_unit(exact):
    summary, units = exact.attrs["summary"], exact.attrs["summary_units"]
    labels = {key for key, value in summary.items() if isinstance(value, bool)}
    assert labels == {"converged", "found"}
    assert set(units) == set(summary) - labels
    assert units["min_preload"] == "N" and units["creep_limit"] == "m"
