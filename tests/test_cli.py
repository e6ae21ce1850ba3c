"""The command line: run, check, demo on the shipped scenes; exit codes; files.
(The study command: tests/test_cli_study.py.)"""

import importlib.util
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import leadscrew as ls
import leadscrew.scenes as shipped
from helpers.cli_runs import assert_one_line_error, fake_studies, read_series, run_main, scene_file
from leadscrew import cli


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


def test_check_prints_self_locking_at_rest_with_mu_static_and_in_motion_with_mu(capsys, tmp_path):
    """(A new user's trial: mu 0.03 with the scene's mu_static 0.15 printed
    "self-locking: no" for a thread that static friction holds.) Both
    coefficients' closed forms, each named."""
    path = tmp_path / "mu003.toml"
    shipped.load("seat_adjuster").replace(friction={"mu": 0.03, "mu_static": 0.15}).to_toml(path)
    code, out, err = run_main(capsys, "check", str(path))
    assert code == 0 and err == ""
    thread = shipped.load("seat_adjuster").thread
    assert ls.is_self_locking(thread, 0.15) and not ls.is_self_locking(thread, 0.03)
    assert re.search(r"self-locking at rest \(mu_static = 0\.15, .*\): yes", out)
    assert re.search(r"self-locking in motion \(mu = 0\.03\b.*\): no", out)
    assert "holds under pure axial load" not in out


@pytest.mark.parametrize("name", ["default", "thesis_table_5_1", "position_holding",
                                  "seat_adjuster", "seat_adjuster_worm",
                                  "seat_adjuster_worm_flexible"])
def test_check_shipped_scene(capsys, name):
    code, out, err = run_main(capsys, "check", name)
    assert code == 0 and err == ""
    scene = shipped.load(name)
    d = scene.to_dict()
    t = scene.thread
    assert f"scene {name}: valid" in out
    assert re.search(r"self-locking .*:\s+yes", out)  # all of them are self-locking
    assert f"efficiency forward {ls.efficiency(t, d['friction']['mu']):.6g}" in out
    exact = (d.get("backlash") or {}).get("contact", "exact") == "exact"
    for key, value in scene.derived().items():
        # (a penalty flank's contact values only where the play has one)
        assert (f"{key} = {value:.6g}" in out) != (exact and key.startswith("contact_")), key
    assert "dynamic jamming" in out


def test_a_python_warning_is_a_one_line_note(capsys, tmp_path):
    """(A new user's review: the unverified profile's ProfileWarning came out
    as the warnings module's two lines, file, line number and source line.)
    The command line prints it once as a note; exit code and output as
    without it. With --debug the warning is Python's."""
    note = ("leadscrew: note: profile 'iso16750_3_test_iv' is not verified against "
            "ISO 16750-3")
    for argv in (["check", "seat_adjuster_vibration"],
                 ["run", "seat_adjuster_vibration", "--t-end", "0.002", "-o", tmp_path],
                 ["study", "holding_under_vibration", "seat_adjuster_vibration", "seeds=2",
                  "duration=0.002", "points=11", "progress=false", "-o", tmp_path]):
        code, out, err = run_main(capsys, *argv)
        assert code == 0, err
        assert err.count("\n") == 1 and err.startswith(note), err
        assert "ProfileWarning" not in err and ".py:" not in err
    with pytest.warns(ls.profiles.ProfileWarning):
        assert cli.main(["check", "seat_adjuster_vibration", "--debug"]) == 0


def test_check_reports_the_drive_train(capsys, tmp_path):
    # (A review: check ignored the motor, the stops and the preload.)
    code, out, _ = run_main(capsys, "check", "seat_adjuster")
    assert code == 0
    seat = shipped.load("seat_adjuster")
    stall = ls.studies.motor_characteristics(seat, [100.0], t_end=0.2, progress=False)
    assert f"stall load from rest (rigid drive, plain nut) {stall.attrs['summary']['stall_load']:.6g} N" in out
    assert "stall current 20 A, stall torque 0.6 N*m, no-load speed 400 rad/s" in out
    assert "gear stage: ideal, n = 5" in out
    assert "end stops: lower -0.01 m, upper 0.23 m (from the load's start), contact penalty" in out
    # A preloaded nut: the efficiency raising the scene's static load, closed form.
    d = shipped.load("default").to_dict()
    d["concept"], d["nut"]["preload"] = "rigid", 40.0
    d["friction"].pop("mu_static", None)
    d["loads"] = {"drive_torque": 0.0, "axial_force": 25.0}
    path = tmp_path / "preloaded.toml"
    ls.Scene.from_dict(d).to_toml(path)
    code, out, _ = run_main(capsys, "check", str(path))
    t, mu = ls.Scene.from_dict(d).thread, d["friction"]["mu"]
    alpha, rho = t.lead_angle, math.atan(mu / math.cos(t.flank_angle / 2))
    eta = 25.0 * math.tan(alpha) / (65.0 * math.tan(alpha + rho) + 40.0 * math.tan(rho - alpha))
    assert code == 0 and f"preloaded split nut: P = 40 N; efficiency raising 25 N {eta:.6g}" in out


def test_check_reports_a_load_spring(capsys, tmp_path):
    # (A review of issue 18: check ignored the elements of the core's registry.)
    d = shipped.load("default").to_dict()
    d["load_spring"] = {"stiffness": "2 N/mm", "preload": 5.0}
    path = tmp_path / "sprung.toml"
    ls.Scene.from_dict(d).to_toml(path)
    code, out, _ = run_main(capsys, "check", str(path))
    assert code == 0
    assert "load_spring: stiffness 2000 N/m, preload 5 N, damping 0 N*s/m" in out


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
    # (the unverified profile's note: test_a_python_warning_is_a_one_line_note)
    notes = (["leadscrew: note: profile 'iso16750_3_test_iv' is not verified"]
             if name == "seat_adjuster_vibration" else [])
    assert code == 0 and [line[:61] for line in err.splitlines()] == notes, err
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


def test_run_dt_without_an_integrator_runs_moreau(tmp_path, capsys):
    """--dt names its scheme: the default scene (event-driven by default)
    runs on Moreau-Jean with it, as leadscrew.simulate does."""
    path = scene_file(tmp_path)
    code, out, err = run_main(capsys, "run", path, "-o", tmp_path, "--t-end", "0.2",
                              "--points", "11", "--dt", "1e-4")
    assert code == 0, err
    assert "coulomb/moreau" in out
    frame = read_series(tmp_path / "scene.csv")
    scene, t_eval = ls.Scene.from_toml(path), np.linspace(0, 0.2, 11)
    expected = ls.simulate(scene, 0.2, integrator="moreau", dt=1e-4, t_eval=t_eval)
    np.testing.assert_allclose(frame["u_load"], expected["u_load"], rtol=1e-15, atol=0)


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
        # (no integrator takes both: refused naming both)
        (["default", "--dt", "1e-3", "--rtol", "1e-6"],
         ["--dt 0.001 and --rtol 1e-06 conflict", "moreau only"]),
        (["default", "--integrator", "event_driven", "--dt", "1e-3"],
         ["--dt 0.001 is invalid with --integrator event_driven"]),
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


@pytest.mark.parametrize("option", [["--theta", "0.5"], ["--dt", "1e-3"]])
def test_run_refuses_a_moreau_option_no_fitting_integrator_takes(tmp_path, capsys, option):
    """dt and theta left to the default name Moreau-Jean where it fits; a
    law Moreau-Jean does not take (eq. 3.15's, arctan_acceleration: its
    friction follows the slip acceleration) keeps its refusal, before the
    output directory is made."""
    scene = ls.scenes.load("position_holding").replace(
        concept="rigid", backlash=None,
        friction={"law": "arctan_acceleration", "mu": 0.3})
    path = tmp_path / "acceleration_law.toml"
    scene.to_toml(path)
    out_dir = tmp_path / "nd"
    code, out, err = run_main(capsys, "run", str(path), *option, "-o", out_dir)
    assert code == 2 and out == ""
    assert_one_line_error(err, f"{option[0]} {float(option[1]):g} is invalid",
                          "default integrator", "moreau only")
    assert not out_dir.exists()


@pytest.mark.parametrize("argv, fragments", [
    (["--rtol", "1e-6"],
     ["--rtol 1e-06 is invalid with the scene's default integrator moreau",
      "this scene runs on Moreau-Jean only, so --rtol has no use here: a shorter --dt"]),
    (["--theta", "0.3"],
     ["theta = 0.3 is invalid for this drive", "need theta in [0.5, 1]"]),
])
def test_a_moreau_only_scene_offers_no_other_integrator(tmp_path, capsys, argv, fragments):
    """(A new user's review: seat_adjuster_worm_flexible runs on Moreau-Jean
    alone, yet its refusals offered event_driven or cvode_bdf.)"""
    code, out, err = run_main(capsys, "run", "seat_adjuster_worm_flexible", *argv,
                              "-o", tmp_path / "out")
    assert code == 2 and out == ""
    assert_one_line_error(err, *fragments)
    assert "event_driven" not in err and "cvode" not in err and "other integrators" not in err
    assert not (tmp_path / "out").exists()


def test_run_output_path_that_is_a_file(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    code, out, err = run_main(capsys, "run", "default", "-o", blocker / "sub", "--t-end", "0.01")
    assert code == 2 and out == ""
    assert_one_line_error(err, f"-o {blocker / 'sub'}: cannot create the output directory",
                          "is not a directory")


def test_run_output_named_like_a_file_is_refused(tmp_path, capsys):
    """(A new user's review: -o out.csv made a directory named out.csv.)"""
    code, out, err = run_main(capsys, "run", "default", "-o", tmp_path / "out.csv",
                              "--t-end", "0.01")
    assert code == 2 and out == ""
    assert_one_line_error(err, "-o takes the output directory, not a file's name")
    assert not (tmp_path / "out.csv").exists()


def test_an_output_directory_that_is_not_writable_is_a_write_failure(tmp_path, capsys,
                                                                     monkeypatch):
    """(A new user's review: it exited 2, the usage code, and said 'cannot
    create' of a directory that exists.) Exit 1, the path and the cause,
    nothing written. os.access stands in for a read-only directory: the
    suite runs as root, whom chmod does not stop."""
    import os

    target = tmp_path / "locked"
    target.mkdir()
    real = os.access
    monkeypatch.setattr(os, "access", lambda path, mode: False if os.fspath(path) == os.fspath(
        target) else real(path, mode))
    code, out, err = run_main(capsys, "run", "default", "-o", target, "--t-end", "0.01")
    assert code == 1 and out == ""
    assert_one_line_error(err, "WriteError", str(target), "not writable")
    assert list(target.iterdir()) == []


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


def test_the_run_figure_shows_a_dc_motors_current_and_the_stop_force():
    result = ls.simulate(shipped.load("seat_adjuster"), 0.6, t_eval=np.linspace(0, 0.6, 61))
    figure = result.plot(title="seat_adjuster")
    assert len(figure.axes) == 5 and figure.axes[4].get_ylabel() == "motor current [A]"
    assert "end stop" in [line.get_label() for line in figure.axes[2].get_lines()]
    plain = ls.simulate(shipped.load("default"), 0.1).plot()
    assert len(plain.axes) == 4


def test_check_reports_the_preloaded_nuts_lift_off(capsys, tmp_path):
    # A preloaded nut with penalty play on a flexible concept: the spring's
    # force where half A lifts off, P (1 + k_p / k_c) on a linear flank
    # (docs/physics/preloaded_nut.md, "Lift-off").
    d = shipped.load("default").to_dict()
    d["concept"] = "flexible_nut"
    d["nut"].update(preload=50.0, preload_stiffness=1e6)
    d["friction"].pop("mu_static", None)
    d["friction"]["law"] = "coulomb"
    d["backlash"] = {"axial": 1e-4, "contact": "bistop", "stiffness": 1e7, "exponent": 1.0}
    d["loads"] = {"drive_torque": 0.0, "axial_force": -25.0}
    path = tmp_path / "lift_off.toml"
    ls.Scene.from_dict(d).to_toml(path)
    code, out, _ = run_main(capsys, "check", str(path))
    assert code == 0
    assert "lift-off: half A leaves its flank where the spring carries P + k_p d_0 = 55 N" in out
    assert "(d_0 = 5e-06 m" in out
