"""leadscrew.Measured (a recorded load): its interpolation (through every
sample, continuous slope, exact for a quadratic between interior samples),
hold and periodic repetition, scale; its unit from an argument, a CSV
header ``a [unit]``, a row of units (leadscrew's own CSV) or a Parquet
field's metadata, round-tripped through files and scenes; its errors."""

import numpy as np
import pytest

import leadscrew as ls

G0 = 9.80665  # standard gravity [m/s^2], pint's g0


def test_passes_through_samples_and_is_exact_for_a_quadratic():
    t = np.linspace(0.0, 1.0, 11)
    record = ls.Measured(t, 3.0 * t ** 2 - t, unit="m/s^2")
    assert np.array_equal(record(t), 3.0 * t ** 2 - t)
    middle = np.linspace(0.1, 0.9, 81)  # interior segments: central differences are exact
    assert np.allclose(record(middle), 3.0 * middle ** 2 - middle, rtol=0, atol=1e-13)
    # held outside the record
    assert record(-1.0) == 0.0 and record(5.0) == pytest.approx(2.0, abs=1e-15)


def test_slope_is_continuous_at_the_samples():
    rng = np.random.default_rng(1)
    t = np.cumsum(rng.uniform(0.5e-3, 1.5e-3, 50))  # non-uniform
    record = ls.Measured(t, rng.normal(size=50))
    # One-sided differences over h differ by the curvature's h y'' (y'' up to
    # |y| / dt^2 = 4e6: 4e-5 over h = 1e-11) and by round-off (2e-16 / h = 2e-5):
    # a kink's jump in slope (of order |y| / dt = 2e3) would not pass.
    h = 1e-11
    for knot in t[5:-5]:
        left = (record(knot) - record(knot - h)) / h
        right = (record(knot + h) - record(knot)) / h
        assert left == pytest.approx(right, abs=0.2)


def test_repeat_and_scale():
    t = np.arange(0.0, 1.0, 0.01)  # period 1 s: the last sample runs into the first
    values = np.sin(2 * np.pi * t)
    record = ls.Measured(t, values, scale=2.0, repeat=True)
    assert np.allclose(record(t + 3.0), 2.0 * values, rtol=0, atol=1e-12)
    assert record(0.995) == pytest.approx(2.0 * np.sin(2 * np.pi * 0.995), abs=2e-5)
    assert record(-0.25) == pytest.approx(-2.0, abs=1e-12)


def test_unit_from_an_argument_or_strings():
    record = ls.Measured([0.0, 1.0], [1.0, 2.0], unit="g0")
    assert record.unit == "m/s^2" and np.allclose(record.values, [G0, 2 * G0])
    assert ls.Measured(["0 ms", "10 ms"], ["1 kN", "2 kN"]).values.tolist() == [1e3, 2e3]
    with pytest.raises(ValueError, match=r"values\[1\] = '2 N\*m' is invalid: N\*m, but the "
                                         r"record's unit is N"):
        ls.Measured([0.0, 1.0], ["1 N", "2 N*m"])
    with pytest.raises(ValueError, match=r"unit = 'kg' is invalid: .*1 kg.* is not a force"):
        ls.Measured([0.0, 1.0], [1.0, 2.0], unit="kg")
    with pytest.raises(ValueError, match=r"times\[1\] = 0 is invalid: times must be strictly "
                                         r"increasing"):
        ls.Measured([0.0, 0.0], [1.0, 2.0])
    with pytest.raises(ValueError, match=r"at least two samples"):
        ls.Measured([0.0], [1.0])


def _write_csv(path, header, rows, units=None):
    lines = [",".join(header)] + ([",".join(units)] if units else [])
    lines += [",".join(repr(float(x)) for x in row) for row in rows]
    path.write_text("\n".join(lines) + "\n")


def test_csv_round_trip_with_its_unit(tmp_path):
    t = np.arange(0.0, 0.5, 1e-3)
    a = 2.0 * np.sin(2 * np.pi * 7.0 * t)
    path = tmp_path / "record.csv"
    _write_csv(path, ["t [ms]", "a [g0]"], zip(1e3 * t, a))
    record = ls.Measured.from_file(str(path))
    assert record.unit == "m/s^2"
    assert np.allclose(record.times, t, rtol=1e-15, atol=1e-18)
    assert np.allclose(record(t), G0 * a, rtol=0, atol=1e-12)  # (times through ms: 1 ulp off)
    # leadscrew's own CSV: a row of units under the names
    own = tmp_path / "own.csv"
    _write_csv(own, ["t", "x", "force"], zip(t, a, -a), units=["s", "m", "N"])
    forces = ls.Measured.from_file(str(own), column="force")
    assert forces.unit == "N" and np.array_equal(forces.values, -a)
    with pytest.raises(ValueError, match=r"column = 'f' is invalid: must be one of \['x', "
                                         r"'force'\]"):
        ls.Measured.from_file(str(own), column="f")
    with pytest.raises(ValueError, match=r"column = None is invalid.*3 columns"):
        ls.Measured.from_file(str(own))
    with pytest.raises(ValueError, match=r"unit = 'N' is invalid: the file gives 'g0'"):
        ls.Measured.from_file(str(path), unit="N")


def test_parquet_round_trip_with_its_unit(tmp_path):
    import pyarrow as pa  # (the test extra's: never skipped)
    import pyarrow.parquet as pq

    t = np.arange(0.0, 0.2, 1e-3)
    alpha = np.cos(2 * np.pi * 11.0 * t)
    table = pa.table({"t": t, "alpha": alpha}).cast(pa.schema([
        pa.field("t", pa.float64(), metadata={"unit": "s"}),
        pa.field("alpha", pa.float64(), metadata={"unit": "rad/s^2"})]))
    path = tmp_path / "record.parquet"
    pq.write_table(table, path)
    record = ls.Measured.from_file(str(path))
    assert record.unit == "rad/s^2"
    assert np.array_equal(record(t), alpha)


def test_scene_takes_a_record_from_a_file(tmp_path):
    t = np.arange(0.0, 0.1, 1e-3)
    path = tmp_path / "body.csv"
    _write_csv(path, ["t [s]", "a [m/s^2]"], zip(t, np.sin(2 * np.pi * 30 * t)))
    scene = ls.scenes.load("position_holding")
    vibrated = scene.replace(loads={"base_acceleration": {
        "type": "measured", "file": str(path), "scale": 0.5, "repeat": True}})
    stored = vibrated.to_dict()["loads"]["base_acceleration"]
    assert stored["type"] == "measured" and stored["scale"] == 0.5 and stored["repeat"] is True
    assert stored["times"] == t.tolist()
    toml = tmp_path / "scene.toml"
    vibrated.to_toml(toml)
    again = ls.Scene.from_toml(toml)
    assert again == vibrated
    probe = np.linspace(0.0, 0.3, 31)
    assert np.array_equal(again.model().parameters.base_acceleration(probe),
                          vibrated.model().parameters.base_acceleration(probe))
    with pytest.raises(ValueError, match=r"loads.axial_force = Measured.* is invalid: its "
                                         r"values are an acceleration \(m/s\^2\), not a force"):
        scene.replace(loads={"axial_force": {"type": "measured", "file": str(path)}})
    with pytest.raises(ValueError, match=r"loads.base_acceleration.file = 3 is invalid: must be "
                                         r"the path of a CSV or Parquet file"):
        scene.replace(loads={"base_acceleration": {"type": "measured", "file": 3}})
    with pytest.raises(ValueError, match=r"loads.base_acceleration.file = '.*nope.csv' is "
                                         r"invalid: no such file"):
        scene.replace(loads={"base_acceleration": {"type": "measured",
                                                   "file": str(tmp_path / "nope.csv")}})
    with pytest.raises(ValueError, match=r"loads.base_acceleration.column = 'b' is invalid: "
                                         r"must be one of \['a'\]"):
        scene.replace(loads={"base_acceleration": {"type": "measured", "file": str(path),
                                                   "column": "b"}})
    with pytest.raises(ValueError, match=r"loads.base_acceleration.column = 'a' is invalid: "
                                         r"must be absent without file"):
        scene.replace(loads={"base_acceleration": {"type": "measured", "times": [0, 1],
                                                   "values": [0, 1], "column": "a"}})


def test_pickles_with_its_unit():
    import pickle

    record = ls.Measured([0.0, 1.0, 2.0], [1.0, 2.0, 0.0], unit="kN", repeat=True, scale=0.5)
    again = pickle.loads(pickle.dumps(record))
    assert again.unit == "N" and again.repeat and again.scale == 0.5
    t = np.linspace(0.0, 5.0, 51)
    assert np.array_equal(again(t), record(t))


def test_a_scene_file_finds_its_record_beside_it(tmp_path, monkeypatch):
    t = np.arange(0.0, 0.05, 1e-3)
    (tmp_path / "data").mkdir()
    _write_csv(tmp_path / "data" / "body.csv", ["t [s]", "a [m/s^2]"], zip(t, 3.0 * t))
    scene_text = ls.scenes.load("position_holding").to_toml()
    scene_text += '\n[loads.base_acceleration]\ntype = "measured"\nfile = "data/body.csv"\n'
    (tmp_path / "vibrated.toml").write_text(scene_text)
    monkeypatch.chdir(tmp_path / "data")  # not the scene's directory
    scene = ls.Scene.from_toml(tmp_path / "vibrated.toml")
    assert scene.to_dict()["loads"]["base_acceleration"]["values"] == (3.0 * t).tolist()
