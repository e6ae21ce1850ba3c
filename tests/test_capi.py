"""The C API (``leadscrew.h``, ``libleadscrew``): a C program compiled with
the system's ``cc`` against :func:`leadscrew.get_include` and
:func:`leadscrew.get_library`, run as a subprocess on core specs written by
:meth:`leadscrew.Scene.to_core_toml`."""

import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import leadscrew as ls

PROGRAM = pathlib.Path(__file__).resolve().parent / "c" / "capi_check.c"


@pytest.fixture(scope="module")
def capi_check(tmp_path_factory):
    """The compiled tests/c/capi_check.c."""
    cc = shutil.which("cc")
    if cc is None:
        pytest.fail("no C compiler: the C API's test compiles tests/c/capi_check.c with 'cc' "
                    "(install gcc, e.g. apt-get install -y gcc)")
    library = ls.get_library()
    out = tmp_path_factory.mktemp("capi") / "capi_check"
    subprocess.run([cc, "-std=c99", "-Wall", "-Wextra", "-Werror", str(PROGRAM),
                    "-I", ls.get_include(), library,
                    f"-Wl,-rpath,{os.path.dirname(library)}", "-o", str(out)],
                   check=True, capture_output=True, text=True)
    return out


def run(program, *arguments):
    done = subprocess.run([str(program), *map(str, arguments)], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, (done.returncode, done.stdout, done.stderr)
    return done.stdout.splitlines()


def test_paths():
    assert os.path.isfile(os.path.join(ls.get_include(), "leadscrew.h"))
    assert os.path.isfile(ls.get_library())


def test_the_library_needs_no_sundials():
    """A C program needs the C and C++ runtimes alone: SUNDIALS is linked
    statically (a new user found libleadscrew asked for Debian's
    libsundials_cvode.so.6)."""
    ldd = shutil.which("ldd")
    assert ldd, "ldd is needed to list the library's dependencies"
    libraries = subprocess.run([ldd, ls.get_library()], capture_output=True, text=True,
                               check=True).stdout
    assert "sundials" not in libraries and "python" not in libraries, libraries


CHANNELS = ["u_load", "v_load", "omega_drive", "normal_force", "friction_force", "stick",
            "friction_loss"]


def test_the_default_scene_runs_as_simulate(capi_check, tmp_path):
    scene = ls.scenes.load("default")
    spec = tmp_path / "core.toml"
    scene.to_core_toml(spec)
    lines = run(capi_check, "run", spec, 1.0, 0.01, "-", 0, *CHANNELS)
    assert lines[-1].startswith("events ")
    events, count, first = lines[-1].split()[1::2]
    rows = np.array([[float(x) for x in line.split()] for line in lines[:-1]])
    times = rows[:, 0]
    assert len(times) == 100 and times[-1] == 1.0
    reference = ls.simulate(scene, 1.0, t_eval=times)
    assert int(events) == len(reference.events)
    assert int(count) == len(reference.channels) and first == reference.channels[0]
    for k, name in enumerate(CHANNELS, start=1):
        expected = np.asarray(reference[name])
        scale = max(np.max(np.abs(expected)), 1e-12)
        assert np.max(np.abs(rows[:, k] - expected)) <= 1e-5 * scale, name


def test_a_held_input(capi_check, tmp_path):
    scene = ls.scenes.load("default")
    spec = tmp_path / "core.toml"
    scene.to_core_toml(spec)
    lines = run(capi_check, "run", spec, 0.1, 0.01, "drive_torque", -0.03, "u_load")
    held = scene.replace(loads={"drive_torque": -0.03})
    reference = ls.simulate(held, 0.1, t_eval=[0.1])
    assert float(lines[-2].split()[1]) == pytest.approx(reference["u_load"][-1], rel=1e-5)


def test_a_bad_scene_gives_an_error_text(capi_check, tmp_path):
    spec = ls.scenes.load("default").to_core_toml()
    for text, expected in [
            ("concept = ", "not valid TOML"),
            (spec.replace("[parameters]\n", "[parameters]\nload_mas = 1.0\n"),
             "parameters.load_mas is an unknown key"),
            (spec.replace('concept = "rigid"', 'concept = "stiff"'), "drive.concept"),
            (spec.replace("load_mass = 2.0", "load_mass = -2.0"), "load.mass = -2"),
            ("", "format")]:
        (line,) = run(capi_check, "toml", text)
        assert line.startswith("error: ") and expected in line, (expected, line)
    (line,) = run(capi_check, "input", tmp_path / "missing.toml", "axial_force", 1.0)
    assert line.startswith("error: ") and "missing.toml" in line


def test_a_scene_only_moreau_jean_runs_gives_a_plain_error_text(capi_check):
    """`leadscrew scene resolve` writes a Moreau-only scene with integrator
    "" (its default); the C API refuses it saying why, without internals."""
    spec = ls.scenes.load("seat_adjuster_worm_flexible").to_core_toml()
    assert 'integrator = ""' in spec
    (line,) = run(capi_check, "toml", spec)
    assert line.startswith('error: this scene runs only on Moreau-Jean time stepping '
                           '(integrator = "moreau")'), line
    assert "FMU export and the C API do not offer Moreau-Jean" in line
    assert 'the shipped scene "seat_adjuster_worm"' in line
    assert "stepper" not in line and "drive_integrators" not in line


def test_an_unknown_input_gives_an_error_text(capi_check, tmp_path):
    spec = tmp_path / "core.toml"
    ls.scenes.load("default").to_core_toml(spec)
    (line,) = run(capi_check, "input", spec, "torque", 1.0)
    assert line.startswith("error 1: ") and '"drive_torque", "axial_force"' in line
    (line,) = run(capi_check, "input", spec, "axial_force", -5.0)
    assert line == "ok"


def test_a_step_past_the_screws_end_gives_an_error_text(capi_check, tmp_path):
    scene = ls.scenes.load("default").replace(friction={"mu": 0.05},
                                              loads={"drive_torque": 0.05})
    spec = tmp_path / "core.toml"
    scene.to_core_toml(spec)
    lines = run(capi_check, "advance", spec, 10.0)
    assert lines[0].startswith("error 2: ") and "screw" in lines[0]
    assert lines[1].startswith("error 2: ") and "stopped at its failure" in lines[1]
    # The failure's time once (a new user read "at t = X s: ...: at t = X s: ...").
    assert lines[1].count("t = ") == 1 + lines[0].count("t = ") - 1, lines[:2]
    assert lines[2:] == ["ok", "ok"]  # reset, and a step within the screw


def test_null_pointers_are_errors_not_crashes(capi_check):
    lines = run(capi_check, "null", "-")
    assert lines[:2] == ["1", "1"]
    for line in lines[2:7]:
        assert line.startswith("error 1: ") and "is NULL" in line, line
    assert lines[7] == "1 0 0 1"  # NaN time, no channels, no events, no name
