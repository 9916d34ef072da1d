// job(i) for i in [0, count) on `threads` threads (the caller's among them), each taking the next
// i; the first exception (by i) is rethrown once all have finished. The jobs must write only
// their own results. When no more threads can be started, those running share the jobs.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace slipgraph {

template <typename Job>
void RunConcurrently(size_t count, int threads, const Job& job) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<size_t> next{0};
  const auto work = [&] {
    for (size_t i = next++; i < count; i = next++) {
      try {
        job(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  try {
    for (size_t t = 1; t < std::min<size_t>(std::max(1, threads), count); ++t) {
      pool.emplace_back(work);
    }
  } catch (const std::system_error&) {
    // No more threads to be had: the ones running and this one share the jobs.
  }
  work();
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

}  // namespace slipgraph
