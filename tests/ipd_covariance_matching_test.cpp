// The IPD predictions' covariance matching (solvers/ipd_covariance_matching.h): calibrated
// predictions keep their covariance, over-confident ones are scaled to their errors, a prediction
// counts only once its segment has ended, and one wild error is clipped.
#include "solvers/ipd_covariance_matching.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace slipgraph {
namespace {

// A prediction starting at t (2 s segment) with the given errors and predicted sd per axis.
PredictionError Prediction(double t, const Eigen::Vector3d& error, const Eigen::Vector3d& sd) {
  PredictionError e;
  e.t_start = t;
  e.along_m = error[0], e.cross_m = error[1], e.heading_rad = error[2];
  e.predicted_covariance = sd.cwiseAbs2().asDiagonal();
  return e;
}

// Runs predictions every 0.5 s whose errors have `true_sd` while the model predicts `sd`;
// returns the scale at the end.
Eigen::Vector3d ScaleAfter(const Eigen::Vector3d& true_sd, const Eigen::Vector3d& sd, int count) {
  IpdCovarianceMatching matching(20.0);
  std::mt19937 random(3);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < count; ++i) {
    const double t = 0.5 * i;
    const Eigen::Vector3d error(true_sd[0] * gauss(random), true_sd[1] * gauss(random),
                                true_sd[2] * gauss(random));
    PredictionError e = Prediction(t, error, sd);
    matching.Apply(t + 2.0, &e);
  }
  return matching.scale();
}

TEST(IpdCovarianceMatching, LeavesCalibratedPredictionsAlone) {
  const Eigen::Vector3d sd(0.05, 0.06, 0.04);
  const Eigen::Vector3d scale = ScaleAfter(sd, sd, 400);
  for (int a = 0; a < 3; ++a) EXPECT_LT(scale[a], 1.35);  // inflate only, and little
}

TEST(IpdCovarianceMatching, ScalesOverConfidentPredictionsToTheirErrors) {
  // Errors three times the predicted sd: the scale approaches 3 (a little less: the clip at the
  // 99.9 % point trims the tail of the squared errors).
  const Eigen::Vector3d sd(0.05, 0.06, 0.04);
  const Eigen::Vector3d scale = ScaleAfter(3.0 * sd, sd, 400);
  for (int a = 0; a < 3; ++a) {
    EXPECT_GT(scale[a], 2.0);
    EXPECT_LT(scale[a], 3.3);
  }
}

TEST(IpdCovarianceMatching, CountsAPredictionOnlyOnceItsSegmentHasEnded) {
  IpdCovarianceMatching matching(20.0);
  const Eigen::Vector3d sd(0.05, 0.05, 0.05);
  PredictionError wild = Prediction(0.0, 10.0 * sd, sd);
  matching.Apply(2.0, &wild);
  PredictionError before_end = Prediction(1.5, Eigen::Vector3d::Zero(), sd);
  matching.Apply(3.5, &before_end);  // starts before the first segment ends: unscaled
  EXPECT_DOUBLE_EQ(before_end.predicted_covariance(0, 0), 0.05 * 0.05);
  PredictionError after_end = Prediction(2.0, Eigen::Vector3d::Zero(), sd);
  matching.Apply(4.0, &after_end);
  // One error of 10 sd, clipped at 10.83 (not 100): mean 1 + (10.83 - 1) / 20.
  const double expected = 1.0 + (10.83 - 1.0) / 20.0;
  EXPECT_NEAR(after_end.predicted_covariance(0, 0), 0.05 * 0.05 * expected, 1e-12);
  EXPECT_NEAR(matching.scale()[2], std::sqrt(expected), 1e-12);
}

TEST(IpdCovarianceMatching, OffWithNoMemory) {
  IpdCovarianceMatching matching(0.0);
  const Eigen::Vector3d sd(0.05, 0.05, 0.05);
  for (int i = 0; i < 20; ++i) {
    PredictionError e = Prediction(0.5 * i, 10.0 * sd, sd);
    matching.Apply(0.5 * i + 2.0, &e);
    EXPECT_DOUBLE_EQ(e.predicted_covariance(1, 1), 0.05 * 0.05);
  }
  // ... which the calibrations' options take as off, not as an error; a negative memory is one.
  IpdOptions options;
  options.match_covariance_segments = 0.0;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error)) << error;
  options.match_covariance_segments = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
}

}  // namespace
}  // namespace slipgraph
