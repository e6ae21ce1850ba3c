"""``leadscrew run`` takes what ``leadscrew scene resolve`` writes
(python/leadscrew/core_spec.py): the core spec runs as its scene does."""

import numpy as np
import pandas as pd
import pytest

import leadscrew as ls
from helpers.cli_runs import assert_one_line_error, run_main


@pytest.mark.parametrize("name", ["default", "seat_adjuster"])
def test_run_takes_the_core_spec_that_scene_resolve_writes(name, tmp_path, capsys):
    spec = tmp_path / "core.toml"
    assert run_main(capsys, "scene", "resolve", name, "-o", spec)[0] == 0
    code, out, err = run_main(capsys, "run", spec, "--t-end", "0.3", "-o", tmp_path / "a")
    assert code == 0, err
    assert out.startswith("core: core spec, t_end = 0.3 s")
    assert run_main(capsys, "run", name, "--t-end", "0.3", "-o", tmp_path / "b")[0] == 0
    from_spec = pd.read_csv(tmp_path / "a" / "core.csv", skiprows=[1])
    from_scene = pd.read_csv(tmp_path / "b" / f"{name}.csv", skiprows=[1])
    pd.testing.assert_frame_equal(from_spec, from_scene, check_exact=True)
    assert (tmp_path / "a" / "core.png").is_file()


def test_a_core_spec_carries_its_run_options(tmp_path, capsys):
    spec = tmp_path / "core.toml"
    ls.scenes.load("default").to_core_toml(spec, rtol=1e-6)
    code, _, err = run_main(capsys, "run", spec, "--rtol", "1e-9", "-o", tmp_path / "out")
    assert code == 2
    assert_one_line_error(err, "--rtol with the core spec", "carries its run's options")
    assert not (tmp_path / "out").exists()
    every = ls.core_spec.simulate_core_spec(spec, 0.2, t_eval="steps")
    same = ls.simulate(ls.scenes.load("default"), 0.2, rtol=1e-6, t_eval="steps")
    np.testing.assert_array_equal(every["u_load"], same["u_load"])
    assert every.stats["steps"] == same.stats["steps"]


def test_a_scene_file_is_no_core_spec(tmp_path):
    path = tmp_path / "scene.toml"
    ls.scenes.load("default").to_toml(path)
    assert not ls.core_spec.is_core_spec(path.read_text())
    with pytest.raises(ValueError, match="is invalid: a core spec has format = "
                                         "'leadscrew-core-spec'"):
        ls.core_spec.simulate_core_spec(path, 0.1)
