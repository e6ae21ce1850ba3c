// run_in_parallel (core/parallel.hpp): every call runs at once on its own
// thread, the calling thread among them, and all have returned (their writes
// visible) when it returns; the pool is reused, bounded, shared safely by
// concurrent and nested callers, and rebuilt in a forked child.
//
// Prints "PASS <label> (<count>)" or "FAIL <label> (<count>)" per check and
// "RESULT: PASS" at the end if all passed (read by tests/test_core_native.py).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <set>
#include <thread>
#include <vector>

#include "leadscrew/core/parallel.hpp"

namespace {

bool all_passed = true;

void report(bool ok, const char* label, long count) {
  std::printf("%s %s (%ld)\n", ok ? "PASS" : "FAIL", label, count);
  all_passed = all_passed && ok;
}

// Each call waits until `threads` calls have arrived (so they run at once:
// a pool that ran them one after another would never get there), bounded by
// a deadline so that a failure ends instead of hanging.
struct Rendezvous {
  explicit Rendezvous(int threads) : threads(threads), ids(static_cast<std::size_t>(threads)) {}
  void operator()() noexcept {
    const int slot = arrived.fetch_add(1);
    if (slot < threads) ids[static_cast<std::size_t>(slot)] = std::this_thread::get_id();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (arrived.load() < threads && std::chrono::steady_clock::now() < deadline)
      std::this_thread::yield();
    if (arrived.load() < threads) timed_out.store(true);
    returned.fetch_add(1);
  }
  // All calls ran at once, each on its own thread, the caller's among them,
  // and all had returned when run_in_parallel did.
  bool ok() const {
    std::set<std::thread::id> distinct(ids.begin(), ids.end());
    return !timed_out.load() && arrived.load() == threads && returned.load() == threads &&
           static_cast<int>(distinct.size()) == threads &&
           distinct.count(std::this_thread::get_id()) == 1;
  }
  const int threads;
  std::vector<std::thread::id> ids;  // written by the calls, read after the return
  std::atomic<int> arrived{0}, returned{0};
  std::atomic<bool> timed_out{false};
};

// A job of `pieces` pieces shared through a counter; each piece writes its
// own element (plain memory, read after the return).
struct Pieces {
  explicit Pieces(int pieces) : done(static_cast<std::size_t>(pieces), 0) {}
  void operator()() noexcept {
    for (std::size_t i = next.fetch_add(1); i < done.size(); i = next.fetch_add(1)) ++done[i];
  }
  bool each_once() const {
    return std::all_of(done.begin(), done.end(), [](int d) { return d == 1; });
  }
  std::atomic<std::size_t> next{0};
  std::vector<int> done;
};

bool rendezvous_of(int threads) {
  Rendezvous job(threads);
  leadscrew::run_in_parallel(threads, job);
  return job.ok();
}

}  // namespace

int main() {
  // 1. Every thread count, twice (the second time from the pool's sleep).
  for (int round = 0; round < 2; ++round) {
    for (int threads = 1; threads <= 6; ++threads) {
      char label[96];
      std::snprintf(label, sizeof label, "%d calls at once, the caller's among them, round %d",
                    threads, round);
      report(rendezvous_of(threads), label, threads);
    }
  }

  // 2. The pool keeps at most one helper per hardware thread (the rest of a
  // larger request are started per call), and reuses them.
  const int hardware = std::max(1u, std::thread::hardware_concurrency());
  const int pooled = leadscrew::pooled_helper_count();
  report(pooled >= 1 && pooled <= hardware, "the pool keeps 1 to hardware_concurrency helpers",
         pooled);
  // 200 calls on the pool's helpers: no more distinct helper threads than it
  // keeps (a pool that started a thread per call would show 200).
  std::set<std::thread::id> helper_ids;
  bool all_met = true;
  for (int k = 0; k < 200; ++k) {
    Rendezvous job(2);
    leadscrew::run_in_parallel(2, job);
    all_met = all_met && job.ok();
    for (const std::thread::id& id : job.ids)
      if (id != std::this_thread::get_id()) helper_ids.insert(id);
  }
  report(all_met && static_cast<int>(helper_ids.size()) <= pooled &&
             leadscrew::pooled_helper_count() == pooled,
         "the pool reuses its helpers", static_cast<long>(helper_ids.size()));

  // 3. Two threads calling at once (one gets the pool, the other starts its
  // own helpers), many times: each call meets its 3 threads at once, and
  // every job's pieces are done exactly once.
  std::atomic<long> bad_jobs{0};
  auto caller = [&] {
    for (int k = 0; k < 300; ++k) {
      Pieces job(500);
      leadscrew::run_in_parallel(3, job);
      if (!job.each_once() || !rendezvous_of(3)) bad_jobs.fetch_add(1);
    }
  };
  std::thread first(caller), second(caller);
  first.join();
  second.join();
  report(bad_jobs.load() == 0, "concurrent callers: 600 jobs, each on 3 threads at once",
         bad_jobs.load());

  // 4. A call made from inside a call, on the calling thread and on a helper.
  std::atomic<int> inner_ok{0};
  struct Nested {
    std::atomic<int>* inner_ok;
    void operator()() noexcept {
      if (rendezvous_of(2)) inner_ok->fetch_add(1);
    }
  } nested{&inner_ok};
  leadscrew::run_in_parallel(2, nested);
  report(inner_ok.load() == 2, "nested calls on the caller and on a helper", inner_ok.load());

  // 5. A forked child has none of the parent's helper threads: it must build
  // its own pool rather than wait for them (alarm ends a hang).
  std::fflush(stdout);
  const pid_t child = ::fork();
  if (child == 0) {
    ::alarm(30);
    const bool ok = rendezvous_of(2) && rendezvous_of(3) && leadscrew::pooled_helper_count() >= 1;
    std::_Exit(ok ? 0 : 1);
  }
  int status = 0;
  const bool waited = child > 0 && ::waitpid(child, &status, 0) == child;
  report(waited && WIFEXITED(status) && WEXITSTATUS(status) == 0,
         "a forked child runs calls on a pool of its own", waited ? status : -1);
  // ... and the parent's pool still works.
  report(rendezvous_of(2), "the parent's pool after the fork", 2);

  std::printf("RESULT: %s\n", all_passed ? "PASS" : "FAIL");
  return all_passed ? 0 : 1;
}
