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
    pd.testing.assert_frame_equal(frame, _common._public_frame_of(
        _common._labels(tuple(given)), list(given.values())))


def test_frame_of_without_the_pandas_internal(monkeypatch):
    # pandas without DataFrame._from_arrays, or with another signature: the
    # public constructor gives the same frame.
    assert _common._FROM_ARRAYS  # the pandas the tests run with has it
    expected = frame_of(columns())
    monkeypatch.setattr(_common, "_FROM_ARRAYS", False)
    check_frame(frame_of(columns()), columns())
    pd.testing.assert_frame_equal(frame_of(columns()), expected)


def test_the_pandas_internal_is_recognised_by_its_signature(monkeypatch):
    assert _common._has_from_arrays()

    def other(arrays, columns, index, dtype=None):  # no verify_integrity
        raise AssertionError("not to be called")

    monkeypatch.setattr(pd.DataFrame, "_from_arrays", other, raising=False)
    assert not _common._has_from_arrays()
    monkeypatch.delattr(pd.DataFrame, "_from_arrays")
    assert not _common._has_from_arrays()


@pytest.mark.parametrize("internal", [True, False])
def test_frame_of_strings_are_objects_and_labels_are_the_frames_own(monkeypatch, internal):
    monkeypatch.setattr(_common, "_FROM_ARRAYS", internal)
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
