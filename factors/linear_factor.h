// A residual linear in its parameter blocks, r = sum_b A_b x_b - rhs, with its constant Jacobian:
// the profiles' smoothness priors and datum in the Wilcox graph, written over blocks of nodes
// (several rows per factor) instead of one autodiff factor per node.
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace slipgraph {

class LinearFactor : public ceres::CostFunction {
 public:
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  // a[b]: rows x (size of block b); rhs: rows.
  LinearFactor(std::vector<Matrix> a, Eigen::VectorXd rhs)
      : a_(std::move(a)), rhs_(std::move(rhs)) {
    set_num_residuals(static_cast<int>(rhs_.size()));
    for (const Matrix& m : a_)
      mutable_parameter_block_sizes()->push_back(static_cast<int>(m.cols()));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    Eigen::Map<Eigen::VectorXd> r(residuals, rhs_.size());
    r = -rhs_;
    for (size_t b = 0; b < a_.size(); ++b) {
      r += a_[b] * Eigen::Map<const Eigen::VectorXd>(parameters[b], a_[b].cols());
      if (jacobians != nullptr && jacobians[b] != nullptr) {
        Eigen::Map<Matrix>(jacobians[b], a_[b].rows(), a_[b].cols()) = a_[b];
      }
    }
    return true;
  }

 private:
  std::vector<Matrix> a_;
  Eigen::VectorXd rhs_;
};

}  // namespace slipgraph
