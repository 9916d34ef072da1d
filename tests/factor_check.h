// Checks a Ceres cost function's Jacobians against numeric differentiation with
// ceres::GradientChecker, failing the test (not printing) when they disagree.
#pragma once

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace slipgraph {
namespace testing {

inline void ExpectJacobiansMatchNumeric(const ceres::CostFunction& cost,
                                        const std::vector<const double*>& parameters,
                                        double relative_precision = 1e-6) {
  // GradientChecker differentiates with Ridders' method, whose default first step (1 % of the
  // parameter) straddles the kinks of the smoothed force laws' higher derivatives at v_rel = 0
  // and the hinges; a small first step keeps the numeric side honest there.
  ceres::NumericDiffOptions numeric;
  numeric.ridders_relative_initial_step_size = 1e-5;
  const std::vector<const ceres::Manifold*>* euclidean = nullptr;  // all blocks Euclidean
  ceres::GradientChecker checker(&cost, euclidean, numeric);
  ceres::GradientChecker::ProbeResults results;
  const bool ok = checker.Probe(parameters.data(), relative_precision, &results);
  EXPECT_TRUE(ok) << results.error_log;
  EXPECT_TRUE(results.return_value);
}

// Residuals of a cost function at the given parameters.
inline std::vector<double> Residuals(const ceres::CostFunction& cost,
                                     const std::vector<const double*>& parameters) {
  std::vector<double> residuals(cost.num_residuals());
  EXPECT_TRUE(cost.Evaluate(parameters.data(), residuals.data(), nullptr));
  return residuals;
}

}  // namespace testing
}  // namespace slipgraph
