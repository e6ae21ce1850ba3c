"""Native checks of the LCP core that Python cannot make: no heap allocation
while solving (tests/cpp/test_lcp_alloc.cpp, which interposes malloc & co.);
Lemke's fixed-size code paths against its generic one and non-finite input
through the unchecked entry points (tests/cpp/test_lcp_paths.cpp).

The small CMake project tests/cpp is built once per session (the fixture
native_tests_build of tests/conftest.py)."""

import re
import subprocess

import pytest


@pytest.fixture(scope="session")
def alloc_report(native_tests_build):
    run = subprocess.run(
        [str(native_tests_build / "test_lcp_alloc")], capture_output=True, text=True, timeout=60
    )
    return run


def test_native_program_passes(alloc_report):
    assert alloc_report.returncode == 0, alloc_report.stdout + alloc_report.stderr
    assert alloc_report.stdout.strip().endswith("RESULT: PASS")
    assert "FAIL" not in alloc_report.stdout


@pytest.mark.parametrize("method", ["lemke", "pgs", "newton_fb", "enumerate"])
def test_solves_do_not_allocate(alloc_report, method):
    line = re.search(rf"^(PASS|FAIL) no allocation in {method} solves, n <= 16 \((\d+)\)$",
                     alloc_report.stdout, re.MULTILINE)
    assert line, alloc_report.stdout
    assert line.group(1) == "PASS" and line.group(2) == "0"
    solves = re.search(rf"^INFO {method}: (\d+) solves", alloc_report.stdout, re.MULTILINE)
    assert int(solves.group(1)) == (48 if method == "enumerate" else 64)


def test_counter_is_not_blind(alloc_report):
    """Positive controls: the interposed counter sees std::vector, Eigen's
    malloc and a workspace growing for a problem above its capacity."""
    for label in ("counter sees std::vector", "counter sees Eigen's malloc",
                  "a workspace grows for n > capacity"):
        line = re.search(rf"^PASS {re.escape(label)} \((\d+)\)$", alloc_report.stdout, re.MULTILINE)
        assert line and int(line.group(1)) > 0, alloc_report.stdout


def test_friction_builders_do_not_allocate(alloc_report):
    assert re.search(r"^PASS no allocation in the friction builders and their solves \(0\)$",
                     alloc_report.stdout, re.MULTILINE), alloc_report.stdout


@pytest.fixture(scope="session")
def paths_report(native_tests_build):
    return subprocess.run(
        [str(native_tests_build / "test_lcp_paths")], capture_output=True, text=True, timeout=60
    )


def test_paths_program_passes(paths_report):
    assert paths_report.returncode == 0, paths_report.stdout + paths_report.stderr
    assert paths_report.stdout.strip().endswith("RESULT: PASS")
    assert "FAIL" not in paths_report.stdout


@pytest.mark.parametrize("n", range(1, 9))
def test_fixed_size_lemke_paths(paths_report, n):
    """Every fixed-size n: bit for bit the generic path's answer (200 problems
    of five families), the checked entry point's, and enumerate's on the 160
    P-matrix problems."""
    for label, count in [
        (f"fixed-size lemke == generic lemke bit for bit, n={n}", 200),
        (f"checked lemke == unchecked lemke, n={n}", 200),
        (f"lemke solves every problem, n={n}", 200),
        (f"fixed-size lemke == enumerate on P-matrices, n={n}", 160),
    ]:
        line = re.search(rf"^PASS {re.escape(label)} \((\d+)\)$", paths_report.stdout, re.MULTILINE)
        assert line and int(line.group(1)) == count, paths_report.stdout


def test_non_finite_input_never_solved(paths_report):
    for label in ("NaN or inf in M or q never solved (unchecked entry points)",
                  "NaN or inf in M or q throws InvalidArgument (checked entry point)"):
        line = re.search(rf"^PASS {re.escape(label)} \((\d+)\)$", paths_report.stdout, re.MULTILINE)
        assert line and int(line.group(1)) > 5000, paths_report.stdout
    assert re.search(r"^PASS the problems without NaN or inf are solved \(0\)$",
                     paths_report.stdout, re.MULTILINE)
