"""Run a study's cases on any :class:`concurrent.futures.Executor`.

A study builds a list of cases (plain, picklable values) and a case function
(a module-level function, or a :func:`functools.partial` of one, so that
process-based executors such as a Dask distributed client can ship it).
:func:`run_cases` maps the function over the cases and returns one
:class:`Outcome` per case, in input order. A case that raises becomes an
outcome with its error message instead of ending the sweep. Cases travel in
chunks: a simulation of a millisecond would otherwise spend a good part of
its time in scheduling, with the GIL held (a thread pool) or in task overhead
(Dask). By default the chunks are sized as the sweep goes (guided
self-scheduling, :func:`guided_size`): each takes a quarter of the remaining
cases' share per worker, so the chunks shrink along the sweep and no worker
idles long at the end while another finishes a large chunk; once the first
chunks have measured the cost of a case, each chunk also carries at least
:data:`MIN_CHUNK_SECONDS` of work, and when what is left would take less than
that per worker it goes out at once in one equal chunk per worker. Cases of
microseconds thus travel in a few large chunks instead of dozens of tiny ones
whose scheduling would cost more than the cases.
How the cases are split depends on timing; the results must not (every
study's cases are independent).

:func:`run_chunks` is the same machinery one level down: its function takes
a whole chunk (a list of cases) and returns whatever describes them, e.g. the
arrays of one C++ batch call (:mod:`leadscrew.studies._batch`), so that the
Python work is per chunk rather than per case.

:func:`run_batches` is for a chunk function that spreads its cases over
threads of its own (a C++ batch, ``DriveBatch.run(values, workers)``): it
calls it in the calling thread, on the whole sweep at once, or, with a
progress bar, on a few consecutive ranges that each take about
:data:`PROGRESS_SECONDS`, so the bar moves while the thread pool stays in C++.

The default executor is a thread pool with one worker per core this process
may run on (:func:`default_workers`): the
C++ core releases the GIL while it integrates, so threads run simulations in
parallel. :class:`SerialExecutor` runs every case in the calling thread (the
reference for the parallel paths, and the fastest choice for a handful of
cheap cases).
"""

from __future__ import annotations

import concurrent.futures
import functools
import math
import os
import threading
import time
from dataclasses import dataclass
from typing import Any, Callable, List, Optional, Sequence

from .._progress import shown
from ._common import check_count

__all__ = ["Outcome", "ChunkOutcome", "SerialExecutor", "run_cases", "run_chunks",
           "run_batches", "default_workers", "executor_workers", "guided_size",
           "MIN_CHUNK_SECONDS", "PROGRESS_SECONDS"]

# Least work per chunk once the cost of a case is known [s]: the Python
# around a chunk (submission, future, the chunk function's own work) takes
# some 30-50 us on a thread pool, under 5% of this.
MIN_CHUNK_SECONDS = 1e-3

# Wall time of one call of run_batches while a progress bar shows [s]: about
# the bar's own refresh interval (tqdm's mininterval, 0.1 s) or more. Each
# call ends with its threads finishing their last cases unevenly (at most one
# case each), so fewer, longer calls waste less.
PROGRESS_SECONDS = 0.25


@dataclass(frozen=True)
class Outcome:
    """What one case gave.

    Attributes:
        value: the case function's return value (None if it failed).
        error: None, or ``"ExceptionType: message"`` of the failure.
        elapsed: wall time of the case function in its worker [s].
    """

    value: Any
    error: Optional[str]
    elapsed: float

    @property
    def ok(self) -> bool:
        return self.error is None


@dataclass(frozen=True)
class ChunkOutcome:
    """What one chunk of cases gave (:func:`run_chunks`).

    Attributes:
        cases: the indices of the chunk's cases in the sweep.
        value: the chunk function's return value (None if it failed).
        error: None, or ``"ExceptionType: message"`` of the failure (of the
            function, or of the executor that lost or refused the task).
        elapsed: wall time of the chunk function in its worker [s] (0 if it
            never ran).
    """

    cases: range
    value: Any
    error: Optional[str]
    elapsed: float

    @property
    def ok(self) -> bool:
        return self.error is None


class SerialExecutor(concurrent.futures.Executor):
    """An executor that runs each submitted call at once in the calling thread.

    An exception of the call goes into its future, as a pool's would; a
    KeyboardInterrupt or SystemExit (not an ``Exception``) propagates from
    :meth:`submit` at once, so Ctrl-C stops a serial sweep where it is.
    """

    def __init__(self):
        self._shutdown = False
        self._lock = threading.Lock()

    def submit(self, fn, /, *args, **kwargs):
        with self._lock:
            if self._shutdown:
                raise RuntimeError("cannot schedule new calls after shutdown")
        future: concurrent.futures.Future = concurrent.futures.Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except Exception as error:  # the future carries it, as a pool's would
            future.set_exception(error)
        return future

    def shutdown(self, wait=True, *, cancel_futures=False):
        with self._lock:
            self._shutdown = True

    @property
    def is_shutdown(self) -> bool:
        """True once :meth:`shutdown` was called (``submit`` then raises)."""
        return self._shutdown


_HAS_AFFINITY = hasattr(os, "sched_getaffinity")


def default_workers() -> int:
    """Number of workers of the default thread pool.

    Returns:
        One per core this process may run on (its CPU affinity where the
        system has one, else ``os.cpu_count()``), at least 1.
    """
    if _HAS_AFFINITY:  # ~0.4 us, where os.cpu_count() reads /sys (~7 us)
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


def executor_workers(executor: Optional[concurrent.futures.Executor]) -> int:
    """How many calls ``executor`` runs at once, as far as it tells.

    Args:
        executor: None (the default thread pool), a thread or process pool
            (its ``max_workers``), a Dask client's executor (the threads of
            the client's workers now), or any other executor.

    Returns:
        That count, at least 1; :func:`default_workers` for None, for an
        executor that does not tell, and for a Dask cluster without
        workers yet.
    """
    if executor is None:
        return default_workers()
    # concurrent.futures' pools keep max_workers as _max_workers (since 3.2)
    count = getattr(executor, "_max_workers", None)
    if isinstance(count, int) and not isinstance(count, bool) and count >= 1:
        return count
    client = getattr(executor, "_client", None)  # distributed.cfexecutor.ClientExecutor
    nthreads = getattr(client, "nthreads", None)
    if callable(nthreads):
        try:
            total = sum(nthreads().values())
        except Exception:  # a closed client, or another object of that name
            total = 0
        if isinstance(total, int) and total >= 1:
            return total
    return default_workers()


def guided_size(remaining: int, workers: int, seconds_per_case: Optional[float]) -> int:
    """Cases in the next chunk of a sweep (guided self-scheduling).

    Args:
        remaining: cases not yet sent, >= 1.
        workers: number of workers, >= 1.
        seconds_per_case: measured wall time of a case [s] (over the chunks
            done so far), or None while no chunk has finished.

    Returns:
        ceil(remaining / (4 workers)) (guided: about 4 w ln(count) chunks,
        shrinking to single cases), once the cost is known at least the
        cases that take :data:`MIN_CHUNK_SECONDS`; never more than
        ``remaining``. (:func:`run_chunks` sends the last cases, once they
        take less than that per worker, as one equal chunk per worker.)
    """
    size = -(-remaining // (4 * workers))
    if seconds_per_case is not None:
        size = max(size, math.ceil(MIN_CHUNK_SECONDS / max(seconds_per_case, 1e-9)))
    return max(1, min(size, remaining))


def _check_chunk_size(chunk_size: Optional[int]) -> None:
    if chunk_size is not None and (isinstance(chunk_size, bool)
                                   or not isinstance(chunk_size, int) or chunk_size < 1):
        raise ValueError(f"chunk_size = {chunk_size!r} is invalid: must be an integer >= 1")


def _describe(error: BaseException) -> str:
    return f"{type(error).__name__}: {error}"


def _guarded(function: Callable[[Any], Any], case: Any) -> Outcome:
    """Run one case in its worker; a failure becomes the outcome's error.

    Module-level so that process-based executors can pickle it.
    """
    start = time.perf_counter()
    try:
        value = function(case)
    except Exception as error:  # a failed case is a row, not a lost sweep
        return Outcome(None, _describe(error), time.perf_counter() - start)
    return Outcome(value, None, time.perf_counter() - start)


def _guarded_chunk(function: Callable[[Any], Any], cases: Sequence[Any]) -> List[Outcome]:
    """Run several cases in one task (fewer futures, less scheduling per case)."""
    return [_guarded(function, case) for case in cases]


class _NoProgressBar:
    """What the sweeps use of a tqdm bar, doing nothing (``progress=False``):
    a disabled tqdm still costs ~10 us to build, a tenth of a fast sweep's
    Python."""

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        return False

    def update(self, count: int = 1) -> None:
        pass

    def close(self) -> None:
        pass


def _progress_bar(count: int, description: Optional[str], progress: bool):
    """A tqdm bar over ``count`` cases, or a stand-in when ``progress`` is off
    or nobody watches (:func:`leadscrew._progress.shown`)."""
    if not shown(progress):
        return _NoProgressBar()
    from tqdm.auto import tqdm

    return tqdm(total=count, desc=description, leave=False)


def _timed_chunk(function: Callable[[List[Any]], Any], cases: List[Any]):
    """Run a chunk function in its worker: (value, elapsed [s]).

    Module-level so that process-based executors can pickle it.
    """
    start = time.perf_counter()
    value = function(cases)
    return value, time.perf_counter() - start


def run_chunks(
    function: Callable[[List[Any]], Any],
    cases: Sequence[Any],
    executor: Optional[concurrent.futures.Executor] = None,
    progress: bool = True,
    description: Optional[str] = None,
    chunk_size: Optional[int] = None,
) -> List[ChunkOutcome]:
    """Call ``function`` once per chunk of ``cases`` on an executor.

    Args:
        function: called as ``function(list_of_cases)`` in a worker, once per
            chunk; for process-based executors it and the cases must pickle.
        cases: the cases.
        executor: any :class:`concurrent.futures.Executor` (a thread pool,
            a process pool, :class:`SerialExecutor`, or a Dask client's
            ``client.get_executor()``). Default: a thread pool over
            :func:`default_workers` workers, shut down before returning.
            Up to two chunks per worker of it (:func:`executor_workers`)
            are in flight at once; on KeyboardInterrupt those not started
            are cancelled.
        progress: show a tqdm progress bar over the finished cases.
        description: the progress bar's label.
        chunk_size: cases per chunk, >= 1 (default: guided self-scheduling,
            see :func:`guided_size`).

    Returns:
        One :class:`ChunkOutcome` per chunk, in the order of ``cases``; the
        chunks cover every case once. A chunk whose function raised, or that
        the executor refused or lost, has ``error`` set and ``value`` None.

    Raises:
        ValueError: invalid ``chunk_size``.
    """
    cases = list(cases)
    _check_chunk_size(chunk_size)
    count = len(cases)
    if not count:
        return []
    # The executor's own worker count: a 16-thread pool or a Dask cluster of
    # many cores gets chunks for all of them in flight.
    workers = executor_workers(executor)
    # Fixed chunks are all sent at once; guided ones as the sweep goes, at
    # most two per worker in flight (one running, one queued: a worker that
    # finishes a chunk starts the next at once, while the calling thread
    # sizes the one after it).
    window = count if chunk_size is not None else 2 * workers
    owned = executor is None
    if owned:
        executor = concurrent.futures.ThreadPoolExecutor(max_workers=workers)
    outcomes: List[ChunkOutcome] = []
    in_flight: dict = {}
    sent = 0
    measured_cases, measured_seconds = 0, 0.0
    tail: Optional[int] = None  # the size of the last chunks, once decided
    try:
        with _progress_bar(count, description, progress) as bar:
            while sent < count or in_flight:  # each pass sends a chunk or waits for one
                while sent < count and len(in_flight) < window:
                    cost = measured_seconds / measured_cases if measured_cases else None
                    if tail is None and cost is not None and chunk_size is None and \
                            (count - sent) * cost <= workers * MIN_CHUNK_SECONDS:
                        # The rest is less than a chunk's work per worker:
                        # one equal chunk each, sent now (the calling thread
                        # need not wake again to feed the workers).
                        tail = -(-(count - sent) // workers)
                        window = count
                    size = chunk_size or tail or guided_size(count - sent, workers, cost)
                    chunk = range(sent, min(sent + size, count))
                    sent = chunk.stop
                    try:
                        future = executor.submit(_timed_chunk, function,
                                                 list(cases[chunk.start:chunk.stop]))
                        in_flight[future] = chunk
                    except Exception as error:  # e.g. a case does not pickle
                        outcomes.append(ChunkOutcome(chunk, None, _describe(error), 0.0))
                        bar.update(len(chunk))
                if not in_flight:
                    continue
                done, _ = concurrent.futures.wait(
                    in_flight, return_when=concurrent.futures.FIRST_COMPLETED)
                for future in done:
                    chunk = in_flight.pop(future)
                    try:
                        value, elapsed = future.result()
                        outcomes.append(ChunkOutcome(chunk, value, None, elapsed))
                        measured_cases += len(chunk)
                        measured_seconds += elapsed
                    except Exception as error:  # the function failed or the executor lost it
                        outcomes.append(ChunkOutcome(chunk, None, _describe(error), 0.0))
                    bar.update(len(chunk))
    except BaseException:  # e.g. KeyboardInterrupt: drop what has not started
        if owned:
            executor.shutdown(wait=True, cancel_futures=True)
        else:  # the caller's executor stays up; its queued chunks of this sweep go
            for future in in_flight:
                future.cancel()
        raise
    if owned:  # every chunk is done: the threads only exit, nothing to wait for
        executor.shutdown(wait=False)
    outcomes.sort(key=lambda outcome: outcome.cases.start)
    return outcomes


def run_batches(
    function: Callable[[range], Any],
    count: int,
    workers: int,
    progress: bool = True,
    description: Optional[str] = None,
) -> List[ChunkOutcome]:
    """Call ``function`` in the calling thread on consecutive ranges of ``count`` cases.

    For a function that runs a range of cases in parallel itself (a C++
    batch on ``workers`` threads of its own): without a progress bar it is
    called once, on every case; with one, first on one case per worker (to
    measure the sweep's wall time per case), then on ranges that take about
    :data:`PROGRESS_SECONDS` each at that rate, the bar updated after each.

    Args:
        function: called as ``function(range_of_case_indices)``.
        count: number of cases, >= 0.
        workers: the threads ``function`` runs its range on, >= 1 (no range
            but the last is smaller).
        progress: show a tqdm progress bar over the finished cases.
        description: the progress bar's label.

    Returns:
        One :class:`ChunkOutcome` per call, in order; the ranges cover every
        case once. A call that raised has ``error`` set and ``value`` None
        (the later ranges still run).

    Raises:
        ValueError: ``workers`` is not an integer >= 1.
    """
    workers = check_count("workers", workers, 1)
    progress = shown(progress)
    if count <= 0:
        return []
    outcomes: List[ChunkOutcome] = []
    done, measured_cases, measured_seconds = 0, 0, 0.0
    with _progress_bar(count, description, progress) as bar:
        while done < count:  # each pass runs at least `workers` cases
            if not progress:
                size = count  # one call: nothing to report until it ends
            elif measured_cases:
                size = math.ceil(PROGRESS_SECONDS * measured_cases / max(measured_seconds, 1e-9))
            else:
                size = workers
            cases = range(done, min(count, done + max(size, workers)))
            try:
                value, elapsed = _timed_chunk(function, cases)
            except Exception as error:  # the rows say so, as those of a lost chunk
                outcomes.append(ChunkOutcome(cases, None, _describe(error), 0.0))
            else:
                outcomes.append(ChunkOutcome(cases, value, None, elapsed))
                measured_cases += len(cases)
                measured_seconds += elapsed
            done = cases.stop
            bar.update(len(cases))
    return outcomes


def run_cases(
    function: Callable[[Any], Any],
    cases: Sequence[Any],
    executor: Optional[concurrent.futures.Executor] = None,
    progress: bool = True,
    description: Optional[str] = None,
    chunk_size: Optional[int] = None,
) -> List[Outcome]:
    """Map ``function`` over ``cases`` on an executor, in input order.

    Args:
        function: called as ``function(case)`` in a worker; for process-based
            executors it and the cases must pickle.
        cases: the cases.
        executor, progress, description, chunk_size: as :func:`run_chunks`
            (the cases travel in its chunks).

    Returns:
        One :class:`Outcome` per case, in the order of ``cases``. A case that
        raised (in the function, or while the executor shipped it) has
        ``error`` set and ``value`` None.

    Raises:
        ValueError: invalid ``chunk_size``.
    """
    outcomes: List[Outcome] = []
    for chunk in run_chunks(functools.partial(_guarded_chunk, function), cases,
                            executor=executor, progress=progress, description=description,
                            chunk_size=chunk_size):
        if chunk.ok:
            outcomes.extend(chunk.value)
        else:
            outcomes.extend([Outcome(None, chunk.error, 0.0)] * len(chunk.cases))
    return outcomes
