import os
import pathlib
import sys

import pytest
from hypothesis import settings

# Property-based tests draw the same examples on every run (seeded by the
# test, not by the clock; no example database): a CI run is repeatable, and
# a failing draw is added to its test as an @example. Two CI runs failed on
# draws no run before had made (2026-11-27).
settings.register_profile("repeatable", derandomize=True, database=None)
settings.load_profile("repeatable")

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


@pytest.fixture(scope="session")
def core_tests_build(tmp_path_factory):
    """The configured CMake project tests/cpp/core (native tests that link
    the whole core: the integrators' checks, an element defined outside the
    core), in a temporary directory or in $LEADSCREW_NATIVE_BUILD_DIR/core,
    reused across sessions; each test builds its own targets in it
    (helpers.cmake_project.built), so the core compiles once."""
    from helpers.cmake_project import configured

    shared = os.environ.get("LEADSCREW_NATIVE_BUILD_DIR")
    build = pathlib.Path(shared) / "core" if shared else tmp_path_factory.mktemp("core")
    return configured(NATIVE_TESTS / "core", build)


@pytest.fixture
def watched(monkeypatch):
    """Progress bars drawn as where someone watches (a terminal): pytest's
    captured standard error is not one, where leadscrew draws none."""
    monkeypatch.setattr("leadscrew._progress._watched", lambda: True)


@pytest.fixture
def every_step(monkeypatch):
    """simulate's default output keeps every integrator step, as it did
    before it sampled a long run's steps: for tests whose checks read the
    run step by step (tests/helpers/result_invariants.py, the first
    slipping step, the losses never falling between steps). A module uses it
    with ``pytestmark = pytest.mark.usefixtures("every_step")``."""
    import sys

    monkeypatch.setattr("leadscrew.simulation.DEFAULT_ROWS", sys.maxsize)
