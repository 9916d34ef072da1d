// Ward & Iagnemma eq. (12): the first sample initialises the average, the weight is 2 / (1 + p),
// a constant input is held, and a step is followed at the stated rate.
#include "solvers/ema.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slipgraph {
namespace {

TEST(ExponentialMovingAverage, FirstSampleThenWeightTwoOverOnePlusP) {
  ExponentialMovingAverage ema(9.0);  // weight 0.2
  EXPECT_FALSE(ema.initialised());
  EXPECT_EQ(ema.Add(1.0), 1.0);
  EXPECT_DOUBLE_EQ(ema.Add(2.0), 1.0 + 0.2 * (2.0 - 1.0));
  // A step from 0 to 1: after n samples 1 - 0.8^n.
  ema.Reset(0.0);
  double v = 0.0;
  for (int n = 1; n <= 10; ++n) v = ema.Add(1.0);
  EXPECT_NEAR(v, 1.0 - std::pow(0.8, 10), 1e-12);
  ema.Reset(3.0);
  EXPECT_EQ(ema.value(), 3.0);
  EXPECT_EQ(ema.Add(3.0), 3.0);
}

}  // namespace
}  // namespace slipgraph
