#pragma once
// The library's worker pool: a fixed number of tasks shared by a few threads, with progress
// reported on the calling thread and the first exception rethrown there.
//
// Which worker runs a task varies from run to run. Callers keep results independent of the thread
// count by giving each task its own output (added in task order afterwards) or by adding integers
// per worker (any split and any order give the same totals).

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace chaos::detail {

// Where a call's tasks lie in a longer job, for its progress report: task t of the call is unit
// `offset + t` of `total` (a job run as several calls, round after round, reports one rising
// fraction). The default total 0 means the call is the whole job.
struct ProgressSpan {
  std::size_t offset = 0;
  std::size_t total = 0;
};

// Threads that parallel_tasks starts for `tasks` tasks: never more than there are tasks, at least one.
inline std::size_t worker_count(std::size_t threads, std::size_t tasks) noexcept {
  return std::max<std::size_t>(1, std::min(threads, tasks));
}

// Runs f(task, worker) for every task in [0, tasks) on worker_count(threads, tasks) workers that
// take tasks from a shared counter; `worker` is below that count, so per-worker scratch and sums can
// be indexed by it.
//
// With `progress` and more than one worker, the calling thread does not compute: it reports the
// fraction of tasks done (in thousandths, rising, below 1) as tasks end and at least every 10 ms
// while the workers run. The progress hook is where a caller cancels (the Python package checks for
// Ctrl-C there, which only the calling thread may do), so it must run on the calling thread and
// often, not only when that thread finishes a task: on a loaded machine a task can take a second.
// Without `progress` the calling thread is worker 0. An exception from f or from the hook stops the
// workers after their current task and is rethrown here once every thread has stopped.
template <class F>
void parallel_tasks(std::size_t threads, std::size_t tasks, F&& f, const std::function<void(double)>* progress = nullptr,
                    ProgressSpan span = {}) {
  if (progress && !*progress) progress = nullptr;
  const std::size_t workers = worker_count(threads, tasks);
  const std::size_t total = span.total > 0 ? span.total : tasks;
  std::size_t reported = 0;  // thousandths
  const auto report = [&](std::size_t taken) {
    const std::size_t now = std::min(span.offset + taken, total) * 1000 / std::max<std::size_t>(total, 1);
    if (progress && now > reported && now < 1000) (*progress)(static_cast<double>(reported = now) / 1000.0);
  };
  if (workers == 1) {
    for (std::size_t t = 0; t < tasks; ++t) {
      f(t, std::size_t{0});
      report(t + 1);
    }
    return;
  }
  std::atomic<std::size_t> next{0}, done{0};
  std::vector<std::exception_ptr> errors(workers);
  std::mutex mutex;
  std::condition_variable finished;
  std::size_t running = progress ? workers : workers - 1;  // threads started below, guarded by mutex
  const auto body = [&](std::size_t worker) {
    try {
      for (std::size_t t; (t = next.fetch_add(1, std::memory_order_relaxed)) < tasks;) {
        f(t, worker);
        done.fetch_add(1, std::memory_order_relaxed);
        if (progress) finished.notify_one();  // the monitor reports as tasks end (and every 10 ms)
      }
    } catch (...) {
      errors[worker] = std::current_exception();
      next.store(tasks);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers);
  const std::size_t first = progress ? 0 : 1;  // without progress, the caller is worker 0
  for (std::size_t k = first; k < workers; ++k)
    pool.emplace_back([&, k] {
      body(k);
      std::lock_guard<std::mutex> lock(mutex);
      if (--running == 0) finished.notify_one();
    });
  std::exception_ptr hook_error;
  if (progress) {
    std::unique_lock<std::mutex> lock(mutex);
    while (running > 0) {
      finished.wait_for(lock, std::chrono::milliseconds(10));
      if (running == 0 || hook_error) continue;
      lock.unlock();
      try {
        report(done.load(std::memory_order_relaxed));
      } catch (...) {
        hook_error = std::current_exception();
        next.store(tasks);
      }
      lock.lock();
    }
    // A run faster than the monitor still reports once: the last fraction below 1 that was reached.
    if (!hook_error) {
      lock.unlock();
      try {
        report(tasks - 1);
      } catch (...) {
        hook_error = std::current_exception();
      }
    }
  } else {
    body(0);
  }
  for (auto& t : pool) t.join();
  if (hook_error) std::rethrow_exception(hook_error);
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace chaos::detail
