// The EKF's Kalman update: rows applied one after the other equal the stacked update with a
// diagonal R, in Joseph form (state, covariance and log-likelihood); the gate's closed forms for
// one and two rows equal the factorized distance.
#include "solvers/ekf_update.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

namespace slipgraph {
namespace {

using ekf::kStateSize;
using ekf::MeasurementRows;
using ekf::StateMatrix;
using ekf::StateVector;
using Dyn = Eigen::MatrixXd;

StateMatrix RandomCovariance(int seed) {
  std::srand(seed);
  const StateMatrix a = StateMatrix::Random();
  return a * a.transpose() + 0.1 * StateMatrix::Identity();
}

// The rows stacked: H, diagonal R, nu, and S = H P H' + R.
struct Stacked {
  Dyn H, R, S;
  Eigen::VectorXd nu;
};
Stacked Stack(const MeasurementRows& rows, const StateMatrix& P) {
  const int m = rows.size();
  Stacked out{Dyn(m, kStateSize), Dyn::Zero(m, m), Dyn(), Eigen::VectorXd(m)};
  for (int i = 0; i < m; ++i) {
    out.H.row(i) = rows.jacobian(i);
    out.R(i, i) = rows.variance(i);
    out.nu(i) = rows.innovation(i);
  }
  out.S = out.H * P * out.H.transpose() + out.R;
  return out;
}

MeasurementRows ThreeRows() {
  MeasurementRows rows;
  ekf::StateRow h;
  h << 0.5, 1.0, 1.0, -3.0, 2.5, 0.0, 0.0;  // an accelerometer-like row
  rows.Add(0.3, h, 0.04, "accelerometer");
  rows.AddOnState(3, -0.2, 0.0025, "encoder_left");
  rows.AddOnState(0, 0.1, 0.01);  // unnamed
  return rows;
}

TEST(EkfUpdate, SequentialRowsEqualTheStackedUpdate) {
  const MeasurementRows rows = ThreeRows();
  const StateMatrix P0 = RandomCovariance(3);
  StateVector x0;
  x0 << 0.5, 0.01, -0.2, 2.0, 2.1, 0.05, 0.001;

  // The stacked update: K = P H' S^-1, x + K nu, P - K S K'; log N(nu; 0, S).
  const int m = rows.size();
  const Stacked stacked = Stack(rows, P0);
  const Dyn& S = stacked.S;
  const Eigen::VectorXd& nu = stacked.nu;
  const Dyn K = P0 * stacked.H.transpose() * S.inverse();
  const StateVector x_stacked = x0 + K * nu;
  const StateMatrix P_stacked = P0 - K * S * K.transpose();
  const double log_likelihood_stacked =
      -0.5 * (nu.dot(S.ldlt().solve(nu)) + std::log(S.determinant()) + m * std::log(2 * M_PI));

  StateVector x = x0;
  StateMatrix P = P0;
  double normalized[ekf::kMaxRows];
  const double log_likelihood = ekf::ApplySequentialUpdate(rows, true, &x, &P, normalized);
  EXPECT_LT((x - x_stacked).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((P - P_stacked).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(log_likelihood, log_likelihood_stacked, 1e-10);
  // The first row's normalized innovation is its own: nu / sqrt(h P h' + r).
  EXPECT_NEAR(normalized[0], nu(0) / std::sqrt(S(0, 0)), 1e-12);
  // Without the likelihood no logarithm is summed; the update is the same.
  StateVector x2 = x0;
  StateMatrix P2 = P0;
  EXPECT_EQ(ekf::ApplySequentialUpdate(rows, false, &x2, &P2), 0.0);
  EXPECT_EQ(x2, x);
  EXPECT_EQ(P2, P);
}

TEST(EkfUpdate, DistanceClosedFormsEqualTheFactorization) {
  const StateMatrix P = RandomCovariance(5);
  const MeasurementRows three = ThreeRows();
  for (int m = 1; m <= 3; ++m) {
    MeasurementRows rows;
    for (int i = 0; i < m; ++i) {
      rows.Add(three.innovation(i), three.jacobian(i), three.variance(i));
    }
    const Stacked stacked = Stack(rows, P);
    const Dyn& S = stacked.S;
    const Eigen::VectorXd& nu = stacked.nu;
    const ekf::InnovationDistance d = ekf::DistanceOf(rows, P);
    EXPECT_NEAR(d.mahalanobis, nu.dot(S.inverse() * nu), 1e-10) << m << " rows";
    EXPECT_NEAR(d.det_s, S.determinant(), 1e-10 * std::abs(S.determinant())) << m << " rows";
  }
}

TEST(EkfUpdate, RowsKnowTheirStateAndName) {
  const MeasurementRows rows = ThreeRows();
  EXPECT_EQ(rows.size(), 3);
  EXPECT_EQ(rows.on_state(0), -1);
  EXPECT_EQ(rows.on_state(1), 3);
  EXPECT_EQ(rows.on_state(2), 0);
  EXPECT_STREQ(rows.name(1), "encoder_left");
  EXPECT_EQ(rows.name(2), nullptr);
  // A row with a single entry other than 1 is not a unit row.
  MeasurementRows scaled;
  scaled.Add(0.0, 2.0 * ekf::StateRow::Unit(4), 1.0);
  EXPECT_EQ(scaled.on_state(0), -1);
}

}  // namespace
}  // namespace slipgraph
