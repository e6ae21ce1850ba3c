"""Files written whole or not at all (python/leadscrew/files.py): a write
that fails half-way leaves nothing behind, names the path and the cause, and
the command line exits with 1 (a failure while running), not the usage code 2."""

import os
import subprocess
import sys
import textwrap

import pytest

import leadscrew as ls
from leadscrew import files


def test_writing_renames_a_complete_file_and_keeps_the_mode(tmp_path):
    target = tmp_path / "out.txt"
    files.write_text(target, "abc\n")
    assert target.read_text() == "abc\n"
    assert os.listdir(tmp_path) == ["out.txt"]
    mask = os.umask(0)
    os.umask(mask)
    assert target.stat().st_mode & 0o777 == 0o666 & ~mask


def test_a_failed_write_leaves_nothing_and_keeps_an_old_file(tmp_path):
    target = tmp_path / "out.csv"
    with pytest.raises(ls.WriteError, match=r"cannot write .*out\.csv: No space left on device"):
        with files.writing(target) as temporary:
            temporary.write_text("half")
            raise OSError(28, "No space left on device")
    assert os.listdir(tmp_path) == []
    target.write_text("old")
    with pytest.raises(ZeroDivisionError):  # not an OSError: passes unchanged
        with files.writing(target) as temporary:
            temporary.write_text("half")
            1 / 0
    assert os.listdir(tmp_path) == ["out.csv"] and target.read_text() == "old"


def test_a_directory_that_cannot_be_written_is_a_write_error(tmp_path):
    with pytest.raises(ls.WriteError) as caught:
        files.write_text(tmp_path / "missing" / "x.toml", "")
    assert caught.value.filename == str(tmp_path / "missing" / "x.toml")
    assert isinstance(caught.value, OSError)


class _FillingDisk:
    """A file whose write stores half the text, then finds the disk full."""

    def __init__(self, path, *args, **kwargs):
        self._stream = open(path, *args, **kwargs)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._stream.close()

    def write(self, text):
        self._stream.write(text[: len(text) // 2])
        self._stream.flush()
        raise OSError(28, "No space left on device")


@pytest.mark.parametrize("method", ["to_toml", "to_core_toml"])
def test_a_scene_file_is_written_whole(tmp_path, monkeypatch, method):
    scene = ls.scenes.load("default")
    monkeypatch.setattr(files, "open", _FillingDisk, raising=False)
    with pytest.raises(ls.WriteError, match=r"cannot write .*scene\.toml: No space left"):
        getattr(scene, method)(tmp_path / "scene.toml")
    assert os.listdir(tmp_path) == []
    monkeypatch.undo()
    getattr(scene, method)(tmp_path / "scene.toml")
    assert os.listdir(tmp_path) == ["scene.toml"]


def _run_limited(tmp_path, limit, *argv):
    """``leadscrew ARGV`` in a child process whose files may not grow beyond
    ``limit`` bytes (RLIMIT_FSIZE: writes beyond fail with EFBIG)."""
    script = textwrap.dedent(f"""
        import resource, sys
        import matplotlib.figure, pandas  # (their caches written before the limit)
        from leadscrew.cli import main
        resource.setrlimit(resource.RLIMIT_FSIZE, ({limit}, {limit}))
        sys.exit(main({[str(a) for a in argv]!r}))
    """)
    return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300, cwd=tmp_path)


@pytest.mark.parametrize("argv, written", [
    (["run", "default", "--t-end", "0.05", "-o", "out"], "default.csv"),
    (["study", "stick_slip", "default", "t_end=0.02", "progress=false", "-o", "out"],
     "stick_slip_default.csv"),
    (["export-fmu", "default", "-o", "out/default.fmu"], "default.fmu"),
])
def test_a_command_whose_write_fails_leaves_nothing_and_exits_1(tmp_path, argv, written):
    (tmp_path / "out").mkdir()
    done = _run_limited(tmp_path, 2000, *argv)
    assert done.returncode == 1, done.stderr
    path = os.path.join("out", written)
    assert f"leadscrew: error: WriteError: cannot write {path}: File too large" in done.stderr
    assert os.listdir(tmp_path / "out") == []
    # The same command without the limit writes the file.
    done = _run_limited(tmp_path, "resource.RLIM_INFINITY", *argv)
    assert done.returncode == 0, done.stderr
    assert written in os.listdir(tmp_path / "out")


def test_scene_resolve_that_cannot_write_names_the_path_and_the_cause(tmp_path, capsys):
    from helpers.cli_runs import run_main

    target = tmp_path / "missing" / "core.toml"
    code, out, err = run_main(capsys, "scene", "resolve", "default", "-o", target)
    assert code == 1 and out == ""
    assert err.startswith(f"leadscrew: error: WriteError: cannot write {target}: ")
    assert "No such file or directory" in err
    assert not (tmp_path / "missing").exists()
