"""leadscrew.studies.work_precision: the frame, the reference, the convergence
of every integrator with its tolerance, failures and bad input.

The errors are checked against the independent closed form of the thesis's
block (tests/helpers/block_reference.py)."""

import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import leadscrew as ls  # noqa: E402
from helpers.block_reference import solve_block  # noqa: E402
from helpers.scenes import thesis_scene  # noqa: E402
from leadscrew import _core, studies  # noqa: E402

MASS, MU, G, OMEGA, T_END = 1.0, 0.3, 10.0, 4 * math.pi, 2.0


def block(amplitude=6.0):
    return ls.FrictionBlock(MASS, MU, g=G, force=ls.Sine(amplitude, OMEGA))


@pytest.fixture(scope="module")
def closed_form():
    return solve_block(MASS, MU, G, 6.0, OMEGA, t_end=T_END)


MIXED = [
    {"friction": "coulomb", "integrator": "event_driven", "rtol": 1e-8},
    {"friction": "coulomb", "integrator": "moreau", "dt": 1e-3, "theta": 1.0},
    {"friction": "arctan_velocity", "integrator": "cvode_bdf", "k_v": 100.0, "rtol": 1e-6},
    {"friction": "arctan_acceleration", "integrator": "rk_verner6", "k_v": 10.0, "rtol": 1e-6,
     "atol": 1e-9},
]


@pytest.fixture(scope="module")
def mixed_frame(closed_form):
    return studies.work_precision(block(), T_END, configurations=MIXED,
                                  reference=closed_form.position, repeats=2)


def test_registry_and_exports():
    assert studies.STUDIES["work_precision"] is studies.work_precision
    assert set(studies.__all__) >= {"STUDIES", "work_precision", "plot_work_precision"}
    assert all(hasattr(studies, name) for name in studies.__all__)


def test_frame_shape_columns_and_values(mixed_frame, closed_form):
    frame = mixed_frame
    assert list(frame.columns) == list(studies.COLUMNS)
    assert len(frame) == len(MIXED)
    assert list(frame["friction"]) == [c["friction"] for c in MIXED]
    assert list(frame["integrator"]) == [c["integrator"] for c in MIXED]
    # Parameters that do not apply are NaN; a missing atol is 1e-2 rtol.
    assert np.isnan(frame["k_v"][0]) and np.isnan(frame["k_v"][1])
    assert frame["k_v"][2] == 100.0 and frame["k_v"][3] == 10.0
    assert np.isnan(frame["dt"][0]) and frame["dt"][1] == 1e-3 and frame["theta"][1] == 1.0
    assert np.isnan(frame["rtol"][1]) and np.isnan(frame["atol"][1])
    assert frame["atol"][0] == pytest.approx(1e-10) and frame["atol"][3] == 1e-9
    assert (frame["failure"] == "").all()
    for column in ("error_max", "error_final", "wall_time", "wall_time_python"):
        assert np.all(np.isfinite(frame[column])) and np.all(frame[column] > 0)
    assert np.all(frame["error_final"] <= frame["error_max"])
    # The timing through Python includes the C++ run.
    assert np.all(frame["wall_time_python"] >= frame["wall_time"])
    # Counters are those of a run of the same configuration.
    run = ls.simulate(block(), T_END, friction="coulomb", integrator="event_driven",
                      rtol=1e-8, atol=1e-10)
    for column in ("steps", "rhs_evaluations", "events", "lcp_solves", "nonlinear_iterations"):
        assert frame[column][0] == run.stats[column]
    assert frame["events"][0] == len(closed_form.events) == 8
    assert frame["steps"][1] == 2000 and frame["lcp_solves"][1] == 2000
    assert frame["nonlinear_iterations"][3] > 0 and frame["nonlinear_iterations"][2] == 0
    # The error is that of the run against the closed form, recomputed here.
    assert frame["error_max"][0] == pytest.approx(
        np.max(np.abs(run["u"] - closed_form.position(run.t))), rel=1e-12)
    assert frame["error_final"][0] == pytest.approx(
        abs(run["u"][-1] - closed_form.position(T_END)), rel=1e-12)
    assert frame.attrs["quantity"] == "u" and frame.attrs["repeats"] == 2


def test_magnitudes_against_coulomb(mixed_frame):
    """Exact Coulomb to ~1e-10 m event-driven and ~dt with Moreau-Jean; the
    regularized laws are off by their regularization (test_simulation_block)."""
    error = mixed_frame["error_max"]
    assert error[0] < 1e-9
    assert 1e-5 < error[1] < 1e-2
    assert 1e-3 < error[2] < 0.1  # k_V = 100, eq. (3.16)
    assert error[3] > 0.1  # eq. (3.15) does not tend to Coulomb


@pytest.mark.parametrize("amplitude", [6.0, 4.0], ids=["V=6", "V=4"])
def test_default_reference_is_the_closed_form(amplitude):
    """The default reference (event-driven at rtol 1e-13) equals the closed
    form to round-off, at event times too, so errors of 1e-11 m and above are
    measured exactly."""
    exact = solve_block(MASS, MU, G, amplitude, OMEGA, t_end=T_END)
    times = np.sort(np.concatenate([np.linspace(0, T_END, 1001), exact.event_times()]))
    reference = studies.exact_reference(block(amplitude), T_END)
    assert np.max(np.abs(reference(times) - exact.position(times))) <= 1e-13
    assert reference(np.array([[0.5, 1.0]])).shape == (1, 2)
    configurations = [{"integrator": "event_driven", "rtol": 1e-6},
                      {"integrator": "moreau", "dt": 1e-3}]
    default = studies.work_precision(block(amplitude), T_END, configurations, repeats=1)
    closed = studies.work_precision(block(amplitude), T_END, configurations,
                                    reference=exact.position, repeats=1)
    np.testing.assert_allclose(default["error_max"], closed["error_max"], rtol=1e-3, atol=1e-13)
    assert "event_driven" in default.attrs["reference"]


def fitted_order(knobs, errors):
    return np.polyfit(np.log(knobs), np.log(errors), 1)[0]


@pytest.mark.parametrize("amplitude", [6.0, 4.0], ids=["V=6", "V=4"])
def test_event_driven_error_falls_with_tolerance(amplitude):
    """Against the closed form. Looser than 1e-8 the load's time scale bounds
    the step (the error is already ~1e-10 m); from there on it falls about
    like rtol (slope near 1)."""
    exact = solve_block(MASS, MU, G, amplitude, OMEGA, t_end=T_END)
    tolerances = [1e-8, 1e-9, 1e-10, 1e-11, 1e-12]
    frame = studies.work_precision(
        block(amplitude), T_END, [{"integrator": "event_driven", "rtol": r} for r in tolerances],
        reference=exact.position, repeats=1)
    errors = frame["error_max"].to_numpy()
    assert np.all(np.diff(errors) < 0), errors
    assert 0.8 <= fitted_order(tolerances, errors) <= 1.2
    assert np.all(np.diff(frame["steps"]) > 0)


def test_moreau_error_falls_with_dt(closed_form):
    steps = 2e-3 / 2.0 ** np.arange(5)
    frame = studies.work_precision(
        block(), T_END, [{"integrator": "moreau", "dt": dt, "theta": 1.0} for dt in steps],
        reference=closed_form.position, repeats=1)
    assert 0.9 <= fitted_order(steps, frame["error_max"]) <= 1.15
    assert list(frame["steps"]) == [round(T_END / dt) for dt in steps]


REGULARIZED_CASES = [("arctan_velocity", name) for name in
                     _core.block_integrators("arctan_velocity")] + \
                    [("arctan_acceleration", "cvode_bdf"), ("arctan_acceleration", "rk_dopri5")]


@pytest.mark.parametrize("friction, integrator", REGULARIZED_CASES)
def test_regularized_error_falls_with_tolerance(friction, integrator):
    """Against a tight run of the same regularized law (a Result reference):
    the error falls at every tolerance step, and by at least 1e3 over the four
    decades of rtol (all these methods are of order >= 2)."""
    times = np.linspace(0, T_END, 41)
    fine = ls.simulate(block(), T_END, friction=friction, k_v=10.0, integrator="cvode_bdf",
                       rtol=1e-12, atol=1e-14, t_eval=times)
    tolerances = [1e-4, 1e-6, 1e-8]
    frame = studies.work_precision(
        block(), T_END, [{"friction": friction, "integrator": integrator, "k_v": 10.0,
                          "rtol": r} for r in tolerances], reference=fine, repeats=1)
    errors = frame["error_max"].to_numpy()
    assert np.all(np.diff(errors) < 0), errors
    assert errors[-1] <= 1e-3 * errors[0], errors


def test_regularization_error_falls_with_gain(closed_form):
    gains = [1.0, 10.0, 100.0, 1e3, 1e4]
    frame = studies.work_precision(
        block(), T_END, [{"friction": "arctan_velocity", "integrator": "rk_verner6", "k_v": k,
                          "rtol": 1e-10} for k in gains], reference=closed_form.position,
        repeats=1)
    errors = frame["error_max"].to_numpy()
    assert np.all(np.diff(errors) < 0), errors
    assert -0.75 <= fitted_order(gains[2:], errors[2:]) <= -0.55  # k_V^(-2/3)


def test_t_eval_grid_and_result_reference(closed_form):
    times = np.linspace(0, 1.5, 31)  # t_end = 2 is appended for the final error
    exact = studies.work_precision(block(), T_END, [{"integrator": "event_driven", "rtol": 1e-9}],
                                   reference=closed_form.position, t_eval=times, repeats=1)
    grid = np.append(times, T_END)
    run = ls.simulate(block(), T_END, rtol=1e-9, atol=1e-11, t_eval=grid)
    assert exact["error_max"][0] == pytest.approx(
        np.max(np.abs(run["u"] - closed_form.position(grid))), rel=1e-12)
    reference = ls.simulate(block(), T_END, rtol=1e-13, atol=1e-15, t_eval=grid)
    from_result = studies.work_precision(block(), T_END,
                                         [{"integrator": "event_driven", "rtol": 1e-9}],
                                         reference=reference, repeats=1)
    assert from_result["error_max"][0] == pytest.approx(exact["error_max"][0], rel=1e-4)


def test_scene_configurations():
    """A Scene: the configuration's friction law replaces the scene's; the
    default reference is the scene with exact Coulomb friction."""
    scene = ls.Scene.from_dict(thesis_scene())
    frame = studies.work_precision(scene, 0.3, [
        {"integrator": "event_driven", "rtol": 1e-6},
        {"integrator": "event_driven", "rtol": 1e-9},
        {"friction": "arctan_velocity", "k_v": 1e3, "integrator": "rk_verner6", "rtol": 1e-8},
    ], repeats=1)
    assert frame.attrs["quantity"] == "u_load"
    assert list(frame["friction"]) == ["coulomb", "coulomb", "arctan_velocity"]
    assert frame["error_max"][1] < frame["error_max"][0] < 1e-6
    assert frame["error_max"][2] > frame["error_max"][0]
    # Without configurations a Scene takes its own default set (its law on
    # its first integrators: test_a_scenes_default_configurations_run_...).
    assert {c["friction"] for c in studies.default_configurations(scene)} == \
        {scene["friction"]["law"]}
    with pytest.raises(ValueError, match="has no default configurations"):
        studies.default_configurations("a scene")


def test_failure_is_recorded_or_raised(closed_form):
    configurations = [{"integrator": "event_driven", "rtol": 1e-10, "max_steps": 5},
                      {"integrator": "event_driven", "rtol": 1e-8}]
    with pytest.warns(RuntimeWarning, match="max_steps") as caught:
        frame = studies.work_precision(block(), T_END, configurations,
                                       reference=closed_form.position, repeats=1)
    # One warning, a StudyWarning, counting the configurations that raised.
    assert [w.category for w in caught] == [ls.StudyWarning]
    assert "work_precision: 1 of 2 rows raised" in str(caught[0].message)
    assert frame.attrs["summary"]["raised"] == 1
    assert frame.attrs["summary"]["raised_reasons"].startswith("1 SimulationError; first: "
                                                               "SimulationError: ")
    assert "max_steps" in frame["failure"][0] and frame["failure"][1] == ""
    assert np.isnan(frame["error_max"][0]) and np.isnan(frame["wall_time"][0])
    assert frame["error_max"][1] < 1e-9
    with pytest.raises(ls.SimulationError, match="max_steps"):
        studies.work_precision(block(), T_END, configurations, on_failure="raise", repeats=1)


def test_progress_lines(capsys, closed_form, watched):
    studies.work_precision(block(), T_END, [{"integrator": "event_driven", "rtol": 1e-6}],
                           reference=closed_form.position, repeats=1, progress=True)
    assert "[1/1] coulomb event_driven rtol=1e-06: error" in capsys.readouterr().err


def test_default_configurations_cover_the_thesis_study():
    configurations = studies.default_configurations(block())
    keys = {(c["friction"], c["integrator"], c.get("k_v")) for c in configurations}
    for k_v in (1.0, 10.0, 100.0, 1e3, 1e4):
        for integrator in ("cvode_bdf", "dopri5", "rk_verner6"):
            assert ("arctan_velocity", integrator, k_v) in keys
    for k_v in (1.0, 10.0, 100.0):
        assert ("arctan_acceleration", "cvode_bdf", k_v) in keys
    assert ("coulomb", "event_driven", None) in keys and ("coulomb", "moreau", None) in keys
    assert all(set(c) <= set(studies.CONFIGURATION_KEYS) for c in configurations)


def test_plot_draws_one_line_per_method(mixed_frame):
    import matplotlib.pyplot as plt

    figure, ax = plt.subplots()
    assert studies.plot_work_precision(mixed_frame, ax=ax) is ax
    assert len(ax.get_lines()) == len(MIXED)
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    np.testing.assert_allclose(ax.get_lines()[0].get_ydata(), [mixed_frame["error_max"][0]])
    np.testing.assert_allclose(ax.get_lines()[0].get_xdata(), [mixed_frame["wall_time"][0]])
    plt.close(figure)
    figure, ax = plt.subplots()
    frame = studies.work_precision(block(), T_END, [{"integrator": "moreau", "dt": 2e-3},
                                                    {"integrator": "moreau", "dt": 1e-3}],
                                   repeats=1, ax=ax)
    (line,) = ax.get_lines()
    # Loosest first: dt = 2e-3 then 1e-3.
    np.testing.assert_allclose(line.get_ydata(), frame["error_max"])
    plt.close(figure)
    with pytest.raises(ValueError, match="time"):
        studies.plot_work_precision(mixed_frame, time="cpu")
    with pytest.raises(ValueError, match="frame"):
        studies.plot_work_precision(mixed_frame.drop(columns=["error_max"]))


@pytest.mark.parametrize(
    "arguments, name",
    [
        (dict(model="block"), "model"),
        (dict(t_end=0.0), "t_end"),
        (dict(t_end=-1.0), "t_end"),
        (dict(t_end=float("nan")), "t_end"),
        (dict(repeats=0), "repeats"),
        (dict(repeats=1.5), "repeats"),
        (dict(on_failure="ignore"), "on_failure"),
        (dict(configurations={"rtol": 1e-6}), "configurations"),
        (dict(configurations=[]), "configurations"),
        (dict(configurations=["event_driven"]), r"configurations\[0\]"),
        (dict(configurations=[{"tolerance": 1e-6}]), r"configurations\[0\].*tolerance"),
        (dict(configurations=[{"integrator": "event_driven", "dt": 1e-3}]), "dt"),
        (dict(configurations=[{"integrator": "moreau", "rtol": 1e-6}]), "rtol"),
        (dict(configurations=[{"friction": "coulomb", "k_v": 10.0}]), "k_v"),
        (dict(configurations=[{"friction": "viscous"}]), r"configurations\[0\].*friction"),
        (dict(configurations=[{"integrator": "rk4"}]), r"configurations\[0\].*integrator"),
        (dict(configurations=[{"rtol": -1.0}]), r"configurations\[0\].*rtol"),
        # values of the wrong kind, named before anything formats them
        (dict(configurations=[{"rtol": "tight"}]),
         r"configurations\[0\]: rtol = 'tight' is invalid: must be a number"),
        (dict(configurations=[{"rtol": None}]), r"configurations\[0\]: rtol = None"),
        (dict(configurations=[{"integrator": "moreau", "dt": "1e-3"}]),
         r"configurations\[0\]: dt = '1e-3' is invalid"),
        (dict(configurations=[{"rtol": 1e-6}, {"max_steps": 10.5}]),
         r"configurations\[1\]: max_steps = 10.5 is invalid: must be an integer"),
        (dict(configurations=[{"integrator": 3}]), r"configurations\[0\]: integrator = 3"),
        (dict(configurations=[{"k_v": True, "friction": "arctan_velocity"}]),
         r"configurations\[0\]: k_v = True"),
        (dict(t_eval=[0.5, 0.2]), "t_eval"),
        (dict(t_eval=[0.0, 3.0]), "t_eval"),
        (dict(t_eval=[[0.0, 1.0]]), "t_eval"),
        (dict(t_eval=[]), "t_eval"),
        (dict(reference="closed form"), "reference"),
        (dict(reference=lambda t: 0.0), "reference"),
        (dict(reference=lambda t: np.full(np.shape(t), np.nan)), "reference"),
        (dict(quantity="x"), "quantity"),
    ],
)
def test_bad_input_raises_value_error(arguments, name):
    call = dict(model=block(), t_end=1.0, configurations=[{"rtol": 1e-6}], repeats=1)
    call.update(arguments)
    with pytest.raises(ValueError, match=name):
        studies.work_precision(**call)


def test_result_reference_without_the_compared_times():
    reference = ls.simulate(block(), 1.0, rtol=1e-12, t_eval=np.linspace(0, 1, 11))
    with pytest.raises(ValueError, match="reference.*t = 0.05"):
        studies.work_precision(block(), 1.0, [{"rtol": 1e-6}], reference=reference,
                               t_eval=np.linspace(0, 1, 21), repeats=1)
    short = ls.simulate(block(), 0.5, rtol=1e-12)
    with pytest.raises(ValueError, match="reference.*t_end"):
        studies.work_precision(block(), 1.0, [{"rtol": 1e-6}], reference=short, repeats=1)
    with pytest.raises(ValueError, match="reference.*channel 'x'"):
        studies.work_precision(block(), 1.0, [{"rtol": 1e-6}], reference=reference,
                               quantity="x", repeats=1)


def test_configuration_values_simulate_takes_as_none():
    """dt, max_step and first_step default to None in simulate: a
    configuration may say so."""
    frame = studies.work_precision(block(), 1.0, [{"integrator": "event_driven",
                                                   "max_step": None, "first_step": None},
                                                  {"integrator": "moreau", "dt": None}],
                                   repeats=1)
    assert len(frame) == 2 and (frame["failure"] == "").all(), frame["failure"].tolist()
    assert frame["label"].str.endswith("defaults").all(), frame["label"].tolist()



def test_the_frame_has_the_unit_of_every_column():
    """As the other studies' frames (leadscrew study writes them as a row of
    units): the errors in the quantity's unit, k_v in its laws'."""
    frame = studies.work_precision(block(), 0.1, [
        {"friction": "arctan_velocity", "integrator": "dopri5", "k_v": 100.0, "rtol": 1e-6},
        {"friction": "arctan_acceleration", "integrator": "dopri5", "k_v": 10.0, "rtol": 1e-6}],
        repeats=1)
    units = frame.attrs["units"]
    assert list(units) == list(studies.COLUMNS)
    assert units["error_max"] == units["error_final"] == "m" and units["wall_time"] == "s"
    assert units["k_v"] == "s/m or s^2/m" and units["steps"] == "1" and units["label"] == ""
    exact = studies.work_precision(block(), 0.1, [{"rtol": 1e-6}], repeats=1,
                                   quantity="v")
    assert exact.attrs["units"]["k_v"] == "" and exact.attrs["units"]["error_max"] == "m/s"


def test_a_scenes_default_configurations_run_from_the_command_line(tmp_path, capsys):
    """A Scene has a default set too (its law on its first integrators), so
    that the command line needs t_end alone; --help says how."""
    import pandas as pd

    from helpers.cli_runs import run_main

    scene = ls.scenes.load("default")
    configurations = studies.default_configurations(scene)
    assert configurations[:3] == [{"friction": "coulomb", "integrator": "event_driven",
                                   "rtol": rtol} for rtol in (1e-4, 1e-6, 1e-8)]
    assert {c["integrator"] for c in configurations} == {"event_driven", "moreau"}
    code, out, err = run_main(capsys, "study", "work_precision", "default", "t_end=0.1",
                              "repeats=1", "-o", tmp_path)
    assert code == 0, err
    frame = pd.read_csv(tmp_path / "work_precision_default.csv", skiprows=[1])
    assert len(frame) == len(configurations) and frame["failure"].isna().all()
    event_driven = frame[frame["integrator"] == "event_driven"]["error_max"].to_numpy()
    moreau = frame[frame["integrator"] == "moreau"]["error_max"].to_numpy()
    assert event_driven[-1] < event_driven[0] and moreau[-1] < moreau[0]  # tighter: closer
    code, out, _ = run_main(capsys, "study", "--help")
    assert "leadscrew study work_precision default t_end=0.5" in " ".join(out.split())
