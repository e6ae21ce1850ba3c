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


def test_a_friction_blocks_result_plots_its_position_velocity_and_forces():
    """(A new user's trial: r.plot() refused every FrictionBlock result, "no
    channel 'u_load'".) The block's figure draws its channels; with a
    transverse slip also w and the friction across; its result exports with
    the units (to_frame, units)."""
    block = ls.simulate(ls.FrictionBlock(mass=1.0, mu=0.3, g=10.0, force=ls.Sine(6.0, 6.0)), 0.1)
    figure = block.plot(title="block")
    assert [ax.get_ylabel() for ax in figure.axes[:3]] == [
        "block position u [mm]", "velocity [mm/s]", "force [N]"]
    np.testing.assert_array_equal(figure.axes[0].get_lines()[0].get_ydata(), block["u"] * 1e3)
    assert block.plot("energy").axes[1].get_ylabel() == "energy residual [J]"
    slipping = ls.simulate(ls.FrictionBlock(mass=1.0, mu=0.3, force=1.0,
                                            transverse_velocity=ls.Sine(1e-3, 10.0)), 0.2)
    velocity = slipping.plot().axes[1].get_lines()
    np.testing.assert_array_equal(velocity[1].get_ydata(),
                                  slipping["transverse_velocity"] * 1e3)
    units = slipping.units()
    assert units["transverse_velocity"] == "m/s" and units["transverse_friction"] == "N"
    assert units["work_transverse"] == "J"
    assert list(slipping.to_frame().columns) == ["t", *slipping.keys()]


def test_figure_titles_say_what_runs_not_the_scenes_repr(tmp_path, capsys, monkeypatch):
    scene = ls.scenes.load("position_holding")
    assert _title("position_holding", scene) == (
        "position_holding: flexible concept, screw driven, coulomb friction, "
        f"mu = {scene['friction']['mu']:g}, 0.2 mm play (bistop)")
    titles = []
    monkeypatch.setattr(ls.Result, "plot", lambda self, kind="time_series", title=None:
                        titles.append(title) or ls.plotting.plot_result(self, kind, title))
    assert run_main(capsys, "run", "default", "--t-end", "0.05", "-o", tmp_path)[0] == 0
    assert titles == [_title("default", ls.scenes.load("default"))]
    assert "<" not in titles[0] and "Scene" not in titles[0]


# --- the studies' figures ----------------------------------------------------------

import pandas as pd  # noqa: E402


def test_efficiency_vs_mu_keeps_each_loads_points_visible():
    """Loads whose efficiencies coincide: each its own hollow marker, the
    first the largest, so that the 10 N points do not hide under the 50 N."""
    frame = pd.DataFrame({"mu": [0.1, 0.2, 0.1, 0.2], "load": [10.0, 10.0, 50.0, 50.0],
                          "efficiency": [0.5, 0.4, 0.5, 0.4],
                          "efficiency_closed_form": [0.5, 0.4, 0.5, 0.4]})
    ax = ls.studies.plot_efficiency_vs_mu(frame)
    points = [line for line in ax.get_lines() if line.get_label().startswith("simulated")]
    assert [line.get_label() for line in points] == ["simulated, load 10 N",
                                                     "simulated, load 50 N"]
    assert points[0].get_marker() != points[1].get_marker()
    assert all(line.get_fillstyle() == "none" for line in points)
    assert points[0].get_markersize() > points[1].get_markersize()


def test_preload_tradeoff_draws_the_axial_stiffness_too():
    frame = pd.DataFrame({"preload": [0.0, 20.0, 50.0], "efficiency": [0.4, 0.35, 0.3],
                          "efficiency_closed_form": [0.4, 0.35, 0.3],
                          "creep_per_cycle": [1e-6, 1e-7, 0.0],
                          "max_displacement": [1e-4, 1e-4, 1e-4],
                          "axial_stiffness": [2e6, 5e6, np.inf]})
    ax = ls.studies.plot_preload_tradeoff(frame)
    stiffness = [other for other in ax.figure.axes
                 if other.get_ylabel() == "axial stiffness [N/um]"]
    assert len(stiffness) == 1
    (line,) = stiffness[0].get_lines()
    np.testing.assert_array_equal(line.get_ydata(), [2.0, 5.0, np.nan])
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert "axial stiffness (inf: not drawn)" in labels


def test_min_holding_preload_draws_creep_in_um_as_every_study():
    frame = pd.DataFrame({"preload": [10.0, 40.0], "holds": [False, True],
                          "creep_per_cycle": [3e-6, 0.0], "error": [None, None]})
    frame.attrs["summary"] = {"found": True, "bracket_low": 10.0, "bracket_high": 40.0}
    ax = ls.studies.plot_min_holding_preload(frame)
    assert ax.get_ylabel() == "|creep per cycle| [um]"
    creeps = {line.get_label(): line.get_ydata() for line in ax.get_lines()}
    np.testing.assert_allclose(creeps["separates or creeps"], [3.0], rtol=1e-15)


def test_check_names_units_and_no_penalty_contact_for_an_exact_one(capsys):
    code, out, _ = run_main(capsys, "check", "seat_adjuster")  # exact play
    assert code == 0
    assert "contact_" not in out and "N/m^e" not in out
    assert "  nut axial: stiffness 3.987e+07 N/m, damping 33.9514 N*s/m" in out
    assert "  nut torsion: stiffness 543.487 N*m/rad, damping 0.0260645 N*m*s/rad" in out
    code, out, _ = run_main(capsys, "check", "position_holding")  # bistop, exponent 1.5
    assert "  contact_stiffness = 1e+09 N/m^1.5" in out


def test_a_study_frame_plots_with_its_own_figure():
    frame = ls.studies.efficiency_vs_mu(ls.scenes.load("default").replace(concept="rigid"),
                                        mu=[0.1, 0.2], loads=[10.0], progress=False)
    assert frame.attrs["study"] == "efficiency_vs_mu"
    ax = ls.studies.plot(frame)
    assert ax.get_ylabel() == "efficiency eta [1]"
    assert ls.studies.STUDIES["efficiency_vs_mu"] is ls.studies.efficiency_vs_mu
    with pytest.raises(ValueError, match=r"attrs\['study'\] = None"):
        ls.studies.plot(pd.DataFrame({"a": [1]}))


def test_the_time_series_draws_a_base_excitations_inertial_force():
    """(A new user's trial: the force panel left out base_force.)"""
    scene = ls.scenes.load("default").replace(loads={"base_acceleration": 5.0})
    result = ls.simulate(scene, 0.02)
    forces = {line.get_label(): line for line in result.plot().axes[2].get_lines()}
    np.testing.assert_array_equal(forces["base inertial force"].get_ydata(),
                                  result["base_force"])
