"""Native check of run_in_parallel (cpp/include/leadscrew/core/parallel.hpp),
the helper-thread pool under the batches' workers, from tests/cpp/test_parallel.cpp:
what threads do cannot be observed from Python."""

import subprocess

import pytest

from helpers.native_program import pass_count as passed


@pytest.fixture(scope="module")
def parallel_report(native_tests_build):
    return subprocess.run([str(native_tests_build / "test_parallel")], capture_output=True,
                          text=True, timeout=120)


def test_parallel_program_passes(parallel_report):
    assert parallel_report.returncode == 0, parallel_report.stdout + parallel_report.stderr
    assert parallel_report.stdout.strip().endswith("RESULT: PASS")
    assert "FAIL" not in parallel_report.stdout


@pytest.mark.parametrize("threads", range(1, 7))
@pytest.mark.parametrize("round_", [0, 1])
def test_every_call_runs_at_once_and_has_returned(parallel_report, threads, round_):
    """`threads` calls meet at a rendezvous (a pool that ran them one after
    another would never get there), on distinct threads, the caller's among
    them, and all have returned when run_in_parallel does; round 1 from the
    pool's sleep."""
    label = f"{threads} calls at once, the caller's among them, round {round_}"
    assert passed(parallel_report, label) == threads


def test_the_pool_is_bounded_and_reused(parallel_report):
    """200 calls run on no more distinct helper threads than the pool keeps."""
    kept = passed(parallel_report, "the pool keeps 1 to hardware_concurrency helpers")
    assert 1 <= kept
    assert 1 <= passed(parallel_report, "the pool reuses its helpers") <= kept


def test_concurrent_and_nested_callers(parallel_report):
    assert passed(parallel_report, "concurrent callers: 600 jobs, each on 3 threads at once") == 0
    assert passed(parallel_report, "nested calls on the caller and on a helper") == 2


def test_a_forked_child_builds_its_own_pool(parallel_report):
    """The child of a fork() has none of the parent's helper threads: waiting
    for them would hang (the child's alarm would end it with status 14)."""
    assert passed(parallel_report, "a forked child runs calls on a pool of its own") == 0
    assert passed(parallel_report, "the parent's pool after the fork") == 2
