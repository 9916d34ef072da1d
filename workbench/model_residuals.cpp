#include "workbench/model_residuals.h"

#include <ceres/cost_function.h>

#include <cmath>
#include <stdexcept>

#include "factors/catalogue_terms.h"
#include "io/measurement_stream.h"
#include "problems/ward_batch_problem.h"

namespace slipgraph {

const StreamResiduals* ModelResiduals::Find(const std::string& name) const {
  for (const StreamResiduals& s : streams) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

int ModelResiduals::EffectIndex(const std::string& effect) const {
  for (size_t i = 0; i < effect_names.size(); ++i) {
    if (effect_names[i] == effect) return static_cast<int>(i);
  }
  return -1;
}

namespace {

// Evaluates one residual block: residuals and, when wanted, the Jacobian of the first residual
// with respect to each parameter block (row-major, sizes given).
struct Evaluated {
  std::vector<double> r;
  std::vector<std::vector<double>> jacobians;
};

Evaluated Evaluate(const ceres::Problem& problem, ceres::ResidualBlockId id) {
  const ceres::CostFunction* cost = problem.GetCostFunctionForResidualBlock(id);
  Evaluated out;
  out.r.resize(cost->num_residuals());
  const auto& sizes = cost->parameter_block_sizes();
  out.jacobians.resize(sizes.size());
  std::vector<double*> jac(sizes.size());
  for (size_t i = 0; i < sizes.size(); ++i) {
    out.jacobians[i].resize(sizes[i] * cost->num_residuals());
    jac[i] = out.jacobians[i].data();
  }
  double c = 0.0;
  problem.EvaluateResidualBlock(id, false, &c, out.r.data(), jac.data());
  return out;
}

}  // namespace

std::vector<double> PathDistances(const ModelResiduals& m) {
  std::vector<double> s(m.states.size(), 0.0);
  for (size_t k = 1; k < s.size(); ++k) {
    s[k] = s[k - 1] + std::abs(m.states[k - 1].x[ward::kVbx]) * (m.states[k].t - m.states[k - 1].t);
  }
  return s;
}

ModelResiduals EvaluateModelResiduals(const DriveLog& log, const ModelConfig& model,
                                      const SmootherResult& solution,
                                      const BatchSmootherOptions& options) {
  // The same graph with every effect's term present (held at the solution's magnitudes), so the
  // accelerometer factors give the derivatives with respect to each.
  const EffectTerms& terms = TermsOrCatalogue(options.problem.effect_terms);
  ModelConfig all = model;
  all.effects.clear();
  for (const EffectTerm& term : terms.all()) all.effects.push_back(term.name);
  const WardProblemOptions problem_options = WithFilterSettings(options.problem, options.filter);
  std::unique_ptr<WardProblem> problem =
      BuildWardBatchProblem(log, all, solution.ekf.estimates, problem_options);
  const size_t n = problem->states.size();
  if (solution.estimates.size() != n) {
    throw std::invalid_argument("diagnosis: the solution has " +
                                std::to_string(solution.estimates.size()) + " states, the log " +
                                std::to_string(n));
  }
  ModelResiduals out;
  for (size_t k = 0; k < n; ++k) problem->states[k] = solution.estimates[k].x;
  out.accel_offset = solution.estimates.back().accel_offset_mps2;
  out.gyro_offset = solution.estimates.back().gyro_offset_radps;
  problem->offsets = {out.accel_offset, out.gyro_offset};
  for (const EffectTerm* term : problem->effect_terms) out.effect_names.push_back(term->name);
  for (const EffectEstimate& e : solution.effects) {
    const int index = out.EffectIndex(e.name);
    if (index >= 0) problem->effects[index] = e.value;
  }
  out.effects = problem->effects;
  // The law's stiffness walk where the null model has one (DiagnosisOptions::varying_law_*); a
  // solution without it (a failed solve) leaves the nodes at the law's own stiffness.
  if (problem->stiffness.size() == solution.stiffness.size()) {
    problem->stiffness = solution.stiffness;
  }
  for (const GpsSample& g : log.gps) out.gnss_times.push_back(g.t);

  out.states.resize(n);
  for (size_t k = 0; k < n; ++k) {
    StateContext& s = out.states[k];
    s.t = problem->times[k];
    s.x = problem->states[k];
    s.wheel_speeds = problem->wheel_speeds[k];
    s.unexplained_force = std::nan("");
    s.force_sd = std::nan("");
    if (k < solution.velocity_next_correlation.size()) {
      s.force_state_next_correlation = solution.velocity_next_correlation[k];
    }
    // The latest attitude at or before the state (1 us tolerance for stamp rounding), and the
    // IMU sample nearest it: the latest within half a 100 Hz period after, if not staler than 50
    // ms.
    const long a = LatestAtOrBefore(log.attitude, s.t, 1e-6);
    if (a >= 0) s.pitch_rad = log.attitude[a].pitch, s.roll_rad = log.attitude[a].roll;
    long i = LatestAtOrBefore(log.imu, s.t, 0.005);
    if (i >= 0 && log.imu[i].t < s.t - 0.05) i = -1;
    s.accel_x = i >= 0 ? log.imu[i].ax : std::nan("");
    s.accel_z = i >= 0 ? log.imu[i].az : std::nan("");
    s.gyro_z = i >= 0 ? log.imu[i].gz : std::nan("");
  }
  const ceres::Problem& p = *problem->problem;
  const auto Blocks = [&](const char* kind) {
    static const std::vector<ceres::ResidualBlockId> kNone;
    static const std::vector<long> kNoStates;
    const auto it = problem->blocks.find(kind);
    const auto st = problem->block_states.find(kind);
    return std::make_pair(it == problem->blocks.end() ? &kNone : &it->second,
                          st == problem->block_states.end() ? &kNoStates : &st->second);
  };
  // Where the model says the disturbance is ~0 (weak constraint 2's prior is on).
  std::vector<bool> decay_on(n, false);
  {
    const auto [ids, states] = Blocks("act_quickly");
    for (size_t b = 0; b < ids->size(); ++b) {
      if ((*states)[b] >= 0) decay_on[(*states)[b]] = true;
    }
  }
  StreamResiduals accel, gyro, left, right, gnss;
  accel.name = "accelerometer", gyro.name = "gyro", gnss.name = "gnss";
  left.name = "encoder_left", right.name = "encoder_right";
  const auto Push = [](StreamResiduals* s, double t, double r, double sd, size_t k) {
    s->t.push_back(t), s->normalized.push_back(r), s->sd.push_back(sd), s->state.push_back(k);
  };
  {
    const auto [ids, states] = Blocks("accelerometer");
    for (size_t b = 0; b < ids->size(); ++b) {
      const size_t k = (*states)[b];
      const Evaluated e = Evaluate(p, (*ids)[b]);
      // r = (a - pred) / sd with pred linear in a_dist: d r / d a_dist = -1 / sd.
      const double sd = -1.0 / e.jacobians[0][ward::kAdist];
      Push(&accel, out.states[k].t, e.r[0], sd, k);
      StateContext& s = out.states[k];
      if (decay_on[k]) {
        s.unexplained_force = e.r[0] * sd + s.x[ward::kAdist];
        s.force_sd = sd;
        const auto& j = e.jacobians[0];
        const auto& state_sd = solution.estimates[k].sd;
        s.force_state_sd =
            sd * std::sqrt(std::pow(j[ward::kVbx] * state_sd[ward::kVbx], 2) +
                           std::pow(j[ward::kOmegaLeft] * state_sd[ward::kOmegaLeft], 2) +
                           std::pow(j[ward::kOmegaRight] * state_sd[ward::kOmegaRight], 2));
      }
    }
  }
  {
    const auto [ids, states] = Blocks("gyro");
    for (size_t b = 0; b < ids->size(); ++b) {
      const size_t k = (*states)[b];
      const Evaluated e = Evaluate(p, (*ids)[b]);
      Push(&gyro, out.states[k].t, e.r[0], -1.0 / e.jacobians[0][ward::kYawRate], k);
    }
  }
  {
    const auto [ids, states] = Blocks("encoder");
    for (size_t b = 0; b < ids->size(); ++b) {
      const size_t k = (*states)[b];
      const Evaluated e = Evaluate(p, (*ids)[b]);
      const double sd = std::abs(1.0 / e.jacobians[0][ward::kOmegaLeft]);
      Push(&left, out.states[k].t, e.r[0], sd, k);
      Push(&right, out.states[k].t, e.r[1], sd, k);
    }
  }
  {
    const auto [ids, states] = Blocks("gnss");
    for (size_t b = 0; b < ids->size(); ++b) {
      const size_t k = (*states)[b];
      const Evaluated e = Evaluate(p, (*ids)[b]);
      Push(&gnss, out.states[k].t, e.r[0], std::abs(1.0 / e.jacobians[0][ward::kVbx]), k);
    }
  }
  out.streams = {accel, gyro, left, right, gnss};
  std::vector<int> in_model;
  for (const std::string& name : model.effects) {
    if (out.EffectIndex(name) >= 0) in_model.push_back(out.EffectIndex(name));
  }
  auto graph = std::make_shared<GraphProjector>(*problem, in_model);
  out.graph_scores = graph->EffectScores();
  out.graph = std::move(graph);
  return out;
}

}  // namespace slipgraph
