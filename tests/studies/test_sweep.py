"""The sweep machinery of the studies: input order, failed cases as rows,
pickling, and the same results serial, threaded and on a Dask cluster."""

import concurrent.futures
import math
import os
import pickle
import time
import warnings

import distributed
import numpy as np
import pandas as pd
import pytest

import leadscrew as ls
from helpers.scenes import thesis_scene
from leadscrew.studies import _sweep
from leadscrew.studies._sweep import (MIN_CHUNK_SECONDS, SerialExecutor, default_workers,
                                      guided_size, run_batches, run_cases, run_chunks)
from leadscrew.studies.creep import creep_vs_backlash
from leadscrew.studies.drive_efficiency import efficiency_vs_mu


def holding_scene():
    """Table 5.1 drive, 0.2 mm exact backlash, a 5 N mm torque held by the thread."""
    return ls.Scene.from_dict(thesis_scene(backlash={"axial": 2e-4},
                                           loads={"drive_torque": 5e-3, "axial_force": 0.0}))


def sleep_then_square(x):
    time.sleep(0.02 * (4 - x))  # later cases finish first
    return x * x


def fail_on_odd(x):
    if x % 2:
        raise ValueError(f"odd case {x}")
    return -x


@pytest.mark.parametrize("chunk_size", [None, 1, 3, 10])
def test_results_come_back_in_input_order(chunk_size):
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        outcomes = run_cases(sleep_then_square, range(4), executor=pool, progress=False,
                             chunk_size=chunk_size)
    assert [o.value for o in outcomes] == [0, 1, 4, 9]
    assert all(o.ok and o.elapsed > 0 for o in outcomes)


@pytest.mark.parametrize("chunk_size", [0, 1.5, True])
def test_bad_chunk_size(chunk_size):
    with pytest.raises(ValueError, match="chunk_size"):
        run_cases(abs, [1], chunk_size=chunk_size)


@pytest.mark.parametrize("executor", [None, "serial"])
def test_a_failed_case_is_an_outcome_with_its_message(executor):
    """Also inside a chunk: the other cases of the task are kept."""
    executor = SerialExecutor() if executor == "serial" else None
    outcomes = run_cases(fail_on_odd, range(5), executor=executor, progress=False,
                         chunk_size=2)
    assert [o.value for o in outcomes] == [0, None, -2, None, -4]
    assert [o.error for o in outcomes] == [None, "ValueError: odd case 1", None,
                                           "ValueError: odd case 3", None]


def test_cases_an_executor_refuses_become_outcomes():
    pool = concurrent.futures.ThreadPoolExecutor(1)
    pool.shutdown()
    outcomes = run_cases(abs, [-1, -2], executor=pool, progress=False)
    assert all(not o.ok and o.error.startswith("RuntimeError") for o in outcomes)


def test_serial_executor_behaves_like_an_executor():
    with SerialExecutor() as executor:
        assert executor.submit(pow, 2, 10).result() == 1024
        failed = executor.submit(math.sqrt, -1.0)
        assert isinstance(failed.exception(), ValueError)
    with pytest.raises(RuntimeError, match="shutdown"):
        executor.submit(abs, 1)


def test_empty_sweep_and_progress_bar(capsys):
    assert run_cases(abs, [], progress=True) == []
    outcomes = run_cases(abs, [-1, 2], progress=True, description="demo")
    assert [o.value for o in outcomes] == [1, 2]
    assert default_workers() >= 1


def test_default_workers_are_the_cores_this_process_may_use(monkeypatch):
    """One worker per core of the process's CPU affinity (a taskset or a
    container's cpuset), not of the whole machine; os.cpu_count() where the
    system has no affinity."""
    if hasattr(os, "sched_getaffinity"):
        assert default_workers() == len(os.sched_getaffinity(0))
        monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {3}, raising=True)
        assert default_workers() == 1
    monkeypatch.setattr(_sweep, "_HAS_AFFINITY", False)
    monkeypatch.setattr(os, "cpu_count", lambda: None)
    assert default_workers() == 1
    monkeypatch.setattr(os, "cpu_count", lambda: 6)
    assert default_workers() == 6


def test_study_rows_carry_failures():
    """A case that cannot run becomes a row with its message; the other
    cases of the sweep are intact. (The long case's steps of 1e-4 s cannot
    reach its end within max_steps: the core refuses them before it runs,
    it used to run out of steps.)"""
    from leadscrew.studies.creep import creep_vs_frequency

    frame = creep_vs_frequency(holding_scene(), [1.0, 50.0], max_step=1e-4, max_steps=10_000,
                               progress=False)
    assert frame.loc[0, "error"].startswith("ValueError: max_step = 0.0001 is invalid")
    assert np.isnan(frame.loc[0, "creep_per_cycle"])
    assert frame.loc[1, "error"] is None
    assert frame.loc[1, "creep_per_cycle"] < 0


def test_scenes_with_excitation_objects_and_frames_pickle():
    scene = ls.Scene.from_dict(thesis_scene(loads={
        "drive_torque": ls.Sine(-40e-3, 4 * math.pi),
        "axial_force": ls.Table([0.0, 1.0], [-10.0, -20.0])}))
    copy = pickle.loads(pickle.dumps(scene))
    a, b = ls.simulate(scene, 0.5), ls.simulate(copy, 0.5)
    np.testing.assert_array_equal(a["u_load"], b["u_load"])
    result = pickle.loads(pickle.dumps(a))
    np.testing.assert_array_equal(result["u_load"], a["u_load"])
    frame = efficiency_vs_mu(scene, [0.1], [10.0], progress=False)
    restored = pickle.loads(pickle.dumps(frame))
    pd.testing.assert_frame_equal(restored, frame, check_exact=True)
    assert restored.attrs == frame.attrs


def sweeps(executor):
    scene = holding_scene()
    creep = creep_vs_backlash(scene, [1e-4, 2e-4, 3e-4, 4e-4], cycles=4, executor=executor,
                              progress=False)
    efficiency = efficiency_vs_mu(ls.Scene.from_dict(thesis_scene(concept="flexible_nut")),
                                  [0.05, 0.3], [10.0, 50.0], t_end=0.05, executor=executor,
                                  progress=False)
    # Wall times differ between runs; everything else must agree exactly.
    return creep.drop(columns="wall_time"), efficiency.drop(columns="wall_time")


def test_serial_threaded_and_dask_agree():
    serial = sweeps(SerialExecutor())
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        threaded = sweeps(pool)
    default = sweeps(None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with distributed.Client(processes=False, n_workers=1, threads_per_worker=2,
                                dashboard_address=":0") as client:
            in_process = sweeps(client.get_executor())
        # Worker processes: scene, cases and results cross process boundaries.
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                      dashboard_address=":0") as cluster, \
                distributed.Client(cluster) as client:
            processes = sweeps(client.get_executor())
    for other in (threaded, default, in_process, processes):
        for ours, theirs in zip(serial, other):
            pd.testing.assert_frame_equal(ours, theirs, check_exact=True)
    assert serial[0]["error"].isna().all() and serial[1]["error"].isna().all()



def guided_plan(count, workers, seconds_per_case):
    """The chunk sizes guided_size gives along a sweep at a fixed cost per case
    (known once the first chunk is done; None: never)."""
    sizes, sent = [], 0
    while sent < count:  # every pass sends at least one case
        size = guided_size(count - sent, workers, seconds_per_case if sizes else None)
        sizes.append(min(size, count - sent))
        sent += sizes[-1]
    return sizes


@pytest.mark.parametrize("count", [1, 7, 8, 150, 900, 10_000])
@pytest.mark.parametrize("workers", [1, 2, 16])
def test_guided_chunks_of_costly_cases_shrink_to_single_cases(count, workers):
    """A case of 10 ms is above MIN_CHUNK_SECONDS: plain guided scheduling."""
    sizes = guided_plan(count, workers, 10e-3)
    assert sum(sizes) == count and all(size >= 1 for size in sizes)
    assert sizes == sorted(sizes, reverse=True)  # large first, small last
    assert sizes[0] == -(-count // (4 * workers)) and sizes[-1] == 1
    # About 4 w ln(count) tasks: few enough for a cluster's task overhead.
    assert len(sizes) <= 4 * workers * (math.log(count) + 1) + 1


@pytest.mark.parametrize("count", [8, 150, 900, 10_000])
@pytest.mark.parametrize("workers", [1, 2, 16])
def test_guided_chunks_of_cheap_cases_carry_a_millisecond(count, workers):
    """Cases of 10 us travel in chunks of at least MIN_CHUNK_SECONDS (100 cases)."""
    sizes = guided_plan(count, workers, 10e-6)
    floor = round(MIN_CHUNK_SECONDS / 10e-6)
    assert sum(sizes) == count
    assert all(size >= floor for size in sizes[1:-1])
    assert guided_size(10, 2, 0.0) == 10  # a zero cost: everything at once
    assert guided_size(150, 2, 10e-6) == 100 and guided_size(20, 2, 10e-6) == 20
    assert guided_size(150, 2, None) == 19 and guided_size(10_000, 2, 10e-6) == 1250


def square_all(cases):
    return [case * case for case in cases]


@pytest.mark.parametrize("count", [1, 8, 150, 900])
def test_the_last_cheap_cases_go_as_one_equal_chunk_per_worker(count):
    """Once what is left takes less than MIN_CHUNK_SECONDS per worker it is
    split evenly at once: no geometric tail of tiny chunks."""
    workers = default_workers()
    chunks = run_chunks(square_all, range(count), executor=SerialExecutor(), progress=False)
    assert [i for c in chunks for i in c.cases] == list(range(count))
    assert [v for c in chunks for v in c.value] == [i * i for i in range(count)]
    sizes = [len(c.cases) for c in chunks]
    first = guided_plan(count, workers, None)[:2 * workers]  # before the cost is known
    assert sizes[:len(first)] == first[:len(sizes)]
    rest = count - sum(first)
    if rest > 0:  # microsecond cases: the rest at once, one chunk per worker
        share = -(-rest // workers)
        assert sizes[len(first):] == [share] * (rest // share) + ([rest % share]
                                                                  if rest % share else [])


class Stop(BaseException):
    """Not an Exception: like KeyboardInterrupt it ends the sweep."""


def stop_at_three(cases):
    if 3 in cases:
        raise Stop()
    return cases


def test_an_interrupt_ends_the_sweep_and_its_own_pool():
    import threading

    before = threading.active_count()
    with pytest.raises(Stop):
        run_chunks(stop_at_three, range(8), progress=False, chunk_size=1)
    assert threading.active_count() == before  # the default pool was shut down and joined


# run_batches: a chunk function with threads of its own, called in this thread.

def test_run_batches_without_a_bar_is_one_call():
    calls = []
    outcomes = run_batches(lambda cases: calls.append(cases) or len(cases), 10, workers=4,
                           progress=False)
    assert calls == [range(0, 10)]
    assert [(o.cases, o.value, o.error) for o in outcomes] == [(range(0, 10), 10, None)]
    assert outcomes[0].elapsed >= 0.0
    assert run_batches(lambda cases: 1 / 0, 0, workers=2, progress=False) == []


def test_run_batches_with_a_bar_sizes_ranges_by_the_measured_rate(monkeypatch, capsys, watched):
    """One case per worker first, then ranges of about PROGRESS_SECONDS at the
    rate measured so far (never fewer than the workers), covering every case."""
    def cases_of_a_millisecond(cases):
        time.sleep(1e-3 * len(cases))
        return list(cases)

    monkeypatch.setattr(_sweep, "PROGRESS_SECONDS", 0.01)  # ~10 cases of 1 ms
    outcomes = run_batches(cases_of_a_millisecond, 40, workers=2, description="ranges")
    sizes = [len(o.cases) for o in outcomes]
    assert sizes[0] == 2 and all(2 <= n <= 11 for n in sizes[1:]) and len(sizes) >= 4
    assert [case for o in outcomes for case in o.value] == list(range(40))
    assert "ranges" in capsys.readouterr().err


def test_run_batches_keeps_going_after_a_failed_call(monkeypatch, watched):
    def fail_on_the_second(cases):
        if cases.start == 3:
            raise RuntimeError("lost range")
        return len(cases)

    monkeypatch.setattr(_sweep, "PROGRESS_SECONDS", 1e-9)  # every range `workers` cases
    outcomes = run_batches(fail_on_the_second, 8, workers=3, progress=True)
    assert [o.cases for o in outcomes] == [range(0, 3), range(3, 6), range(6, 8)]
    assert [o.error for o in outcomes] == [None, "RuntimeError: lost range", None]
    assert outcomes[1].value is None and outcomes[1].elapsed == 0.0
    single = run_batches(fail_on_the_second, 8, workers=3, progress=False)
    assert [o.cases for o in single] == [range(0, 8)] and single[0].ok


def test_run_batches_refuses_a_worker_count_below_one():
    # A first range of no cases would never end the sweep.
    for workers in (0, -1, 1.5, True):
        with pytest.raises(ValueError, match=r"workers = .* is invalid: must be an integer >= 1"):
            run_batches(lambda cases: len(cases), 4, workers=workers, progress=True)
    assert run_batches(lambda cases: len(cases), 4, workers=np.int64(2), progress=False)[0].ok


# Executors with more workers than this machine has cores, and interrupts.

def test_executor_workers_are_the_executors_own():
    with concurrent.futures.ThreadPoolExecutor(16) as pool:
        assert _sweep.executor_workers(pool) == 16
    assert _sweep.executor_workers(None) == default_workers()
    assert _sweep.executor_workers(SerialExecutor()) == default_workers()

    class Client:  # what a Dask client's executor tells: its workers' threads
        def __init__(self, threads):
            self.threads = threads

        def nthreads(self):
            return self.threads

    class ClientExecutor(SerialExecutor):
        def __init__(self, threads):
            super().__init__()
            self._client = Client(threads)

    assert _sweep.executor_workers(ClientExecutor({"a": 3, "b": 4})) == 7
    assert _sweep.executor_workers(ClientExecutor({})) == default_workers()  # none yet


def test_a_large_pool_gets_chunks_for_all_its_workers(monkeypatch):
    """A caller's 8-thread pool runs 8 chunks at once even where the machine
    (here: pretended) has one core: the chunks in flight follow the pool."""
    import threading

    monkeypatch.setattr(_sweep, "default_workers", lambda: 1)
    lock, running, peak = threading.Lock(), [0], [0]

    def slow_chunk(cases):
        with lock:
            running[0] += 1
            peak[0] = max(peak[0], running[0])
        time.sleep(0.05)
        with lock:
            running[0] -= 1
        return cases

    with concurrent.futures.ThreadPoolExecutor(8) as pool:
        outcomes = run_chunks(slow_chunk, range(64), executor=pool, progress=False)
    assert [case for o in outcomes for case in o.value] == list(range(64))
    assert peak[0] == 8  # with the machine's count: 2 chunks in flight


def interrupt_at_three(case):
    if case == 3:
        raise KeyboardInterrupt
    return case


@pytest.mark.parametrize("chunk_size", [1, None])
def test_an_interrupt_stops_a_serial_sweep_at_once(chunk_size):
    ran = []
    with pytest.raises(KeyboardInterrupt):
        run_cases(lambda case: ran.append(case) or interrupt_at_three(case), range(40),
                  executor=SerialExecutor(), progress=False, chunk_size=chunk_size)
    assert ran == [0, 1, 2, 3]


def test_an_interrupt_cancels_the_chunks_queued_on_the_callers_executor(monkeypatch):
    """Ctrl-C while the caller's one-thread pool runs the first of three
    chunks: the two queued behind it never run, and the pool stays usable.
    The interrupt comes where the sweep waits for its chunks (as a signal
    would end that wait), without a real signal: which thread a signal
    lands on is up to the system."""
    import threading

    started, release, ran = threading.Event(), threading.Event(), []

    def interrupted_wait(*args, **kwargs):
        started.wait(10.0)  # the first chunk runs, the other two are queued
        raise KeyboardInterrupt

    monkeypatch.setattr(concurrent.futures, "wait", interrupted_wait)

    def chunk(cases):
        if cases[0] == 0:
            started.set()
            release.wait(10.0)
        ran.extend(cases)
        return cases

    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        try:
            with pytest.raises(KeyboardInterrupt):
                run_chunks(chunk, range(6), executor=pool, progress=False, chunk_size=2)
        finally:
            release.set()
        assert pool.submit(len, [1]).result(timeout=10.0) == 1
    assert ran == [0, 1]
