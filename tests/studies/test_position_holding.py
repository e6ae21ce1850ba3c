"""position_holding and the static holding band (thesis section 5.2, Fig. 5.4)."""

import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import leadscrew as ls  # noqa: E402
from helpers.scenes import thesis_scene  # noqa: E402
from leadscrew.studies.holding import (  # noqa: E402
    alternating_scene,
    cycle_response,
    plot_position_holding,
    position_holding,
    static_holding_band,
)

CLEARANCE = 2e-4  # m


def holding_scene(torque=5e-3, **changes):
    """Table 5.1 drive (tan a = 0.0159 < mu = 0.3: self-locking), exact backlash
    0.2 mm, a constant torque held by the thread."""
    changes.setdefault("backlash", {"axial": CLEARANCE})
    return ls.Scene.from_dict(thesis_scene(loads={"drive_torque": torque, "axial_force": 0.0},
                                           **changes))


@pytest.fixture(scope="module")
def held():
    return position_holding(holding_scene(), amplitude=30.0, frequency=20.0)


def test_static_load_holds_and_alternating_load_creeps(held):
    s = held.attrs["summary"]
    assert s["self_locking"] and s["holds_statically"]
    # Static: the nut crosses half the backlash onto the flank and sticks
    # there (the torque turns the screw a little during that flight).
    assert s["static_creep_per_cycle"] == pytest.approx(0.0, abs=1e-15)
    assert s["static_max_displacement"] == pytest.approx(CLEARANCE / 2, rel=1e-3)
    # Alternating: the flank unloads twice per cycle, the nut flies, the
    # torque turns the screw in flight (forward: the load moves along -x).
    assert s["dynamic_separations"] >= 2 * 8 - 2
    assert 0.05 < s["dynamic_flight_fraction"] < 0.95
    assert s["dynamic_creep_per_cycle"] < -1e-8
    assert s["dynamic_max_displacement"] > s["static_max_displacement"]


def test_creep_is_the_screw_turning(held):
    """u_load = -h p phi + (play change): over whole cycles, once the nut
    returns to the same flank, the creep is the lead per radian times the turn."""
    p = ls.Thread(1e-3, 20e-3).lead_per_radian
    per_cycle = 200  # points_per_cycle
    u = held["u_load_dynamic"].to_numpy()[::per_cycle]
    phi = held["phi_drive_dynamic"].to_numpy()[::per_cycle]
    np.testing.assert_allclose(np.diff(u[1:]), -p * np.diff(phi[1:]), rtol=1e-6)
    assert np.mean(np.diff(u[1:])) == pytest.approx(
        held.attrs["summary"]["dynamic_creep_per_cycle"], rel=1e-6)


def test_without_torque_a_self_locking_drive_does_not_creep():
    """Pure axial load, static or alternating: the nut flies across the play,
    but every plastic impact on a self-locking flank sticks, so nothing turns."""
    frame = position_holding(holding_scene(torque=0.0), amplitude=30.0, frequency=20.0,
                             cycles=4)
    s = frame.attrs["summary"]
    assert s["self_locking"] and s["holds_statically"]
    assert s["dynamic_separations"] > 0
    assert s["static_creep_per_cycle"] == 0.0
    assert abs(s["dynamic_creep_per_cycle"]) <= 1e-18  # round-off of the impacts
    # The impact impulses leave the screw at rest up to round-off (2e-17 rad seen).
    assert np.max(np.abs(frame["phi_drive_dynamic"])) <= 1e-15
    assert s["static_max_displacement"] == pytest.approx(CLEARANCE / 2, rel=1e-12)


def test_a_thread_that_is_not_self_locking_runs_down_under_pure_axial_load():
    scene = holding_scene(torque=0.0, friction={"law": "coulomb", "mu": 0.01})  # mu < tan a
    frame = position_holding(scene, amplitude=30.0, frequency=20.0, cycles=3)
    s = frame.attrs["summary"]
    assert not s["self_locking"] and not s["holds_statically"]
    # The -30 N force back-drives it along -x; the heavy screw (J / p^2 of
    # some 3000 kg) spins up slowly: tens of micrometres per cycle.
    assert s["static_creep_per_cycle"] < -1e-6


@pytest.mark.parametrize("drive", ["screw", "nut"])
@pytest.mark.parametrize("hand", ["right", "left"])
@pytest.mark.parametrize("force", [-20.0, 20.0])
def test_static_band_is_where_the_simulated_drive_holds(drive, hand, force):
    """Just inside the band the stuck drive stays put; just outside it moves
    (thread without play, the drive stuck at rest from t = 0)."""
    scene = ls.Scene.from_dict(thesis_scene(
        drive=drive, thread={"pitch": 1e-3, "mean_diameter": 20e-3, "hand": hand},
        load={"mass": 0.5},  # below the nut drive's jamming mass
        loads={"drive_torque": 0.0, "axial_force": force}))
    low, high = static_holding_band(scene, force)
    assert low < 0.0 < high
    for edge in (low, high):
        for factor, holds in ((0.98, True), (1.02, False)):
            loaded = scene.replace(loads={"drive_torque": factor * edge})
            u = ls.simulate(loaded, 0.02)["u_load"]
            assert (np.max(np.abs(u)) == 0.0) == holds, (edge, factor)


def test_static_band_closed_form():
    thread = ls.Thread(1e-3, 20e-3)
    low, high = static_holding_band(holding_scene(), -10.0)
    # Right hand: a positive torque moves the load along -x, with the force.
    assert high == pytest.approx(ls.lower_torque(thread, 0.3, 10.0), rel=1e-14)
    assert low == pytest.approx(-ls.raise_torque(thread, 0.3, 10.0), rel=1e-14)
    assert static_holding_band(holding_scene(), 0.0) == (0.0, 0.0)
    with pytest.raises(ValueError, match="axial_force"):
        static_holding_band(holding_scene(), math.inf)


@pytest.mark.parametrize("ratio", [5.0, -5.0, 0.5])
def test_static_band_behind_an_ideal_gear_stage(ratio):
    """(A new user's review: the band refused every geared scene.) Behind
    an ideal stage the rotor's torque T puts n T on the driven part (no
    loss), so the band is the driven part's divided by n, its ends swapped
    for a reversing stage; the static equilibrium exists just inside it and
    not just outside it (the rigid and the flexible drive), and the rigid
    drive run from rest stays put just inside it and moves just outside."""
    plain = static_holding_band(holding_scene(), -10.0)
    geared = static_holding_band(holding_scene(gear={"type": "ideal", "ratio": ratio}), -10.0)
    expected = sorted((plain[0] / ratio, plain[1] / ratio))
    assert geared == pytest.approx(expected, rel=1e-15)
    assert (geared[0] < 0.0 < geared[1]) and geared != pytest.approx(plain)
    for concept in ("rigid", "flexible_nut"):
        for edge in geared:
            for factor, holds in ((0.98, True), (1.02, False)):
                scene = ls.Scene.from_dict(thesis_scene(
                    concept=concept, gear={"type": "ideal", "ratio": ratio},
                    loads={"drive_torque": factor * edge, "axial_force": -10.0},
                    initial={"state": "equilibrium"}))
                if concept == "rigid":  # (and the drive run from rest)
                    u = ls.simulate(scene.replace(initial={"state": "relaxed"}), 0.02)["u_load"]
                    assert (np.max(np.abs(u)) == 0.0) == holds, (edge, factor)
                if holds:
                    scene.initial_state()
                else:
                    with pytest.raises(ls.NoEquilibriumError, match="friction cone"):
                        scene.initial_state()


def test_static_band_refuses_a_lossy_or_worm_stage():
    for stage in ({"type": "lossy", "ratio": 5.0, "efficiency": 0.9},
                  {"type": "worm", "ratio": 10.0, "lead_angle": 0.1, "mu": 0.1}):
        with pytest.raises(ValueError, match=rf"^gear.type = '{stage['type']}' is invalid for "
                                             r"static_holding_band: the band is derived for an "
                                             r"ideal stage only"):
            static_holding_band(holding_scene(gear=stage), -10.0)


@pytest.mark.parametrize("contact", ["bistop", "cubic"])
def test_a_penalty_contact_counts_its_flights(contact):
    """A penalty contact has no flank states (no events to 'open'): its
    separations are the flights that begin on the output times, at least
    one per half cycle as with the exact contact (12 in 6 cycles)."""
    scene = holding_scene(backlash={"axial": CLEARANCE, "contact": contact})
    out = cycle_response(alternating_scene(scene, 30.0, 20.0), 20.0, cycles=6,
                         points_per_cycle=200, series=True)
    assert 0.1 < out["flight_fraction"] < 0.5
    assert out["separations"] >= 2 * 6 - 1
    in_flight = out["result"]["gap"] > 1e-6 * CLEARANCE
    assert out["separations"] == sum(1 for before, now in zip(in_flight, in_flight[1:])
                                     if now and not before)


def test_the_two_runs_go_to_an_executor(held):
    import concurrent.futures

    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        pooled = position_holding(holding_scene(), amplitude=30.0, frequency=20.0,
                                  executor=pool, progress=False)
    columns = [c for c in held.columns]
    assert pooled[columns].equals(held[columns])
    summary = {k: v for k, v in pooled.attrs["summary"].items()}
    assert summary == held.attrs["summary"]


def test_amplitude_and_frequency_come_from_the_scenes_sine(held):
    sine = {"type": "sine", "amplitude": -30.0, "omega": 2 * math.pi * 20.0}
    from_scene = position_holding(holding_scene().replace(loads={"axial_force": sine}),
                                  progress=False)
    s = from_scene.attrs["summary"]
    assert s["excitation_from"] == "scene"
    assert s["amplitude"] == 30.0 and s["frequency"] == pytest.approx(20.0, rel=1e-15)
    assert held.attrs["summary"]["excitation_from"] == "arguments"
    defaults = position_holding(holding_scene(), cycles=2, progress=False).attrs["summary"]
    assert defaults["excitation_from"] == "defaults"
    assert (defaults["amplitude"], defaults["frequency"]) == (30.0, 20.0)


def test_cycle_response_and_alternating_scene():
    scene = alternating_scene(holding_scene(), 30.0, 20.0, offset=-40.0, on_flank=True)
    assert scene["initial"]["play_position"] == CLEARANCE / 2  # -x force, nut drive: upper
    assert scene["loads"]["axial_force"]["offset"] == -40.0
    out = cycle_response(scene, 20.0, cycles=3, points_per_cycle=50, series=True)
    assert out["separations"] == 0 and out["flight_fraction"] == 0.0
    assert out["creep_per_cycle"] == 0.0 and out["max_displacement"] == 0.0
    assert len(out["t"]) == 151 and out["t"][-1] == pytest.approx(0.15)
    with pytest.raises(ValueError, match="cycles"):
        cycle_response(scene, 20.0, cycles=1, settle_cycles=1)
    with pytest.raises(ValueError, match="frequency"):
        alternating_scene(holding_scene(), 30.0, 0.0)
    with pytest.raises(ValueError, match="offset"):
        alternating_scene(holding_scene(), 30.0, 20.0, offset=float("nan"))


def test_columns_units_and_plot(held):
    assert list(held.columns) == ["t", "axial_force_static", "u_load_static",
                                  "axial_force_dynamic", "u_load_dynamic", "phi_drive_dynamic",
                                  "gap_dynamic"]
    assert held.attrs["units"]["u_load_dynamic"] == "m"
    assert len(held) == 8 * 200 + 1
    assert np.all(held["axial_force_static"] == -30.0)
    np.testing.assert_allclose(held["axial_force_dynamic"],
                               30.0 * np.sin(2 * np.pi * 20.0 * held["t"]), atol=1e-12)
    ax = plot_position_holding(held)
    assert len(ax.lines) == 2


def test_bad_scenes_and_arguments():
    with pytest.raises(ValueError, match="drive_torque"):
        position_holding(ls.Scene.from_dict(thesis_scene()))  # the sine torque of (5.1)
    with pytest.raises(ValueError, match="drive_speed"):
        position_holding(ls.Scene.from_dict(thesis_scene(
            loads={"drive_torque": None, "drive_speed": 1.0})))
    with pytest.raises(ValueError, match="amplitude"):
        position_holding(holding_scene(), amplitude=0.0)
    with pytest.raises(ValueError, match="frequency"):
        position_holding(holding_scene(), frequency=-1.0)
    # Checked before either run: one message, not a failure of the first run.
    with pytest.raises(ValueError, match="rtol = -1 is invalid"):
        position_holding(holding_scene(), rtol=-1.0, progress=False)
    with pytest.raises(ValueError, match="cycles = 1 is invalid"):
        position_holding(holding_scene(), cycles=1, settle_cycles=1, progress=False)
    with pytest.raises(TypeError, match="frequncy"):
        position_holding(holding_scene(), frequncy=10.0, progress=False)


def test_position_holding_of_the_bistop_scene_without_torque():
    """The shipped scene (flexible, bistop, arctan_velocity) without drive
    torque: the static run (a constant -50 N) stopped at t = 4.8 ms, "the
    nut reached the end of the screw" (a Newton iterate at 0.55 m)."""
    scene = ls.scenes.load("position_holding").replace(loads={"drive_torque": 0.0})
    s = position_holding(scene, amplitude=50.0, progress=False).attrs["summary"]
    assert s["self_locking"] and s["holds_statically"]
    clearance = scene["backlash"]["axial"]
    # Onto the flank (half the play, a few um penetration and bounce) and held:
    # without torque only the arctan law's own slow slip, below a nanometre.
    assert clearance / 2 < s["static_max_displacement"] < clearance
    assert abs(s["static_creep_per_cycle"]) < 1e-9
    assert abs(s["dynamic_creep_per_cycle"]) < 1e-9


def test_every_number_of_the_summary_has_its_unit(held):
    summary, units = held.attrs["summary"], held.attrs["summary_units"]
    labels = {key for key, value in summary.items() if isinstance(value, (bool, str))}
    assert labels == {"self_locking", "holds_statically", "excitation_from"}
    assert set(units) == set(summary) - labels
    assert units["holding_torque"] == "N*m" and units["frequency"] == "Hz"
