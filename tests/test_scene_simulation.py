"""A scene's [simulation] section: the run's options stored with the scene
(issue 34, item 5). simulate takes them as its defaults for the scene, a
keyword given overrides one; the study batches, the command line and the
core spec take them alike; the section is checked with key paths and the
ranges simulate's options have."""

import numpy as np
import pytest

import leadscrew as ls
from helpers.cli_runs import assert_one_line_error, run_main
from helpers.scenes import thesis_scene
from leadscrew.scene import describe_schema
from leadscrew.studies._batch import DriveBatch, check_simulate_options


def holding(**simulation):
    """The shipped position_holding scene (exact Coulomb, bistop flanks) with
    its [simulation] section replaced by ``simulation`` (none if empty)."""
    scene = ls.scenes.load("position_holding").replace(simulation=None)
    return scene.replace(simulation=simulation) if simulation else scene


def with_section(**simulation):
    """The thesis drive (rigid, exact Coulomb, no play) with a [simulation]
    section."""
    return ls.Scene.from_dict(thesis_scene(simulation=simulation))


def test_the_section_round_trips_through_dict_and_toml(tmp_path):
    scene = with_section(rtol=1e-6, atol=1e-12, max_steps=200_000, max_events=500,
                         integrator="event_driven", smooth_integrator="rk_verner6")
    assert scene["simulation"] == {"integrator": "event_driven",
                                   "smooth_integrator": "rk_verner6", "rtol": 1e-6,
                                   "atol": 1e-12, "max_steps": 200_000, "max_events": 500}
    assert ls.Scene.from_dict(scene.to_dict()) == scene
    text = scene.to_toml(tmp_path / "stored.toml")
    assert "\n[simulation]\nintegrator = \"event_driven\"\n" in text
    again = ls.Scene.from_toml(tmp_path / "stored.toml")
    assert again == scene and again["simulation"] == scene["simulation"]
    # A scene with other options is another scene; without the section the same
    assert with_section(rtol=1e-7) != with_section(rtol=1e-6)
    assert "simulation" not in with_section().replace(simulation=None)


def test_a_value_with_a_unit_is_converted():
    scene = holding(integrator="moreau", dt="30 us", theta=1)
    assert scene["simulation"] == {"integrator": "moreau", "dt": pytest.approx(3e-5, rel=1e-12),
                                   "theta": 1.0}


@pytest.mark.parametrize("section, message", [
    ({"rtol": 0}, "simulation.rtol = 0 is invalid: must be a finite number in (0, 0.001]"),
    ({"rtol": 2e-3}, "simulation.rtol = 0.002 is invalid: must be a finite number in (0, 0.001]"),
    ({"atol": 0.0}, "simulation.atol = 0.0 is invalid: must be a finite number in [1e-100, "
                    "0.001]"),
    ({"dt": -1e-4}, "simulation.dt = -0.0001 is invalid: must be a finite number > 0"),
    ({"theta": 1.5}, "simulation.theta = 1.5 is invalid: must be a finite number in [0, 1]"),
    ({"max_steps": 0}, "simulation.max_steps = 0 is invalid: must be an integer >= 1"),
    ({"max_steps": 1.5}, "simulation.max_steps = 1.5 is invalid: must be an integer >= 1"),
    ({"max_order": -1}, "simulation.max_order = -1 is invalid: must be an integer >= 0"),
    ({"max_step": "1 m"}, 'simulation.max_step = "1 m" is invalid'),
    ({"rtol": "tight"}, "simulation.rtol"),
    ({"integrator": "lsoda"}, "simulation.integrator = 'lsoda' is invalid: must be one of "
                              "'cvode_bdf', 'cvode_adams'"),
])
def test_an_invalid_value_names_its_key_path_and_range(section, message):
    with pytest.raises(ValueError) as error:
        with_section(**section)
    assert str(error.value).startswith(message)


@pytest.mark.parametrize("name, value", [("rtol", 1e-3), ("rtol", 1.0001e-3), ("rtol", 1e-300),
                                         ("atol", 1e-3), ("atol", 2e-3), ("atol", 1e-100),
                                         ("atol", 1e-101), ("max_steps", 1),
                                         ("max_step", 0.0), ("first_step", -1e-9)])
def test_the_section_and_simulate_refuse_the_same_values(name, value):
    """The section's ranges are those simulate's keywords have (the core's
    checks of the options before a run)."""
    base = ls.Scene.from_dict(thesis_scene())
    try:
        check_simulate_options(base, {name: value}, 0.01)
        simulate_refuses = False
    except ValueError:
        simulate_refuses = True
    try:
        with_section(**{name: value})
        section_refuses = False
    except ValueError as error:
        assert str(error).startswith(f"simulation.{name} = ")
        section_refuses = True
    assert section_refuses == simulate_refuses


def test_none_leaves_an_option_out_as_in_every_section():
    assert with_section(rtol=None, atol=1e-12)["simulation"] == {"atol": 1e-12}
    assert holding(rtol=1e-6).replace(simulation={"rtol": None})["simulation"] == {}


def test_an_unknown_key_or_section_gets_a_close_match():
    with pytest.raises(ValueError, match=r"^simulation\.rtl is not a known key \(did you mean "
                                         r"'rtol'\?\); simulation takes integrator, "):
        with_section(rtl=1e-6)
    with pytest.raises(ValueError, match=r"^simulaton is not a known section \(did you mean "
                                         r"'simulation'\?\)"):
        ls.Scene.from_dict({**thesis_scene(), "simulaton": {"rtol": 1e-6}})


@pytest.mark.parametrize("section, message", [
    ({"integrator": "moreau", "rtol": 1e-6},
     "simulation.rtol = 1e-06 is invalid with simulation.integrator = 'moreau': moreau is a "
     "fixed-step scheme"),
    ({"integrator": "cvode_bdf", "dt": 1e-4},
     "simulation.dt = 0.0001 is invalid with simulation.integrator = 'cvode_bdf': dt is taken "
     "by moreau only"),
    ({"integrator": "cvode_bdf", "smooth_integrator": "cvode_adams"},
     "simulation.smooth_integrator = 'cvode_adams' is invalid: must be absent with "
     "simulation.integrator = 'cvode_bdf': only 'event_driven' takes one"),
    ({"bounce_threshold": 1e-5},
     "simulation.bounce_threshold = 1e-05 is invalid for this scene: it has "
     "backlash.contact = 'bistop'"),
])
def test_options_the_stored_integrator_or_the_scene_would_ignore_are_refused(section, message):
    with pytest.raises(ValueError) as error:
        holding(**section)
    assert str(error.value).startswith(message)


def test_simulate_takes_the_stored_options_and_a_keyword_overrides_them():
    plain, stored = holding(), holding(rtol=1e-6, max_events=10_000)
    run = ls.simulate(stored, 0.05, t_eval="steps")
    same = ls.simulate(plain, 0.05, t_eval="steps", rtol=1e-6)
    assert run.stats["steps"] == same.stats["steps"]
    np.testing.assert_array_equal(run["phi_drive"], same["phi_drive"])
    default = ls.simulate(plain, 0.05, t_eval="steps")
    assert default.stats["steps"] > run.stats["steps"]  # rtol 1e-8 takes more steps
    overridden = ls.simulate(stored, 0.05, t_eval="steps", rtol=1e-8)
    np.testing.assert_array_equal(overridden["phi_drive"], default["phi_drive"])
    # the stored bound holds: 10 events are not enough
    with pytest.raises(ls.SimulationError, match="max_events"):
        ls.simulate(holding(max_events=10), 0.05)
    ls.simulate(holding(max_events=10), 0.05, max_events=100_000)  # overridden


def test_another_integrator_given_leaves_the_stored_options_it_does_not_take():
    """The scene's rtol was set for its event-driven run: under
    integrator="moreau" it is left out (not refused), and the stored dt of a
    Moreau-Jean scene is left out under event_driven."""
    stored = holding(rtol=1e-6)
    moreau = ls.simulate(stored, 0.02, integrator="moreau", dt=1e-4)
    plain = ls.simulate(holding(), 0.02, integrator="moreau", dt=1e-4)
    np.testing.assert_array_equal(moreau["phi_drive"], plain["phi_drive"])
    stepping = holding(integrator="moreau", dt=5e-5)
    assert ls.simulate(stepping, 0.02).integrator == "moreau"
    assert ls.simulate(stepping, 0.02, integrator="event_driven").integrator == "event_driven"
    with pytest.raises(ValueError, match=r"^rtol = 1e-06 is invalid with integrator 'moreau'"):
        ls.simulate(stepping, 0.02, rtol=1e-6)  # given: refused as ever


def test_an_error_about_a_stored_option_names_its_key_path():
    with pytest.raises(ValueError) as error:
        ls.simulate(holding(integrator="dopri5"), 0.01)
    assert str(error.value).startswith(
        'simulation.integrator = "dopri5" is invalid for backlash.contact = "bistop" with '
        'friction.law = "coulomb": must be one of "event_driven", "moreau"')
    assert "simulate's integrator=... overrides it" in str(error.value)
    # (a stored dt names Moreau-Jean, as a dt given does; a stored rtol
    # beside it no integrator takes: the section is refused,
    # test_a_stored_dt_with_a_stored_rtol_is_refused_where_the_scene_is_read)
    assert ls.simulate(holding(dt=1e-4), 0.01).integrator == "moreau"
    with pytest.raises(ValueError, match=r"^simulation\.max_step = 1e-09 is invalid: reaching "
                                         r"t_end = 0\.01 s takes more steps"):
        ls.simulate(holding(max_step=1e-9), 0.01)
    # the same option given is named as given
    with pytest.raises(ValueError, match=r"^max_step = 1e-09 is invalid"):
        ls.simulate(holding(), 0.01, max_step=1e-9)


def test_the_study_batches_take_the_stored_options():
    """DriveBatch and the studies' option check (their runs go through
    simulate or the batch) apply the same rule as simulate."""
    batch = DriveBatch(holding(rtol=1e-6), ["mu"], ["phi_drive"], 0.05, [0.05])
    assert batch._arguments["rtol"] == 1e-6
    assert DriveBatch(holding(rtol=1e-6), ["mu"], ["phi_drive"], 0.05, [0.05],
                      rtol=1e-7)._arguments["rtol"] == 1e-7
    samples, errors, _ = batch.run(np.array([[0.3]]))
    single = ls.simulate(holding(rtol=1e-6), 0.05, t_eval=[0.05])
    assert errors[0] is None
    assert samples[0, 0, 0] == pytest.approx(single["phi_drive"][-1], rel=1e-12)
    check_simulate_options(holding(dt=1e-4), {}, 0.05)  # (dt names Moreau-Jean)
    check_simulate_options(holding(dt=1e-4), {"integrator": "moreau"}, 0.05)


def test_the_command_line_takes_the_stored_options(tmp_path, capsys):
    path = tmp_path / "stepping.toml"
    holding(integrator="moreau", dt=5e-5).to_toml(path)
    code, out, err = run_main(capsys, "run", path, "--t-end", "0.01", "-o", tmp_path / "out")
    assert code == 0, err
    code, out, err = run_main(capsys, "run", path, "--t-end", "0.01", "--rtol", "1e-6",
                              "-o", tmp_path / "out2")
    assert code == 2
    assert_one_line_error(err, "--rtol 1e-06 is invalid with the scene's integrator moreau "
                               "(simulation.integrator)")
    code, out, err = run_main(capsys, "check", "position_holding")
    assert code == 0
    assert ("run options ([simulation], simulate's defaults for this scene): rtol = 1e-06, "
            "atol = 1e-08" in out.splitlines())


def test_describe_schema_documents_the_section():
    lines = describe_schema().splitlines()
    rtol = next(line for line in lines if line.startswith("simulation.rtol"))
    assert rtol.startswith("simulation.rtol (default simulate's default 1e-8; a finite number "
                           "in (0, 0.001]): relative tolerance")
    assert any(line.startswith("simulation.dt [s] (") for line in lines)
    assert any(line.startswith("simulation.integrator (default simulate's default, the first "
                               "that fits the scene; one of 'cvode_bdf'") for line in lines)


def test_a_dt_given_overrides_the_scenes_stored_adaptive_options():
    """(A new user's review: `leadscrew run position_holding --dt 1e-5` was
    refused, the scene's stored rtol and atol kept beside the dt given.) A
    dt given names Moreau-Jean; the scene's options of the other scheme give
    way, as they do under integrator="moreau"."""
    scene = ls.scenes.load("position_holding")
    assert scene["simulation"]["rtol"] == 1e-6
    result = ls.simulate(scene, 0.01, dt=1e-5)
    assert result.integrator == "moreau"
    explicit = ls.simulate(scene, 0.01, integrator="moreau", dt=1e-5)
    np.testing.assert_array_equal(result["u_load"], explicit["u_load"])


STORED_CONFLICT = (r"simulation\.dt = 0\.0001 and simulation\.rtol = 1e-06 conflict: "
                   r"simulation\.dt is taken by moreau only \(the fixed-step Moreau-Jean "
                   r"scheme\), simulation\.rtol by the adaptive integrators only")


def test_a_stored_dt_with_a_stored_rtol_is_refused_where_the_scene_is_read(tmp_path, capsys):
    """(A new user's review: `leadscrew check` passed a scene whose
    [simulation] section stores dt and rtol, which every `leadscrew run`
    refused.) The section's rule is simulate's (option_conflict), applied
    where the scene is read: check and run refuse the file with one
    message, naming both keys; with an integrator stored the rule is the
    integrator's."""
    with pytest.raises(ValueError, match="^" + STORED_CONFLICT):
        holding(dt=1e-4, rtol=1e-6)
    path = tmp_path / "both.toml"
    text = ls.scenes.load("position_holding").to_toml()
    path.write_text(text.replace("[simulation]", "[simulation]\ndt = 1e-4"))
    errors = []
    for command in (["check", path], ["run", path, "--t-end", "0.01", "-o", tmp_path / "out"]):
        code, out, err = run_main(capsys, *command)
        assert code == 2 and out == ""
        assert_one_line_error(err, "both.toml: simulation.dt = 0.0001 and simulation.rtol = "
                                   "1e-06 conflict")
        errors.append(err)
    assert errors[0] == errors[1]
    with pytest.raises(ValueError, match=r"^simulation\.rtol = 1e-06 is invalid with "
                                         r"simulation\.integrator = 'moreau'"):
        holding(integrator="moreau", dt=1e-4, rtol=1e-6)


@pytest.mark.parametrize("section", [{"integrator": "dopri5"}, {"max_step": 1e-9}])
def test_check_refuses_the_stored_options_run_refuses(tmp_path, capsys, section):
    """`leadscrew check` applies the run's rules to the stored options (as
    `leadscrew run SCENE` at its default t_end, through the studies' own
    check of simulate's options): a stored integrator that does not fit the
    scene, a max_step too short for the run, refused by both with the same
    message (check's names the file)."""
    path = tmp_path / "stored.toml"
    holding(**section).to_toml(path)
    code, out, check_err = run_main(capsys, "check", path)
    assert code == 2 and out == ""
    code, out, run_err = run_main(capsys, "run", path, "-o", tmp_path / "out")
    assert code == 2 and out == ""
    assert_one_line_error(run_err, f"simulation.{next(iter(section))} = ")
    assert check_err == run_err.replace("leadscrew: error: ", f"leadscrew: error: {path}: ")
    code, out, _ = run_main(capsys, "check", "position_holding")
    assert code == 0 and "valid" in out
