"""Options a drive's run would ignore are refused, and an option left to
the default integrator names its scheme (leadscrew.simulate, and the check a
sweep makes before its cases alike). Split from test_simulation_drive.py."""

import numpy as np
import pytest

import leadscrew as ls
from helpers.scenes import thesis_scene

EXACT = {"axial": 1e-4, "contact": "exact"}
BISTOP = {"axial": 1e-4, "contact": "bistop"}

# (scene changes, options, message): the options the integrator that runs (or
# the scene) would ignore.
IGNORED_OPTIONS = [
    # (left to the default, dt runs Moreau-Jean where it fits: not for eq.
    # 3.15's law, whose friction follows the slip acceleration)
    (dict(friction={"law": "arctan_acceleration", "mu": 0.3}), {"dt": 1e-3},
     r"^dt = 0.001 is invalid with integrator 'cvode_bdf' \(the default here\): dt is taken "
     r"by moreau only"),
    # (Moreau-Jean takes dt, but not bounce_threshold: no integrator takes both)
    (dict(backlash=EXACT), {"dt": 1e-3, "bounce_threshold": 1e-5},
     r"^dt = 0.001 is invalid with integrator 'event_driven' \(the default here\): dt is "
     r"taken by moreau only"),
    ({}, {"integrator": "event_driven", "dt": 1e-3},
     r"^dt = 0.001 is invalid with integrator 'event_driven': dt is taken by moreau only"),
    (dict(friction={"law": "arctan_velocity", "mu": 0.3}), {"integrator": "cvode_bdf",
                                                            "theta": 1.0},
     r"^theta = 1 is invalid with integrator 'cvode_bdf'"),
    *[({}, {"integrator": "moreau", name: value},
       rf"^{name} = {value!r} is invalid with integrator 'moreau': moreau is a fixed-step "
       rf"scheme without error or step-size control \(its step is dt\); {name} is taken by the "
       r"other integrators")
      for name, value in (("rtol", 1e-6), ("atol", 1e-9), ("max_order", 3), ("max_step", 1e-3),
                          ("first_step", 1e-6))],
    ({}, {"bounce_threshold": 1e-5}, r"^bounce_threshold = 1e-05 is invalid for this Scene: "
                                     r"it has no backlash, and bounce_threshold is taken by a "
                                     r"Scene with an exact backlash"),
    (dict(backlash=BISTOP), {"bounce_threshold": 1e-5},
     r"^bounce_threshold = 1e-05 is invalid for this Scene: it has backlash.contact = "
     r"'bistop', "),
    (dict(backlash=EXACT), {"integrator": "moreau", "bounce_threshold": 1e-5},
     r"^bounce_threshold = 1e-05 is invalid with integrator 'moreau': bounce_threshold is "
     r"taken by integrator 'event_driven' only"),
]


@pytest.mark.parametrize("changes, options, message", IGNORED_OPTIONS)
def test_options_the_run_would_ignore_are_refused(changes, options, message):
    """As the command line: an option the integrator that runs (or the
    scene) would ignore is refused, by simulate and by the check a sweep
    makes before its cases (DriveBatch's keywords) alike."""
    from leadscrew.studies._batch import check_simulate_options

    scene = ls.Scene.from_dict(thesis_scene(**changes))
    with pytest.raises(ValueError, match=message):
        ls.simulate(scene, 0.01, **options)
    with pytest.raises(ValueError, match=message):
        check_simulate_options(scene, options, 0.01)


@pytest.mark.parametrize("options", [{"dt": 2e-4}, {"theta": 1.0}, {"dt": 2e-4, "theta": 1.0}])
def test_an_option_left_to_the_default_integrator_names_its_scheme(options):
    """dt and theta are Moreau-Jean's: given without an integrator on a scene
    whose default is event-driven, the run is Moreau-Jean's with them (the
    same numbers as integrator = "moreau"), and Result.integrator says so;
    a sweep's check and its cases' arguments take the same rule."""
    from leadscrew.studies._batch import _core_arguments, check_simulate_options

    scene = ls.Scene.from_dict(thesis_scene())
    times = np.linspace(0.0, 0.01, 11)
    result = ls.simulate(scene, 0.01, t_eval=times, **options)
    assert result.integrator == "moreau"
    explicit = ls.simulate(scene, 0.01, integrator="moreau", t_eval=times, **options)
    np.testing.assert_array_equal(result["u_load"], explicit["u_load"])
    if "theta" in options:  # theta reached the scheme: the default 0.5 gives other numbers
        half = ls.simulate(scene, 0.01, integrator="moreau", dt=options.get("dt"), t_eval=times)
        assert np.max(np.abs(result["u_load"] - half["u_load"])) > 0.0
    check_simulate_options(scene, options, 0.01)
    assert _core_arguments(scene, 0.01, times, options)["integrator"] == "moreau"
    # Left out, the default runs.
    assert ls.simulate(scene, 0.01, t_eval=times).integrator == "event_driven"


def test_an_option_no_fitting_integrator_takes_is_still_refused():
    """rtol on a scene that runs on Moreau-Jean alone, and an option the
    integrator given would ignore, are refused as before."""
    moreau_only = ls.scenes.load("seat_adjuster_worm_flexible")
    with pytest.raises(ValueError, match=r"^rtol = 1e-06 is invalid with integrator 'moreau' "
                                         r"\(the default here\)"):
        ls.simulate(moreau_only, 0.01, rtol=1e-6)
    scene = ls.Scene.from_dict(thesis_scene())
    with pytest.raises(ValueError, match=r"^dt = 0.0002 is invalid with integrator "
                                         r"'event_driven': dt is taken by moreau only"):
        ls.simulate(scene, 0.01, integrator="event_driven", dt=2e-4)
    with pytest.raises(ValueError, match=r"^rtol = 1e-06 is invalid with integrator 'moreau': "):
        ls.simulate(scene, 0.01, integrator="moreau", rtol=1e-6)


def test_options_left_out_or_used_are_not_refused():
    """The defaults never trip the refusal (only options given count), nor
    do options the run uses."""
    scene = ls.Scene.from_dict(thesis_scene())
    times = [0.01]
    default = ls.simulate(scene, 0.01, t_eval=times)
    moreau = ls.simulate(scene, 0.01, integrator="moreau", t_eval=times)
    assert default.integrator == "event_driven" and moreau.integrator == "moreau"
    # None is "left out", whatever the integrator
    ls.simulate(scene, 0.01, integrator="moreau", rtol=None, atol=None, max_order=None,
                t_eval=times)
    ls.simulate(scene, 0.01, dt=None, theta=None, bounce_threshold=None, t_eval=times)
    # the defaults given explicitly give the same run
    explicit = ls.simulate(scene, 0.01, rtol=1e-8, atol=1e-10, t_eval=times)
    np.testing.assert_array_equal(explicit["u_load"], default["u_load"])
    same = ls.simulate(scene, 0.01, integrator="moreau", dt=1e-4, theta=0.5, t_eval=times)
    np.testing.assert_array_equal(same["u_load"], moreau["u_load"])
    # an exact backlash run event-driven takes bounce_threshold, and checks its range
    exact = ls.Scene.from_dict(thesis_scene(backlash=EXACT))
    ls.simulate(exact, 0.01, bounce_threshold=1e-5, t_eval=times)
    with pytest.raises(ValueError, match=r"bounce_threshold = -1 is invalid: must be"):
        ls.simulate(exact, 0.01, bounce_threshold=-1.0)


# (A new user's review: dt with rtol was refused naming dt alone, as if
# event_driven ignored it, while moreau would ignore the rtol as well.)
@pytest.mark.parametrize("options, first, second", [
    ({"dt": 1e-4, "rtol": 1e-6}, "dt = 0.0001", "rtol = 1e-06"),
    ({"dt": 1e-4, "max_step": 1e-3}, "dt = 0.0001", "max_step = 0.001"),
    ({"dt": 1e-4, "first_step": 1e-6}, "dt = 0.0001", "first_step = 1e-06"),
    ({"theta": 1.0, "atol": 1e-9}, "theta = 1", "atol = 1e-09"),
])
def test_options_no_integrator_takes_together_name_both(options, first, second):
    """Moreau-Jean's option beside an adaptive one, the integrator left to
    the default: the refusal names both with their values and which scheme
    takes which (simulate, a sweep's check, the command line alike)."""
    from leadscrew.studies._batch import check_simulate_options

    scene = ls.Scene.from_dict(thesis_scene())
    moreau, adaptive = (name.split(" = ")[0] for name in (first, second))
    message = (rf"^{first} and {second} conflict: {moreau} is taken by moreau only \(the "
               rf"fixed-step Moreau-Jean scheme\), {adaptive} by the adaptive integrators only "
               r"\(event_driven, cvode_bdf, \.\.\.: error and step-size control\), and none "
               r"takes both; give one of them")
    with pytest.raises(ValueError, match=message):
        ls.simulate(scene, 0.01, **options)
    with pytest.raises(ValueError, match=message):
        check_simulate_options(scene, options, 0.01)
    block = ls.FrictionBlock(1.0, 0.3)
    with pytest.raises(ValueError, match=message):
        ls.simulate(block, 0.01, **options)


def test_the_command_line_names_both_conflicting_options(tmp_path, capsys):
    from helpers.cli_runs import assert_one_line_error, run_main

    code, _, err = run_main(capsys, "run", "default", "--dt", "1e-4", "--rtol", "1e-6",
                            "--t-end", "0.01", "-o", tmp_path)
    assert code == 2
    assert_one_line_error(err, "--dt 0.0001 and --rtol 1e-06 conflict: --dt is taken by moreau "
                               "only", "--rtol by the adaptive integrators only",
                          "(--integrator moreau takes --dt, another --rtol)")
    assert not list(tmp_path.iterdir())  # refused before anything ran


_INTEGRATORS = ("cvode_bdf, cvode_adams, dopri5, verner6, rk_dopri5, rk_verner6, event_driven, "
                "moreau")


def test_a_name_no_integrator_has_is_refused_as_such():
    """(A new user's review: integrator = "foo" was refused as if it were an
    integrator that does not fit the law, and on a drive train without a
    list.) The message names the key and the value, the closest name, and
    lists the integrators (simulate on a Scene and a FrictionBlock, a sweep's
    check alike)."""
    from leadscrew.studies._batch import check_simulate_options

    message = (r"^integrator = \"moreu\" is invalid: no integrator has that name \(did you mean "
               rf"'moreau'\?\); the integrators are {_INTEGRATORS}")
    scene = ls.scenes.load("seat_adjuster_worm_flexible")
    with pytest.raises(ValueError, match=message):
        ls.simulate(scene, 0.01, integrator="moreu")
    with pytest.raises(ValueError, match=message):
        ls.simulate(ls.FrictionBlock(1.0, 0.3), 0.01, integrator="moreu")
    with pytest.raises(ValueError, match=message):
        check_simulate_options(scene, {"integrator": "moreu"}, 0.01)


def test_the_command_line_lists_the_integrators_and_those_the_scene_takes(tmp_path, capsys):
    from helpers.cli_runs import assert_one_line_error, run_main

    code, _, err = run_main(capsys, "run", "seat_adjuster_worm_flexible", "--integrator", "foo",
                            "-o", tmp_path)
    assert code == 2
    assert_one_line_error(err, f"--integrator foo is invalid: no integrator has that name; the "
                               f"integrators are {_INTEGRATORS}; this scene takes moreau")
