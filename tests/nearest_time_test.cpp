#include "io/nearest_time.h"

#include <gtest/gtest.h>

#include <vector>

namespace slipgraph {
namespace {

struct Stamped {
  double t;
};

TEST(NearestInTime, NearestWithTiesToTheEarlierAndClampedAtTheEnds) {
  const std::vector<Stamped> s = {{0.0}, {1.0}, {2.0}, {4.0}};
  const auto at = [&](double t) {
    return NearestInTime(s, t, [](const Stamped& e) { return e.t; });
  };
  EXPECT_EQ(at(-5.0), 0u);
  EXPECT_EQ(at(0.0), 0u);
  EXPECT_EQ(at(0.4), 0u);
  EXPECT_EQ(at(0.5), 0u);  // a tie: the earlier
  EXPECT_EQ(at(0.6), 1u);
  EXPECT_EQ(at(2.0), 2u);
  EXPECT_EQ(at(3.0), 2u);
  EXPECT_EQ(at(3.1), 3u);
  EXPECT_EQ(at(9.0), 3u);
  const std::vector<double> one = {7.0};
  EXPECT_EQ(NearestInTime(one, -1.0, [](double t) { return t; }), 0u);
  EXPECT_EQ(NearestInTime(one, 9.0, [](double t) { return t; }), 0u);
}

}  // namespace
}  // namespace slipgraph
