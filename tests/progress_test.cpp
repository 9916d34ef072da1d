#include "evaluation/progress.h"

#include <gtest/gtest.h>

#include <sstream>

#include "solvers/batch_smoother.h"
#include "solvers/window_smoother.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

// A clock the test moves by hand.
struct ManualClock {
  double now = 100.0;
  ProgressPrinter::Clock clock() {
    return [this] { return now; };
  }
};

TEST(ProgressPrinter, SilentForTheFirstSecondsThenOneLineRewrittenAndCleared) {
  ManualClock time;
  std::ostringstream out;
  {
    ProgressPrinter printer(true, out, time.clock());
    printer.Show({"batch smoother: iteration", 1, 0, 1800.0});
    EXPECT_EQ(out.str(), "");  // a short run prints nothing
    time.now += 2.5;
    printer.Show({"batch smoother: iteration", 7, 0, 1790.5});
    EXPECT_EQ(out.str(), "\rbatch smoother: iteration 7, cost 1.79e+03, 2 s");
    time.now += 0.1;  // within the interval: not rewritten
    printer.Show({"batch smoother: iteration", 8, 0, 1790.0});
    EXPECT_EQ(out.str(), "\rbatch smoother: iteration 7, cost 1.79e+03, 2 s");
  }
  // The destructor clears the line it left.
  const std::string text = out.str();
  EXPECT_EQ(text.substr(text.size() - 1), "\r");
}

TEST(ProgressPrinter, ChunksShowTheirTotalAndTheTimeLeft) {
  ManualClock time;
  std::ostringstream out;
  ProgressPrinter printer(true, out, time.clock());
  time.now += 10.0;
  printer.Show({"chunk", 2, 10});
  EXPECT_EQ(out.str(), "\rchunk 2 of 10, 10 s, about 40 s left");
  out.str("");
  time.now += 0.01;
  printer.Show({"chunk", 10, 10});  // the last is shown whatever the interval
  EXPECT_NE(out.str().find("chunk 10 of 10, 10 s"), std::string::npos);
  EXPECT_EQ(out.str().find("left"), std::string::npos);
}

TEST(ProgressPrinter, DisabledPrintsNothing) {
  ManualClock time;
  std::ostringstream out;
  ProgressPrinter printer(false, out, time.clock());
  time.now += 60.0;
  printer.Show({"chunk", 1, 2});
  printer.Finish();
  EXPECT_EQ(out.str(), "");
}

TEST(Progress, TheSmoothersReportEachIterationAndEachChunk) {
  const DriveLog log = testing::SimulatedScenario("ward21/01");
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  std::vector<ProgressUpdate> seen;
  BatchSmootherOptions options;
  options.regate_decay_prior = false;
  options.covariance = false;
  options.progress = [&](const ProgressUpdate& u) { seen.push_back(u); };
  const SmootherResult result = SmoothBatch(log, model, options);
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.size(), result.summary.iterations.size());
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i].done, static_cast<long>(i));
  EXPECT_DOUBLE_EQ(seen.back().cost, result.summary.final_cost);

  seen.clear();
  SmoothWindowed(log, model, ChunkedOptions(0.1, 2.0, 100.0, options));
  ASSERT_GE(seen.size(), 3u);
  EXPECT_EQ(seen.front().stage, "chunk");
  EXPECT_EQ(seen.back().done, seen.back().total);
  EXPECT_EQ(seen.size(), static_cast<size_t>(seen.back().total));
}

}  // namespace
}  // namespace slipgraph
