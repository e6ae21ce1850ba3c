import os
import pathlib
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
    from helpers.cmake_project import built, configured

    build = os.environ.get("LEADSCREW_NATIVE_BUILD_DIR") or str(tmp_path_factory.mktemp("native"))
    return built(configured(NATIVE_TESTS, build))
