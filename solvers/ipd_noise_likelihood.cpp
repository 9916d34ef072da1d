#include "solvers/ipd_noise_likelihood.h"

#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

namespace slipgraph {
namespace {

class NoiseObjectiveFunction : public ceres::FirstOrderFunction {
 public:
  NoiseObjectiveFunction(const std::vector<NoiseLikelihoodSegment>& segments, int blocks,
                         const NoiseLikelihoodOptions& options)
      : segments_(segments), blocks_(blocks), options_(options) {}

  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    *cost = NoiseObjective(segments_, blocks_, options_, parameters, gradient);
    return std::isfinite(*cost);  // a step into a non-positive S: the line search steps back
  }
  int NumParameters() const override { return 3 * blocks_; }

 private:
  const std::vector<NoiseLikelihoodSegment>& segments_;
  int blocks_;
  NoiseLikelihoodOptions options_;
};

}  // namespace

bool NoiseLikelihoodOptions::IsValid(std::string* error) const {
  if (!(block_s > 0.0 && log_q_walk_sd > 0.0 && log_q_prior_sd > 0.0 && segment_weight > 0.0 &&
        max_iterations > 0 && (q_prior.array() > 0.0).all())) {
    *error =
        "block_s, log_q_walk_sd, log_q_prior_sd, segment_weight, max_iterations and q_prior "
        "must be positive";
    return false;
  }
  return true;
}

double SegmentNoiseNegativeLogLikelihood(const NoiseLikelihoodSegment& segment,
                                         const Eigen::Vector3d& q, Eigen::Vector3d* gradient) {
  const Eigen::LLT<Eigen::Matrix3d> llt(segment.terms.Total(q));
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::Matrix3d L = llt.matrixL();
  const double log_det = 2.0 * L.diagonal().array().log().sum();
  const Eigen::Vector3d s_inv_r = llt.solve(segment.residual);
  if (gradient != nullptr) {
    const Eigen::Matrix3d s_inv = llt.solve(Eigen::Matrix3d::Identity());
    for (int j = 0; j < 3; ++j) {
      const Eigen::Matrix3d& B = segment.terms.input[j];
      (*gradient)[j] += 0.5 * (s_inv.cwiseProduct(B).sum() - s_inv_r.dot(B * s_inv_r));
    }
  }
  return 0.5 * (segment.residual.dot(s_inv_r) + log_det);
}

double NoiseObjective(const std::vector<NoiseLikelihoodSegment>& segments, int blocks,
                      const NoiseLikelihoodOptions& options, const double* log_q,
                      double* gradient) {
  if (gradient != nullptr) std::fill(gradient, gradient + 3 * blocks, 0.0);
  const auto q_of = [&](int b) {
    return Eigen::Vector3d(std::exp(log_q[3 * b]), std::exp(log_q[3 * b + 1]),
                           std::exp(log_q[3 * b + 2]));
  };
  double cost = 0.0;
  for (const NoiseLikelihoodSegment& segment : segments) {
    const Eigen::Vector3d q = q_of(segment.block);
    Eigen::Vector3d d_q = Eigen::Vector3d::Zero();
    cost += options.segment_weight *
            SegmentNoiseNegativeLogLikelihood(segment, q, gradient != nullptr ? &d_q : nullptr);
    if (!std::isfinite(cost)) return cost;
    if (gradient != nullptr) {
      for (int j = 0; j < 3; ++j) {
        gradient[3 * segment.block + j] += options.segment_weight * d_q[j] * q[j];  // d q/d log q
      }
    }
  }
  const double walk_information =
      1.0 / (options.log_q_walk_sd * options.log_q_walk_sd * options.block_s);
  for (int b = 1; b < blocks; ++b) {
    for (int j = 0; j < 3; ++j) {
      const double step = log_q[3 * b + j] - log_q[3 * (b - 1) + j];
      cost += 0.5 * walk_information * step * step;
      if (gradient != nullptr) {
        gradient[3 * b + j] += walk_information * step;
        gradient[3 * (b - 1) + j] -= walk_information * step;
      }
    }
  }
  const double prior_information = 1.0 / (options.log_q_prior_sd * options.log_q_prior_sd);
  for (int j = 0; j < 3; ++j) {
    const double offset = log_q[j] - std::log(options.q_prior[j]);
    cost += 0.5 * prior_information * offset * offset;
    if (gradient != nullptr) gradient[j] += prior_information * offset;
  }
  return cost;
}

NoiseLikelihoodResult FitNoiseByLikelihood(const std::vector<NoiseLikelihoodSegment>& segments,
                                           int blocks, const NoiseLikelihoodOptions& options,
                                           const std::vector<Eigen::Vector3d>& q_start) {
  NoiseLikelihoodResult result;
  if (!options.IsValid(&result.message)) return result;
  if (blocks <= 0 || segments.empty()) {
    result.message = "no segments";
    return result;
  }
  std::vector<double> log_q(3 * blocks);
  for (int b = 0; b < blocks; ++b) {
    const Eigen::Vector3d& start =
        static_cast<int>(q_start.size()) == blocks ? q_start[b] : options.q_prior;
    for (int j = 0; j < 3; ++j) log_q[3 * b + j] = std::log(std::max(start[j], 1e-12));
  }
  if (!std::isfinite(NoiseObjective(segments, blocks, options, log_q.data(), nullptr))) {
    result.message = "a segment's covariance is not positive definite at the start";
    return result;
  }
  ceres::GradientProblem problem(new NoiseObjectiveFunction(segments, blocks, options));
  ceres::GradientProblemSolver::Options solver_options;
  solver_options.max_num_iterations = options.max_iterations;
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(solver_options, problem, log_q.data(), &summary);
  result.message = summary.message;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.ok = summary.IsSolutionUsable();
  result.q.resize(blocks);
  for (int b = 0; b < blocks; ++b) {
    for (int j = 0; j < 3; ++j) result.q[b][j] = std::exp(log_q[3 * b + j]);
  }
  return result;
}

}  // namespace slipgraph
