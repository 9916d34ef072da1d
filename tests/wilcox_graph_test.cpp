// Wilcox's estimator as a factor graph: on the hand-made profile it recovers every advance to a
// fraction of a millimetre (the baseline: 7 mm); the suite figures are in docs/wilcox.md.
#include "solvers/wilcox_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tests/wilcox_test_logs.h"

namespace slipgraph {
namespace {

using testing::HandMadeLog;
using testing::PointContact;

TEST(WilcoxGraph, RecoversAdvanceAndSinkageOnAHandMadeProfile) {
  const DriveLog log = HandMadeLog(0.003, 0.003);
  const WilcoxResult result = EstimateWilcoxGraph(log, PointContact());
  for (const WilcoxSide& side : result.sides) {
    ASSERT_EQ(side.cycles.size(), 40u);
    double worst = 0.0;
    for (const WilcoxCycle& c : side.cycles) worst = std::max(worst, std::abs(c.advance_m - 0.05));
    std::printf("%s: worst advance error %.5f m, total %.5f m\n", side.side.c_str(), worst,
                side.total_advance_m);
    EXPECT_LT(worst, 0.002);
    EXPECT_NEAR(side.total_advance_m, 2.0, 0.005);
  }
}

}  // namespace
}  // namespace slipgraph
