"""Helpers shared by the studies (leadscrew.studies._common)."""

import numpy as np
import pandas as pd
import pytest

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
