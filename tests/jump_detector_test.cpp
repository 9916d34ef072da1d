#include "solvers/jump_detector.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

namespace slipgraph {
namespace {

using Detector = JumpDetector<2, 1>;

// A Kalman filter on a constant 2-vector theta seen through z_k = h_k' theta + w_k, w ~ N(0, R).
struct LinearFilter {
  Eigen::Vector2d theta = Eigen::Vector2d::Zero();
  Eigen::Matrix2d P = Eigen::Matrix2d::Identity();
  double R = 0.01;

  static Detector::Jacobian H(int k) {
    Detector::Jacobian h;
    h << 1.0, std::sin(0.7 * k);
    return h;
  }
  // Innovation, its covariance, and the update; returns the gain used.
  Detector::Gain Update(const Detector::Jacobian& h, double r, double S) {
    const Detector::Gain K = P * h.transpose() / S;
    theta += K * r;
    P = (Eigen::Matrix2d::Identity() - K * h) * P;
    return K;
  }
};

// The detector's Bayes factor and jump estimate are the exact ones of the linear-Gaussian
// problem: the innovations after the jump are G nu + w with w ~ N(0, S) independent, nu ~
// N(0, J), so ln B = ln N(r; 0, S + G J G') - ln N(r; 0, S) over the stacked innovations and the
// jump's posterior mean is J G' (S + G J G')^-1 r.
TEST(JumpDetector, BayesFactorAndEstimateAreTheExactLinearGaussianOnes) {
  constexpr int kMeasurements = 6;
  JumpDetectorOptions options;
  options.jump_sd = 0.3;
  options.log_bayes_factor = -1e9;  // report the first hypothesis once it has every measurement
  options.min_measurements = kMeasurements;
  options.window = 100;
  Detector detector(options);
  LinearFilter filter;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, std::sqrt(filter.R));
  const Eigen::Vector2d truth(0.4, -0.2);  // the filter starts at 0: a "jump" from its prior
  Eigen::Matrix2d F = Eigen::Matrix2d::Identity();
  Eigen::VectorXd r(kMeasurements), S(kMeasurements);
  Eigen::MatrixXd G(kMeasurements, 2);
  Detector::Jump jump;
  bool fired = false;
  for (int k = 0; k < kMeasurements; ++k) {
    const Detector::Jacobian h = LinearFilter::H(k);
    r[k] = h.dot(truth) + noise(rng) - h.dot(filter.theta);
    S[k] = (h * filter.P * h.transpose())(0, 0) + filter.R;
    G.row(k) = h * F;
    fired = detector.Measure(k, Detector::Residual::Constant(r[k]), h,
                             Eigen::Matrix<double, 1, 1>::Constant(S[k]), &jump);
    if (fired) break;
    const Detector::Gain K = filter.Update(h, r[k], S[k]);
    detector.Updated(K, h);
    F = (Eigen::Matrix2d::Identity() - K * h) * F;
  }
  ASSERT_TRUE(fired);
  EXPECT_EQ(jump.t, 0.0);
  EXPECT_EQ(jump.measurements, kMeasurements);
  const Eigen::Matrix2d J = Eigen::Matrix2d::Identity() * options.jump_sd * options.jump_sd;
  const Eigen::MatrixXd S0 = S.asDiagonal();
  const Eigen::MatrixXd S1 = S0 + G * J * G.transpose();
  const auto log_normal = [&](const Eigen::MatrixXd& cov) {
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(cov);
    return -0.5 * r.dot(ldlt.solve(r)) - 0.5 * ldlt.vectorD().array().log().sum();
  };
  EXPECT_NEAR(jump.log_bayes_factor, log_normal(S1) - log_normal(S0), 1e-9);
  // F at the last measurement (the hypothesis has seen kMeasurements - 1 updates).
  const Eigen::Vector2d nu = J * G.transpose() * S1.ldlt().solve(r);
  EXPECT_TRUE(jump.correction.isApprox(F * nu, 1e-9))
      << jump.correction.transpose() << " vs " << (F * nu).transpose();
}

// A jump in a long-settled filter: found within a few measurements, placed at the right
// measurement, and 30 measurements after the jump the estimate is close to the new value, where
// the filter alone (its covariance small) has barely moved.
TEST(JumpDetector, FindsAndCorrectsAJumpThatASettledFilterFollowsSlowly) {
  JumpDetectorOptions options;  // defaults: sd 0.05, ln B 6.9, 40 hypotheses
  Detector detector(options);
  LinearFilter filter;
  filter.R = 0.0025;
  LinearFilter blind = filter;  // the same filter without the detector
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, std::sqrt(filter.R));
  Eigen::Vector2d truth(0.10, -0.05);
  constexpr int kJumpAt = 400;
  int found_at = -1;
  Detector::Jump jump;
  Eigen::Vector2d jump_t_and_k(-1.0, -1.0);
  for (int k = 0; k < kJumpAt + 30; ++k) {
    if (k == kJumpAt) truth += Eigen::Vector2d(-0.08, 0.06);
    const Detector::Jacobian h = LinearFilter::H(k);
    const double z = h.dot(truth) + noise(rng);
    for (LinearFilter* f : {&filter, &blind}) {
      const double r = z - h.dot(f->theta);
      const double S = (h * f->P * h.transpose())(0, 0) + f->R;
      if (f == &filter) {
        if (detector.Measure(k, Detector::Residual::Constant(r), h,
                             Eigen::Matrix<double, 1, 1>::Constant(S), &jump)) {
          filter.theta += jump.correction;
          filter.P += jump.covariance;
          detector.Restart();
          if (found_at < 0) found_at = k, jump_t_and_k = Eigen::Vector2d(jump.t, k);
          continue;
        }
        detector.Updated(filter.Update(h, r, S), h);
      } else {
        blind.Update(h, r, S);
      }
    }
  }
  ASSERT_GE(found_at, kJumpAt) << "a jump declared before there was one";
  EXPECT_LE(found_at, kJumpAt + 10);
  EXPECT_NEAR(jump_t_and_k[0], kJumpAt, 2.0);
  // 30 measurements after the jump: a third of the blind filter's error or less (what is left
  // is noise: the estimate's own sd is about 0.013 per component then).
  EXPECT_LT((filter.theta - truth).norm(), 3.0 * std::sqrt(filter.P.trace()));
  EXPECT_LT((filter.theta - truth).norm(), 0.3 * (blind.theta - truth).norm())
      << "with the jump " << filter.theta.transpose() << ", blind " << blind.theta.transpose()
      << ", truth " << truth.transpose();
}

// Without a jump the Bayes-factor threshold of 1000 over 40 open hypotheses keeps false jumps
// rare: 3 in 40000 measurements of a settled filter (8 runs), where a sign or scale error in d or
// C fires hundreds of times.
TEST(JumpDetector, FalseJumpsAreRareWithoutOne) {
  int fired = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    Detector detector(JumpDetectorOptions{});
    LinearFilter filter;
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, std::sqrt(filter.R));
    const Eigen::Vector2d truth(0.1, 0.2);
    Detector::Jump jump;
    for (int k = 0; k < 5000; ++k) {
      const Detector::Jacobian h = LinearFilter::H(k);
      const double r = h.dot(truth) + noise(rng) - h.dot(filter.theta);
      const double S = (h * filter.P * h.transpose())(0, 0) + filter.R;
      if (k > 50 && detector.Measure(k, Detector::Residual::Constant(r), h,
                                     Eigen::Matrix<double, 1, 1>::Constant(S), &jump)) {
        ++fired;
        detector.Restart();
      }
      detector.Updated(filter.Update(h, r, S), h);
    }
  }
  EXPECT_LE(fired, 10);
  RecordProperty("false_jumps", fired);
}

// Overlapping measurements (each datum in `overlap` of them) count 1 / overlap each: the same
// innovations give half the evidence with overlap 2.
TEST(JumpDetector, OverlapDividesTheEvidence) {
  JumpDetectorOptions options;
  options.log_bayes_factor = -1e9;
  options.min_measurements = 3;
  JumpDetectorOptions halved = options;
  halved.overlap = 2.0;
  Detector a(options), b(halved);
  Detector::Jump ja, jb;
  const Detector::Jacobian h = LinearFilter::H(1);
  const auto S = Eigen::Matrix<double, 1, 1>::Constant(0.01);
  bool fa = false, fb = false;
  for (int k = 0; k < 3; ++k) {
    fa = a.Measure(k, Detector::Residual::Constant(0.2), h, S, &ja);
    fb = b.Measure(k, Detector::Residual::Constant(0.2), h, S, &jb);
  }
  ASSERT_TRUE(fa && fb);
  EXPECT_GT(ja.log_bayes_factor, jb.log_bayes_factor + 1.0);
  // The same as doubling S.
  Detector c(options);
  Detector::Jump jc;
  for (int k = 0; k < 3; ++k) c.Measure(k, Detector::Residual::Constant(0.2), h, 2.0 * S, &jc);
  EXPECT_NEAR(jc.log_bayes_factor, jb.log_bayes_factor, 1e-12);
}

}  // namespace
}  // namespace slipgraph
