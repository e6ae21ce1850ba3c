"""``leadscrew list`` and ``leadscrew scene copy`` (python/leadscrew/cli_catalog.py)."""

import leadscrew as ls
import leadscrew.scenes as shipped
from helpers.cli_runs import assert_one_line_error, run_main


def test_list_names_every_scene_study_friction_law_and_profile_with_what_it_is(capsys):
    code, out, err = run_main(capsys, "list")
    assert code == 0 and err == ""
    sections, heading = {}, None
    for line in out.splitlines():
        if line.startswith("  "):
            sections[heading][line.split()[0]] = line
        else:
            heading = line.split()[0]
            sections[heading] = {}
    assert list(sections) == ["scenes", "studies", "friction", "vibration"]
    assert list(sections["vibration"]) == ls.profiles.names()
    for name, line in sections["vibration"].items():
        assert ls.profiles.info(name).source in line
        assert ("not verified" in line) == (not ls.profiles.info(name).verified)
    assert list(sections["scenes"]) == shipped.available()
    assert list(sections["studies"]) == sorted(ls.studies.STUDIES)
    assert list(sections["friction"]) == [law["name"] for law in ls.friction_laws()]
    for entries in sections.values():
        for name, line in entries.items():
            assert len(line.split()) > 2, line  # a description follows the name
    assert "A power-seat longitudinal adjuster" in sections["scenes"]["seat_adjuster"]
    assert sections["studies"]["efficiency_vs_mu"].endswith(
        "Efficiency of raising each axial load, simulated and in closed form (Fig. 5.6).")

def test_scene_copy_writes_the_shipped_file_with_its_comments(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_main(capsys, "scene", "copy", "seat_adjuster")
    assert code == 0, err
    copied = tmp_path / "seat_adjuster.toml"
    assert copied.read_text() == shipped.path("seat_adjuster").read_text()
    assert "wrote seat_adjuster.toml" in out
    assert ls.Scene.from_toml(copied).to_dict() == shipped.load("seat_adjuster").to_dict()
    # Into a directory, and to a file of another name.
    (tmp_path / "d").mkdir()
    assert run_main(capsys, "scene", "copy", "default", "d")[0] == 0
    assert (tmp_path / "d" / "default.toml").is_file()
    assert run_main(capsys, "scene", "copy", "default.toml", "mine.toml")[0] == 0
    assert (tmp_path / "mine.toml").read_text() == shipped.path("default").read_text()


def test_scene_copy_refuses_what_it_cannot_do_well(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "default.toml").write_text("mine")
    for argv, fragments in [
        (["default"], ["default.toml exists", "does not overwrite"]),
        (["default", "x.txt"], ["a scene file ends in .toml", "x.txt.toml"]),
        (["nosuch"], ["nosuch: not a shipped scene", "seat_adjuster"]),
        (["default", "y.toml", "-o", "z.toml"], ["scene copy takes PATH, not -o"]),
    ]:
        code, out, err = run_main(capsys, "scene", "copy", *argv)
        assert code == 2, (argv, err)
        assert_one_line_error(err, *fragments)
    assert (tmp_path / "default.toml").read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["default.toml"]
    code, _, err = run_main(capsys, "scene", "resolve", "default", "core.toml")
    assert code == 2
    assert_one_line_error(err, "scene resolve writes to -o FILE")


def test_a_misspelled_shipped_scene_gets_the_nearest_name(tmp_path, capsys, monkeypatch):
    """(A new user's review: studies and keys suggested, scene names did not.)"""
    monkeypatch.chdir(tmp_path)
    for argv in (("run", "seat_adjustr", "--t-end", "0.01"), ("scene", "copy", "seat_adjustr")):
        code, out, err = run_main(capsys, *argv)
        assert code == 2 and out == ""
        assert_one_line_error(err, "not a shipped scene (did you mean 'seat_adjuster'?)")
    assert list(tmp_path.iterdir()) == []
