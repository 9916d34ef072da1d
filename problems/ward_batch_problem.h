// Builds the whole-log factor graph of the Ward & Iagnemma model: one 7-state block per wheel
// sample, the constant IMU offsets as one 2-block, every step's factors from WardFactorSource
// (dynamics, disturbance random walk (robust), accelerometer and yaw gyro, encoders, GNSS
// velocity, weak constraints 1, 2, 4 and 5 as soft priors), and priors on the first state and the
// offsets. Initial values come from a front end's run over the same log.
#pragma once

#include <ceres/problem.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "factors/effect_term.h"
#include "io/drive_log.h"
#include "io/state_estimate.h"
#include "model/model_config.h"
#include "problems/ward_factor_source.h"

namespace slipgraph {

struct WardProblem {
  WardProblem() = default;
  WardProblem(const WardProblem&) = delete;
  WardProblem& operator=(const WardProblem&) = delete;
  // Deletes the problem, then the cost and loss functions of its residual blocks: `problem` owns
  // neither (Ceres would keep a map entry for each, about 1 kB a state, and free them slowly).
  ~WardProblem();

  std::vector<double> times;                  // state times: the wheel samples
  std::vector<std::array<double, 7>> states;  // parameter blocks, one per time
  std::array<double, 2> offsets{};            // [c_ax, c_gz]
  // The effect terms the model names (factors/effect_term.h) and their magnitudes, in that
  // order: one parameter block when there is any, with a weak prior of each term's prior_sd.
  std::vector<const EffectTerm*> effect_terms;
  std::vector<double> effects;
  std::vector<std::string> ignored_effects;  // named in the model, no term for them
  // The tire law's slip-stiffness walk (WardProblemOptions::stiffness_walk_sd): one block per
  // node, empty when off.
  std::vector<double> stiffness;
  std::vector<std::array<double, 2>> wheel_speeds;  // measured driven-side speeds per state
  std::unique_ptr<ceres::Problem> problem;
  // Residual blocks by factor kind ("dynamics", "accelerometer", ...), for cost breakdowns.
  std::map<std::string, std::vector<ceres::ResidualBlockId>> blocks;
  // The state index each of those blocks belongs to (same order; -1 for the global priors; a
  // stiffness node's prior or walk step, the last state at or before the node).
  std::map<std::string, std::vector<long>> block_states;
  FactorCounts counts;
};

// Half the sum of squared (loss-applied) residuals of each factor kind at the current values.
std::map<std::string, double> CostByKind(const WardProblem& problem);

// `initial`: a front end's estimates over the log, one per wheel sample (the states' times and
// initial values). Throws std::invalid_argument when it is empty (no wheel data).
std::unique_ptr<WardProblem> BuildWardBatchProblem(const DriveLog& log, const ModelConfig& model,
                                                   const std::vector<WardEstimate>& initial,
                                                   const WardProblemOptions& options = {});

}  // namespace slipgraph
