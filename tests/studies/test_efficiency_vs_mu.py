"""efficiency_vs_mu: eq. (5.2) from simulated steady driving against the
closed form tan a / tan(a + rho') (thesis section 5.3, Fig. 5.6)."""

import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import leadscrew as ls  # noqa: E402
from helpers.scenes import thesis_scene  # noqa: E402
from leadscrew.studies import drive_efficiency  # noqa: E402
from leadscrew.studies.drive_efficiency import efficiency_vs_mu, plot_efficiency_vs_mu  # noqa: E402

MU = [0.0, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5]
LOADS = [5.0, 20.0, 80.0]  # N


def scene(**changes):
    return ls.Scene.from_dict(thesis_scene(**changes))


@pytest.fixture(scope="module")
def rigid():
    return efficiency_vs_mu(scene(), MU, LOADS, progress=False)


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
def test_simulated_efficiency_matches_the_closed_form(concept, rigid):
    """At steady state the motor needs the raising torque, so eta = tan a /
    tan(a + rho'); the flexible drives start with relaxed springs and settle
    (damping ratio 0.05) before the window."""
    frame = rigid if concept == "rigid" else efficiency_vs_mu(
        scene(concept=concept), [0.05, 0.3], [20.0], t_end=0.1, progress=False)
    assert frame["error"].isna().all() and frame["simulated"].all()
    np.testing.assert_allclose(frame["efficiency"], frame["efficiency_closed_form"], rtol=1e-3)
    assert (frame["window_change"] < 1e-3).all()
    thread = ls.Thread(1e-3, 20e-3)
    for row in frame.itertuples():
        assert row.efficiency_closed_form == ls.efficiency(thread, row.mu)
        # The motor's torque is the power-screw raising torque (the rotor turns
        # backwards to move the load along +x: the torque is negative).
        assert -row.drive_torque == pytest.approx(ls.raise_torque(thread, row.mu, row.load),
                                                  rel=1e-3)
        assert row.load_speed == pytest.approx(10.0 * thread.lead_per_radian, rel=1e-6)


def test_rigid_efficiency_is_exact_and_load_independent(rigid):
    np.testing.assert_allclose(rigid["efficiency"], rigid["efficiency_closed_form"], rtol=1e-12)
    by_mu = rigid.pivot(index="mu", columns="load", values="efficiency")
    table = by_mu.to_numpy()
    np.testing.assert_allclose(table, np.repeat(table[:, :1], len(LOADS), axis=1), rtol=1e-12)
    # Output work F v dt over the window, against the motor's work.
    thread = ls.Thread(1e-3, 20e-3)
    window = 0.1
    out = rigid["load"] * 10.0 * thread.lead_per_radian * window
    np.testing.assert_allclose(rigid["work_drive"] - rigid["friction_loss"], out, rtol=1e-12)


def test_efficiency_falls_with_mu(rigid):
    for _, group in rigid.groupby("load"):
        eta = group.sort_values("mu")["efficiency"].to_numpy()
        assert eta[0] == pytest.approx(1.0, abs=1e-15)
        assert np.all(np.diff(eta) < 0)


def test_non_drivable_friction_gives_zero_without_nan():
    """mu' >= cot(alpha) = 62.8: no torque turns the thread (eq. 3.7)."""
    cot = 1.0 / math.tan(ls.Thread(1e-3, 20e-3).lead_angle)
    frame = efficiency_vs_mu(scene(), [0.3, 1.01 * cot], [10.0], progress=False)
    assert list(frame["drivable"]) == [True, False]
    assert list(frame["simulated"]) == [True, False]
    row = frame.iloc[1]
    assert row["efficiency"] == 0.0 and row["efficiency_closed_form"] == 0.0
    assert row["relative_error"] == 0.0 and row["drive_torque"] == math.inf
    numeric = frame.select_dtypes("number")
    assert not numeric.isna().any().any()


def test_regularized_friction_loses_less_than_coulomb():
    """The arctan law gives a friction force below mu' N at finite slip, so
    the efficiency lies above the closed form (and tends to it as k_V grows)."""
    frame = efficiency_vs_mu(scene(friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4}),
                             [0.1, 0.3], [20.0], t_end=0.05, progress=False)
    assert (frame["efficiency"] > frame["efficiency_closed_form"]).all()
    assert (frame["relative_error"] < 0.05).all()


def test_failed_simulations_are_rows():
    frame = efficiency_vs_mu(scene(concept="flexible"), [0.1], [20.0], t_end=0.1,
                             max_steps=50, progress=False)
    assert frame.loc[0, "error"].startswith("SimulationError")
    assert np.isnan(frame.loc[0, "efficiency"])
    assert frame.loc[0, "efficiency_closed_form"] == ls.efficiency(ls.Thread(1e-3, 20e-3), 0.1)



@pytest.mark.parametrize("undrivable", [False, True])
def test_each_case_keeps_its_row_on_every_path(monkeypatch, undrivable):
    """A failed case among good ones, with and without a case that is not
    simulated: one batch call on every case (whose measures become the
    columns as they are) and chunks through an executor (placed row by row)
    give the same rows, the failure in its own."""
    from concurrent.futures import ThreadPoolExecutor

    from leadscrew.studies import _batch

    run = _batch.DriveBatch.run

    def second_mu_fails(self, values, workers=1):
        samples, errors, wall_time = run(self, values, workers)
        failing = np.flatnonzero(np.asarray(values)[:, 0] == MU[2])
        samples, errors, wall_time = samples.copy(), list(errors), wall_time.copy()
        samples[failing], wall_time[failing] = np.nan, np.nan
        for row in failing:
            errors[row] = "SimulationError: injected"
        return samples, errors, wall_time

    monkeypatch.setattr(_batch.DriveBatch, "run", second_mu_fails)
    cot = 1.0 / math.tan(ls.Thread(1e-3, 20e-3).lead_angle)
    mu = MU[:4] + ([1.01 * cot] if undrivable else [])
    with pytest.warns(ls.StudyWarning, match="efficiency_vs_mu: 2 of "):
        one_call = efficiency_vs_mu(scene(), mu, LOADS[:2], progress=False)
    with ThreadPoolExecutor(2) as executor:
        chunked = efficiency_vs_mu(scene(), mu, LOADS[:2], executor=executor, progress=False)
    failed = one_call["mu"] == MU[2]
    for frame in (one_call, chunked):  # the two loads of MU[2]
        assert frame.attrs["summary"]["raised"] == 2
        assert frame.attrs["summary"]["raised_reasons"] == (
            "2 SimulationError; first: SimulationError: injected")
    assert one_call["error"].tolist() == [
        "SimulationError: injected" if bad else None for bad in failed]
    assert one_call.loc[failed, "efficiency"].isna().all()
    assert (one_call.loc[~failed & one_call["drivable"], "relative_error"] < 1e-6).all()
    assert list(one_call["simulated"]) == [m < cot for m in one_call["mu"]]
    numeric = [c for c in one_call.columns if c not in ("wall_time", "error")]
    assert chunked[numeric].equals(one_call[numeric])
    assert chunked["error"].tolist() == one_call["error"].tolist()

@pytest.mark.parametrize("progress", [False, True])
def test_a_serial_executor_runs_the_batch_on_the_calling_thread(rigid, monkeypatch, progress):
    # SerialExecutor: the default path's batch calls with one worker (the
    # calling thread), the same rows as the core's thread pool.
    import threading

    from leadscrew.studies import _batch
    from leadscrew.studies._sweep import SerialExecutor

    calls = []
    run = _batch.DriveBatch.run

    def recording(self, values, workers=1):
        calls.append((workers, threading.current_thread() is threading.main_thread()))
        return run(self, values, workers)

    def no_chunks(*args, **kwargs):
        raise AssertionError("a SerialExecutor's sweep went through run_chunks")

    monkeypatch.setattr(_batch.DriveBatch, "run", recording)
    monkeypatch.setattr(drive_efficiency, "run_chunks", no_chunks)
    frame = efficiency_vs_mu(scene(), MU, LOADS, executor=SerialExecutor(), progress=progress)
    assert calls and all(call == (1, True) for call in calls)
    assert len(calls) == 1 or progress
    numeric = [c for c in frame.columns if c not in ("wall_time", "error")]
    assert frame[numeric].equals(rigid[numeric])
    assert frame["error"].tolist() == rigid["error"].tolist()


def test_a_shut_down_serial_executor_refuses_the_cases():
    from leadscrew.studies._sweep import SerialExecutor

    executor = SerialExecutor()
    executor.shutdown()
    frame = efficiency_vs_mu(scene(), [0.1, 0.2], [20.0], executor=executor, progress=False)
    assert frame["error"].str.contains("cannot schedule new calls after shutdown").all()
    assert frame["efficiency"].isna().all()


def test_columns_units_and_plot(rigid):
    assert len(rigid) == len(MU) * len(LOADS)
    assert list(rigid["mu"]) == [m for m in MU for _ in LOADS]
    units = rigid.attrs["units"]
    assert set(units) == set(rigid.columns)
    assert units["efficiency"] == "1" and units["load"] == "N" and units["work_drive"] == "J"
    assert rigid.attrs["summary"] == {"speed": 10.0, "window": (0.1, 0.2), "raised": 0,
                                      "raised_reasons": "none"}
    ax = plot_efficiency_vs_mu(rigid)
    assert len(ax.lines) == len(LOADS) + 1


@pytest.mark.parametrize("kwargs, match", [
    (dict(mu=[-0.1]), "mu"), (dict(loads=[0.0]), "loads"), (dict(speed=0.0), "speed"),
    (dict(window=(0.1, 0.05)), "window"), (dict(window=(0.0, 1.0)), "window"),
    (dict(window="late"), "window"), (dict(t_end=0.0), "t_end")])
def test_bad_arguments(kwargs, match):
    arguments = dict(mu=[0.1], loads=[10.0])
    arguments.update(kwargs)
    with pytest.raises(ValueError, match=match):
        efficiency_vs_mu(scene(), progress=False, **arguments)


def test_a_preloaded_nut_shows_its_cost():
    """With nut.preload P the closed form is F tan a / [(F + P) tan(a + rho')
    + P tan(rho' - a)] (docs/physics/preloaded_nut.md): load-dependent, below
    the plain thread's (efficiency_without_preload) wherever mu > 0."""
    from helpers import preloaded_nut_reference as reference

    preload = 50.0
    frame = efficiency_vs_mu(scene(nut={"preload": preload}), [0.0, 0.1, 0.3], [5.0, 80.0],
                             progress=False)
    np.testing.assert_allclose(frame["efficiency"], frame["efficiency_closed_form"], rtol=1e-9)
    thread = ls.Thread(1e-3, 20e-3)
    for row in frame.itertuples():
        mu_eff = reference.effective_mu(row.mu, thread.flank_angle)
        assert row.efficiency_closed_form == pytest.approx(
            reference.efficiency(row.load, preload, thread.lead_angle, mu_eff), rel=1e-12)
        assert row.efficiency_without_preload == ls.efficiency(thread, row.mu)
        if row.mu == 0.0:
            assert row.efficiency == pytest.approx(1.0, abs=1e-12)
        else:
            assert row.efficiency < row.efficiency_without_preload
    assert frame.attrs["summary"]["preload"] == preload
    assert frame.attrs["units"]["efficiency_without_preload"] == "1"
    ax = plot_efficiency_vs_mu(frame)
    assert len(ax.lines) == 2 + 2 + 1  # simulated and closed form per load, the plain thread


def test_a_left_hand_thread_is_raised_by_the_mirrored_turn(rigid):
    """Issue 31, item 12 (left-hand threads in the studies whose runs depend
    on the hand): the study raises the load, which on a left-hand thread
    takes the rotor's opposite turn (the load moves along -h x per forward
    turn). The mirror image of the right-hand drive: the same efficiency and
    load speed, the torque of the opposite sign. Turning as for a right hand
    would lower the load (a back-driving efficiency)."""
    left = efficiency_vs_mu(scene(thread={"pitch": 1e-3, "mean_diameter": 20e-3,
                                          "hand": "left"}), MU, LOADS, progress=False)
    assert left["error"].isna().all()
    for column in ("efficiency", "efficiency_closed_form", "load_speed", "friction_loss"):
        np.testing.assert_allclose(left[column], rigid[column], rtol=1e-12, atol=1e-15,
                                   err_msg=column)
    np.testing.assert_allclose(left["drive_torque"], -rigid["drive_torque"], rtol=1e-12,
                               atol=1e-15)
