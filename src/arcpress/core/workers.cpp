// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/core/workers.hpp"

namespace arcpress {
namespace {

/// One thread of the pool, waiting for its next job.
struct PoolThread {
  std::mutex m;
  std::condition_variable cv;
  std::function<void()> job;
  bool has_job = false;
};

/// The idle threads. Never destroyed: its threads wait on it until the process ends.
struct Pool {
  std::mutex m;
  std::vector<PoolThread*> idle;
};

Pool& pool() {
  static Pool* p = new Pool;
  return *p;
}

void serve(PoolThread* t) {
  for (;;) {
    std::function<void()> job;
    {
      std::unique_lock lk(t->m);
      t->cv.wait(lk, [&] { return t->has_job; });
      job = std::move(t->job);
      t->has_job = false;
    }
    job();
    job = nullptr;  // what the job holds goes before the thread is idle again
    std::lock_guard lk(pool().m);
    pool().idle.push_back(t);
  }
}

void run_on_pool(std::function<void()> job) {
  PoolThread* t = nullptr;
  {
    std::lock_guard lk(pool().m);
    if (!pool().idle.empty()) {
      t = pool().idle.back();
      pool().idle.pop_back();
    }
  }
  if (!t) {
    t = new PoolThread;  // kept for the process's life, as the thread is
    std::thread([t] { serve(t); }).detach();
  }
  {
    std::lock_guard lk(t->m);
    t->job = std::move(job);
    t->has_job = true;
  }
  t->cv.notify_one();
}

}  // namespace

PooledThread::PooledThread(std::function<void()> job) : done_(std::make_shared<Done>()) {
  run_on_pool([done = done_, job = std::move(job)]() noexcept {
    job();
    {
      std::lock_guard lk(done->m);
      done->done = true;
    }
    done->cv.notify_all();
  });
}

PooledThread::~PooledThread() {
  if (done_) join();
}

void PooledThread::join() {
  if (!done_) return;
  std::unique_lock lk(done_->m);
  done_->cv.wait(lk, [&] { return done_->done; });
  lk.unlock();
  done_.reset();
}

}  // namespace arcpress
