"""The command line's study command (python/leadscrew/cli_study.py): options
and their units, dispatch, summaries, CSV with units, figures, every study on a
tiny case."""

import functools
import json
import math
import re
import shlex
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import leadscrew as ls
import leadscrew.scenes as shipped
from helpers.cli_runs import (assert_one_line_error, fake_studies, fake_study, run_main,
                              scene_file)
from leadscrew import cli


# --- study ------------------------------------------------------------------------


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


README = Path(__file__).resolve().parents[1] / "README.md"
CLI_GUIDE = README.parent / "docs" / "guide" / "cli.md"


def test_readme_study_example_runs(tmp_path, capsys, monkeypatch):
    """The command-line guide's `leadscrew study` line, as written, on the
    real study (the README's table shows it too)."""
    assert "`leadscrew study efficiency_vs_mu " in README.read_text(encoding="utf-8")
    lines = [line for line in CLI_GUIDE.read_text(encoding="utf-8").splitlines()
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
        "missing": None, "unbounded": "-inf", "count": 3, "value": 1.5, "holds": True,
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
    "preload_tradeoff": ({"loads": {"drive_torque": 2e-2, "axial_force": -10.0},
                          "nut": {"preload_stiffness": 1e6}},
                         ["preloads=0,20", "amplitude=30", "frequency=20", *_HOLDING_RUNS]),
    "holding_under_vibration": ({"loads": {"drive_torque": 0.0, "axial_force": -10.0}}, [
        'excitation={type="random", frequencies=[20.0, 200.0], psd=[2.0, 2.0]}',
        "duration=0.05", "seeds=2", "points=11"]),
    "end_stop_jam": ({"loads": {"drive_torque": 0.5, "axial_force": 0.0},
                      "end_stops": {"lower": -2e-4, "stiffness": 1e8, "damping": 1e4}},
                     ["t_drive=0.3", "t_reverse=0.05", "runs=6"]),
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
        empty = isinstance(value, (list, tuple)) and not value  # "none", no unit
        line = f"  {key}: {cli._summary_text(value)}" + ("" if unit in ("", "1") or empty
                                                         else f" {unit}")
        assert line in lines, (line, out)


def test_an_empty_list_in_a_summary_prints_none_without_its_unit(tmp_path, capsys,
                                                                 monkeypatch):
    """Issue 33: end_stop_jam's summary printed 'undecided:  V' (no reverse
    undecided: an empty value followed by its unit)."""
    assert cli._summary_text([], "V") == "none" and cli._summary_text((), "") == "none"
    assert cli._summary_text([1.5, 2.0], "V") == "1.5, 2 V"
    titles, save_figure = [], ls.studies.save_figure

    def recorded(name, frame, path, title=None, **options):
        titles.append(title)
        return save_figure(name, frame, path, title, **options)

    monkeypatch.setattr(ls.studies, "save_figure", recorded)
    frame, out = run_tiny_study(tmp_path, capsys, monkeypatch, "end_stop_jam")
    assert frame.attrs["summary"]["undecided"] == []
    assert "  undecided: none" in out.splitlines()
    assert not any(line.rstrip().endswith(": V") or ":  " in line for line in out.splitlines())
    # the figure's title names the study and the scene's file, not the Scene's repr
    assert titles == ["end_stop_jam on scene"]


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


@pytest.mark.parametrize("text, value", [
    ('{"friction.mu"=["uniform",0.08,0.12]}', {"friction.mu": ["uniform", 0.08, 0.12]}),
    ('{"nut.preload"=["normal","100 N","10 N"]}', {"nut.preload": ["normal", "100 N", "10 N"]}),
    ("1 mm,[2, 3]", ["1 mm", [2, 3]]),
    ('5 Hz,"a,b"', ["5 Hz", "a,b"]),
])
def test_study_option_values_split_only_at_top_level_commas(text, value):
    """(A new user's review: a scatter given without spaces was split at the
    commas inside its list.) Unspaced TOML stays one value; a list's items
    are split at the commas outside brackets and quotes."""
    assert cli._option_value(text) == value


def test_a_value_that_opens_a_table_but_is_no_toml_is_refused(tmp_path, capsys):
    """What the shell leaves of an unquoted scatter: its quotes taken
    (not TOML: refused naming the option and how to quote it, not split at
    its commas), or its braces expanded at the commas (the option three
    times: refused as given twice)."""
    with pytest.raises(cli.UsageError, match=r"^study option scatter=\{friction\.mu=\[uniform,"
                                             r"0\.08,0\.12\]\} is invalid: not a TOML inline "
                                             r"table \(.*\); quote strings inside it and the "
                                             r"whole option for the shell, e\.g\. 'scatter="):
        cli._option_value("{friction.mu=[uniform,0.08,0.12]}", "scatter")
    for argv in (["scatter={friction.mu=[uniform,0.08,0.12]}"],
                 ["scatter=friction.mu=[uniform", "scatter=0.08", "scatter=0.12]"]):
        code, _, err = run_main(capsys, "study", "holding_under_vibration",
                                "seat_adjuster_vibration", *argv, "-o", tmp_path)
        assert code == 2
        assert_one_line_error(err, "study option scatter")
        assert not list(tmp_path.iterdir())
    assert "is given twice (scatter='friction.mu=[uniform' and 'scatter=0.08')" in err
