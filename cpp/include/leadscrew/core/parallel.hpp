// Running one job on several threads at once, with helper threads kept
// between calls.
//
// A sweep of cheap cases (150 rigid drives of ~11 us each) is over in about a
// millisecond, so what it costs to get a second thread going is part of the
// speed-up: starting a std::thread and joining it took 80-130 us per call on
// the 2-core test machine, waking a thread that sleeps in a pool 30-50 us, of
// which the calling thread does useful work meanwhile. The helpers therefore
// live in one process-wide pool, asleep between calls, and are never joined:
// they end with the process. POSIX only (pthread_atfork, below).
#pragma once

#include <type_traits>

namespace leadscrew {

// A job's body: called once on each thread taking part, with the job's context.
using ParallelWork = void (*)(void* context) noexcept;

// Calls work(context) on `threads` threads at once (the calling thread and
// threads - 1 helpers) and returns once every call has returned; what the
// calls wrote is then visible to the caller. threads <= 1 calls it on the
// calling thread alone.
//
// `work` must finish the whole job with any number >= 1 of calls, e.g. each
// call taking the next piece from a shared counter until none is left: a
// helper the system will not start is left out (the calling thread always
// takes part), and a helper may begin after the others have taken every
// piece. The helpers come from the pool; while another call uses it (two
// Python threads each running a batch, or a nested call) or when more are
// wanted than it keeps (one per hardware thread), the rest are started for
// this call as std::threads and joined. After a fork() the child, which has
// none of the parent's helpers, builds its own pool (a pthread_atfork
// handler makes it forget the parent's).
//
// The helpers stay until the process ends, so after a call with threads > 1
// the process has more than one thread: Python 3.12 and later then warn
// (DeprecationWarning) at os.fork(), as for any threaded extension.
void run_in_parallel(int threads, ParallelWork work, void* context) noexcept;

// The same for a callable: work() on each of `threads` threads.
template <class Work>
void run_in_parallel(int threads, Work& work) noexcept {
  static_assert(std::is_nothrow_invocable_v<Work&>,
                "the work of run_in_parallel must not throw: catch inside it");
  run_in_parallel(
      threads, [](void* context) noexcept { (*static_cast<Work*>(context))(); }, &work);
}

// Helper threads the process's pool has started so far (for tests).
int pooled_helper_count() noexcept;

}  // namespace leadscrew
