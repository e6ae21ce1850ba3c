"""Native check of Moreau-Jean's iteration matrix (cpp/src/model/drive/
moreau_iteration.hpp, tests/cpp/test_moreau_iteration.cpp): W0's factors kept
while it holds, refactorized where an entry changed, and the penalty flank's
rank-one term solved by Sherman-Morrison to round-off; its fixed-size
kernels and the step's dot products (lane_dot, lane_abs_dot, theta_dot) bit
for bit the Eigen expressions they replaced. The class is internal to the
core: not reachable from Python."""

import subprocess

import pytest

from helpers.native_program import assert_program_passes, pass_count


@pytest.fixture(scope="module")
def iteration_report(native_tests_build):
    return subprocess.run([str(native_tests_build / "test_moreau_iteration")],
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("label, count", [
    ("rank-one solves: residual of W y = x below 1e-12", 600),
    ("without the rank-one term: W0's solves bit for bit", 600),
    ("rank-one solves: Eigen's expressions bit for bit", 600),
    ("the step's dot products: Eigen's bit for bit", 6000),
    ("the same W0: its factors kept", 600),
    ("W0 changed by an ulp: factorized again", 600),
])
def test_iteration_matrix(iteration_report, label, count):
    assert pass_count(iteration_report, label) == count


def test_iteration_program_passes(iteration_report):
    assert_program_passes(iteration_report)
