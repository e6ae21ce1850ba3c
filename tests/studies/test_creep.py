"""creep_vs_frequency, creep_vs_backlash, creep_map (thesis Fig. 5.5)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

import leadscrew as ls  # noqa: E402
from helpers.scenes import thesis_scene  # noqa: E402
from leadscrew.studies.creep import (  # noqa: E402
    creep_map,
    creep_vs_backlash,
    creep_vs_frequency,
    plot_creep,
    plot_creep_map,
)
from leadscrew.studies.holding import alternating_scene, cycle_response  # noqa: E402

BACKLASH = [5e-5, 1e-4, 2e-4, 3e-4, 5e-4]  # m
FREQUENCIES = [5.0, 10.0, 20.0, 40.0, 80.0]  # Hz


def holding_scene(torque=5e-3):
    """Table 5.1 drive, exact backlash 0.2 mm, a 5 N mm torque held by the thread."""
    return ls.Scene.from_dict(thesis_scene(backlash={"axial": 2e-4},
                                           loads={"drive_torque": torque, "axial_force": 0.0}))


@pytest.fixture(scope="module")
def by_backlash():
    return creep_vs_backlash(holding_scene(), BACKLASH, frequency=20.0, progress=False)


@pytest.fixture(scope="module")
def by_frequency():
    return creep_vs_frequency(holding_scene(), FREQUENCIES, progress=False)


def test_creep_grows_with_backlash(by_backlash):
    """More play, longer flights: the torque turns the screw further per cycle."""
    assert by_backlash["error"].isna().all()
    creep = -by_backlash["creep_per_cycle"].to_numpy()  # forward torque: along -x
    assert np.all(creep > 0) and np.all(np.diff(creep) > 0)
    assert np.all(np.diff(by_backlash["flight_fraction"]) > 0)
    # The largest displacement is the crossing of half the play plus the creep.
    np.testing.assert_array_less(np.array(BACKLASH) / 2, by_backlash["max_displacement"])


def test_creep_per_cycle_falls_with_frequency(by_frequency):
    """Shorter half-periods, shorter flights: less turning per cycle (while the
    nut spends a growing share of the cycle in flight)."""
    assert by_frequency["error"].isna().all()
    creep = -by_frequency["creep_per_cycle"].to_numpy()
    assert np.all(creep > 0) and np.all(np.diff(creep) < 0)
    assert np.all(np.diff(by_frequency["flight_fraction"]) > 0)
    np.testing.assert_allclose(by_frequency["creep_rate"],
                               by_frequency["creep_per_cycle"] * by_frequency["frequency"],
                               rtol=1e-15)
    assert (by_frequency["separations"] >= 2 * (6 - 1)).all()


def test_creep_follows_the_torque():
    """Reversed torque, reversed creep; no torque, no creep at all (the
    self-locking flank sticks at every plastic impact)."""
    reversed_ = creep_vs_backlash(holding_scene(-5e-3), [1e-4, 3e-4], progress=False)
    assert np.all(reversed_["creep_per_cycle"] > 0)
    assert np.diff(reversed_["creep_per_cycle"])[0] > 0
    none = creep_map(holding_scene(0.0), [10.0, 40.0], [1e-4, 3e-4], cycles=3, progress=False)
    assert np.all(np.abs(none["creep_per_cycle"]) <= 1e-18)
    assert np.all(none["separations"] > 0)


@pytest.mark.parametrize("concept", ["flexible_nut", "flexible"])
def test_flexible_concepts_creep_with_the_torque_only(concept):
    """The light flexible nut rattles in the play, yet the screw turns (and
    the load creeps) only under the torque, more with more play; without it
    the screw stays put up to the integration tolerance (atol 1e-10 rad,
    times p = 1.6e-4 m/rad)."""
    scene = ls.Scene.from_dict(thesis_scene(concept=concept, backlash={"axial": 2e-4},
                                            loads={"drive_torque": 5e-3, "axial_force": 0.0}))
    frame = creep_vs_backlash(scene, [1e-4, 2e-4, 4e-4], progress=False)
    creep = -frame["creep_per_cycle"].to_numpy()
    assert frame["error"].isna().all()
    assert np.all(creep > 0) and np.all(np.diff(creep) > 0)
    assert (frame["flight_fraction"] > 0.5).all()  # the nut body rattles
    still = creep_vs_backlash(scene.replace(loads={"drive_torque": 0.0}), [1e-4, 4e-4],
                              cycles=4, progress=False)
    assert np.all(np.abs(still["creep_per_cycle"]) < 1e-14)


def test_nut_drive_creep_is_the_load_drift():
    """drive = "nut": the rotor turns the nut, the screw carries the load;
    back on its flank at every cycle boundary the rigid drive's load moves by
    exactly the creep per cycle."""
    scene = ls.Scene.from_dict(thesis_scene(drive="nut", load={"mass": 0.5},
                                            backlash={"axial": 2e-4},
                                            loads={"drive_torque": 5e-3, "axial_force": 0.0}))
    # Both measures come from one simulation; they agree to its tolerance.
    out = cycle_response(alternating_scene(scene, 30.0, 20.0), 20.0, cycles=6, series=True,
                         rtol=1e-12, atol=1e-14)
    drift = np.diff(out["result"]["u_load"][::100][1:])
    assert out["creep_per_cycle"] < 0
    np.testing.assert_allclose(drift, out["creep_per_cycle"], rtol=1e-9)


@pytest.mark.parametrize("drive", ["screw", "nut"])
def test_a_left_hand_thread_creeps_as_the_mirrored_right_hand_one(drive):
    """Issue 31, item 12: no left-hand creep was tested, so a creep per cycle
    that ignored the thread's hand passed. The mirror image of a right-hand
    drive under the torque M is the left-hand drive under -M: the rotor
    turns the other way and the load moves alike, so both creep by the same
    amount per cycle, and on the rigid drive (back on its flank at each cycle
    boundary) that is the load's drift per cycle (a measure of its own, from
    u_load)."""
    def creep(hand, torque):
        scene = ls.Scene.from_dict(thesis_scene(
            drive=drive, load={"mass": 0.5}, backlash={"axial": 2e-4},
            thread={"pitch": 1e-3, "mean_diameter": 20e-3, "hand": hand},
            loads={"drive_torque": torque, "axial_force": 0.0}))
        return cycle_response(alternating_scene(scene, 30.0, 20.0), 20.0, cycles=6,
                              series=True, rtol=1e-12, atol=1e-14)

    right, left = creep("right", 5e-3), creep("left", -5e-3)
    assert right["creep_per_cycle"] != 0.0
    assert left["creep_per_cycle"] == pytest.approx(right["creep_per_cycle"], rel=1e-9)
    drift = np.diff(left["result"]["u_load"][::100][1:])
    np.testing.assert_allclose(drift, left["creep_per_cycle"], rtol=1e-9)


def test_map_agrees_with_the_line_sweeps(by_backlash, by_frequency):
    frame = creep_map(holding_scene(), [10.0, 20.0], [1e-4, 2e-4, 5e-4], progress=False)
    assert len(frame) == 6
    assert list(frame["frequency"]) == [10.0] * 3 + [20.0] * 3
    assert list(frame["backlash"]) == [1e-4, 2e-4, 5e-4] * 2
    at_20 = frame[frame["frequency"] == 20.0].drop(columns="wall_time").reset_index(drop=True)
    line = by_backlash[by_backlash["backlash"].isin([1e-4, 2e-4, 5e-4])]
    pd.testing.assert_frame_equal(at_20, line.drop(columns="wall_time").reset_index(drop=True),
                                  check_exact=True)
    at_2e4 = frame[frame["backlash"] == 2e-4]
    line = by_frequency[by_frequency["frequency"].isin([10.0, 20.0])]
    np.testing.assert_array_equal(at_2e4["creep_per_cycle"], line["creep_per_cycle"])


def test_columns_units_and_plots(by_backlash, by_frequency):
    units = by_backlash.attrs["units"]
    assert set(units) == set(by_backlash.columns)
    assert units["creep_per_cycle"] == "m" and units["frequency"] == "Hz"
    assert by_backlash.attrs["summary"] == {"amplitude": 30.0, "cycles": 6, "settle_cycles": 1,
                                            "excitation_from": "defaults", "raised": 0,
                                            "raised_reasons": "none"}
    ax = plot_creep(by_backlash)
    assert ax.get_xlabel() == "backlash [mm]"
    ax = plot_creep(by_frequency, quantity="max_displacement")
    assert ax.get_xlabel() == "frequency [Hz]"
    frame = creep_map(holding_scene(), [10.0, 20.0], [1e-4, 2e-4], cycles=3, progress=False)
    ax = plot_creep_map(frame)
    assert ax.get_ylabel() == "backlash [mm]"
    with pytest.raises(ValueError, match="exactly one"):
        plot_creep(frame)
    with pytest.raises(ValueError, match="quantity"):
        plot_creep(by_backlash, quantity="creep")


@pytest.mark.parametrize("grid", [[], [0.0], [-1.0], [float("nan")], [[1.0, 2.0]]])
def test_bad_grids(grid):
    with pytest.raises(ValueError, match="frequencies"):
        creep_vs_frequency(holding_scene(), grid)


def test_bad_scenes_and_arguments():
    no_play = ls.Scene.from_dict(thesis_scene(loads={"drive_torque": 5e-3}))
    with pytest.raises(ValueError, match="backlash"):
        creep_vs_frequency(no_play, [10.0])
    frame = creep_vs_backlash(no_play, [1e-4], cycles=3, progress=False)  # adds exact play
    assert frame.loc[0, "creep_per_cycle"] < 0
    with pytest.raises(ValueError, match="drive_torque"):
        creep_vs_backlash(ls.Scene.from_dict(thesis_scene()), [1e-4])
    with pytest.raises(ValueError, match="cycles"):
        creep_vs_backlash(holding_scene(), [1e-4], cycles=1)
    with pytest.raises(ValueError, match="amplitude"):
        creep_map(holding_scene(), [10.0], [1e-4], amplitude=-3.0)
    # Simulate options: checked once, before the cases run.
    with pytest.raises(ValueError, match="rtol = nan is invalid"):
        creep_vs_frequency(holding_scene(), [10.0, 20.0], rtol=float("nan"), progress=False)
    with pytest.raises(ValueError, match="max_steps = 0 is invalid"):
        creep_map(holding_scene(), [10.0], [1e-4, 2e-4], max_steps=0, progress=False)
    with pytest.raises(TypeError, match="bogus"):
        creep_vs_backlash(holding_scene(), [1e-4], bogus=True, progress=False)


def test_the_excitation_is_the_scenes_unless_an_argument_gives_it(by_frequency):
    """One rule for every study: the scene's sine is the default (its
    amplitude, and its frequency where the study does not sweep it), an
    argument overrides; without a sine, 30 N and 20 Hz."""
    sine = {"type": "sine", "amplitude": -30.0, "omega": 2 * np.pi * 20.0}
    scene = holding_scene().replace(loads={"axial_force": sine})
    from_scene = creep_vs_frequency(scene, FREQUENCIES, progress=False)
    assert from_scene.attrs["summary"]["excitation_from"] == "scene"
    assert from_scene.attrs["summary"]["amplitude"] == 30.0
    assert by_frequency.attrs["summary"]["excitation_from"] == "defaults"
    measures = ["creep_per_cycle", "max_displacement", "separations", "flight_fraction"]
    pd.testing.assert_frame_equal(from_scene[measures], by_frequency[measures])
    # 30 N of the scene, not 10 N: the argument overrides the scene's amplitude.
    loud = scene.replace(loads={"axial_force": dict(sine, amplitude=10.0, omega=2 * np.pi * 5)})
    given = creep_vs_frequency(loud, [20.0], amplitude=30.0, progress=False)
    assert given.attrs["summary"]["excitation_from"] == "arguments"
    assert given["creep_per_cycle"].iloc[0] == by_frequency["creep_per_cycle"].iloc[2]
    # creep_vs_backlash takes the scene's frequency (5 Hz) and amplitude (10 N).
    frame = creep_vs_backlash(loud, [2e-4], cycles=3, progress=False)
    assert list(frame["frequency"]) == [pytest.approx(5.0, rel=1e-15)]
    assert frame.attrs["summary"]["amplitude"] == 10.0
    expected = creep_vs_backlash(holding_scene(), [2e-4], frequency=5.0, amplitude=10.0,
                                 cycles=3, progress=False)
    np.testing.assert_array_equal(frame["creep_per_cycle"], expected["creep_per_cycle"])
    assert creep_map(loud, [20.0], [2e-4], cycles=3,
                     progress=False).attrs["summary"]["amplitude"] == 10.0


def test_a_sweep_of_one_value_is_drawn_against_the_parameter_given(by_frequency):
    one = by_frequency.iloc[:1]
    with pytest.raises(ValueError, match="or give x"):
        plot_creep(one)
    ax = plot_creep(one, x="frequency")
    assert ax.get_xlabel() == "frequency [Hz]" and len(ax.lines[0].get_xdata()) == 1
    assert plot_creep(one, x="backlash").get_xlabel() == "backlash [mm]"
    with pytest.raises(ValueError, match="x = 'mu' is invalid"):
        plot_creep(one, x="mu")


def test_cases_that_raised_are_counted_and_warned(monkeypatch):
    """A case that raises is a row with its message and NaN numbers; the
    summary counts such rows by exception type, and a StudyWarning names
    them (as the command line's warning does)."""
    import leadscrew.studies.creep as creep

    def case(pair, *args, **kwargs):
        frequency, _ = pair
        if frequency == 20.0:
            raise ls.JammingError("jammed at t = 0.1 s")
        if frequency == 40.0:
            raise ls.SimulationError("too many steps")
        return {name: 0.0 for name in creep._MEASURES}

    monkeypatch.setattr(creep, "_creep_case", case)
    with pytest.warns(ls.StudyWarning, match=r"creep_vs_frequency: 2 of 5 rows raised and "
                                             r"decide nothing \(their error column says why\): "
                                             r"1 JammingError, 1 SimulationError; first: "
                                             r"JammingError: jammed at t = 0.1 s"):
        frame = creep_vs_frequency(holding_scene(), FREQUENCIES, progress=False)
    summary = frame.attrs["summary"]
    assert summary["raised"] == 2 and frame.attrs["summary_units"]["raised"] == "1"
    assert frame["error"].notna().tolist() == [False, False, True, True, False]
    assert frame.loc[2:3, "creep_per_cycle"].isna().all()
