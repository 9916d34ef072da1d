#include "solvers/ipd_noise_likelihood.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>

namespace slipgraph {
namespace {

// Eq. (15)-shaped terms: pose noise of a few cm and each input's PSD spread over the pose.
ipd::PredictionCovarianceTerms RandomTerms(std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  ipd::PredictionCovarianceTerms terms;
  terms.measurement = Eigen::Vector3d(4e-4, 4e-4, 1e-4).asDiagonal();
  for (int j = 0; j < 3; ++j) {
    Eigen::Matrix<double, 3, 2> G;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 2; ++c) G(r, c) = n(*rng);
    }
    G.col(0)[j] += 3.0;  // each input mostly drives "its" axis
    terms.input[j] = G * G.transpose();
  }
  return terms;
}

// A residual drawn from N(0, S(q)).
Eigen::Vector3d Draw(const ipd::PredictionCovarianceTerms& terms, const Eigen::Vector3d& q,
                     std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Matrix3d L = terms.Total(q).llt().matrixL();
  return L * Eigen::Vector3d(n(*rng), n(*rng), n(*rng));
}

TEST(IpdNoiseLikelihood, GradientMatchesCentralDifferences) {
  std::mt19937 rng(3);
  const int blocks = 3;
  std::vector<NoiseLikelihoodSegment> segments;
  for (int k = 0; k < 30; ++k) {
    NoiseLikelihoodSegment s;
    s.terms = RandomTerms(&rng);
    s.block = k % blocks;
    s.residual = Draw(s.terms, Eigen::Vector3d(2e-3, 1e-3, 5e-4), &rng);
    segments.push_back(s);
  }
  NoiseLikelihoodOptions options;
  options.segment_weight = 0.25;
  std::uniform_real_distribution<double> u(-9.0, -5.0);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> log_q(3 * blocks);
    for (double& v : log_q) v = u(rng);
    std::vector<double> gradient(3 * blocks);
    NoiseObjective(segments, blocks, options, log_q.data(), gradient.data());
    for (int i = 0; i < 3 * blocks; ++i) {
      std::vector<double> plus = log_q, minus = log_q;
      const double h = 1e-6;
      plus[i] += h;
      minus[i] -= h;
      const double numeric = (NoiseObjective(segments, blocks, options, plus.data(), nullptr) -
                              NoiseObjective(segments, blocks, options, minus.data(), nullptr)) /
                             (2.0 * h);
      // Central differences of a smooth function of order 10-100: error ~ h^2 f''' + eps f / h.
      EXPECT_NEAR(gradient[i], numeric, 1e-5 * (1.0 + std::abs(numeric))) << "parameter " << i;
    }
  }
}

TEST(IpdNoiseLikelihood, RecoversANoiseThatChangesWithTheTerrain) {
  // 40 blocks of 40 independent segments; the noise doubles (x4 in q) halfway, as on a softer
  // terrain. Each block's q is known from its 40 residuals plus its neighbours through the walk.
  std::mt19937 rng(11);
  const int blocks = 40;
  const Eigen::Vector3d q_first(2e-3, 1e-3, 4e-4), q_second = 4.0 * q_first;
  std::vector<NoiseLikelihoodSegment> segments;
  for (int b = 0; b < blocks; ++b) {
    for (int k = 0; k < 40; ++k) {
      NoiseLikelihoodSegment s;
      s.terms = RandomTerms(&rng);
      s.block = b;
      s.residual = Draw(s.terms, b < blocks / 2 ? q_first : q_second, &rng);
      segments.push_back(s);
    }
  }
  NoiseLikelihoodOptions options;
  options.segment_weight = 1.0;  // independent draws
  options.q_prior = Eigen::Vector3d::Constant(1e-3);
  const NoiseLikelihoodResult fit = FitNoiseByLikelihood(segments, blocks, options);
  ASSERT_TRUE(fit.ok) << fit.message;
  ASSERT_EQ(fit.q.size(), static_cast<size_t>(blocks));
  // Away from the change (5 blocks either side), the mean over a half is within 30 % of the
  // truth. Over ten seeds of this test the ratios spread with an sd of about 0.07 (the three
  // inputs overlap, so the q trade off), worst 0.79; with 200 segments a block all are within
  // 0.05 of 1 (no bias).
  Eigen::Vector3d mean[2];
  for (int half = 0; half < 2; ++half) {
    mean[half].setZero();
    int n = 0;
    for (int b = half == 0 ? 0 : blocks / 2 + 5; b < (half == 0 ? blocks / 2 - 5 : blocks); ++b) {
      mean[half] += fit.q[b];
      ++n;
    }
    mean[half] /= n;
    const Eigen::Vector3d truth = half == 0 ? q_first : q_second;
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(mean[half][j] / truth[j], 1.0, 0.3) << "half " << half << " q" << j;
    }
  }
  // And the change is seen: the noise after it several times the noise before (truth: 4).
  for (int j = 0; j < 3; ++j) EXPECT_GT(mean[1][j], 2.5 * mean[0][j]) << j;
}

TEST(IpdNoiseLikelihood, RefusesBadOptionsAndNoData) {
  NoiseLikelihoodOptions options;
  options.q_prior[1] = 0.0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_FALSE(FitNoiseByLikelihood({NoiseLikelihoodSegment{}}, 1, options).ok);
  EXPECT_FALSE(FitNoiseByLikelihood({}, 1, NoiseLikelihoodOptions{}).ok);
}

}  // namespace
}  // namespace slipgraph
