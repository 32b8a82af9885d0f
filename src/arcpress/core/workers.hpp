// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Work shared among threads: the number of workers to use, and running one function per
// worker with the first failure passed on to the caller.
#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace arcpress {

/// The workers for `requested` threads (0: one per hardware thread), at most `jobs`, at least 1.
inline size_t worker_count(unsigned requested, size_t jobs) {
  const size_t want = requested > 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
  return std::max<size_t>(1, std::min(want, jobs));
}

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
  std::vector<std::thread> pool;
  for (size_t w = 1; w < workers; ++w) pool.emplace_back(guarded, w);
  guarded(0);
  for (auto& t : pool) t.join();
  for (const auto& f : failures)
    if (f) std::rethrow_exception(f);
}

}  // namespace arcpress
