// An estimate of a known truth checked in the truth's units, not in the sd the estimator reports
// alone: within `tolerance` of the truth, with a finite, positive sd no wider than `max_sd` (an
// inflated sd cannot widen the bound) that still covers the error (|error| <= 3 sd: a collapsed
// sd fails too). Use: EXPECT_TRUE(testing::EstimateOf(value, sd, truth, tolerance, max_sd)).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

namespace slipgraph {
namespace testing {

inline ::testing::AssertionResult EstimateOf(double value, double sd, double truth,
                                             double tolerance, double max_sd) {
  const double error = value - truth;
  const auto failure = [&](const char* what) {
    return ::testing::AssertionFailure()
           << what << ": estimate " << value << " +- " << sd << " of truth " << truth << " (error "
           << error << ", tolerance " << tolerance << ", sd at most " << max_sd << ")";
  };
  if (!std::isfinite(value) || !std::isfinite(sd) || !(sd > 0.0)) {
    return failure("not a finite estimate with a positive sd");
  }
  if (std::abs(error) > tolerance) return failure("farther from the truth than the tolerance");
  if (sd > max_sd) return failure("an sd wider than the bound");
  if (std::abs(error) > 3.0 * sd) return failure("an error beyond 3 sd");
  return ::testing::AssertionSuccess();
}

}  // namespace testing
}  // namespace slipgraph
