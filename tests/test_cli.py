"""The command line: run, check, study, demo on the shipped scenes; exit codes; files."""

import functools
import importlib.util
import json
import math
import os
import re
import shlex
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import leadscrew as ls
import leadscrew.scenes as shipped
from helpers.scenes import thesis_scene
from leadscrew import cli


def run_main(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def assert_one_line_error(err, *fragments):
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("leadscrew: error: ")
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert "Traceback" not in err


def read_series(path):
    """The time series a run (or demo) wrote: its row of units, under the
    names, is each column's SI unit; then the data."""
    units = pd.read_csv(path, nrows=1, dtype=str, keep_default_na=False).iloc[0].to_dict()
    frame = pd.read_csv(path, skiprows=[1])
    assert units == {name: ls.units.channel_unit(name) for name in frame.columns}
    assert units["t"] == "s" and units["u_load"] == "m" and units["stick"] == ""
    return frame


def scene_file(tmp_path, name="scene", **changes):
    path = tmp_path / f"{name}.toml"
    ls.Scene.from_dict(thesis_scene(**changes)).to_toml(path)
    return path


# --- check ------------------------------------------------------------------------


def test_check_without_scene_keeps_the_thread_verdicts(capsys):
    code, out, err = run_main(capsys, "check")
    assert code == 0 and err == ""
    assert "lead angle 0.9118 deg" in out
    assert re.search(r"self-locking .*:\s+yes", out) and re.search(r"drivable .*:\s+yes", out)
    t = ls.Thread(1e-3, 20e-3)
    assert f"efficiency forward {ls.efficiency(t, 0.3):.6g}" in out
    code, out, _ = run_main(capsys, "check", "--pitch", "0.02", "--mu", "0.1", "--load", "100")
    t = ls.Thread(0.02, 20e-3)
    assert code == 0 and re.search(r"self-locking .*:\s+no", out)
    assert f"torque to raise 100 N: {ls.raise_torque(t, 0.1, 100.0):.6g} N*m" in out


@pytest.mark.parametrize("name", ["default", "thesis_table_5_1", "position_holding"])
def test_check_shipped_scene(capsys, name):
    code, out, err = run_main(capsys, "check", name)
    assert code == 0 and err == ""
    scene = shipped.load(name)
    d = scene.to_dict()
    t = scene.thread
    assert f"scene {name}: valid" in out
    assert re.search(r"self-locking .*:\s+yes", out)  # all three are self-locking
    assert f"efficiency forward {ls.efficiency(t, d['friction']['mu']):.6g}" in out
    for key, value in scene.derived().items():
        assert f"{key} = {value:.6g}" in out
    assert "dynamic jamming" in out


def jamming_line(out, index):
    lines = [line for line in out.splitlines() if line.strip().startswith(("m r^2", "J cot"))]
    return lines[index]


def test_check_jamming_matches_the_physics_reference(tmp_path, capsys):
    """docs/physics/rigid_drive.md section 11: with a 1e-6 kg m^2 rotor the
    screw-driven Table 5.1 drive jams from a translating mass of 139.2 kg, the
    nut-driven one from a load of 2.04 kg (translating mass 3.27 kg)."""
    screw = scene_file(tmp_path, "screw", rotor={"inertia": 1e-6})
    code, out, _ = run_main(capsys, "check", screw)
    assert code == 0
    assert "J = rotor + screw = 6.26538e-05 kg*m^2, m = nut + load = 1.00387 kg" in out
    first = jamming_line(out, 0)
    assert ": no (jams from m = 139.2" in first
    assert "mu' <= cot a: never" in jamming_line(out, 1)

    nut = scene_file(tmp_path, "nut", drive="nut", rotor={"inertia": 1e-6})
    code, out, _ = run_main(capsys, "check", nut)
    assert "J = rotor + nut = 1.47219e-06 kg*m^2, m = screw + load = 2.23308 kg" in out
    critical_load = float(re.search(r"load mass ([0-9.]+) kg", jamming_line(out, 0)).group(1))
    assert critical_load == pytest.approx(2.039, abs=1e-3)

    heavy = scene_file(tmp_path, "heavy", drive="nut", rotor={"inertia": 1e-6}, load={"mass": 2.5})
    code, out, _ = run_main(capsys, "check", heavy)
    assert code == 0 and ": YES, jams" in jamming_line(out, 0)
    # ... and the simulation agrees: the heavy nut drive jams, exit code 1.
    code, _, err = run_main(capsys, "run", heavy, "-o", tmp_path, "--t-end", "0.2")
    assert code == 1
    assert_one_line_error(err, "JammingError")


def test_jamming_margins_are_the_two_inequalities():
    t = ls.Thread(1e-3, 20e-3)
    r, tan_a, mu = 0.01, math.tan(t.lead_angle), 0.3
    J, m = 6.265376e-5, 1.003870
    jm = cli.jamming_margins(t, mu, J, m)
    assert jm["lhs1"] == pytest.approx(m * r * r * tan_a * (mu - tan_a), rel=1e-14)
    assert jm["rhs1"] == pytest.approx(J * (1 + mu * tan_a), rel=1e-14)
    assert not jm["jams1"] and not jm["jams2"]
    # At the critical mass both sides are equal (the boundary jams, ">=").
    at = cli.jamming_margins(t, mu, J, jm["mass1"])
    assert at["lhs1"] == pytest.approx(at["rhs1"], rel=1e-12)
    assert cli.jamming_margins(t, mu, J, jm["mass1"] * (1 + 1e-9))["jams1"]
    # A thread no torque can turn (mu' > cot a) jams with a heavy rotor.
    steep = ls.Thread(0.2, 0.01)
    jm = cli.jamming_margins(steep, 0.5, 1e-6, 1.0)
    assert math.isfinite(jm["inertia2"]) and not jm["jams2"]
    assert cli.jamming_margins(steep, 0.5, jm["inertia2"] * 1.01, 1.0)["jams2"]


def test_check_bad_file_is_one_line_exit_2(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text('[thread]\npitch = "3 N"\nmean_diameter = "20 mm"\n[friction]\nmu = 0.3\n')
    code, out, err = run_main(capsys, "check", path)
    assert code == 2 and out == ""
    assert_one_line_error(err, str(path), 'thread.pitch = "3 N" is invalid', "not a length")
    code, _, err = run_main(capsys, "check", "default", "--pitch", "0.002")
    assert code == 2
    assert_one_line_error(err, "--pitch apply without SCENE only")


@pytest.mark.parametrize("command", ["check", "run", "study"])
def test_a_directory_or_an_empty_file_as_scene_says_so(tmp_path, capsys, monkeypatch, command):
    calls = fake_studies(monkeypatch)
    folder = tmp_path / "scenes"
    folder.mkdir()
    empty = tmp_path / "empty.toml"
    empty.write_text("")
    out_dir = tmp_path / "out"
    for scene, fragments in ((folder, [f"{folder}: is a directory, not a scene file"]),
                             (empty, [f"{empty}: the file is empty", "[thread], [friction]"])):
        argv = {"check": ["check", scene], "run": ["run", scene, "-o", out_dir],
                "study": ["study", "sweep_mu", scene, "-o", out_dir]}[command]
        code, out, err = run_main(capsys, *argv)
        assert code == 2 and out == ""
        assert_one_line_error(err, *fragments)
    assert calls == [] and not out_dir.exists()


def test_a_directory_named_like_a_shipped_scene_does_not_hide_it(tmp_path, capsys, monkeypatch):
    (tmp_path / "default").mkdir()
    monkeypatch.chdir(tmp_path)
    code, out, err = run_main(capsys, "check", "default")
    assert code == 0 and err == "" and out.startswith("scene default: valid")


def test_check_validates_the_whole_scene_before_printing(tmp_path, capsys):
    """A scene whose values are each valid but whose model cannot be built
    (zero load mass on the flexible drive) is not called valid: nothing is
    printed, and the error names the file, for check as for run."""
    path = scene_file(tmp_path, "m0", concept="flexible", load={"mass": 0.0})
    code, out, err = run_main(capsys, "check", path)
    assert code == 2 and out == ""
    assert_one_line_error(err, f"{path}: load.mass = 0 is invalid")
    out_dir = tmp_path / "out"
    code, out, err = run_main(capsys, "run", path, "-o", out_dir, "--t-end", "0.01")
    assert code == 2 and out == "" and not out_dir.exists()
    assert_one_line_error(err, f"{path}: load.mass = 0 is invalid")


# --- run --------------------------------------------------------------------------


def test_run_writes_series_and_figure(tmp_path, capsys):
    code, out, err = run_main(capsys, "run", "default", "-o", tmp_path, "--t-end", "0.5",
                              "--points", "101")
    assert code == 0 and err == ""
    csv, png = tmp_path / "default.csv", tmp_path / "default.png"
    assert f"wrote {csv}" in out and f"wrote {png}" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    frame = read_series(csv)
    expected = ls.simulate(shipped.load("default"), 0.5, t_eval=np.linspace(0, 0.5, 101))
    assert list(frame.columns) == ["t"] + expected.channels
    np.testing.assert_array_equal(frame["t"], expected.t)
    for name in ("u_load", "omega_drive", "normal_force", "friction_force", "stick"):
        np.testing.assert_allclose(frame[name], expected[name], rtol=1e-15, atol=0)


@pytest.mark.parametrize("name", ["default", "thesis_table_5_1", "position_holding"])
def test_run_every_shipped_scene(tmp_path, capsys, name):
    """run on each shipped scene (a short run: position_holding's arctan law
    with k_v = 1e6 s/m takes about a million BDF steps per simulated second)
    writes its series and figure, and the series is simulate's."""
    code, out, err = run_main(capsys, "run", name, "-o", tmp_path, "--t-end", "0.05",
                              "--points", "11")
    assert code == 0 and err == ""
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"{name}.csv", f"{name}.png"]
    frame = read_series(tmp_path / f"{name}.csv")
    expected = ls.simulate(shipped.load(name), 0.05, t_eval=np.linspace(0, 0.05, 11))
    np.testing.assert_allclose(frame["u_load"], expected["u_load"], rtol=1e-15, atol=0)


@pytest.mark.parametrize("name", shipped.available())
def test_every_shipped_scene_runs_with_the_cli_defaults(tmp_path, capsys, name):
    """leadscrew run NAME without options (t_end 1 s, simulate's tolerances,
    max_steps 1e6): position_holding ended in CV_TOO_MUCH_WORK at 0.867 s
    (1.15 million steps per simulated second; 0.64 million since its
    flank is softer, see the scene file)."""
    code, out, err = run_main(capsys, "run", name, "-o", tmp_path)
    assert code == 0 and err == "", err
    frame = pd.read_csv(tmp_path / f"{name}.csv", skiprows=[1])  # row 1: the units
    assert len(frame) == cli.DEFAULT_POINTS and frame["t"].iloc[-1] == cli.DEFAULT_T_END
    assert np.isfinite(frame.to_numpy()).all()
    assert (tmp_path / f"{name}.png").stat().st_size > 10_000


@pytest.mark.parametrize("scene, study", [
    ("position_holding", "position_holding"), ("position_holding", "min_holding_preload"),
    ("position_holding", "stick_slip"), ("thesis_table_5_1", "stick_slip"),
    ("thesis_table_5_1", "compare_concepts"), ("default", "stick_slip"),
    ("default", "compare_concepts")])
def test_the_studies_of_each_shipped_scene_run_with_their_defaults(tmp_path, capsys, scene,
                                                                  study):
    """The studies that need no more than a scene, on each shipped scene
    made for them, with their defaults (the position_holding scene's
    excitation: the studies' rule): min_holding_preload takes the scene's
    sine; stick_slip's 2 s of the position_holding scene take 1.3 million
    steps (its max_steps: 1e6 per simulated second)."""
    code, out, err = run_main(capsys, "study", study, scene, "progress=false", "-o", tmp_path)
    assert code == 0 and err == "", err
    stem = tmp_path / f"{study}_{scene}"
    assert stem.with_suffix(".png").stat().st_size > 10_000
    frame = pd.read_csv(stem.with_suffix(".csv"), skiprows=[1])  # row 1: the units
    if study == "min_holding_preload":
        summary = json.loads(stem.with_suffix(".summary.json").read_text())
        assert summary["found"] and summary["monotonic"] and summary["bracket_verified"]
        assert summary["excitation_from"] == "scene" and summary["amplitude"] == 50.0
        # the flexible drive's answer lies above the rigid closed form, within 1 %
        assert 1.0 < summary["min_preload"] / summary["quasi_static_preload"] < 1.01
    elif study == "compare_concepts":
        assert len(frame) == 3
    else:
        assert frame["t"].iloc[-1] == pytest.approx(0.4 if study == "position_holding" else 2.0)


def test_run_a_scene_file_with_options(tmp_path, capsys):
    path = scene_file(tmp_path, friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 100.0})
    out_dir = tmp_path / "new" / "dir"
    code, out, _ = run_main(capsys, "run", path, "-o", out_dir, "--t-end", "0.2",
                            "--integrator", "cvode_adams", "--rtol", "1e-6", "--points", "0")
    assert code == 0 and "arctan_velocity/cvode_adams" in out
    frame = read_series(out_dir / "scene.csv")
    assert len(frame) > 10 and frame["t"].iloc[-1] == pytest.approx(0.2, rel=1e-12)
    assert (out_dir / "scene.png").is_file()


@pytest.mark.parametrize(
    "argv, fragments",
    [
        (["run", "missing.toml"], ["missing.toml", "no such file", "default"]),
        (["run", "default", "--t-end", "-1"], ["--t-end -1 is invalid"]),
        (["run", "default", "--points", "1"], ["--points 1 is invalid"]),
        (["run", "default", "--integrator", "dopri5"], ["integrator"]),
        (["run", "default", "--format", "xlsx"], ["--format", "xlsx"]),
        (["run"], ["SCENE"]),
        ([], ["command"]),
        (["simulate", "default"], ["simulate"]),
    ],
)
def test_usage_errors_exit_2_with_one_line(tmp_path, capsys, argv, fragments):
    code, out, err = run_main(capsys, *argv, *(["-o", tmp_path] if argv[:1] == ["run"]
                                                and len(argv) > 1 else []))
    assert code == 2
    assert_one_line_error(err, *fragments)


def test_parquet_without_pyarrow_is_a_clear_usage_error(tmp_path, capsys, monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "pyarrow" else real(name, *a))
    code, _, err = run_main(capsys, "run", "default", "-o", tmp_path, "--format", "parquet")
    assert code == 2
    assert_one_line_error(err, "--format parquet needs pyarrow", "pip install pyarrow")
    assert not any(tmp_path.iterdir())  # checked before simulating


def test_parquet_format(tmp_path, capsys):
    """Parquet where pyarrow is installed, the clear error where it is not."""
    code, out, err = run_main(capsys, "run", "default", "-o", tmp_path, "--t-end", "0.2",
                              "--format", "parquet", "--points", "11")
    if importlib.util.find_spec("pyarrow") is None:
        assert code == 2 and "needs pyarrow" in err
        return
    assert code == 0
    frame = pd.read_parquet(tmp_path / "default.parquet")
    expected = ls.simulate(shipped.load("default"), 0.2, t_eval=np.linspace(0, 0.2, 11))
    np.testing.assert_array_equal(frame["u_load"], expected["u_load"])
    # The units: in each field's metadata, and as the frame's attrs.
    import pyarrow.parquet as pq

    schema = pq.read_schema(tmp_path / "default.parquet")
    units = expected.units()
    assert schema.names == list(units)
    assert {f.name: f.metadata[b"unit"].decode() for f in schema} == units
    assert frame.attrs["units"] == units


def test_debug_shows_the_traceback(tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        cli.main(["--debug", "run", str(tmp_path / "missing.toml")])
    with pytest.raises(ValueError, match="no such file"):
        cli.main(["run", str(tmp_path / "missing.toml"), "--debug"])


def test_run_keeps_a_dotted_scene_name(tmp_path, capsys):
    """drive_v1.2.toml gives drive_v1.2.csv, not drive_v1.csv (the ".2" is no suffix)."""
    path = scene_file(tmp_path, "drive_v1.2")
    out_dir = tmp_path / "out"
    code, out, err = run_main(capsys, "run", path, "-o", out_dir, "--t-end", "0.05",
                              "--points", "11")
    assert code == 0, err
    assert sorted(p.name for p in out_dir.iterdir()) == ["drive_v1.2.csv", "drive_v1.2.png"]
    assert f"wrote {out_dir / 'drive_v1.2.csv'}" in out
    assert len(read_series(out_dir / "drive_v1.2.csv")) == 11


def test_run_moreau_takes_dt_and_theta(tmp_path, capsys):
    path = scene_file(tmp_path)
    code, out, err = run_main(capsys, "run", path, "-o", tmp_path, "--t-end", "0.2",
                              "--points", "11", "--integrator", "moreau", "--dt", "1e-4",
                              "--theta", "1")
    assert code == 0, err
    assert "coulomb/moreau" in out
    frame = read_series(tmp_path / "scene.csv")
    scene, t_eval = ls.Scene.from_toml(path), np.linspace(0, 0.2, 11)
    expected = ls.simulate(scene, 0.2, integrator="moreau", dt=1e-4, theta=1.0, t_eval=t_eval)
    np.testing.assert_allclose(frame["u_load"], expected["u_load"], rtol=1e-15, atol=0)
    # theta reached the integrator: the default theta = 0.5 gives other numbers.
    default = ls.simulate(scene, 0.2, integrator="moreau", dt=1e-4, t_eval=t_eval)
    assert np.abs(frame["u_load"] - default["u_load"]).max() > 1e-9


@pytest.mark.parametrize(
    "argv, fragments",
    [
        (["default", "--dt", "1e-4"],
         ["--dt 0.0001 is invalid with the scene's default integrator event_driven", "moreau"]),
        (["default", "--theta", "0.5"], ["--theta 0.5 is invalid", "moreau only"]),
        (["default", "--integrator", "event_driven", "--dt", "1e-3"],
         ["--dt 0.001 is invalid with --integrator event_driven"]),
        (["position_holding", "--dt", "1e-3"], ["--dt 0.001", "default integrator cvode_bdf"]),
        (["default", "--integrator", "moreau", "--rtol", "1e-6"],
         ["--rtol 1e-06 is invalid with --integrator moreau", "--dt"]),
        (["default", "--integrator", "moreau", "--atol", "1e-9"], ["--atol 1e-09 is invalid"]),
        (["default", "--t-end", "-1"], ["--t-end -1 is invalid"]),
        (["default", "--t-end", "nan"], ["--t-end nan is invalid"]),
        (["default", "--points", "1"], ["--points 1 is invalid"]),
        (["missing.toml"], ["no such file"]),
    ],
)
def test_run_refuses_before_creating_the_output_directory(tmp_path, capsys, argv, fragments):
    """Options the integrator would ignore are errors, and every argument is
    checked before the output directory is created."""
    out_dir = tmp_path / "nd" / "sub"
    code, out, err = run_main(capsys, "run", *argv, "-o", out_dir)
    assert code == 2 and out == ""
    assert_one_line_error(err, *fragments)
    assert not (tmp_path / "nd").exists()


def test_run_output_path_that_is_a_file(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    code, out, err = run_main(capsys, "run", "default", "-o", blocker / "sub", "--t-end", "0.01")
    assert code == 2 and out == ""
    assert_one_line_error(err, f"-o {blocker / 'sub'}: cannot create the output directory",
                          "is not a directory")


# --- study ------------------------------------------------------------------------


def fake_studies(monkeypatch):
    calls = []

    def sweep_mu(scene, mu=(0.1, 0.2), label="x", t_end=0.1):
        calls.append((scene, mu, label, t_end))
        rows = []
        for value in mu:
            result = ls.simulate(scene.replace(friction={"mu": value}), t_end)
            rows.append({"mu": value, "label": label, "u_end": result["u_load"][-1]})
        return pd.DataFrame(rows)

    def broken(scene, **options):
        raise RuntimeError("the study failed on purpose")

    def not_a_frame(scene):
        return [1, 2, 3]

    fake_study(monkeypatch, sweep_mu=sweep_mu, broken=broken, not_a_frame=not_a_frame)
    return calls


def test_study_dispatches_options_and_writes_csv(tmp_path, capsys, monkeypatch):
    calls = fake_studies(monkeypatch)
    code, out, err = run_main(capsys, "study", "sweep_mu", "default", "mu=0.1,0.3",
                              "label=abc", "t-end=0.2", "-o", tmp_path)
    assert code == 0, err
    (scene, mu, label, t_end), = calls
    assert scene == shipped.load("default") and mu == [0.1, 0.3] and label == "abc"
    assert t_end == 0.2
    frame = pd.read_csv(tmp_path / "sweep_mu_default.csv", skiprows=[1])  # row 1: the units
    assert list(frame.columns) == ["mu", "label", "u_end"]
    assert frame["mu"].tolist() == [0.1, 0.3]
    expected = ls.simulate(shipped.load("default").replace(friction={"mu": 0.3}), 0.2)
    assert frame["u_end"].iloc[1] == pytest.approx(expected["u_load"][-1], rel=1e-12)
    assert f"wrote {tmp_path / 'sweep_mu_default.csv'}" in out


@pytest.mark.parametrize(
    "argv, code, fragments",
    [
        (["study", "nope", "default"], 2, ["study 'nope' is unknown", "broken, not_a_frame, sweep_mu"]),
        (["study", "sweep_mu", "default", "omega=3"], 2,
         ["has no option 'omega'", "mu, label, t_end"]),
        (["study", "sweep_mu", "default", "novalue"], 2, ["KEY=VALUE"]),
        (["study", "sweep_mu", "missing.toml"], 2, ["no such file"]),
        (["study", "broken", "default"], 1, ["the study failed on purpose"]),
        (["study", "not_a_frame", "default"], 1, ["returned list, not a DataFrame"]),
    ],
)
def test_study_errors(tmp_path, capsys, monkeypatch, argv, code, fragments):
    fake_studies(monkeypatch)
    got, _, err = run_main(capsys, *argv, "-o", tmp_path)
    assert got == code
    assert_one_line_error(err, *fragments)


@pytest.mark.parametrize("order", [
    ["mu=0.1,0.3", "label=abc", "-o", "{out}", "t-end=0.2"],
    ["-o", "{out}", "mu=0.1,0.3", "label=abc", "t-end=0.2"],
    ["mu=0.1,0.3", "-o", "{out}", "label=abc", "t-end=0.2"],
])
def test_study_options_stand_before_or_after_o(tmp_path, capsys, monkeypatch, order):
    """KEY=VALUE options after -o DIR are options like those before it (the
    README's example writes progress=false before -o; a user writes it after)."""
    calls = fake_studies(monkeypatch)
    argv = [item.format(out=tmp_path) for item in order]
    code, out, err = run_main(capsys, "study", "sweep_mu", "default", *argv)
    assert code == 0, err
    (_, mu, label, t_end), = calls
    assert (mu, label, t_end) == ([0.1, 0.3], "abc", 0.2)
    assert (tmp_path / "sweep_mu_default.csv").is_file()


@pytest.mark.parametrize("argv, fragments", [
    (["study", "sweep_mu", "default", "-o", "{out}", "--bogus"],
     ["unrecognized arguments: --bogus", "leadscrew study --help"]),
    (["run", "default", "extra", "-o", "{out}"], ["unrecognized arguments: extra"]),
    (["study", "sweep_mu", "default", "-o", "{out}", "novalue"], ["novalue", "KEY=VALUE"]),
])
def test_arguments_no_command_takes_are_one_line_usage_errors(tmp_path, capsys, monkeypatch,
                                                              argv, fragments):
    calls = fake_studies(monkeypatch)
    code, out, err = run_main(capsys, *[item.format(out=tmp_path) for item in argv])
    assert code == 2 and out == "" and calls == []
    assert_one_line_error(err, *fragments)
    assert not any(tmp_path.iterdir())


def test_version(capsys):
    code, out, err = run_main(capsys, "--version")
    assert code == 0 and err == ""
    assert out == f"leadscrew {ls.__version__}\n"
    assert re.fullmatch(r"\d+\.\d+\.\d+\S*", ls.__version__)


def test_study_without_the_studies_module(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "leadscrew.studies", None)  # import fails
    code, _, err = run_main(capsys, "study", "stick_slip", "default", "-o", tmp_path)
    assert code == 1
    assert_one_line_error(err, "leadscrew.studies cannot be imported")


def fake_study(monkeypatch, **functions):
    module = types.ModuleType("leadscrew.studies")
    module.STUDIES = functions
    monkeypatch.setitem(sys.modules, "leadscrew.studies", module)


README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_study_example_runs(tmp_path, capsys, monkeypatch):
    """The README's `leadscrew study` line, as written, on the real study."""
    lines = [line for line in README.read_text(encoding="utf-8").splitlines()
             if line.startswith("leadscrew study ")]
    assert len(lines) == 1, lines
    argv = shlex.split(lines[0], comments=True)[1:]
    monkeypatch.chdir(tmp_path)
    code, out, err = run_main(capsys, *argv)
    assert code == 0, err
    options = dict(a.split("=", 1) for a in argv if "=" in a)
    name, scene_name, out_dir = argv[1], argv[2], argv[argv.index("-o") + 1]
    csv = Path(out_dir) / f"{name}_{scene_name}.csv"
    assert f"wrote {csv}" in out
    frame = pd.read_csv(tmp_path / csv, skiprows=[1])  # row 1: the units
    mus = [float(v) for v in options["mu"].split(",")]
    loads = [float(v) for v in options["loads"].split(",")]
    assert frame["mu"].tolist() == [m for m in mus for _ in loads]
    assert frame["load"].tolist() == loads * len(mus)
    assert frame["error"].isna().all() and frame["simulated"].all()
    # The simulated efficiency is the closed form's (eq. 5.2 at steady state).
    assert (frame["relative_error"] < 1e-6).all(), frame["relative_error"]


def test_study_fails_when_every_case_failed(tmp_path, capsys):
    """Every case of a real sweep fails at run time (3 steps are too few):
    exit 1 with the first message, nothing written."""
    out_dir = tmp_path / "out"
    code, out, err = run_main(capsys, "study", "efficiency_vs_mu", "default", "mu=0.1,0.2",
                              "loads=10", "progress=false", "max_steps=3", "-o", out_dir)
    assert code == 1
    assert_one_line_error(err, "study 'efficiency_vs_mu' on default: all 2 cases failed",
                          "the first: SimulationError", "max_steps")
    assert not out_dir.exists()


def test_study_warns_when_some_cases_failed(tmp_path, capsys, monkeypatch):
    def partly(scene, runs=3):
        return pd.DataFrame({"case": range(runs),
                             "error": [None, "SimulationError: at t = 0.5 s:\n boom", None][:runs]})

    def precision(scene):  # work_precision's column is "failure"
        return pd.DataFrame({"label": ["a", "b"], "failure": [float("nan"), "too many steps"]})

    fake_study(monkeypatch, partly=partly, precision=precision)
    code, out, err = run_main(capsys, "study", "partly", "default", "-o", tmp_path)
    assert code == 0
    assert err == "leadscrew: warning: 1 of 3 cases failed: SimulationError: at t = 0.5 s: boom\n"
    frame = pd.read_csv(tmp_path / "partly_default.csv", skiprows=[1])  # row 1: the units
    assert frame["error"].notna().tolist() == [False, True, False]
    code, _, err = run_main(capsys, "study", "partly", "default", "runs=2", "-o", tmp_path)
    assert code == 0 and "1 of 2 cases failed" in err
    code, _, err = run_main(capsys, "study", "precision", "default", "-o", tmp_path)
    assert code == 0 and err == "leadscrew: warning: 1 of 2 cases failed: too many steps\n"


@pytest.mark.parametrize(
    "argv, fragments",
    [
        (["efficiency_vs_mu", "thesis_table_5_1"],
         ["study 'efficiency_vs_mu' needs mu=... loads=...", "speed", "max_steps"]),
        (["work_precision", "default"], ["study 'work_precision' needs t_end=..."]),
        (["creep_vs_frequency", "position_holding"], ["needs frequencies=..."]),
        (["position_holding", "position_holding", "frequncy=10"],
         ["study 'position_holding' has no option 'frequncy'", "frequency",
          "leadscrew.simulate's", "integrator", "max_steps"]),
        (["stick_slip", "default", "t_eval=0,1"], ["has no option 't_eval'"]),
        (["efficiency_vs_mu", "default", "mu=0.1", "loads=10", "executor=serial"],
         ["study option executor = 'serial' is invalid", "Python object"]),
        (["work_precision", "default", "t_end=0.1", "reference=exact"],
         ["study option reference = 'exact' is invalid"]),
        (["work_precision", "default", "t_end=0.1", "ax=1"], ["study option ax = 1 is invalid"]),
    ],
)
def test_study_options_are_checked_against_the_real_studies(tmp_path, capsys, argv, fragments):
    out_dir = tmp_path / "out"
    code, out, err = run_main(capsys, "study", *argv, "-o", out_dir)
    assert code == 2 and out == ""
    assert_one_line_error(err, *fragments)
    if "it takes" in err:  # the list of options leaves out what the command line cannot give
        takes = err.split("it takes", 1)[1]
        assert not re.search(r"\b(executor|ax|reference)\b", takes), takes
        # simulate()'s scene and times are the study's to set
        forwarded = takes.split("leadscrew.simulate's", 1)[1] if "simulate" in takes else ""
        assert not re.search(r"\b(model|t_end|t_eval)\b", forwarded), forwarded
    assert not out_dir.exists()


def test_study_options_that_take_objects(tmp_path, capsys, monkeypatch):
    def needs_pool(scene, pool, n=2):
        raise AssertionError("not to be called")

    def maybe_pool(scene, pool=None, callback: "Optional[Callable]" = None, n: "int" = 2):
        raise AssertionError("not to be called")

    fake_study(monkeypatch, needs_pool=needs_pool, maybe_pool=maybe_pool)
    code, _, err = run_main(capsys, "study", "maybe_pool", "default", "pool=4", "-o", tmp_path)
    assert code == 2
    assert_one_line_error(err, "study option pool = 4 is invalid")
    code, _, err = run_main(capsys, "study", "maybe_pool", "default", "callback=f", "-o", tmp_path)
    assert code == 2
    assert_one_line_error(err, "study option callback = 'f' is invalid")
    code, _, err = run_main(capsys, "study", "maybe_pool", "default", "m=1", "-o", tmp_path)
    assert code == 2
    assert_one_line_error(err, "has no option 'm'; it takes n")
    # An unannotated required parameter may be anything the study checks.
    code, _, err = run_main(capsys, "study", "needs_pool", "default", "-o", tmp_path)
    assert code == 2
    assert_one_line_error(err, "needs pool=...")


def test_study_summary_is_printed_and_written(tmp_path, capsys):
    """position_holding's verdicts (frame.attrs["summary"]): one line each,
    with the unit its attrs["summary_units"] tells, and the same numbers in
    the JSON file."""
    code, out, err = run_main(capsys, "study", "position_holding", "position_holding",
                              "cycles=3", "-o", tmp_path)
    assert code == 0, err
    expected = ls.studies.position_holding(shipped.load("position_holding"), cycles=3)
    summary = expected.attrs["summary"]
    path = tmp_path / "position_holding_position_holding.summary.json"
    assert f"wrote {path}" in out
    written = json.loads(path.read_text())
    assert written.pop("units") == expected.attrs["summary_units"]
    assert written == summary  # all finite here: numbers as they are
    lines = out.splitlines()
    assert "summary:" in lines
    assert "  self_locking: true" in lines
    creep = summary["dynamic_creep_per_cycle"]
    assert f"  dynamic_creep_per_cycle: {creep:.6g} m" in lines
    assert f"  dynamic_separations: {summary['dynamic_separations']}" in lines
    for key in summary:
        assert sum(line.startswith(f"  {key}: ") for line in lines) == 1, key


def test_study_summary_json_of_special_values(tmp_path, capsys, monkeypatch):
    def summarized(scene):
        frame = pd.DataFrame({"creep_per_cycle": [1e-9]})
        frame.attrs["units"] = {"creep_per_cycle": "m"}
        frame.attrs["summary_units"] = {"torque": "N*m", "ratio": "1",
                                        "dynamic_creep_per_cycle": "m"}
        # creep_per_cycle is named as a column with a unit, but the units of
        # a summary are those of summary_units only (no guess from columns).
        frame.attrs["summary"] = {
            "missing": float("nan"), "unbounded": -math.inf, "count": np.int64(3),
            "value": np.float64(1.5), "holds": np.bool_(True), "window": (0.1, 0.2),
            "label": "x", "dynamic_creep_per_cycle": 2e-9, "torque": 0.5, "ratio": 0.25,
            "creep_per_cycle": 3e-9}
        return frame

    fake_study(monkeypatch, summarized=summarized)
    path = scene_file(tmp_path, "drive_v1.2")
    code, out, err = run_main(capsys, "study", "summarized", path, "-o", tmp_path / "out")
    assert code == 0, err
    json_path = tmp_path / "out" / "summarized_drive_v1.2.summary.json"
    text = json_path.read_text()
    assert "NaN" not in text and "Infinity" not in text
    written = json.loads(text)
    # the units of the entries summary_units names and the summary has
    assert written.pop("units") == {"torque": "N*m", "ratio": "1",
                                    "dynamic_creep_per_cycle": "m"}
    assert written == {
        "missing": None, "unbounded": None, "count": 3, "value": 1.5, "holds": True,
        "window": [0.1, 0.2], "label": "x", "dynamic_creep_per_cycle": 2e-9, "torque": 0.5,
        "ratio": 0.25, "creep_per_cycle": 3e-9}
    lines = out.splitlines()
    for line in ("  missing: nan", "  unbounded: -inf", "  count: 3", "  value: 1.5",
                 "  holds: true", "  window: 0.1, 0.2", "  label: x",
                 "  dynamic_creep_per_cycle: 2e-09 m", "  torque: 0.5 N*m", "  ratio: 0.25",
                 "  creep_per_cycle: 3e-09"):
        assert line in lines, (line, out)
    assert (tmp_path / "out" / "summarized_drive_v1.2.csv").is_file()


# Each study of leadscrew.studies.STUDIES on a tiny grid (a few ms each): its
# scene file's changes to the thesis scene and its KEY=VALUE options.
_HOLDING = {"backlash": {"axial": 2e-4}, "loads": {"drive_torque": 5e-3, "axial_force": 0.0}}
_HOLDING_RUNS = ["cycles=2", "points_per_cycle=10"]
TINY_STUDIES = {
    "work_precision": ({}, ["t_end=0.05", "repeats=1",
                            'configurations=[{integrator="event_driven", rtol=1e-6}]']),
    "stick_slip": ({}, ["t_end=0.1"]),
    "compare_concepts": ({}, ["t_end=0.02", "points=11"]),
    "position_holding": (_HOLDING, ["amplitude=30", "frequency=20", *_HOLDING_RUNS]),
    "creep_vs_frequency": (_HOLDING, ["frequencies=20", *_HOLDING_RUNS]),
    "creep_vs_backlash": (_HOLDING, ["backlash=2e-4", *_HOLDING_RUNS]),
    "creep_map": (_HOLDING, ["frequencies=20", "backlash=2e-4", *_HOLDING_RUNS]),
    "min_holding_preload": (_HOLDING, [
        f'excitation={{type="sine", amplitude=30.0, omega={2 * math.pi * 20}}}',
        "max_iterations=3", *_HOLDING_RUNS]),
    "efficiency_vs_mu": ({}, ["mu=0.3", "loads=10"]),
    "motor_characteristics": ({"loads": None, "motor": {
        "type": "dc", "voltage": 3.0, "resistance": 2.0, "inductance": 1e-3,
        "torque_constant": 0.05}}, ["loads=10", "t_end=0.05"]),
}


def test_every_study_has_a_tiny_case():
    assert set(TINY_STUDIES) == set(ls.studies.STUDIES)


def run_tiny_study(tmp_path, capsys, monkeypatch, name):
    """Run a study's tiny case with leadscrew study (into tmp_path / "out",
    its scene file "scene.toml"): the frame the study returned and what was
    printed."""
    study, frames = ls.studies.STUDIES[name], []

    @functools.wraps(study)  # the command line checks the options against its signature
    def recorded(*args, **kwargs):
        frames.append(study(*args, **kwargs))
        return frames[-1]

    monkeypatch.setitem(ls.studies.STUDIES, name, recorded)
    changes, options = TINY_STUDIES[name]
    path = scene_file(tmp_path, **changes)
    code, out, err = run_main(capsys, "study", name, path, *options, "progress=false",
                              "-o", tmp_path / "out")
    assert code == 0 and err == "", err
    (frame,) = frames
    assert not cli._failures(frame)[0]
    return frame, out


@pytest.mark.parametrize("name", sorted(TINY_STUDIES))
def test_every_number_a_study_sums_up_is_printed_with_its_unit(tmp_path, capsys, monkeypatch,
                                                               name):
    """Every summary entry but the labels (booleans, strings) has its unit in
    the frame's attrs["summary_units"] ("1" for counts and ratios), which is
    where leadscrew study takes the units it prints from."""
    frame, out = run_tiny_study(tmp_path, capsys, monkeypatch, name)
    summary = frame.attrs.get("summary") or {}
    units = frame.attrs.get("summary_units") or {}
    labels = {key for key, value in summary.items() if isinstance(value, (bool, np.bool_, str))}
    assert set(units) == set(summary) - labels
    lines = out.splitlines()
    for key, value in summary.items():
        unit = units.get(key, "1")
        line = f"  {key}: {cli._summary_text(value)}" + ("" if unit in ("", "1") else f" {unit}")
        assert line in lines, (line, out)


@pytest.mark.parametrize("name", sorted(TINY_STUDIES))
def test_every_study_writes_the_units_of_its_csv_and_its_summary(tmp_path, capsys,
                                                                 monkeypatch, name):
    """A study's CSV has a row of units under its names, as a run's (the
    frame's attrs["units"], "" for labels and flags), and its summary file
    the units of its numbers ("units": attrs["summary_units"])."""
    frame, _ = run_tiny_study(tmp_path, capsys, monkeypatch, name)
    csv = tmp_path / "out" / f"{name}_scene.csv"
    header = pd.read_csv(csv, nrows=1, dtype=str, keep_default_na=False)
    written = pd.read_csv(csv, skiprows=[1])
    columns = [c for c in frame.columns if c in written.columns]
    assert columns and list(header.columns) == list(written.columns)
    units = header.iloc[0].to_dict()
    assert {c: units[c] for c in columns} == {c: frame.attrs["units"].get(c, "")
                                              for c in columns}
    numeric = [c for c in columns if pd.api.types.is_numeric_dtype(frame[c])
               and not pd.api.types.is_bool_dtype(frame[c])]
    # every number has its unit (a column of NaN only, such as work_precision's
    # k_v without an arctan law, may have none)
    assert all(units[c] for c in numeric if frame[c].notna().any()), units
    assert len(written) == len(frame)
    for column in numeric:  # the data below the units, as numbers
        np.testing.assert_allclose(written[column].to_numpy(dtype=float),
                                   frame[column].to_numpy(dtype=float), rtol=1e-15)
    summary = frame.attrs.get("summary")
    path = tmp_path / "out" / f"{name}_scene.summary.json"
    if summary:
        assert json.loads(path.read_text())["units"] == frame.attrs["summary_units"]
    else:
        assert not path.exists()


@pytest.mark.parametrize("name", sorted(TINY_STUDIES))
def test_every_study_writes_its_figure_beside_its_csv(tmp_path, capsys, name):
    """leadscrew study wrote no figure: each study's plot (studies.PLOTS) goes
    to NAME_SCENE.png beside NAME_SCENE.csv, also for a sweep of one value."""
    changes, options = TINY_STUDIES[name]
    path = scene_file(tmp_path, "drive", **changes)
    code, out, err = run_main(capsys, "study", name, path, *options, "progress=false",
                              "-o", tmp_path / "out")
    assert code == 0 and err == "", err
    png = tmp_path / "out" / f"{name}_drive.png"
    assert f"wrote {png}" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    assert (tmp_path / "out" / f"{name}_drive.csv").is_file()
    assert set(ls.studies.PLOTS) == set(ls.studies.STUDIES)


def test_a_study_without_a_figure_writes_none(tmp_path, capsys, monkeypatch):
    def bare(scene):
        return pd.DataFrame({"x": [1.0]})

    fake_study(monkeypatch, bare=bare)
    code, out, err = run_main(capsys, "study", "bare", scene_file(tmp_path), "-o", tmp_path)
    assert code == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bare_scene.csv", "scene.toml"]


def test_min_preload_not_found_names_the_range(tmp_path, capsys, monkeypatch):
    """A min_holding_preload that finds no preload printed 'min_preload: nan N'."""
    import leadscrew.studies.holding as holding

    monkeypatch.setattr(holding, "_preload_case", lambda preload, *args, **kwargs: {
        "creep_per_cycle": 1e-6, "separations": 0, "flight_fraction": 0.0,
        "max_displacement": 0.0, "wall_time": 0.0})
    changes, options = TINY_STUDIES["min_holding_preload"]
    code, out, err = run_main(capsys, "study", "min_holding_preload",
                              scene_file(tmp_path, **changes), *options, "upper=10",
                              "progress=false", "-o", tmp_path)
    assert code == 0, err
    lines = out.splitlines()
    assert "  min_preload: not found in [0, 10240] N" in lines
    assert "  bracket_high: nan N" in lines and "nan N" not in "\n".join(
        line for line in lines if line.startswith("  min_preload"))
    summary = json.loads((tmp_path / "min_holding_preload_scene.summary.json").read_text())
    assert summary["min_preload"] == "not found in [0, 10240] N" and summary["found"] is False


def test_study_options_take_strings_with_units(tmp_path, capsys):
    """Study options with a unit as strings, as in a scene file: a list of
    frequencies, an amplitude; one of another dimension exits 2 naming it."""
    changes, _ = TINY_STUDIES["creep_vs_frequency"]
    path = scene_file(tmp_path, **changes)
    code, out, err = run_main(capsys, "study", "creep_vs_frequency", path,
                              "frequencies=20 Hz,0.04 kHz", "amplitude=30 N", *_HOLDING_RUNS,
                              "progress=false", "-o", tmp_path / "out")
    assert code == 0 and err == "", err
    frame = pd.read_csv(tmp_path / "out" / "creep_vs_frequency_scene.csv", skiprows=[1])
    assert frame["frequency"].tolist() == [20.0, 40.0] and frame["error"].isna().all()
    summary = json.loads((tmp_path / "out" / "creep_vs_frequency_scene.summary.json").read_text())
    assert summary["amplitude"] == 30.0 and summary["units"]["amplitude"] == "N"
    code, _, err = run_main(capsys, "study", "creep_vs_frequency", path, "frequencies=20 Hz",
                            "amplitude=30 m", "-o", tmp_path / "out")
    assert code == 2
    assert_one_line_error(err, 'amplitude = "30 m" is invalid: "30 m" is not a force (N)')


@pytest.mark.parametrize(
    "text, value",
    [("5,10,20", [5, 10, 20]), ("[5, 10.5]", [5, 10.5]), ("0.5", 0.5), ("true", True),
     ("rigid,flexible", ["rigid", "flexible"]), ('"a,b"', "a,b"), ("rigid", "rigid"),
     ('["1 mm", "2 mm"]', ["1 mm", "2 mm"]), ("1e-3", 1e-3)],
)
def test_study_option_values(text, value):
    assert cli._option_value(text) == value


# --- demo and the entry points ----------------------------------------------------


def test_demo_writes_its_figures(tmp_path, capsys):
    code, out, err = run_main(capsys, "demo", "-o", tmp_path / "demo")
    assert code == 0 and err == ""
    for name in ("default.csv", "default.png", "default_energy.png"):
        path = tmp_path / "demo" / name
        assert path.is_file() and path.stat().st_size > 1000, name
        assert f"wrote {path}" in out
    assert "scene default: valid" in out and "dynamic jamming" in out
    frame = read_series(tmp_path / "demo" / "default.csv")
    assert len(frame) == cli.DEFAULT_POINTS and frame["t"].iloc[-1] == cli.DEFAULT_T_END


def test_python_m_leadscrew_and_console_script(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, "-m", "leadscrew", "check", "thesis_table_5_1"],
                          capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
    assert done.returncode == 0 and "scene thesis_table_5_1: valid" in done.stdout
    done = subprocess.run([sys.executable, "-m", "leadscrew", "run", "missing.toml"],
                          capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
    assert done.returncode == 2 and done.stdout == ""
    assert_one_line_error(done.stderr, "missing.toml")
    done = subprocess.run([sys.executable, "-m", "leadscrew", "--debug", "run", "missing.toml"],
                          capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
    assert done.returncode != 0 and "Traceback" in done.stderr
    script = Path(sys.executable).parent / "leadscrew"
    done = subprocess.run([str(script), "--help"], capture_output=True, text=True, env=env,
                          timeout=120)
    assert done.returncode == 0 and "run" in done.stdout and "study" in done.stdout


def test_run_max_steps_reaches_the_integrator(tmp_path, capsys):
    path = scene_file(tmp_path)
    code, out, err = run_main(capsys, "run", path, "-o", tmp_path, "--t-end", "0.2",
                              "--max-steps", "3")
    assert code == 1 and "max_steps" in err and "= 3" in err and "Traceback" not in err
    assert not (tmp_path / "scene.csv").exists()
    code, out, err = run_main(capsys, "run", path, "-o", tmp_path, "--t-end", "0.2",
                              "--points", "11", "--max-steps", "100000")
    assert code == 0, err
    code, out, err = run_main(capsys, "run", path, "-o", tmp_path, "--max-steps", "0")
    assert code == 2 and "max_steps = 0 is invalid" in err


def header_commands():
    """The commands the shipped scene files advertise in their headers."""
    folder = Path(shipped.__file__).parent
    commands = []
    for path in sorted(folder.glob("*.toml")):
        for line in path.read_text().splitlines():
            match = re.match(r"#\s+leadscrew (run|check) (\S+)((?: --?[a-z-]+ \S+)*)", line)
            if match:
                commands.append([match.group(1), match.group(2)] + match.group(3).split())
    return commands


@pytest.mark.parametrize("argv", header_commands(), ids=" ".join)
def test_the_commands_in_the_scene_headers_run(tmp_path, capsys, argv):
    """What a scene file tells its reader to run runs (the position-holding
    drive, rattling in its play, takes its second in ~0.65 million steps at
    the tolerances its header gives)."""
    code, out, err = run_main(capsys, *argv, *(["-o", tmp_path] if argv[0] == "run" else []))
    assert code == 0, err
    if argv[0] == "run":
        assert (tmp_path / f"{argv[1]}.csv").exists()


def test_every_scene_header_advertises_a_command():
    assert {argv[1] for argv in header_commands()} == set(shipped.available())
