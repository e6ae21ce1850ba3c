"""The element interface (cpp/include/leadscrew/model/element.hpp) proved
by an element defined outside the core (tests/cpp/core/test_brake.cpp): a
rotor brake with one state (its temperature rise) and one event (its fade),
added by its own file and one registration line, runs on both schemes
against its closed form (omega(t), the fade's time, its heat equal to the
kinetic energy lost), with every result check passing and the energy
account closed; Moreau-Jean converges at second order before the fade and
at first order across it (the fade at a step's end)."""

import subprocess

import pytest

from helpers.cmake_project import built
from helpers.native_program import assert_program_passes, pass_count


@pytest.fixture(scope="module")
def brake_report(core_tests_build):
    built(core_tests_build, "test_brake")
    return subprocess.run([str(core_tests_build / "test_brake")], capture_output=True, text=True,
                          timeout=300)


@pytest.mark.parametrize("label", [
    "event-driven: omega follows the closed form",
    "event-driven: one fade, at its closed-form time",
    "event-driven: the brake's heat is the kinetic energy lost",
    "event-driven: every result check passes",
    "event-driven: energy account closes with the brake's heat",
    "moreau: second order before the fade",
    "moreau: at least first order across the fade",
])
def test_brake_element_runs_on_both_schemes(brake_report, label):
    assert pass_count(brake_report, label) >= 1, brake_report.stdout + brake_report.stderr


@pytest.mark.parametrize("dt", ["0.000400", "0.000200", "0.000100"])
def test_brake_element_account_closes_on_moreau(brake_report, dt):
    label = f"moreau dt {dt}: energy account closes with the brake's heat"
    assert pass_count(brake_report, label) > 1000, brake_report.stdout + brake_report.stderr
    assert pass_count(brake_report, f"moreau dt {dt}: every result check passes") >= 1


def test_brake_program_passes(brake_report):
    assert_program_passes(brake_report)
