"""The core's own arctan (cpp/include/leadscrew/friction/arctan.hpp), used by
the regularized friction laws of the block (eq. 3.15, 3.16) instead of
std::atan: within 2 ulp of std::atan over the whole double range (observed:
1), exact at the special values, odd and monotonic, and within its proven
bound of 1.15 ulp of the exact arctan (mpmath at 40 digits).

tests/cpp/test_arctan.cpp is compiled here with the flags of the extension's
Release build (-O3, GNU C++17, no -march) and run once per session."""

import pathlib
import re
import shutil
import subprocess

import mpmath
import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
SOURCE = ROOT / "tests" / "cpp" / "test_arctan.cpp"
PROVEN_BOUND_ULPS = 1.15  # the error analysis in arctan.hpp


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    compiler = shutil.which("c++") or shutil.which("g++")
    assert compiler, "a C++ compiler is needed to build tests/cpp/test_arctan.cpp"
    program = tmp_path_factory.mktemp("arctan") / "test_arctan"
    build = subprocess.run(
        [compiler, "-O3", "-DNDEBUG", "-std=gnu++17", "-I", str(ROOT / "cpp" / "include"),
         str(SOURCE), "-o", str(program)], capture_output=True, text=True)
    assert build.returncode == 0, build.stdout + build.stderr
    run = subprocess.run([str(program)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    return run.stdout


@pytest.mark.parametrize("points", ["binades", "dense", "edges"])
def test_within_two_ulp_of_std_atan(report, points):
    line = re.search(rf"^MAXULP {points} (\d+) (\d+) (\S+)$", report, re.MULTILINE)
    assert line, report[:2000]
    ulps, count = int(line.group(1)), int(line.group(2))
    assert count >= 240_000  # the sweep ran
    assert ulps <= 2, f"{ulps} ulp from std::atan at x = {line.group(3)}"


@pytest.mark.parametrize("name", ["plus_zero", "minus_zero", "plus_inf", "minus_inf", "nan",
                                  "max", "lowest", "subnormal_and_min_identity", "odd",
                                  "monotonic"])
def test_special_values_and_shape(report, name):
    assert re.search(rf"^SPECIAL {name} PASS$", report, re.MULTILINE), \
        [line for line in report.splitlines() if line.startswith("SPECIAL")]


def ulp_of(value):
    """The spacing of doubles at |value| (an mpmath number), subnormals included."""
    magnitude = abs(value)
    exponent = max(int(mpmath.floor(mpmath.log(magnitude, 2))), -1022)
    return mpmath.mpf(2) ** (exponent - 52)


def test_within_proven_bound_of_exact_arctan(report):
    samples = [tuple(float.fromhex(v) for v in line.split()[1:])
               for line in report.splitlines() if line.startswith("SAMPLE")]
    assert len(samples) == 6400
    worst = 0.0
    with mpmath.workdps(40):
        for x, ours in samples:
            exact = mpmath.atan(mpmath.mpf(x))
            error = float(abs(mpmath.mpf(ours) - exact) / ulp_of(exact))
            worst = max(worst, error)
            assert error <= PROVEN_BOUND_ULPS, (x.hex(), error)
    # Not vacuous: the samples do reach rounding level (a correctly rounded
    # result is up to 0.5 ulp off).
    assert worst > 0.4
