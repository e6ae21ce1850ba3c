"""Helpers shared by the studies (leadscrew.studies._common)."""

import numpy as np
import pandas as pd
import pytest

from leadscrew.studies import _common
from leadscrew.studies._common import annotate, frame_of


def columns():
    count = 7
    rng = np.random.default_rng(3)
    errors = np.full(count, None, dtype=object)
    errors[2] = "SimulationError: t = 0.1 s: step size too small"
    return {"mu": rng.random(count), "load": rng.random(count), "drivable": rng.random(count) > 0.5,
            "steps": np.arange(count), "efficiency": rng.random(count), "error": errors}


def check_frame(frame, given):
    assert frame.columns.tolist() == list(given)
    assert frame.columns.dtype == object
    assert isinstance(frame.index, pd.RangeIndex) and len(frame) == 7
    for name, values in given.items():
        assert frame[name].dtype == values.dtype, name
        assert frame[name].tolist() == values.tolist(), name
    assert frame["error"].tolist()[:3] == [None, None, given["error"][2]]


def test_frame_of_keeps_order_dtypes_and_none():
    given = columns()
    frame = frame_of(given)
    check_frame(frame, given)


def test_frame_of_takes_other_dtypes_sequence_cells_and_no_rows():
    # a datetime column, and no rows
    dates = {"t": np.array(["2026-11-22", "2026-11-23"], dtype="datetime64[ns]"),
             "x": np.arange(2.0)}
    pd.testing.assert_frame_equal(frame_of(dates), pd.DataFrame(dates), check_column_type=False,
                                  check_exact=True)
    pairs = np.empty(2, dtype=object)
    pairs[:] = [[1, 2], (3, 4)]  # cells that are sequences stay cells
    assert frame_of({"pair": pairs, "x": np.arange(2.0)})["pair"].tolist() == [[1, 2], (3, 4)]
    empty = frame_of({"mu": np.zeros(0), "error": np.zeros(0, dtype=object)})
    assert empty.shape == (0, 2) and empty.dtypes.tolist() == [np.float64, object]


def test_frame_of_strings_are_objects_and_labels_are_the_frames_own():
    given = {"name": np.array(["a", "bc", "d"]), "value": np.arange(3.0)}
    first = frame_of(given)
    assert first["name"].dtype == object and first["name"].tolist() == ["a", "bc", "d"]
    first.columns.name = "quantity"  # another frame of the same labels keeps its own
    assert frame_of(given).columns.name is None


@pytest.mark.parametrize("bad", [{"a": np.zeros(3), "b": np.zeros(4)},
                                 {"a": np.zeros((3, 2)), "b": np.zeros(3)}])
def test_frame_of_rejects_ragged_or_2d_columns(bad):
    with pytest.raises(ValueError, match="1-D arrays of one length"):
        frame_of(bad)


def test_annotate_converts_missing_errors_unless_told_they_are_checked():
    frame = pd.DataFrame([{"mu": 0.1, "error": "ValueError: x"}, {"mu": 0.2}])
    assert frame["error"].isna().tolist() == [False, True]
    annotated = annotate(frame.copy(), {"mu": "1", "error": ""})
    assert annotated["error"].tolist() == ["ValueError: x", None]
    assert annotated.attrs["units"] == {"mu": "1", "error": ""}
    checked = annotate(frame_of(columns()), {"mu": "1"}, errors_checked=True, speed=2.0)
    assert checked["error"].tolist()[:3] == [None, None, columns()["error"][2]]
    assert checked.attrs["summary"] == {"speed": 2.0}


def test_annotate_keeps_the_units_of_the_summary_it_stores():
    frame = annotate(frame_of(columns()), {"mu": "1"}, errors_checked=True,
                     summary_units={"speed": "rad/s", "other": "m"}, speed=2.0, label="a")
    assert frame.attrs["summary"] == {"speed": 2.0, "label": "a"}
    assert frame.attrs["summary_units"] == {"speed": "rad/s"}
    assert "summary_units" not in annotate(frame_of(columns()), {}, speed=1.0).attrs


# --- with_tolerances: a study passes rtol and atol on only where given -------

def _moreau_cases():
    import leadscrew as ls
    from helpers.scenes import thesis_scene
    from leadscrew import studies

    plain = ls.Scene.from_dict(thesis_scene())
    holding = ls.Scene.from_dict(thesis_scene(
        backlash={"axial": 2e-4},
        loads={"drive_torque": 5e-3,
               "axial_force": {"type": "sine", "amplitude": 30.0, "omega": 125.0}}))
    quiet = {"progress": False}
    return {
        "stick_slip": lambda **o: studies.stick_slip(plain, t_end=0.2, **o),
        "compare_concepts": lambda **o: studies.compare_concepts(plain, t_end=0.2, **quiet, **o),
        "efficiency_vs_mu": lambda **o: studies.efficiency_vs_mu(plain, [0.1], [10.0], **quiet,
                                                                 **o),
        "position_holding": lambda **o: studies.position_holding(holding, cycles=2, **o),
        "creep_vs_frequency": lambda **o: studies.creep_vs_frequency(holding, [20.0], cycles=2,
                                                                     **quiet, **o),
        "creep_vs_backlash": lambda **o: studies.creep_vs_backlash(holding, [2e-4], cycles=2,
                                                                   **quiet, **o),
        "creep_map": lambda **o: studies.creep_map(holding, [20.0], [2e-4], cycles=2, **quiet,
                                                   **o),
        "min_holding_preload": lambda **o: studies.min_holding_preload(
            holding, max_iterations=2, **quiet, **o),
    }


@pytest.mark.parametrize("name", sorted(_moreau_cases()))
def test_studies_run_moreau_and_refuse_its_ignored_options(name):
    """A study's own rtol and atol defaults are not "given": it runs with
    integrator="moreau" (which takes neither); rtol given with it is refused,
    as by simulate, before any case runs."""
    run = _moreau_cases()[name]
    frame = run(integrator="moreau", dt=1e-4)
    if "error" in frame:
        assert frame["error"].isna().all(), frame["error"].tolist()
    with pytest.raises(ValueError, match=r"rtol = 1e-06 is invalid with integrator 'moreau'"):
        run(integrator="moreau", dt=1e-4, rtol=1e-6)


def test_with_tolerances_adds_only_the_tolerances_given():
    options = {"integrator": "moreau"}
    assert _common.with_tolerances(options) == {"integrator": "moreau"}
    assert _common.with_tolerances(options, 1e-6) == {"integrator": "moreau", "rtol": 1e-6}
    assert _common.with_tolerances(options, None, 1e-9) == {"integrator": "moreau",
                                                             "atol": 1e-9}
    assert options == {"integrator": "moreau"}  # not changed


# --- arguments with units: strings as a scene's fields take them -------------

def test_check_grid_takes_strings_with_units():
    np.testing.assert_array_equal(
        _common.check_grid("frequencies", ["5 Hz", 10.0, "1.2 kHz"], unit="Hz"),
        [5.0, 10.0, 1200.0])
    np.testing.assert_array_equal(_common.check_grid("frequencies", "5 Hz", unit="Hz"), [5.0])
    np.testing.assert_array_equal(_common.check_grid("backlash", np.array(["0.2 mm"]), unit="m"),
                                  [2e-4])
    # Hz is a turn per second: 2 pi rad/s is 1 Hz
    assert _common.check_grid("frequencies", [f"{2 * np.pi!r} rad/s"], unit="Hz")[0] == \
        pytest.approx(1.0, rel=1e-15)
    with pytest.raises(ValueError, match=r'^frequencies\[1\] = "5 N" is invalid: "5 N" is not '
                                         r"an angular velocity or frequency \(Hz\)$"):
        _common.check_grid("frequencies", [5.0, "5 N"], unit="Hz")
    # the range is checked after the conversion, naming the entry
    with pytest.raises(ValueError, match=r"^frequencies entry = -5.0 is invalid: must be a finite "
                                         r"number > 0$"):
        _common.check_grid("frequencies", ["-5 Hz"], unit="Hz")
    # without a unit (a count), strings with units stay refused
    with pytest.raises(ValueError, match=r"must be a sequence of numbers"):
        _common.check_grid("cycles", ["5 s"])


def test_check_positive_and_finite_take_strings_with_units():
    assert _common.check_positive("amplitude", "20 N", unit="N") == 20.0
    assert _common.check_positive("t_end", "250 ms", unit="s") == pytest.approx(0.25, rel=1e-15)
    assert _common.check_finite("static_force", "-0.1 kN", unit="N") == pytest.approx(-100.0)
    assert _common.check_positive("tolerance", "0.1 %", unit="") == pytest.approx(1e-3)
    with pytest.raises(ValueError, match=r'^amplitude = "20 m" is invalid: "20 m" is not a force '
                                         r"\(N\)$"):
        _common.check_positive("amplitude", "20 m", unit="N")
    with pytest.raises(ValueError, match=r"^amplitude = '20 N' is invalid: must be a finite "
                                         r"number > 0$"):
        _common.check_positive("amplitude", "20 N")  # no unit: no string
    assert _common.in_unit("cycles", "3", None) == "3"


def _scenes():
    import leadscrew as ls
    from helpers.scenes import thesis_scene

    plain = ls.Scene.from_dict(thesis_scene())
    holding = ls.Scene.from_dict(thesis_scene(
        backlash={"axial": 2e-4}, loads={"drive_torque": 5e-3, "axial_force": 0.0}))
    return plain, holding


def _wrong_dimensions():
    """(study call, message): each study's arguments with a unit, given a
    string of another dimension."""
    import leadscrew as ls
    from leadscrew import studies

    plain, holding = _scenes()
    sine = {"type": "sine", "amplitude": "30 N", "omega": "20 Hz"}
    quiet = {"progress": False}
    return [
        (lambda: studies.creep_vs_frequency(holding, ["5 N"], **quiet),
         r'^frequencies\[0\] = "5 N" is invalid: "5 N" is not an angular velocity or '
         r"frequency \(Hz\)$"),
        (lambda: studies.creep_vs_frequency(holding, [20.0], amplitude="30 m", **quiet),
         r'^amplitude = "30 m" is invalid: "30 m" is not a force \(N\)$'),
        (lambda: studies.creep_vs_backlash(holding, ["0.2 N"], **quiet),
         r'^backlash\[0\] = "0.2 N" is invalid: "0.2 N" is not a length \(m\)$'),
        (lambda: studies.creep_vs_backlash(holding, [2e-4], frequency="20 N", **quiet),
         r'^frequency = "20 N" is invalid: "20 N" is not an angular velocity'),
        (lambda: studies.creep_map(holding, ["20 Hz"], "2 s", **quiet),
         r'^backlash = "2 s" is invalid: "2 s" is not a length \(m\)$'),
        (lambda: studies.position_holding(holding, amplitude="30 N*m"),
         r'^amplitude = "30 N\*m" is invalid: "30 N\*m" is not a force \(N\)$'),
        (lambda: studies.position_holding(holding, static_force="1 m"),
         r'^static_force = "1 m" is invalid: "1 m" is not a force \(N\)$'),
        (lambda: studies.min_holding_preload(holding, {**sine, "amplitude": "30 N*m"}, **quiet),
         r'^excitation.amplitude = "30 N\*m" is invalid: "30 N\*m" is not a force \(N\)$'),
        (lambda: studies.min_holding_preload(holding, {**sine, "omega": "20 m"}, **quiet),
         r'^excitation.omega = "20 m" is invalid: "20 m" is not an angular velocity'),
        (lambda: studies.min_holding_preload(holding, {**sine, "phase": "1 s"}, **quiet),
         r'^excitation.phase = "1 s" is invalid: "1 s" is not an angle'),
        (lambda: studies.min_holding_preload(holding, ls.Sine("30 N*m", 125.0), **quiet),
         r"^excitation = .* is invalid: its values are a torque \(N\*m\), not a force \(N\)$"),
        (lambda: studies.min_holding_preload(holding, sine, upper="1 m", **quiet),
         r'^upper = "1 m" is invalid: "1 m" is not a force \(N\)$'),
        (lambda: studies.min_holding_preload(holding, sine, creep_limit="1 N", **quiet),
         r'^creep_limit = "1 N" is invalid: "1 N" is not a length \(m\)$'),
        (lambda: studies.efficiency_vs_mu(plain, [0.1], ["10 N*m"], **quiet),
         r'^loads\[0\] = "10 N\*m" is invalid: "10 N\*m" is not a force \(N\)$'),
        (lambda: studies.efficiency_vs_mu(plain, ["0.1 m"], [10.0], **quiet),
         r'^mu\[0\] = "0.1 m" is invalid: "0.1 m" is not a plain number$'),
        (lambda: studies.efficiency_vs_mu(plain, [0.1], [10.0], speed="10 m/s", **quiet),
         r'^speed = "10 m/s" is invalid: "10 m/s" is not an angular velocity'),
        (lambda: studies.efficiency_vs_mu(plain, [0.1], [10.0], t_end="1 m", **quiet),
         r'^t_end = "1 m" is invalid: "1 m" is not a time \(s\)$'),
        (lambda: studies.efficiency_vs_mu(plain, [0.1], [10.0], window=("0.1 s", "2 N"),
                                          **quiet),
         r'^window\[1\] = "2 N" is invalid: "2 N" is not a time \(s\)$'),
        (lambda: studies.stick_slip(plain, t_end="2 N"),
         r'^t_end = "2 N" is invalid: "2 N" is not a time \(s\)$'),
        (lambda: studies.compare_concepts(plain, t_end="2 m", **quiet),
         r'^t_end = "2 m" is invalid: "2 m" is not a time \(s\)$'),
        (lambda: studies.work_precision(plain, t_end="2 m", progress=False),
         r'^t_end = "2 m" is invalid: "2 m" is not a time \(s\)$'),
        (lambda: studies.static_holding_band(plain, "10 m"),
         r'^axial_force = "10 m" is invalid: "10 m" is not a force \(N\)$'),
        (lambda: studies.alternating_scene(plain, "30 N", "20 m"),
         r'^frequency = "20 m" is invalid: "20 m" is not an angular velocity'),
    ]


@pytest.mark.parametrize("index", range(len(_wrong_dimensions())))
def test_a_study_argument_of_another_dimension_is_refused_naming_it(index):
    call, message = _wrong_dimensions()[index]
    with pytest.raises(ValueError, match=message):
        call()


def _without_wall_time(frame):
    return frame.drop(columns=[c for c in ("wall_time",) if c in frame])


def _same_study(run, with_units, in_si):
    """The study run with strings with units gives the frame (and the
    summary) it gives with the SI numbers."""
    given, expected = run(**with_units), run(**in_si)
    pd.testing.assert_frame_equal(_without_wall_time(given), _without_wall_time(expected),
                                  check_exact=True)
    summaries = [{key: value for key, value in (frame.attrs.get("summary") or {}).items()
                  if key != "wall_time"} for frame in (given, expected)]
    assert summaries[0] == summaries[1]
    return given


def test_studies_take_strings_with_units_as_the_si_numbers():
    from leadscrew import studies

    plain, holding = _scenes()
    quiet = {"progress": False}
    runs = {"cycles": 2, "points_per_cycle": 10, **quiet}
    _same_study(lambda **a: studies.creep_vs_frequency(holding, **a, **runs),
                {"frequencies": ["20 Hz", "0.04 kHz"], "amplitude": "0.03 kN"},
                {"frequencies": [20.0, 40.0], "amplitude": 30.0})
    _same_study(lambda **a: studies.creep_map(holding, **a, **runs),
                {"frequencies": "20 Hz", "backlash": ["0.2 mm"]},
                {"frequencies": [20.0], "backlash": [2e-4]})
    _same_study(lambda **a: studies.position_holding(holding, cycles=2, points_per_cycle=10,
                                                     **a),
                {"amplitude": "30 N", "frequency": "20 Hz", "static_force": "-0.05 kN"},
                {"amplitude": 30.0, "frequency": 20.0, "static_force": -50.0})
    frame = _same_study(
        lambda **a: studies.min_holding_preload(holding, max_iterations=2, **a, **runs),
        {"excitation": {"type": "sine", "amplitude": "30 N", "omega": "125 rad/s",
                        "phase": "90 deg", "offset": "-1 N"}, "upper": "0.06 kN"},
        {"excitation": {"type": "sine", "amplitude": 30.0, "omega": 125.0,
                        "phase": np.pi / 2, "offset": -1.0}, "upper": 60.0})
    assert frame.attrs["summary"]["amplitude"] == 30.0
    _same_study(lambda **a: studies.efficiency_vs_mu(plain, **a, **quiet),
                {"mu": ["30 %"], "loads": ["10 N", "0.02 kN"], "speed": "10 rad/s",
                 "t_end": "100 ms", "window": ("50 ms", "100 ms")},
                {"mu": [0.3], "loads": [10.0, 20.0], "speed": 10.0, "t_end": 0.1,
                 "window": (0.05, 0.1)})
    _same_study(lambda **a: studies.stick_slip(plain, **a), {"t_end": "50 ms"},
                {"t_end": 0.05})


def test_count_columns_are_integers_with_a_missing_value_for_a_raised_row():
    """A study's step and event counts are integers (pandas' nullable Int64),
    a raised row's <NA>; other columns stay as they are."""
    import pandas as pd

    from leadscrew.studies._common import as_counts

    frame = as_counts(pd.DataFrame({"steps": [12.0, float("nan")], "events": [3, 4],
                                    "wall_time": [0.5, float("nan")]}))
    assert str(frame["steps"].dtype) == str(frame["events"].dtype) == "Int64"
    assert frame["steps"].tolist()[0] == 12 and frame["steps"].isna().tolist() == [False, True]
    assert frame["wall_time"].dtype == float
