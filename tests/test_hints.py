"""The nearest valid name in the message that refuses a misspelled one
(python/leadscrew/_hints.py): scene keys and sections, study options and
names, simulate's options through a study."""

import pytest

import leadscrew as ls
from helpers.cli_runs import assert_one_line_error, run_main
from helpers.scenes import thesis_scene


@pytest.mark.parametrize("change, message", [
    ({"thread": {"pich": 1e-3}}, "thread.pich is not a known key (did you mean 'pitch'?); "
                                 "thread takes "),
    ({"frction": {"mu": 0.3}}, "frction is not a known section (did you mean 'friction'?); "),
    ({"thread": {"zzz": 1}}, "thread.zzz is not a known key; thread takes "),  # none close
])
def test_a_misspelled_scene_key_gets_the_nearest(change, message):
    data = thesis_scene()
    for section, fields in change.items():
        data.setdefault(section, {}).update(fields)
    with pytest.raises(ValueError) as caught:
        ls.Scene.from_dict(data)
    assert message in str(caught.value)


@pytest.mark.parametrize("argv, fragments", [
    (["stick_slip", "default", "t_ned=0.1"],
     ["study 'stick_slip' has no option 't_ned' (did you mean 't_end'?); it takes "]),
    (["stick_slip", "default", "integrater=dopri5"],
     ["has no option 'integrater' (did you mean 'integrator'?)"]),
    (["stik_slip", "default"], ["study 'stik_slip' is unknown (did you mean 'stick_slip'?)"]),
])
def test_a_misspelled_study_option_or_name_gets_the_nearest(tmp_path, capsys, argv, fragments):
    code, _, err = run_main(capsys, "study", *argv, "-o", tmp_path)
    assert code == 2
    assert_one_line_error(err, *fragments)
    assert list(tmp_path.iterdir()) == []


def test_a_misspelled_simulate_option_of_a_study_gets_the_nearest():
    scene = ls.scenes.load("default")
    with pytest.raises(TypeError, match=r"'rtoll' \(did you mean 'rtol'\?\)"):
        ls.studies.efficiency_vs_mu(scene, mu=[0.2], loads=[10.0], rtoll=1e-6, progress=False)
