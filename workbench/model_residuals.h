// The model beside the measurements: every measurement factor of the Ward graph evaluated at a
// smoother's solution, as time series per stream, plus what the workbench's effect tests need at
// each state (the force balance the model cannot explain, the effect terms' derivatives, the
// operating conditions).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "model/model_config.h"
#include "solvers/batch_smoother.h"
#include "workbench/graph_score_test.h"

namespace slipgraph {

// One measurement stream's residuals at the solution: r = (z - h(x)) / sd, and sd.
struct StreamResiduals {
  std::string name;  // "accelerometer", "gyro", "encoder_left", "encoder_right", "gnss"
  std::vector<double> t, normalized, sd;
  // Index of the state each residual belongs to.
  std::vector<size_t> state;
};

// Per state (wheel sample): the solution and the accelerometer's view of it.
struct StateContext {
  double t = 0.0;
  std::array<double, 7> x{};
  double pitch_rad = 0.0, roll_rad = 0.0;  // attitude (REP-103) at the state
  // The accelerometer sample's unexplained force balance
  //   u = a_x - (f_tire(x) + c_ax + b_ax)   (m/s^2, a_dist not subtracted)
  // where the model says a_dist ~ 0 (weak constraint 2 on), NaN elsewhere or without a sample;
  // and its sd.
  double unexplained_force = 0.0;
  double force_sd = 0.0;
  // The part of u's uncertainty that comes from the solution's own uncertainty: the
  // sensitivity of u to v_bx and the wheel speeds times their marginal sd. It is not noise that
  // averages out: the tire law's slope makes 1 cm/s of velocity worth about 0.6 m/s^2.
  double force_state_sd = 0.0;
  // Correlation of that error with the next state's (the velocity error's, from the chain
  // covariance; 1 when unknown, i.e. fully correlated).
  double force_state_next_correlation = 1.0;
  double accel_x = 0.0, accel_z = 0.0;  // the IMU sample nearest the state (NaN if none)
  double gyro_z = 0.0;
  std::array<double, 2> wheel_speeds{};  // measured driven-side [left, right]
};

struct ModelResiduals {
  std::vector<StreamResiduals> streams;
  std::vector<StateContext> states;
  double accel_offset = 0.0, gyro_offset = 0.0;
  // Every effect term (the smoother's options' terms, factors/effect_term.h): its name, the
  // solution's magnitude (0 when off), and its score test on the whole graph (untested for those
  // in the model); and the graph's projector for signatures that test other force shapes (null
  // if it could not be built).
  std::vector<std::string> effect_names;
  std::vector<double> effects;
  std::vector<GraphScore> graph_scores;
  std::vector<double> gnss_times;  // the GNSS samples' times, for averaging
  std::shared_ptr<const GraphProjector> graph;
  const StreamResiduals* Find(const std::string& name) const;
  // The index of the term named `effect` in effect_names, or -1.
  int EffectIndex(const std::string& effect) const;
};

// Distance driven along the path (m) at each state: the integral of |v_bx| over the states.
std::vector<double> PathDistances(const ModelResiduals& m);

// Evaluates the factors of the log's batch problem at `solution` (a SmoothBatch result on the same
// log and model). Throws std::invalid_argument when the solution does not match the log.
ModelResiduals EvaluateModelResiduals(const DriveLog& log, const ModelConfig& model,
                                      const SmootherResult& solution,
                                      const BatchSmootherOptions& options = {});

}  // namespace slipgraph
