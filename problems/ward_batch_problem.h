// Builds the whole-log factor graph of the Ward & Iagnemma model: one 7-state block per wheel
// sample, the constant IMU offsets as one 2-block, and the factors of factors/ between them:
// dynamics, disturbance random walk (robust), accelerometer and yaw gyro, encoders, GNSS
// velocity, weak constraints 1, 2, 4 and 5 as soft priors, and priors on the first state and the
// offsets. Initial values come from an EKF run over the same log.
#pragma once

#include <ceres/problem.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "model/model_config.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {

struct WardProblemOptions {
  VelocityModel velocity_model = VelocityModel::kAccelerometerDriven;
  bool use_gps = true;
  // |w| below this reads as a stopped wheel (weak constraints 1 and 4), as in the EKF.
  double wheel_still_radps = EkfOptions().wheel_still_radps;
  // Huber scale of the disturbance random walk, in standard deviations of one step.
  double disturbance_huber_sigmas = 3.0;
  // Cauchy scale of the disturbance decay prior (weak constraint 2), in its standard deviations:
  // quadratic near zero (a creeping disturbance decays), nearly flat far out (a hold-back's
  // disturbance, which the accelerometer and the tire law insist on, is left alone).
  double decay_cauchy_sigmas = 1.0;
  // Density (m/s^2 sqrt(s)) of that prior. The EKF's WC2 applies only under its conditions with
  // WeakConstraintConfig::sd_act_quickly; this always-on robust form is stronger near zero.
  double decay_sd_density = 0.1;
};

struct WardProblem {
  std::vector<double> times;                        // state times: the wheel samples
  std::vector<std::array<double, 7>> states;        // parameter blocks, one per time
  std::array<double, 2> offsets{};                  // [c_ax, c_gz]
  std::vector<std::array<double, 2>> wheel_speeds;  // measured driven-side speeds per state
  std::unique_ptr<ceres::Problem> problem;
  // Residual blocks by factor kind ("dynamics", "accelerometer", ...), for cost breakdowns.
  std::map<std::string, std::vector<ceres::ResidualBlockId>> blocks;
  // How many factors of each kind went in, for the report.
  long dynamics = 0, accelerometer = 0, gyro = 0, encoders = 0, gnss = 0, oppose_motion = 0,
       act_quickly = 0, at_rest = 0, bounds = 0;
};

// Half the sum of squared (loss-applied) residuals of each factor kind at the current values.
std::map<std::string, double> CostByKind(const WardProblem& problem);

// Throws std::invalid_argument when the EKF run has no estimates (no wheel data).
std::unique_ptr<WardProblem> BuildWardBatchProblem(const DriveLog& log, const ModelConfig& model,
                                                   const FilterResult& ekf,
                                                   const WardProblemOptions& options = {});

}  // namespace slipgraph
