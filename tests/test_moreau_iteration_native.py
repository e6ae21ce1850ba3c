"""Native check of Moreau-Jean's iteration matrix (cpp/src/model/drive/
moreau_iteration.hpp, tests/cpp/test_moreau_iteration.cpp): W0's factors kept
while it holds, refactorized where an entry changed, and the penalty flank's
rank-one term solved by Sherman-Morrison to round-off. The class is internal
to the core: not reachable from Python."""

import subprocess

import pytest

from helpers.native_program import assert_program_passes, pass_count


@pytest.fixture(scope="module")
def iteration_report(native_tests_build):
    return subprocess.run([str(native_tests_build / "test_moreau_iteration")],
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("label", [
    "rank-one solves: residual of W y = x below 1e-12",
    "without the rank-one term: W0's solves bit for bit",
    "the same W0: its factors kept",
    "W0 changed by an ulp: factorized again",
])
def test_iteration_matrix(iteration_report, label):
    assert pass_count(iteration_report, label) == 500


def test_iteration_program_passes(iteration_report):
    assert_program_passes(iteration_report)
