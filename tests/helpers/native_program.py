"""Building and running the native check of the core's own elementary
function (tests/cpp/test_sine.cpp; the own arctan and its check were removed
in issue 18) and reading its report (the line formats are listed in
tests/cpp/ulp_sweep.hpp)."""

import pathlib
import re
import shutil
import subprocess

import mpmath

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
INCLUDE = ROOT / "cpp" / "include"
NATIVE_TESTS = ROOT / "tests" / "cpp"  # ulp_sweep.hpp


def compile_and_run(source, build_dir, timeout=120):
    """Compile the C++ file `source` with the flags of the extension's Release
    build (-O3, GNU C++17, no -march, -ffp-contract=off) against cpp/include
    and tests/cpp into `build_dir`, run it once and return its standard
    output.

    Fails the calling test if there is no compiler, the build fails or the
    program exits with an error."""
    source = pathlib.Path(source)
    compiler = shutil.which("c++") or shutil.which("g++")
    assert compiler, f"a C++ compiler is needed to build {source.relative_to(ROOT)}"
    program = pathlib.Path(build_dir) / source.stem
    build = subprocess.run(
        [compiler, "-O3", "-DNDEBUG", "-std=gnu++17", "-ffp-contract=off", "-I", str(INCLUDE),
         "-I", str(NATIVE_TESTS), str(source), "-o", str(program)],
        capture_output=True, text=True)
    assert build.returncode == 0, build.stdout + build.stderr
    run = subprocess.run([str(program)], capture_output=True, text=True, timeout=timeout)
    assert run.returncode == 0, run.stderr
    return run.stdout


def ulp_of(value):
    """The spacing of doubles at |value| (an mpmath number), subnormals included."""
    magnitude = abs(value)
    exponent = max(int(mpmath.floor(mpmath.log(magnitude, 2))), -1022)
    return mpmath.mpf(2) ** (exponent - 52)


def max_ulp_line(report, name):
    """The line `MAXULP <name> <ulps> <points> <worst x>` of `report`, as
    (ulps, points, worst x as printed); fails the calling test if it is missing."""
    line = re.search(rf"^MAXULP {name} (\d+) (\d+) (\S+)$", report, re.MULTILINE)
    assert line, report[:2000]
    return int(line.group(1)), int(line.group(2)), line.group(3)


def assert_special_passed(report, name):
    """Fails unless `report` has the line `SPECIAL <name> PASS`."""
    assert re.search(rf"^SPECIAL {name} PASS$", report, re.MULTILINE), \
        [line for line in report.splitlines() if line.startswith("SPECIAL")]


def samples(report):
    """The `SAMPLE <x> <f(x)>` lines of `report` as pairs of floats."""
    return [tuple(float.fromhex(v) for v in line.split()[1:])
            for line in report.splitlines() if line.startswith("SAMPLE")]


def worst_ulp_error(points, exact, bound_ulps, digits):
    """The largest error, in ulps of the exact value, of the (x, f(x)) pairs
    `points` against `exact` (an mpmath function) at `digits` decimal digits;
    fails the calling test at the first point beyond `bound_ulps`."""
    worst = 0.0
    with mpmath.workdps(digits):
        for x, ours in points:
            exact_value = exact(mpmath.mpf(x))
            error = float(abs(mpmath.mpf(ours) - exact_value) / ulp_of(exact_value))
            worst = max(worst, error)
            assert error <= bound_ulps, (x.hex(), error)
    return worst


def pass_count(report, label):
    """The count of the native program's line `PASS <label> (<count>)` in
    the completed process `report`; fails the calling test if it is missing."""
    line = re.search(rf"^PASS {re.escape(label)} \((-?\d+)\)$", report.stdout, re.MULTILINE)
    assert line, report.stdout + report.stderr
    return int(line.group(1))


def assert_program_passes(report):
    """The native program exited 0 and ended its report with OK."""
    assert report.returncode == 0, report.stdout + report.stderr
    assert report.stdout.strip().endswith("OK")
