"""Native check of the drive's force elements (cpp/include/leadscrew/model/
elements/, tests/cpp/test_elements.cpp): each element's force, its energy,
its Jacobians (the stiffness and damping matrices Moreau-Jean's iteration
matrix and the static equilibrium use) and its damping power agree, by
central differences. The elements are internals of the core: not reachable
from Python."""

import subprocess

import pytest

from helpers.native_program import assert_program_passes, pass_count


@pytest.fixture(scope="module")
def elements_report(native_tests_build):
    return subprocess.run([str(native_tests_build / "test_elements")], capture_output=True,
                          text=True, timeout=120)


@pytest.mark.parametrize("label", [
    "force is minus the energy gradient",
    "stiffness matrix is minus the force Jacobian",
    "damping matrix is minus the velocity Jacobian",
    "damping power",
])
def test_force_elements_are_consistent(elements_report, label):
    assert pass_count(elements_report, label) == 200


def test_elements_program_passes(elements_report):
    assert_program_passes(elements_report)
