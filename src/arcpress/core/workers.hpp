// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Work shared among threads: the number of workers to use, threads taken from a pool that
// keeps them for the next job, and running one function per worker with the first failure
// passed on to the caller.
//
// The pool's threads live as long as the process: the fitter and the measures keep scratch
// memory per thread (thread_local), which a thread that stays is spared allocating again
// for every piece of a long program, and which no thread ends up destroying while the
// process runs. (With MinGW's static runtime, a thread that ends runs its thread_local
// destructors after part of its thread storage is freed, which corrupts the heap now and
// then; threads that never end before the process never do.)
#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace arcpress {

/// The workers for `requested` threads (0: one per hardware thread), at most `jobs`, at least 1.
inline size_t worker_count(unsigned requested, size_t jobs) {
  const size_t want = requested > 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
  return std::max<size_t>(1, std::min(want, jobs));
}

/// A job running on one of the pool's threads, as a std::thread runs it: started at once
/// (on an idle thread of the pool, or a new one when none is idle), and join() waits for
/// it to end. The job must not throw (the program ends if it does, as with std::thread).
/// Joined before it is destroyed.
class PooledThread {
 public:
  explicit PooledThread(std::function<void()> job);
  PooledThread(PooledThread&&) noexcept = default;
  PooledThread& operator=(PooledThread&&) noexcept = default;
  ~PooledThread();
  void join();

 private:
  struct Done {
    std::mutex m;
    std::condition_variable cv;
    bool done = false;
  };
  std::shared_ptr<Done> done_;
};

/// Calls work(w) for every w in [0, workers), each on its own thread (w = 0 on the caller's),
/// and returns when all are done; the first exception any of them threw is rethrown.
template <class Work>
void run_workers(size_t workers, Work&& work) {
  std::vector<std::exception_ptr> failures(workers);
  auto guarded = [&](size_t w) {
    try {
      work(w);
    } catch (...) {
      failures[w] = std::current_exception();
    }
  };
  std::vector<PooledThread> pool;
  for (size_t w = 1; w < workers; ++w) pool.emplace_back([&guarded, w] { guarded(w); });
  guarded(0);
  for (auto& t : pool) t.join();
  for (const auto& f : failures)
    if (f) std::rethrow_exception(f);
}

}  // namespace arcpress
