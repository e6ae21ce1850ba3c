"""``progress`` (python/leadscrew/_progress.py): one rule for simulate, every
study and the command line: True or False, nothing else; a bar only where
someone watches (standard error a terminal), never into a log."""


import pytest

import leadscrew as ls
from helpers.cli_runs import assert_one_line_error, run_main, scene_file
from test_cli_study import TINY_STUDIES

REFUSED = ["no", "maybe", "false", "True", 1, 0, None]
# The positional arguments a study needs besides its scene.
_REQUIRED = {"work_precision": (0.1,), "creep_vs_frequency": ([5.0],),
             "creep_vs_backlash": ([1e-4],), "creep_map": ([5.0], [1e-4]),
             "efficiency_vs_mu": ([0.1], [10.0]), "motor_characteristics": ([10.0],),
             "preload_tradeoff": ([0.0],)}


@pytest.mark.parametrize("value", REFUSED)
def test_simulate_refuses_what_is_not_a_bool(value):
    with pytest.raises(ValueError, match=r"progress = .* is invalid: must be True or False"):
        ls.simulate(ls.scenes.load("default"), 0.01, progress=value)


@pytest.mark.parametrize("name", sorted(TINY_STUDIES))
def test_every_study_refuses_what_simulate_refuses(name, tmp_path, capsys, monkeypatch):
    """Each study checks progress as simulate does, first (its simulations
    stubbed out: a study that ran one before would fail otherwise)."""
    def no_run(*args, **kwargs):
        raise AssertionError("a simulation ran before progress was checked")

    for module in (ls.simulation, *(m for m in vars(ls.studies).values()
                                    if getattr(m, "__name__", "").startswith("leadscrew.studies."))):
        if hasattr(module, "simulate"):
            monkeypatch.setattr(module, "simulate", no_run)
    changes, options = TINY_STUDIES[name]
    path = scene_file(tmp_path, **changes)
    for value in ("no", "1"):
        code, _, err = run_main(capsys, "study", name, path, *options,
                                f"progress={value}", "-o", tmp_path / "out")
        assert code == 2, err
        assert_one_line_error(err, "progress = ", "is invalid: must be True or False")
    with pytest.raises(ValueError, match=r"progress = 'no' is invalid: must be True or False"):
        ls.studies.STUDIES[name](ls.Scene.from_toml(path), *_REQUIRED.get(name, ()),
                                 progress="no")


def test_a_bar_only_where_someone_watches(capsys, watched, monkeypatch):
    scene = ls.scenes.load("default")
    ls.simulate(scene, 0.05, progress=True)
    assert "simulate" in capsys.readouterr().err
    monkeypatch.undo()  # standard error captured: not a terminal
    ls.simulate(scene, 0.05, progress=True)
    ls.studies.efficiency_vs_mu(scene, mu=[0.1, 0.2], loads=[10.0], progress=True)
    assert capsys.readouterr().err == ""


def test_the_study_command_refuses_what_simulate_refuses(tmp_path, capsys):
    for value in ("no", "maybe", '"false"'):
        code, _, err = run_main(capsys, "study", "stick_slip", "default", f"progress={value}",
                                "-o", tmp_path)
        assert code == 2, err
        assert_one_line_error(err, "progress = ", "is invalid: must be True or False")
    assert list(tmp_path.iterdir()) == []
