"""Run a study's cases on any :class:`concurrent.futures.Executor`.

A study builds a list of cases (plain, picklable values) and a case function
(a module-level function, or a :func:`functools.partial` of one, so that
process-based executors such as a Dask distributed client can ship it).
:func:`run_cases` maps the function over the cases and returns one
:class:`Outcome` per case, in input order. A case that raises becomes an
outcome with its error message instead of ending the sweep. Cases travel in
chunks: a simulation of a millisecond would otherwise spend a good part of
its time in scheduling, with the GIL held (a thread pool) or in task overhead
(Dask). By default the chunks shrink along the sweep (guided scheduling: each
takes a quarter of the remaining cases' share per worker), so the first tasks
are large and the last ones small, and no worker idles long at the end while
another finishes a large chunk.

:func:`run_chunks` is the same machinery one level down: its function takes
a whole chunk (a list of cases) and returns whatever describes them, e.g. the
arrays of one C++ batch call (:mod:`leadscrew.studies._batch`), so that the
Python work is per chunk rather than per case.

The default executor is a thread pool over ``os.cpu_count()`` workers: the
C++ core releases the GIL while it integrates, so threads run simulations in
parallel. :class:`SerialExecutor` runs every case in the calling thread (the
reference for the parallel paths, and the fastest choice for a handful of
cheap cases).
"""

from __future__ import annotations

import concurrent.futures
import functools
import os
import threading
import time
from dataclasses import dataclass
from typing import Any, Callable, List, Optional, Sequence

__all__ = ["Outcome", "ChunkOutcome", "SerialExecutor", "run_cases", "run_chunks",
           "default_workers", "guided_chunks"]


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
    """An executor that runs each submitted call at once in the calling thread."""

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
        except BaseException as error:  # the future carries it, as a pool's would
            future.set_exception(error)
        return future

    def shutdown(self, wait=True, *, cancel_futures=False):
        with self._lock:
            self._shutdown = True


def default_workers() -> int:
    """Number of workers of the default thread pool: ``os.cpu_count()`` (at least 1)."""
    return max(1, os.cpu_count() or 1)


def guided_chunks(count: int, workers: int) -> List[range]:
    """Split ``count`` cases into consecutive chunks that shrink along the sweep.

    Each chunk takes ceil(remaining / (4 workers)) cases: about 4 w ln(count)
    tasks in all, the first ones large (little scheduling per case), the last
    ones single cases (the workers finish together).

    Args:
        count: number of cases, >= 0.
        workers: number of workers, >= 1.

    Returns:
        The chunks as index ranges, in order, covering 0 .. count - 1.
    """
    chunks: List[range] = []
    start = 0
    while start < count:  # every pass takes at least one case
        size = -(-(count - start) // (4 * workers))
        chunks.append(range(start, start + size))
        start += size
    return chunks


def _describe(error: BaseException) -> str:
    return f"{type(error).__name__}: {error}"


def _chunks(count: int, chunk_size: Optional[int]) -> List[range]:
    """Guided chunks (None) or chunks of ``chunk_size`` cases."""
    if chunk_size is None:
        return guided_chunks(count, default_workers())
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 1:
        raise ValueError(f"chunk_size = {chunk_size!r} is invalid: must be an integer >= 1")
    return [range(start, min(start + chunk_size, count)) for start in range(0, count, chunk_size)]


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
        progress: show a tqdm progress bar over the finished cases.
        description: the progress bar's label.
        chunk_size: cases per chunk, >= 1 (default: guided, shrinking
            chunks, see :func:`guided_chunks`).

    Returns:
        One :class:`ChunkOutcome` per chunk, in the order of ``cases``; the
        chunks cover every case once. A chunk whose function raised, or that
        the executor refused or lost, has ``error`` set and ``value`` None.

    Raises:
        ValueError: invalid ``chunk_size``.
    """
    cases = list(cases)
    chunks = _chunks(len(cases), chunk_size)
    if not chunks:
        return []
    owned = executor is None
    if owned:
        executor = concurrent.futures.ThreadPoolExecutor(max_workers=default_workers())
    from tqdm.auto import tqdm

    outcomes: List[Optional[ChunkOutcome]] = [None] * len(chunks)
    try:
        with tqdm(total=len(cases), desc=description, disable=not progress,
                  leave=False) as bar:
            futures = {}
            for k, chunk in enumerate(chunks):
                try:
                    future = executor.submit(_timed_chunk, function,
                                             [cases[i] for i in chunk])
                    futures[future] = k
                except Exception as error:  # e.g. a case does not pickle
                    outcomes[k] = ChunkOutcome(chunk, None, _describe(error), 0.0)
                    bar.update(len(chunk))
            for future in concurrent.futures.as_completed(futures):
                k = futures[future]
                try:
                    value, elapsed = future.result()
                    outcomes[k] = ChunkOutcome(chunks[k], value, None, elapsed)
                except Exception as error:  # the function failed or the executor lost it
                    outcomes[k] = ChunkOutcome(chunks[k], None, _describe(error), 0.0)
                bar.update(len(chunks[k]))
    finally:
        if owned:
            executor.shutdown(wait=True)
    return outcomes  # type: ignore[return-value]


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
