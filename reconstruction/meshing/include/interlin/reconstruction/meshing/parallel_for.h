#pragma once
// A minimal work-sharing loop on std::thread (no pool, no dependency). Tasks are handed
// out by an atomic counter, so uneven tasks (sub-boxes that cut the surface vs empty ones)
// balance themselves.

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace interlin::detail {

// 0 (or less) means all hardware threads; the result is at least 1.
inline int resolve_threads(int threads) {
  if (threads > 0)
    return threads;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? int(hw) : 1;
}

// Calls body(task, worker) for every task in [0, tasks) on up to `threads` workers (worker in
// [0, workers)); returns after all tasks are done. The first exception thrown by a task is
// rethrown here after every worker has stopped; remaining tasks are skipped.
template <class Body>
void parallel_for(long tasks, int threads, Body&& body) {
  const int workers = int(std::min<long>(std::max(1, threads), std::max<long>(tasks, 1)));
  if (workers <= 1) {
    for (long t = 0; t < tasks; ++t)
      body(t, 0);
    return;
  }
  std::atomic<long> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&](int worker) {
    for (long t = next++; t < tasks && !failed; t = next++) {
      try {
        body(t, worker);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error)
          error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(std::size_t(workers - 1));
  for (int w = 1; w < workers; ++w)
    pool.emplace_back(run, w);
  run(0);
  for (std::thread& t : pool)
    t.join();
  if (error)
    std::rethrow_exception(error);
}

// The number of chunks of `chunk` rows that cover [0, n).
inline long chunk_count(long n, long chunk) {
  return (n + chunk - 1) / chunk;
}

// Calls body(task, r0, r1) for every chunk [r0, r1) = [task chunk, min(n, (task + 1) chunk)) of
// [0, n), task in [0, chunk_count(n, chunk)), on up to `threads` workers (0: all cores). The
// chunks do not depend on the thread count, so sums kept per task and added in task order are
// the same on any number of threads.
template <class Body>
void parallel_chunks(long n, long chunk, int threads, Body&& body) {
  parallel_for(chunk_count(n, chunk), resolve_threads(threads), [&](long task, int) {
    const long r0 = task * chunk;
    body(task, r0, std::min(n, r0 + chunk));
  });
}

} // namespace interlin::detail
