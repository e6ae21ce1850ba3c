"""The core's own arctan (cpp/include/leadscrew/friction/arctan.hpp), used by
the regularized friction laws of the block (eq. 3.15, 3.16) instead of
std::atan: within 2 ulp of std::atan over the whole double range (observed:
1), exact at the special values, odd and monotonic, and within its proven
bound of 1.15 ulp of the exact arctan (mpmath at 40 digits).

tests/cpp/test_arctan.cpp is compiled here with the flags of the extension's
Release build (-O3, GNU C++17, no -march) and run once per session."""

import pathlib

import mpmath
import pytest

from helpers.native_program import (assert_special_passed, compile_and_run, max_ulp_line,
                                    samples, worst_ulp_error)

ROOT = pathlib.Path(__file__).resolve().parent.parent
SOURCE = ROOT / "tests" / "cpp" / "test_arctan.cpp"
PROVEN_BOUND_ULPS = 1.15  # the error analysis in arctan.hpp


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    return compile_and_run(SOURCE, tmp_path_factory.mktemp("arctan"))


@pytest.mark.parametrize("points", ["binades", "dense", "edges"])
def test_within_two_ulp_of_std_atan(report, points):
    ulps, count, worst_x = max_ulp_line(report, points)
    assert count >= 240_000  # the sweep ran
    assert ulps <= 2, f"{ulps} ulp from std::atan at x = {worst_x}"


@pytest.mark.parametrize("name", ["plus_zero", "minus_zero", "plus_inf", "minus_inf", "nan",
                                  "max", "lowest", "subnormal_and_min_identity", "odd",
                                  "monotonic"])
def test_special_values_and_shape(report, name):
    assert_special_passed(report, name)


def test_within_proven_bound_of_exact_arctan(report):
    points = samples(report)
    assert len(points) == 6400
    worst = worst_ulp_error(points, mpmath.atan, PROVEN_BOUND_ULPS, digits=40)
    # Not vacuous: the samples do reach rounding level (a correctly rounded
    # result is up to 0.5 ulp off).
    assert worst > 0.4
