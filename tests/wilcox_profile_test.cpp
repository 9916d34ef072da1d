// Profiles on a grid: linear between nodes, clamped at the run's ends, a contact patch's mean by
// Simpson's rule (exact for a linear profile), and the run of nodes covering an interval.
#include "factors/wilcox_profile.h"

#include <gtest/gtest.h>

#include <vector>

namespace slipgraph {
namespace {

using wilcox::GridRun;

struct Nodes {
  std::vector<double> values;
  std::vector<const double*> pointers;
  explicit Nodes(std::vector<double> v) : values(std::move(v)) {
    for (const double& x : values) pointers.push_back(&x);
  }
};

TEST(WilcoxProfile, LinearBetweenNodesAndClampedAtTheEnds) {
  const GridRun run{10, 4, 0.01};  // nodes at x = 0.10, 0.11, 0.12, 0.13
  const Nodes n({1.0, 2.0, 4.0, 3.0});
  EXPECT_NEAR(wilcox::ProfileAt(run, n.pointers.data(), 0.105), 1.5, 1e-12);
  EXPECT_NEAR(wilcox::ProfileAt(run, n.pointers.data(), 0.1175), 3.5, 1e-12);
  EXPECT_NEAR(wilcox::ProfileAt(run, n.pointers.data(), 0.05), 1.0, 1e-12);
  EXPECT_NEAR(wilcox::ProfileAt(run, n.pointers.data(), 0.2), 3.0, 1e-12);
}

TEST(WilcoxProfile, PatchMeanExactForALine) {
  const GridRun run{0, 11, 0.01};
  std::vector<double> v;
  for (int i = 0; i < 11; ++i) v.push_back(0.5 + 2.0 * 0.01 * i);  // y = 0.5 + 2 x
  const Nodes n(v);
  EXPECT_NEAR(wilcox::WheelProfileAt(run, n.pointers.data(), 0.05, 0.04), 0.5 + 2.0 * 0.05, 1e-12);
  EXPECT_NEAR(wilcox::WheelProfileAt(run, n.pointers.data(), 0.05, 0.0), 0.6, 1e-12);
}

TEST(WilcoxProfile, RunCoveringAnInterval) {
  const GridRun run = wilcox::RunCovering(0.105, 0.2, 0.02, 0.01, 100);
  EXPECT_EQ(run.first, 8);
  EXPECT_EQ(run.first + run.count - 1, 22);
  const GridRun start = wilcox::RunCovering(0.0, 0.01, 0.05, 0.01, 100);
  EXPECT_EQ(start.first, 0);
  const GridRun end = wilcox::RunCovering(0.95, 2.0, 0.0, 0.01, 100);
  EXPECT_EQ(end.first + end.count, 100);
}

}  // namespace
}  // namespace slipgraph
