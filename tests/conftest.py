import os
import pathlib
import shutil
import subprocess
import sys

import pytest

# tests/helpers is importable as `helpers` from every test module.
sys.path.insert(0, os.path.dirname(__file__))

NATIVE_TESTS = pathlib.Path(__file__).resolve().parent / "cpp"


@pytest.fixture(scope="session")
def native_tests_build(tmp_path_factory):
    """The built CMake project tests/cpp (native checks of the core: LCP
    allocation and paths, run_in_parallel), in a temporary directory or in
    $LEADSCREW_NATIVE_BUILD_DIR, reused across sessions."""
    cmake = shutil.which("cmake")
    assert cmake, "cmake is needed to build tests/cpp (pip install cmake)"
    build = os.environ.get("LEADSCREW_NATIVE_BUILD_DIR") or str(tmp_path_factory.mktemp("native"))
    configure = [cmake, "-S", str(NATIVE_TESTS), "-B", build, "-DCMAKE_BUILD_TYPE=Release"]
    if shutil.which("ninja"):
        configure += ["-G", "Ninja"]
    if not (pathlib.Path(build) / "CMakeCache.txt").exists():
        subprocess.run(configure, check=True, capture_output=True, text=True)
    done = subprocess.run(
        [cmake, "--build", build, "--parallel", "2"], capture_output=True, text=True
    )
    assert done.returncode == 0, done.stdout + done.stderr
    return pathlib.Path(build)
