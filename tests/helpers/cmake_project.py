"""Configuring and building the small CMake projects of the native checks
(tests/cpp, benchmarks/integrate) from the tests."""

import pathlib
import shutil
import subprocess


def configured(source, build):
    """The build directory `build` of the CMake project `source`, configured
    (Release, Ninja if there is one) unless it already is; returns it as a Path.

    Fails the calling test if there is no cmake."""
    cmake = shutil.which("cmake")
    assert cmake, f"cmake is needed to build {source} (pip install cmake)"
    build = pathlib.Path(build)
    if not (build / "CMakeCache.txt").exists():
        configure = [cmake, "-S", str(source), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        subprocess.run(configure, check=True, capture_output=True, text=True)
    return build


def built(build, target=None):
    """Builds `target` (default: every target) in the configured directory
    `build`; fails the calling test if the build fails."""
    command = [shutil.which("cmake"), "--build", str(build), "--parallel", "2"]
    if target is not None:
        command += ["--target", target]
    done = subprocess.run(command, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    return build
