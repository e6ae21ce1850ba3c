"""stick_slip: the alternating-torque case of thesis section 5.1 (Fig. 5.1)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import leadscrew as ls  # noqa: E402
from helpers import rigid_drive_reference as reference  # noqa: E402
from helpers.scenes import thesis_scene  # noqa: E402
from leadscrew.studies.stickslip import plot_stick_slip, stick_slip, stick_slip_phases  # noqa: E402


@pytest.fixture(scope="module")
def frame():
    # The reference's rotor inertia (1e-6 kg m^2), load case (5.1).
    return stick_slip(ls.Scene.from_dict(thesis_scene(rotor={"inertia": 1e-6})), t_end=2.0,
                      rtol=1e-12, atol=1e-14)


def test_phases_match_the_independent_reference(frame):
    """Stick and slip phases start and end where the closed-form rigid drive
    of tests/helpers/rigid_drive_reference.py switches."""
    expected = reference.simulate(reference.thesis_drive(), *reference.thesis_loads(), 2.0)
    phases = stick_slip_phases(frame)
    assert len(phases) == len(expected.phases)
    for ours, theirs in zip(phases.itertuples(), expected.phases):
        assert ours.phase.rstrip("+-") == theirs.kind
        assert ours.start == pytest.approx(theirs.t0, abs=1e-9)
        assert ours.end == pytest.approx(theirs.t1, abs=1e-9)
    stick_time = sum(p.t1 - p.t0 for p in expected.phases if p.kind == "stick")
    summary = frame.attrs["summary"]
    assert summary["stick_phases"] == sum(p.kind == "stick" for p in expected.phases) == 8
    assert summary["slip_phases"] == 8
    assert summary["stick_fraction"] == pytest.approx(stick_time / 2.0, abs=1e-9)
    assert summary["events"] == len(expected.events)


def test_phase_labels_agree_with_the_friction_law(frame):
    """Stuck: the load rests and the friction force lies inside the cone;
    slipping: it is on the cone and opposes the slip."""
    mu = 0.3  # flank angle 0: mu' = mu
    stick = frame[frame["phase"] == "stick"]
    # Stuck, the load's velocity is zero up to round-off of the stick map
    # (1e-32 m/s seen).
    assert np.all(np.abs(stick["v_load"]) <= 1e-20)
    assert np.all(np.abs(stick["friction_force"]) <= mu * np.abs(stick["normal_force"]) + 1e-12)
    # Off the event instants (where the slip velocity is zero up to round-off).
    between = ~frame["t"].duplicated(keep=False)
    slip = frame[frame["phase"].isin(["slip+", "slip-"]) & between]
    np.testing.assert_allclose(np.abs(slip["friction_force"]),
                               mu * np.abs(slip["normal_force"]), rtol=1e-9)
    sign = np.where(slip["phase"] == "slip+", 1.0, -1.0)
    assert np.all(np.sign(slip["slip_velocity"]) == sign)
    assert np.all(np.sign(slip["friction_force"]) == -sign)
    for row in stick_slip_phases(frame).itertuples():
        if row.phase == "stick":
            inside = frame[(frame["t"] >= row.start) & (frame["t"] <= row.end)]
            assert np.ptp(inside["u_load"]) <= 1e-18


def test_columns_units_and_plot(frame):
    units = frame.attrs["units"]
    assert set(units) == set(frame.columns)
    assert units["t"] == "s" and units["u_load"] == "m" and units["drive_torque"] == "N*m"
    assert frame["t"].iloc[-1] == 2.0 and frame["t"].is_monotonic_increasing
    assert set(frame["phase"]) <= {"stick", "slip+", "slip-"}
    ax = plot_stick_slip(frame)
    assert ax.get_ylabel() == "load position u [mm]"
    assert len(ax.lines) == 1 and len(ax.patches) == 8  # one shade per stick phase


def test_backlash_adds_open_phases():
    scene = ls.Scene.from_dict(thesis_scene(backlash={"axial": 2e-4}))
    frame = stick_slip(scene, t_end=0.6)
    assert "gap" in frame and frame.attrs["units"]["gap"] == "m"
    is_open = (frame["phase"] == "open") & ~frame["t"].duplicated(keep=False)
    assert is_open.any()  # the initial flight onto the flank the -10 N press it against
    assert np.all(frame.loc[is_open, "gap"] > 0.0)
    assert np.all(frame.loc[is_open, "normal_force"] == 0.0)


@pytest.mark.parametrize("t_end", [0.0, -1.0, float("nan")])
def test_bad_arguments(t_end):
    with pytest.raises(ValueError, match="t_end"):
        stick_slip(ls.Scene.from_dict(thesis_scene()), t_end=t_end)
    with pytest.raises(ValueError, match="scene"):
        stick_slip("thesis", t_end=1.0)
    with pytest.raises(ValueError, match="phase"):
        stick_slip_phases(ls.simulate(ls.Scene.from_dict(thesis_scene()), 0.1).to_frame())


def test_the_simulation_runs_on_an_executor(frame):
    import concurrent.futures

    scene = ls.Scene.from_dict(thesis_scene(rotor={"inertia": 1e-6}))
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        pooled = stick_slip(scene, t_end=2.0, rtol=1e-12, atol=1e-14, executor=pool,
                            progress=False)
    assert pooled.drop(columns="phase").equals(frame.drop(columns="phase"))
    assert pooled["phase"].tolist() == frame["phase"].tolist()
    summary = dict(pooled.attrs["summary"], wall_time=None)
    assert summary == dict(frame.attrs["summary"], wall_time=None)
    # the run's own exception comes back from the executor
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        with pytest.raises(ls.SimulationError):
            stick_slip(scene, t_end=2.0, executor=pool, max_steps=3)


def test_every_number_of_the_summary_has_its_unit(frame):
    assert set(frame.attrs["summary_units"]) == set(frame.attrs["summary"])
    assert frame.attrs["summary_units"]["u_final"] == "m"


def test_the_series_has_the_requested_points_and_the_phases_stay_exact(frame):
    """stick_slip wrote every integrator step (a flexible drive: 187,235
    rows, 36.7 MB for 1 s); it samples ``points`` times (default 2001, as
    leadscrew run), and its phases still start and end at the events."""
    scene = ls.Scene.from_dict(thesis_scene(rotor={"inertia": 1e-6}))
    sampled = stick_slip(scene, t_end=2.0, points=101, rtol=1e-12, atol=1e-14)
    assert len(sampled) == 101
    np.testing.assert_array_equal(sampled["t"], np.linspace(0.0, 2.0, 101))
    phases, exact = stick_slip_phases(sampled), stick_slip_phases(frame)
    assert len(phases) == len(exact) == 16
    assert (phases["phase"] == exact["phase"]).all()
    np.testing.assert_allclose(phases[["start", "end"]], exact[["start", "end"]], atol=1e-9)
    assert sampled.attrs["summary"]["stick_phases"] == frame.attrs["summary"]["stick_phases"]
    assert len(frame) == 2001  # the default
    every = stick_slip(scene, t_end=2.0, points=0)  # every step, every event twice
    assert every["t"].duplicated().sum() == len(every.attrs["events"]) == 15
    with pytest.raises(ValueError, match="points = 1 is invalid"):
        stick_slip(scene, t_end=1.0, points=1)
    with pytest.raises(ValueError, match="points = -2 is invalid"):
        stick_slip(scene, t_end=1.0, points=-2)
    with pytest.raises(ValueError, match="points = 11 is invalid with t_eval"):
        stick_slip(scene, t_end=1.0, points=11, t_eval=[0.0, 1.0])
    assert len(stick_slip(scene, t_end=1.0, t_eval=[0.0, 0.5, 1.0])) == 3


def test_a_flexible_drive_writes_its_points_not_its_steps():
    """The shipped thesis drive (flexible screw and nut) takes tens of
    thousands of steps for 0.2 s; the frame holds the 2001 points."""
    scene = ls.scenes.load("thesis_table_5_1")
    frame = stick_slip(scene, t_end=0.2)
    assert len(frame) == 2001 and frame["t"].iloc[-1] == 0.2
    phases = stick_slip_phases(frame)
    assert phases["start"].iloc[0] == 0.0 and phases["end"].iloc[-1] == 0.2
    assert (phases["duration"] > 0).all()
    events = [time for time, kind in frame.attrs["events"] if "->" in kind]
    assert np.isin(phases["start"].iloc[1:], events).all()  # the phases change at events
