"""Native check of the result checks' `finite` invariant
(cpp/src/model/result_checks.cpp, tests/cpp/test_result_checks.cpp): its
four-lane test of v - v sees a non-finite value at every position of the
channels and the output times, and names its row. The kernel is internal to
the core: a public run cannot produce a non-finite channel (the loads and
the integrators refuse them first)."""

import re
import subprocess

import pytest


@pytest.fixture(scope="module")
def checks_report(native_tests_build):
    return subprocess.run([str(native_tests_build / "test_result_checks")], capture_output=True,
                          text=True, timeout=120)


@pytest.mark.parametrize("label, count", [
    ("finite results pass", 50),
    ("a non-finite value fails at its row", 3920),
    ("a non-finite time fails at its row", 180),
])
def test_finite_check_sees_every_position(checks_report, label, count):
    line = re.search(rf"^PASS {re.escape(label)} \((\d+)\)$", checks_report.stdout, re.MULTILINE)
    assert line, checks_report.stdout + checks_report.stderr
    assert int(line.group(1)) == count


def test_result_checks_program_passes(checks_report):
    assert checks_report.returncode == 0, checks_report.stdout + checks_report.stderr
    assert checks_report.stdout.strip().endswith("OK")
