"""Result.plot (python/leadscrew/plotting.py) and the command line's figure
titles."""

import numpy as np
import pytest

import leadscrew as ls
from helpers.cli_runs import run_main
from leadscrew.cli_output import _title


def test_result_plot_draws_the_time_series_and_the_energy_account():
    result = ls.simulate(ls.scenes.load("seat_adjuster"), 0.6, t_eval=np.linspace(0, 0.6, 61))
    figure = result.plot(title="seat")
    assert [ax.get_ylabel() for ax in figure.axes] == [
        "load position u [mm]", "rotor speed [rad/s]", "force [N]", "drive torque [N*mm]",
        "motor current [A]"]
    assert figure._suptitle.get_text() == "seat"
    u = figure.axes[0].get_lines()[0].get_ydata()
    np.testing.assert_array_equal(u, result["u_load"] * 1e3)
    energy = result.plot("energy")
    assert energy.axes[1].get_ylabel() == "energy residual [J]" and energy._suptitle is None


def test_result_plot_refuses_what_it_cannot_draw():
    result = ls.simulate(ls.scenes.load("default"), 0.05)
    with pytest.raises(ValueError, match="kind = 'phase' is invalid: must be one of "
                                         "time_series, energy"):
        result.plot("phase")
    block = ls.simulate(ls.FrictionBlock(mass=1.0, mu=0.3, g=10.0, force=ls.Sine(6.0, 6.0)), 0.1)
    with pytest.raises(ValueError, match="has no channel 'u_load'"):
        block.plot()


def test_figure_titles_say_what_runs_not_the_scenes_repr(tmp_path, capsys, monkeypatch):
    scene = ls.scenes.load("position_holding")
    assert _title("position_holding", scene) == (
        "position_holding: flexible concept, screw driven, arctan_velocity friction, "
        f"mu = {scene['friction']['mu']:g}, 0.2 mm play (bistop)")
    titles = []
    monkeypatch.setattr(ls.Result, "plot", lambda self, kind="time_series", title=None:
                        titles.append(title) or ls.plotting.plot_result(self, kind, title))
    assert run_main(capsys, "run", "default", "--t-end", "0.05", "-o", tmp_path)[0] == 0
    assert titles == [_title("default", ls.scenes.load("default"))]
    assert "<" not in titles[0] and "Scene" not in titles[0]
