"""The core's own sine (cpp/include/leadscrew/excitation/sine.hpp), used by
the sine excitation (Excitation::sine_value) instead of std::sin: within
2 ulp of std::sin over every binade, densely over the working range and
around multiples of pi/2 (observed: 1), exact at the special values, odd, and
within its proven bound of 0.95 ulp of the exact sine (mpmath at 40 digits);
its constants are checked against their derivation (the Cody-Waite parts of
pi/2 and the polynomial fit errors).

tests/cpp/test_sine.cpp is compiled here with the flags of the extension's
Release build (-O3, GNU C++17, no -march, -ffp-contract=off) and run once per
session."""

import pathlib
import re

import mpmath
import pytest

from helpers.native_program import (assert_special_passed, compile_and_run, max_ulp_line,
                                    samples, worst_ulp_error)

ROOT = pathlib.Path(__file__).resolve().parent.parent
SOURCE = ROOT / "tests" / "cpp" / "test_sine.cpp"
HEADER = ROOT / "cpp" / "include" / "leadscrew" / "excitation" / "sine.hpp"
PROVEN_BOUND_ULPS = 0.95  # the error analysis in sine.hpp
REDUCED_RANGE = 2.0 ** 18  # below it, the own Cody-Waite reduction


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    return compile_and_run(SOURCE, tmp_path_factory.mktemp("sine"))


@pytest.mark.parametrize("points, at_least", [("binades", 6_000_000), ("dense", 4_000_000),
                                              ("multiples", 5_000_000), ("edges", 900_000)])
def test_within_two_ulp_of_std_sin(report, points, at_least):
    ulps, count, worst_x = max_ulp_line(report, points)
    assert count >= at_least  # the sweep ran
    assert ulps <= 2, f"{ulps} ulp from std::sin at x = {worst_x}"


@pytest.mark.parametrize("name", ["plus_zero", "minus_zero", "plus_inf", "minus_inf", "nan",
                                  "max", "subnormal_and_tiny_identity", "odd", "range",
                                  "monotonic_across_quadrant_switches"])
def test_special_values_and_shape(report, name):
    assert_special_passed(report, name)


def test_within_proven_bound_of_exact_sine(report):
    points = samples(report)
    assert len(points) == 5400
    # |r| >= 2^-61 relative to |x| < 2^18: 60 digits keep 100 bits
    worst = worst_ulp_error(points, mpmath.sin, PROVEN_BOUND_ULPS, digits=60)
    smallest_result = min(1.0, *(abs(ours) for _, ours in points))
    # Not vacuous: the samples reach rounding level (a correctly rounded
    # result is up to 0.5 ulp off) and the hard reductions (sin x ~ 1e-16
    # next to multiples of pi).
    assert worst > 0.4
    assert smallest_result < 1e-15


# --------------------------------------------------------------------------
# The constants of sine.hpp against their derivation

def header_constant(name):
    match = re.search(rf"constexpr double {name} = (\S+);", HEADER.read_text())
    assert match, name
    return float.fromhex(match.group(1))


def significant_bits(value):
    mantissa, _ = float(value).as_integer_ratio()
    return mantissa.bit_length()


def test_cody_waite_parts_of_half_pi():
    parts = [header_constant(f"pio2_{i}") for i in (1, 2, 3)]
    largest_k = int(REDUCED_RANGE * 2 / mpmath.pi) + 1
    # k P1 and k P2 are exact products for every k the reduction meets.
    for part in parts[:2]:
        assert significant_bits(part) + largest_k.bit_length() <= 53
    with mpmath.workdps(60):
        defect = abs(mpmath.pi / 2 - sum(mpmath.mpf(p) for p in parts))
        # the analysis: |k| |pi/2 - P1 - P2 - P3| <= 2^-112 over the range
        assert defect * largest_k < mpmath.mpf(2) ** -112
        assert defect > 0  # an honest split, not an identity


def polynomial_coefficients(name):
    """Coefficients of the polynomial `name` (sin_poly or cos_poly) in z, lowest first."""
    text = HEADER.read_text()
    body = re.search(rf"const double {name} =(.*?);", text, re.S).group(1)
    return [float.fromhex(c) for c in re.findall(r"-?0x[0-9a-f.]+p[-+]\d+", body)]


@pytest.mark.parametrize("name, exact, weight_power, bound_log2", [
    # sin: hi z S(z) relative to hi -> z |S - exact|; cos: z^2 |C - exact| absolute
    ("sin_poly", lambda z: sum((-1) ** (j + 1) * z ** j / mpmath.factorial(2 * j + 3)
                               for j in range(25)), 1, -57),
    ("cos_poly", lambda z: sum((-1) ** j * z ** j / mpmath.factorial(2 * j + 4)
                               for j in range(25)), 2, -59.5),
])
def test_polynomial_fit_errors(name, exact, weight_power, bound_log2):
    coefficients = polynomial_coefficients(name)
    assert len(coefficients) == (7 if name == "sin_poly" else 6)
    with mpmath.workdps(40):
        z_max = mpmath.mpf("0.7854") ** 2  # (pi/4 + slack of the rounded k)^2
        worst = 0
        for j in range(801):
            z = z_max * j / 800
            value = sum(mpmath.mpf(c) * z ** i for i, c in enumerate(coefficients))
            worst = max(worst, abs(value - exact(z)) * z ** weight_power)
        assert worst < mpmath.mpf(2) ** bound_log2
        assert worst > mpmath.mpf(2) ** (bound_log2 - 4)  # the real fit, not something else
