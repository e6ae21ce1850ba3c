"""Native check of the ODE integrators that Python cannot make: no heap
allocation after initialize, in restarts, advances, root location and dense
output, for every method (benchmarks/integrate/alloc_check.cpp, which
interposes malloc & co. for the whole process, SUNDIALS included); and a
model's own Runge-Kutta stage loop against the engine's, bit for bit
(benchmarks/integrate/rk_kernel_check.cpp).

Builds the targets integrate_alloc_check and rk_kernel_check of
benchmarks/integrate in the native core tests' build (tests/cpp/core, which
adds benchmarks/integrate: the fixture core_tests_build of conftest.py), so
the core compiles once for these and the element tests."""

import re
import subprocess

import pytest

import leadscrew.integrate as li
from helpers.cmake_project import built


@pytest.fixture(scope="session")
def native_build(core_tests_build):
    """The configured build directory of the native core tests."""
    return core_tests_build


def build_and_run(build, target):
    built(build, target)
    return subprocess.run([str(build / "integrate" / target)], capture_output=True, text=True,
                          timeout=120)


@pytest.fixture(scope="session")
def alloc_report(native_build):
    return build_and_run(native_build, "integrate_alloc_check")


@pytest.fixture(scope="session")
def rk_kernel_report(native_build):
    return build_and_run(native_build, "rk_kernel_check")


def test_own_stage_loops_give_the_same_bits(rk_kernel_report):
    # A model's own Runge-Kutta stage loop (its rhs inlined, as the friction
    # block's) against the engine's virtual calls: dopri5 and verner6 on 2
    # and 4 states; the loop against its definition; the engine takes it
    # (benchmarks/integrate/rk_kernel_check.cpp).
    out = rk_kernel_report.stdout
    assert rk_kernel_report.returncode == 0 and out.strip().endswith("RESULT: PASS"), \
        out + rk_kernel_report.stderr
    for method in ("rk_dopri5", "rk_verner6"):
        assert f"PASS stage loop as defined: {method}" in out
        taken = re.search(rf"^PASS the engine takes the system's own stage loop: {method} "
                          rf"\((\d+) calls\)$", out, re.MULTILINE)
        assert taken and int(taken.group(1)) > 50, out
        for states in (2, 4):
            assert re.search(rf"^PASS same bits with the own stage loop: {method}, {states} "
                             rf"states \((\d+) steps\)$", out, re.MULTILINE), out
            assert f"PASS own stage loop offered: {method}, {states} states" in out


def test_native_program_passes(alloc_report):
    assert alloc_report.returncode == 0, alloc_report.stdout + alloc_report.stderr
    assert alloc_report.stdout.strip().endswith("RESULT: PASS")


@pytest.mark.parametrize("method", li.METHODS)
def test_restarts_advances_and_roots_do_not_allocate(alloc_report, method):
    line = re.search(rf"^(PASS|FAIL) no allocation in {method} restarts, advances, roots \((\d+)\)$",
                     alloc_report.stdout, re.MULTILINE)
    assert line, alloc_report.stdout
    assert line.group(1) == "PASS" and line.group(2) == "0"
    # The measured run really restarted at events (10 events, 22 restarts
    # over the two runs: one reinitialize per run and one per event).
    info = re.search(rf"^INFO {method}: (\d+) events, (\d+) steps, (\d+) restarts",
                     alloc_report.stdout, re.MULTILINE)
    assert info and int(info.group(1)) == 10 and int(info.group(3)) == 22, alloc_report.stdout


def test_counter_is_not_blind(alloc_report):
    for label in ("counter sees std::vector", "counter sees SUNDIALS allocating in initialize"):
        line = re.search(rf"^PASS {re.escape(label)} \((\d+)\)$", alloc_report.stdout,
                         re.MULTILINE)
        assert line and int(line.group(1)) > 0, alloc_report.stdout
