#include "leadscrew/core/parallel.hpp"

#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace leadscrew {

namespace {

void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// Helper threads asleep on a condition variable between jobs; one job at a
// time, that of the call that claimed the pool. Never destroyed: its threads
// block in wait() until the process ends (a joinable std::thread must not be
// destroyed).
class HelperPool {
 public:
  HelperPool() = default;
  HelperPool(const HelperPool&) = delete;
  HelperPool& operator=(const HelperPool&) = delete;

  // Claims the pool for one call (false: another call has it, perhaps an
  // outer call on this same thread); release() gives it back.
  bool claim() noexcept { return !in_use_.exchange(true, std::memory_order_acquire); }
  void release() noexcept { in_use_.store(false, std::memory_order_release); }

  // Starts work(context) on up to `wanted` helpers (starting pool threads up
  // to the pool's size as needed) and returns how many take part. Requires
  // the claim; the job must be waited for (wait()) before the next.
  int start(int wanted, ParallelWork work, void* context) noexcept {
    std::unique_lock<std::mutex> lock(state_);
    taking_part_ = grow(wanted);
    if (taking_part_ == 0) return 0;
    work_ = work;
    context_ = context;
    running_.store(taking_part_, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
    lock.unlock();
    wake_.notify_all();
    return static_cast<int>(taking_part_);
  }

  // Returns once every helper of the job has returned from its call.
  void wait() noexcept {
    // The last helper is mostly in the middle of its last piece: spin for a
    // while rather than sleep at once, because waking a sleeping thread
    // costs tens of microseconds on a virtual machine.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::microseconds(200);
    while (running_.load(std::memory_order_acquire) != 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        std::unique_lock<std::mutex> lock(state_);
        finished_.wait(lock, [this] { return running_.load(std::memory_order_acquire) == 0; });
        return;
      }
      for (int k = 0; k < 64; ++k) cpu_relax();
    }
  }

  int size() noexcept {
    const std::lock_guard<std::mutex> lock(state_);
    return static_cast<int>(threads_.size());
  }

 private:
  // The pool's threads, min(wanted, its size) of them (as many as the system
  // starts); requires state_.
  std::size_t grow(int wanted) noexcept {
    // One per hardware thread (the studies' default_workers counts the cores
    // of the process's affinity, never more): more are started per call.
    const std::size_t size = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t needed = std::min(static_cast<std::size_t>(std::max(wanted, 0)), size);
    try {
      while (threads_.size() < needed) {
        const std::size_t index = threads_.size();
        // A new thread must not take the jobs before this one for its own.
        threads_.emplace_back([this, index, seen = generation_.load(std::memory_order_relaxed)] {
          serve(index, seen);
        });
      }
    } catch (const std::exception&) {
      // No more threads (system_error, bad_alloc): those there are take part.
    }
    return std::min(needed, threads_.size());
  }

  void serve(std::size_t index, std::uint64_t seen) noexcept {
    std::unique_lock<std::mutex> lock(state_);
    for (;;) {
      wake_.wait(lock, [&] { return generation_.load(std::memory_order_relaxed) != seen; });
      seen = generation_.load(std::memory_order_relaxed);
      if (index >= taking_part_) continue;  // a job for fewer helpers
      const ParallelWork work = work_;
      void* const context = context_;
      lock.unlock();
      work(context);
      // The caller may return, and its context go, as soon as the count is
      // zero: after this, touch only the pool.
      if (running_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        lock.lock();  // the caller is before its check or inside wait(): not in between
        finished_.notify_all();
      } else {
        lock.lock();
      }
    }
  }

  std::atomic<bool> in_use_{false};
  std::mutex state_;
  std::condition_variable wake_;      // a new job (generation_ changed)
  std::condition_variable finished_;  // running_ reached zero
  std::vector<std::thread> threads_;
  // Jobs started; changed under state_.
  std::atomic<std::uint64_t> generation_{0};
  std::size_t taking_part_ = 0;  // helpers 0 .. taking_part_ - 1 run the current job
  ParallelWork work_ = nullptr;
  void* context_ = nullptr;
  std::atomic<std::size_t> running_{0};  // helpers of the job not yet returned
};

std::atomic<HelperPool*> process_pool{nullptr};
std::atomic<bool> pool_being_built{false};

// In the child of a fork(): none of the parent's helper threads followed, so
// the child must not wait for them. It forgets the parent's pool (left as it
// is: its mutexes may have been copied locked) and builds its own at first
// use.
void forget_pool_in_child() noexcept {
  process_pool.store(nullptr, std::memory_order_relaxed);
  pool_being_built.store(false, std::memory_order_relaxed);
}

// This process's pool, built at first use; null if another thread is
// building it just now (the caller then starts threads of its own).
HelperPool* pool_of_this_process() noexcept {
  HelperPool* pool = process_pool.load(std::memory_order_acquire);
  if (pool != nullptr) return pool;
  if (pool_being_built.exchange(true, std::memory_order_acq_rel)) return nullptr;
  pool = process_pool.load(std::memory_order_acquire);
  if (pool == nullptr) {
    static const bool fork_handler_registered =
        ::pthread_atfork(nullptr, nullptr, forget_pool_in_child) == 0;
    if (fork_handler_registered) {  // without it a forked child could hang: no pool then
      try {
        pool = new HelperPool();
        process_pool.store(pool, std::memory_order_release);
      } catch (const std::bad_alloc&) {
        pool = nullptr;
      }
    }
  }
  pool_being_built.store(false, std::memory_order_release);
  return pool;
}

}  // namespace

void run_in_parallel(int threads, ParallelWork work, void* context) noexcept {
  if (threads <= 1) {
    work(context);
    return;
  }
  const int wanted = threads - 1;
  int pooled = 0;
  HelperPool* pool = pool_of_this_process();
  const bool claimed = pool != nullptr && pool->claim();
  if (claimed) pooled = pool->start(wanted, work, context);
  std::vector<std::thread> extra;
  try {
    if (pooled < wanted) extra.reserve(static_cast<std::size_t>(wanted - pooled));
    for (int k = pooled; k < wanted; ++k) extra.emplace_back([work, context] { work(context); });
  } catch (const std::exception&) {
    // The system would not start another thread: those running take the job.
  }
  work(context);
  for (std::thread& helper : extra) helper.join();
  if (pooled > 0) pool->wait();
  if (claimed) pool->release();
}

int pooled_helper_count() noexcept {
  // Asks only: a process that never ran a job has no pool (and gets none).
  HelperPool* pool = process_pool.load(std::memory_order_acquire);
  return pool == nullptr ? 0 : pool->size();
}

}  // namespace leadscrew
