// One Ceres problem over one or more logs of the same robot in which the model's parameters are
// parameter blocks beside the states: the tire and rolling laws' coefficients and the two sides'
// rolling-radius errors (factors/tire_law_coefficients.h), shared by every log, and each
// log's states and constant IMU offsets (every factor of problems/ward_factor_source, as the
// whole-log smoother). Weak Gaussian priors around the model's values keep the parameters the
// data do not see where the user put them; bounds keep the law physical.
#pragma once

#include <ceres/problem.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "factors/tire_law_coefficients.h"
#include "io/drive_log.h"
#include "io/state_estimate.h"
#include "model/model_config.h"
#include "problems/ward_factor_source.h"

namespace slipgraph {

// The prior sd of each identified parameter around the model's value, and its bounds.
struct IdentificationPriors {
  std::array<double, kLawCoefficientCount> law_sd = {0.5, 20.0, 0.1, 0.05, 0.05};
  std::array<double, kLawCoefficientCount> law_min = {0.02, 0.5, -0.5, 0.0, 0.0};
  std::array<double, kLawCoefficientCount> law_max = {2.0, 200.0, 1.0, 0.5, 0.5};
  double radius_error_sd = 0.05;
  double radius_error_bound = 0.3;
};

struct IdentificationLogBlocks {
  std::vector<double> times;
  std::vector<std::array<double, 7>> states;
  std::array<double, 2> offsets{};  // [c_ax, c_gz]
};

struct IdentificationProblem {
  std::array<double, kLawCoefficientCount> law{};
  std::array<double, 2> radius_error{};  // [left, right]
  std::vector<IdentificationLogBlocks> logs;
  std::unique_ptr<ceres::Problem> problem;
  // Residual blocks by factor kind ("accelerometer", "gnss", ...), over all logs.
  std::map<std::string, std::vector<ceres::ResidualBlockId>> blocks;
  FactorCounts counts;
};

// logs[i] with initial[i], a front end's estimates over it (one per wheel sample). The model's
// effects are not modelled here (an effect and the law would explain the same force); the
// options' stiffness walk is ignored. Throws std::invalid_argument when the sizes differ or a
// log has no wheel data.
std::unique_ptr<IdentificationProblem> BuildIdentificationProblem(
    const std::vector<const DriveLog*>& logs, const ModelConfig& model,
    const std::vector<const std::vector<WardEstimate>*>& initial, const WardProblemOptions& options,
    const IdentificationPriors& priors = {});

}  // namespace slipgraph
