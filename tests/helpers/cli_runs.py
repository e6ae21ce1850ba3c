"""Running the command line in-process (leadscrew.cli.main) and reading what
it writes: shared by tests/test_cli.py and tests/test_cli_study.py."""

import sys
import types

import pandas as pd

import leadscrew as ls
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


# A fake studies module: the study command's dispatch without the real studies.
def fake_study(monkeypatch, **functions):
    module = types.ModuleType("leadscrew.studies")
    module.STUDIES = functions
    monkeypatch.setitem(sys.modules, "leadscrew.studies", module)


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
