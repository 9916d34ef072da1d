// RunConcurrently (solvers/run_concurrently.h): every job once, whatever the thread count, and
// the first failure by index rethrown after all have run.
#include "solvers/run_concurrently.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace slipgraph {
namespace {

TEST(RunConcurrently, RunsEveryJobOnceOnAnyNumberOfThreads) {
  for (int threads : {1, 2, 3, 64}) {
    std::vector<int> runs(100, 0);
    RunConcurrently(runs.size(), threads, [&](size_t i) { ++runs[i]; });
    for (size_t i = 0; i < runs.size(); ++i)
      EXPECT_EQ(runs[i], 1) << threads << " threads, job " << i;
  }
  RunConcurrently(0, 2, [](size_t) { FAIL() << "no job to run"; });
}

TEST(RunConcurrently, RethrowsTheFirstFailureByIndexAfterEveryJobRan) {
  std::atomic<int> ran{0};
  try {
    RunConcurrently(20, 2, [&](size_t i) {
      ++ran;
      if (i == 7 || i == 13) throw std::runtime_error("job " + std::to_string(i));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "job 7");
  }
  EXPECT_EQ(ran.load(), 20);
}

}  // namespace
}  // namespace slipgraph
