#include "problems/ward_factor_source.h"

#include <ceres/loss_function.h>
#include <ceres/normal_prior.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "factors/accelerometer_factor.h"
#include "factors/at_rest_prior.h"
#include "factors/bound_prior.h"
#include "factors/catalogue_terms.h"
#include "factors/diagonal_prior.h"
#include "factors/disturbance_decay_prior.h"
#include "factors/encoder_factor.h"
#include "factors/frames.h"
#include "factors/gnss_velocity_factor.h"
#include "factors/linear_factor.h"
#include "factors/no_pull_back_prior.h"
#include "factors/oppose_motion_prior.h"
#include "factors/rate_bound_prior.h"
#include "factors/state_walk_factor.h"
#include "factors/tire_law_uncertainty.h"
#include "factors/ward_dynamics_factor.h"
#include "io/gnss_heading_offsets.h"
#include "io/measurement_stream.h"
#include "io/nearest_time.h"
#include "model/option_check.h"

namespace slipgraph {

bool WardProblemOptions::IsValid(std::string* error) const {
  for (const std::string& kind : only_kinds) {
    const std::vector<std::string>& known = WardFactorKinds();
    if (std::find(known.begin(), known.end(), kind) == known.end()) {
      *error = "WardProblemOptions.only_kinds: '" + kind + "' is not a factor kind";
      return false;
    }
  }
  return OptionCheck("WardProblemOptions", error)
      .Positive("gnss_gate_chi2", gnss_gate_chi2)
      .NonNegative("gnss_max_consecutive_rejections", gnss_max_consecutive_rejections)
      .Positive("wheel_still_radps", wheel_still_radps)
      .Positive("disturbance_huber_sigmas", disturbance_huber_sigmas)
      .Positive("decay_cauchy_sigmas", decay_cauchy_sigmas)
      .Positive("decay_sd_density", decay_sd_density)
      .NonNegative("no_pull_back_sd_density", no_pull_back_sd_density)
      .Require("tire_law_correlation_time_s",
               std::isnan(tire_law_correlation_time_s) || tire_law_correlation_time_s >= 0.0,
               tire_law_correlation_time_s, "must be non-negative (NaN: the model's)")
      .Require("omega_walk_radps2_per_sqrt_hz",
               std::isnan(omega_walk_radps2_per_sqrt_hz) || omega_walk_radps2_per_sqrt_hz > 0.0,
               omega_walk_radps2_per_sqrt_hz, "must be positive (NaN: the model's)")
      .NonNegative("omega_walk_huber_sigmas", omega_walk_huber_sigmas)
      .NonNegative("stiffness_prior_sd", stiffness_prior_sd)
      .Positive("stiffness_node_s", stiffness_node_s)
      .NonNegative("stiffness_walk_sd", stiffness_walk_sd)
      .Require("stiffness_min", stiffness_min > -1.0 && stiffness_min <= 0.0, stiffness_min,
               "must lie in (-1, 0] (the law's scale 1 + theta stays positive)");
}

using namespace ward;  // NOLINT: state indices

// Sensor context at a time: the latest attitude and accelerometer reading at or before it.
struct WardFactorSource::Context {
  Attitude<double> attitude{0.0, 0.0};
  double pitch_sd = 0.0;  // the attitude source's stated pitch sd (0 when not given)
  double yaw = 0.0;
  bool have_attitude = false;
  double accel_x = std::nan("");
};

namespace {

// Stamps within this of a time count as at it (the EKF holds inputs the same way).
constexpr double kStampToleranceS = 1e-9;

// A body-velocity measurement with a value and a positive sd (others are left out).
bool Usable(const BodyVelocityMeasurement& m) { return std::isfinite(m.v_mps) && m.sd_mps > 0.0; }

// For samples sorted by time: begin[k] = first sample attached to state k (nearest to it, and
// within half a second of the state range), begin[n] = one past the last attached sample.
template <typename Samples>
std::vector<size_t> AttachToStates(const Samples& samples, const std::vector<double>& times) {
  const size_t n = times.size();
  std::vector<size_t> begin(n + 1, samples.size());
  size_t k = 0;
  size_t i = 0;
  while (i < samples.size() && samples[i].t < times.front() - 0.5) ++i;
  for (; i < samples.size() && samples[i].t <= times.back() + 0.5; ++i) {
    const size_t nearest = NearestInTime(times, samples[i].t, [](double time) { return time; });
    while (k <= nearest) begin[k++] = i;
  }
  while (k <= n) begin[k++] = i;
  return begin;
}

}  // namespace

std::string FactorCounts::Describe() const {
  std::ostringstream out;
  out << "factors: " << dynamics << " dynamics, " << accelerometer << " accelerometer, " << gyro
      << " gyro, " << encoders << " encoder, " << gnss << " GNSS (" << gnss_gated
      << " outliers left out), "
      << (body_velocity > 0 ? std::to_string(body_velocity) + " body velocity, " : std::string())
      << (body_velocity_too_late > 0
              ? std::to_string(body_velocity_too_late) + " body velocity too late for the window, "
              : std::string())
      << oppose_motion << " oppose-motion, " << act_quickly << " decay, "
      << (no_pull_back > 0 ? std::to_string(no_pull_back) + " no-pull-back, " : std::string())
      << (wheel_bias_checks > 0 ? std::to_string(wheel_bias_checks) + " wheels' bias check, "
                                : std::string())
      << at_rest << " at-rest, " << bounds << " bound, " << rate_bounds << " rate-bound priors";
  return out.str();
}

WardFactorSource::WardFactorSource(const DriveLog& log, const ModelConfig& model,
                                   const std::vector<WardEstimate>& initial,
                                   const WardProblemOptions& options)
    : log_(log),
      model_(model),
      initial_(initial),
      options_(options),
      params_(MakeParams(log.vehicle, model)),
      tire_uncertainty_(model.tire_uncertainty) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  const EffectTerms& terms = TermsOrCatalogue(options.effect_terms);
  for (const EffectTerm& term : terms.all()) {
    if (std::find(model.effects.begin(), model.effects.end(), term.name) != model.effects.end()) {
      effect_terms_.push_back(&term);
    }
  }
  for (const std::string& name : model.effects) {
    if (terms.Find(name) == nullptr &&
        std::find(effects_without_term_.begin(), effects_without_term_.end(), name) ==
            effects_without_term_.end()) {
      effects_without_term_.push_back(name);
    }
  }
  if (std::isfinite(options.tire_law_correlation_time_s)) {
    tire_uncertainty_.correlation_time_s = options.tire_law_correlation_time_s;
  }
  if (initial.empty()) throw std::invalid_argument("the front end produced no estimates");
  const size_t n = initial.size();
  if (!options.law_per_state.empty() && options.law_per_state.size() != n) {
    throw std::invalid_argument("law_per_state has " +
                                std::to_string(options.law_per_state.size()) + " laws for " +
                                std::to_string(n) + " states");
  }
  const size_t densities = options.disturbance_density_per_state.size();
  if (densities != 0 && densities != n) {
    throw std::invalid_argument("disturbance_density_per_state has " + std::to_string(densities) +
                                " densities for " + std::to_string(n) + " states");
  }
  times_.resize(n);
  wheel_speeds_.assign(n, {0.0, 0.0});
  stop_timers_.resize(n);
  for (size_t k = 0; k < n; ++k) times_[k] = initial[k].t;
  for (size_t k = 0; k < n && k < log.wheels.size(); ++k) {
    const SideSpeeds s = DrivenSideSpeeds(log.wheels[k], log.vehicle.type);
    wheel_speeds_[k] = {s.left_radps, s.right_radps};
  }
  // Weak constraint 4's at-rest rule as it stood at each state, as the EKF reads it.
  WheelRestTimer rest(model.weak_constraints.still_smoothing_s, options.wheel_still_radps);
  for (size_t k = 0; k < n; ++k) {
    rest.Update(times_[k], wheel_speeds_[k][0], wheel_speeds_[k][1]);
    stop_timers_[k] = rest.Timer();
  }
  imu_begin_ = AttachToStates(log.imu, times_);
  if (options.use_gps) {
    gps_begin_ = AttachToStates(log.gps, times_);
  } else {
    gps_begin_.assign(n + 1, 0);
  }
  velocity_begin_ = AttachToStates(options.body_velocity, times_);
  for (size_t i = 0; i < options.accel_bias.size(); ++i) {
    const double t = options.accel_bias[i].t;
    if (!std::isfinite(t) || (i > 0 && t < options.accel_bias[i - 1].t)) {
      throw std::invalid_argument("accel_bias[" + std::to_string(i) + "].t (" + std::to_string(t) +
                                  ") is not finite or goes back in time");
    }
  }
  accel_bias_begin_ = AttachToStates(options.accel_bias, times_);
  if (options.body_velocity_when_available) {  // the order AddLateBodyVelocity reads them in
    velocity_state_.assign(options.body_velocity.size(), n);
    for (size_t k = 0; k < n; ++k) {
      for (size_t i = velocity_begin_[k]; i < velocity_begin_[k + 1]; ++i) {
        velocity_state_[i] = k;
        velocity_by_availability_.push_back(i);
      }
    }
    std::stable_sort(velocity_by_availability_.begin(), velocity_by_availability_.end(),
                     [&](size_t a, size_t b) {
                       return options.body_velocity[a].available_t <
                              options.body_velocity[b].available_t;
                     });
  }
  if (log.imu.size() > 1) {
    imu_period_s_ = (log.imu.back().t - log.imu.front().t) / (log.imu.size() - 1);
  }
  // The gate on GNSS (WardProblemOptions::gnss_gate_chi2), against the front end's estimate at
  // each fix's state.
  gnss_.assign(log.gps.size(), GnssFix{});
  int consecutive = 0;
  // Each fix on the yaw corrected by the course, as the front end corrects it.
  const std::vector<double> heading_offsets = GnssHeadingOffsets(log, model);
  for (size_t k = 0; k < n; ++k) {
    for (size_t i = gps_begin_[k]; i < gps_begin_[k + 1]; ++i) {
      GnssFix& fix = gnss_[i];
      fix.usable = GnssAlong(k, log.gps[i], heading_offsets[i], &fix.along_mps, &fix.sd_mps);
      if (!fix.usable) continue;
      const double v = initial[k].x[ward::kVbx], sd_v = initial[k].sd[ward::kVbx];
      const double d2 =
          (fix.along_mps - v) * (fix.along_mps - v) / (sd_v * sd_v + fix.sd_mps * fix.sd_mps);
      if (!std::isfinite(d2)) {
        fix.admitted = false;
      } else if (d2 <= options.gnss_gate_chi2) {
        consecutive = 0;
      } else if (++consecutive <= options.gnss_max_consecutive_rejections) {
        fix.admitted = false;
      } else {
        consecutive = 0;
      }
    }
  }
}

size_t WardFactorSource::stiffness_node_count() const {
  if (times_.empty()) return 0;
  return static_cast<size_t>(
             std::floor((times_.back() - times_.front()) / options_.stiffness_node_s)) +
         2;
}

void WardFactorSource::StiffnessNodesAt(double t, size_t* first, double* u) const {
  const double position = std::max(0.0, (t - times_.front()) / options_.stiffness_node_s);
  const size_t last_first = stiffness_node_count() - 2;
  *first = std::min(last_first, static_cast<size_t>(std::floor(position)));
  *u = std::clamp(position - static_cast<double>(*first), 0.0, 1.0);
}

void WardFactorSource::AddStiffnessNode(size_t j, double* nodes, ceres::Problem* problem,
                                        std::vector<AddedFactor>* added) const {
  if (!(options_.stiffness_walk_sd > 0.0 && options_.stiffness_node_s > 0.0)) {
    throw std::invalid_argument("the slip-stiffness walk needs a positive density and spacing");
  }
  problem->AddParameterBlock(&nodes[j], 1);
  problem->SetParameterLowerBound(&nodes[j], 0, options_.stiffness_min);
  if (!options_.Builds(j == 0 ? "stiffness_prior" : "stiffness_walk")) return;
  if (j == 0) {
    added->push_back({"stiffness_prior",
                      problem->AddResidualBlock(
                          new ceres::NormalPrior(
                              Eigen::MatrixXd::Constant(1, 1, 1.0 / options_.stiffness_prior_sd),
                              Eigen::VectorXd::Zero(1)),
                          nullptr, &nodes[0])});
    return;
  }
  const double walk = options_.stiffness_walk_sd * std::sqrt(options_.stiffness_node_s);
  std::vector<LinearFactor::Matrix> a = {LinearFactor::Matrix::Constant(1, 1, -1.0 / walk),
                                         LinearFactor::Matrix::Constant(1, 1, 1.0 / walk)};
  added->push_back(
      {"stiffness_walk", problem->AddResidualBlock(new LinearFactor(a, Eigen::VectorXd::Zero(1)),
                                                   nullptr, &nodes[j - 1], &nodes[j])});
}

bool WardFactorSource::GnssAlong(size_t k, const GpsSample& g, double heading_offset_rad,
                                 double* along, double* sd) const {
  if (!std::isfinite(g.vx) || !std::isfinite(g.vy) || !std::isfinite(g.vz)) return false;
  const Context c = ContextAt(g.t);
  const double wheel_sum = wheel_speeds_[k][0] + wheel_speeds_[k][1];
  *along = GnssVelocityAlongBodyX(g.vx, g.vy, g.vz, c.have_attitude, c.attitude.pitch_rad,
                                  c.yaw + heading_offset_rad, wheel_sum);
  *sd = GnssVelocitySd(g, model_.measurement.gps_sd_v_mps);
  return std::isfinite(*along);
}

double EffectWindowWeight(const ModelConfig& model, const EffectTerm& term, double t) {
  return term.acts_on_windows && model.InEffectWindow(term.name, t) ? 1.0 : 0.0;
}

EffectContext EffectContextAt(const DriveLog& log, const ModelConfig& model,
                              const ward::Params& params, const EffectTerm& term, double t) {
  EffectContext c;
  c.t_s = t;
  const long a = LatestAtOrBefore(log.attitude, t, kStampToleranceS);
  if (a >= 0) c.attitude = {log.attitude[a].roll, log.attitude[a].pitch};
  c.loads = ward::ComputeAttitudeLoads(c.attitude, params);
  const long i = LatestAtOrBefore(log.imu, t, kStampToleranceS);
  if (i >= 0) c.accel_x_mps2 = log.imu[i].ax;
  c.window = EffectWindowWeight(model, term, t);
  return c;
}

WardFactorSource::Context WardFactorSource::ContextAt(double t) const {
  Context c;
  const long a = LatestAtOrBefore(log_.attitude, t, kStampToleranceS);
  if (a >= 0) {
    c.attitude = {log_.attitude[a].roll, log_.attitude[a].pitch};
    c.yaw = log_.attitude[a].yaw;
    c.pitch_sd = std::isfinite(log_.attitude[a].sd_pitch) ? log_.attitude[a].sd_pitch : 0.0;
    c.have_attitude = true;
  }
  const long i = LatestAtOrBefore(log_.imu, t, kStampToleranceS);
  if (i >= 0) c.accel_x = log_.imu[i].ax;
  return c;
}

void WardFactorSource::AddStatePrior(size_t k, double* x, ceres::Problem* problem,
                                     std::vector<AddedFactor>* added) const {
  if (!options_.Builds("first_state_prior")) return;
  std::array<double, kStateSize> mean, sd;
  for (int i = 0; i < kStateSize; ++i) {
    mean[i] = initial_[k].x[i];
    sd[i] = std::max(initial_[k].sd[i], 1e-6);
  }
  added->push_back(
      {"first_state_prior",
       problem->AddResidualBlock(DiagonalPrior<kStateSize>::Create(mean, sd), nullptr, x)});
}

void WardFactorSource::AddOffsetPrior(const std::array<double, 2>& mean, double* offsets,
                                      ceres::Problem* problem,
                                      std::vector<AddedFactor>* added) const {
  if (!options_.Builds("offset_prior")) return;
  const SensorNoise& noise = model_.measurement;
  const ProcessNoiseConfig& q = model_.process;
  added->push_back({"offset_prior", problem->AddResidualBlock(
                                        DiagonalPrior<2>::Create(
                                            mean, {noise.imu_sd_accel_mps2 + q.accel_bias_sd_mps2,
                                                   noise.imu_sd_gyro_radps + q.gyro_bias_sd_radps}),
                                        nullptr, offsets)});
}

bool WardFactorSource::PushesAlong(size_t k, double vel_dir, const Params& params) const {
  std::array<double, kStateSize> measured = initial_[k].x;
  measured[kOmegaLeft] = wheel_speeds_[k][0];
  measured[kOmegaRight] = wheel_speeds_[k][1];
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(ContextAt(times_[k]).attitude, params);
  const double f_tire = HeldStillTireForce(measured.data(), loads, params);
  return vel_dir * (f_tire - loads.gravity_along_x_mps2) > 0.0;
}

void WardFactorSource::AddStep(size_t k, double* previous, double* x, const GlobalBlocks& globals,
                               ceres::Problem* problem, std::vector<AddedFactor>* added,
                               FactorCounts* counts) const {
  double* offsets = globals.offsets;
  double* effects = globals.effects;
  double* stiffness_nodes = globals.stiffness;
  Params params = params_;
  if (k < options_.law_per_state.size()) {
    params.tire = options_.law_per_state[k].tire;
    params.rolling = options_.law_per_state[k].rolling;
  }
  const SensorNoise& noise = model_.measurement;
  const ProcessNoiseConfig& q = model_.process;
  const WeakConstraintConfig& wc = model_.weak_constraints;
  const size_t n = size();
  const auto Add = [&](const char* kind, ceres::CostFunction* cost, ceres::LossFunction* loss,
                       auto... blocks) {
    if (!options_.Builds(kind)) {
      delete cost;
      delete loss;
      return;
    }
    added->push_back({kind, problem->AddResidualBlock(cost, loss, blocks...)});
  };
  const auto& w = wheel_speeds_[k];

  // Measurements.
  if (k < log_.wheels.size()) {
    Add("encoder", EncoderFactor::Create(w[0], w[1], noise.wheels_sd_omega_radps), nullptr, x);
    ++counts->encoders;
  }
  for (size_t i = imu_begin_[k]; i < imu_begin_[k + 1]; ++i) {
    const ImuSample& imu = log_.imu[i];
    const Context c = ContextAt(imu.t);
    double sd_a = noise.imu_sd_accel_mps2;
    if (options_.velocity_model == VelocityModel::kAccelerometerDriven) {
      sd_a = std::sqrt(sd_a * sd_a +
                       TireLawSampleVariance(initial_[k].x.data(),
                                             ward::ComputeAttitudeLoads(c.attitude, params), params,
                                             tire_uncertainty_, imu_period_s_));
    }
    if (std::isfinite(imu.ax) && options_.Builds("accelerometer")) {
      AccelerometerUnknowns unknowns;
      std::vector<double*> blocks = {x, offsets};
      if (globals.law != nullptr) {
        unknowns.law = true;
        blocks.insert(blocks.end(), {globals.law, globals.radius_error});
      } else if (stiffness_nodes != nullptr) {
        size_t j = 0;
        unknowns.stiffness = true;
        StiffnessNodesAt(imu.t, &j, &unknowns.stiffness_share);
        blocks.insert(blocks.end(), {&stiffness_nodes[j], &stiffness_nodes[j + 1]});
      }
      if (effects != nullptr) {
        unknowns.effects = effect_terms_;
        unknowns.t_s = imu.t;
        for (const EffectTerm* term : effect_terms_) {
          unknowns.windows.push_back(EffectWindowWeight(model_, *term, imu.t));
        }
        blocks.push_back(effects);
      }
      added->push_back({"accelerometer",
                        problem->AddResidualBlock(
                            AccelerometerFactor::Create(params, c.attitude, imu.ax, sd_a, unknowns),
                            nullptr, blocks)});
      ++counts->accelerometer;
    }
    if (std::isfinite(imu.gz)) {
      Add("gyro", YawGyroFactor::Create(imu.gz, noise.imu_sd_gyro_radps), nullptr, x, offsets);
      ++counts->gyro;
    }
  }
  for (size_t i = gps_begin_[k]; i < gps_begin_[k + 1]; ++i) {
    const GnssFix& fix = gnss_[i];
    if (!fix.usable) continue;
    if (!fix.admitted) {
      ++counts->gnss_gated;
      continue;
    }
    Add("gnss", GnssVelocityFactor::Create(fix.along_mps, fix.sd_mps), nullptr, x);
    ++counts->gnss;
  }
  // Another estimator's body-x velocity: the same residual as GNSS projected on body x (online,
  // only if it already exists; AddLateBodyVelocity adds it when it does).
  for (size_t i = velocity_begin_[k]; i < velocity_begin_[k + 1]; ++i) {
    const BodyVelocityMeasurement& m = options_.body_velocity[i];
    if (!Usable(m)) continue;
    if (options_.body_velocity_when_available && m.available_t > times_[k]) continue;
    Add("body_velocity", GnssVelocityFactor::Create(m.v_mps, m.sd_mps), nullptr, x);
    ++counts->body_velocity;
  }

  // The front end's wheels' checks: (c_ax + b_ax - measured) / sd.
  for (size_t i = accel_bias_begin_[k]; i < accel_bias_begin_[k + 1]; ++i) {
    const AccelBiasMeasurement& m = options_.accel_bias[i];
    if (!(std::isfinite(m.bias_mps2) && m.sd_mps2 > 0.0)) continue;
    constexpr int kOffsets = 2, kAccelOffset = 0;  // the offsets block: [c_ax, c_gz]
    LinearFactor::Matrix on_state = LinearFactor::Matrix::Zero(1, kStateSize);
    LinearFactor::Matrix on_offsets = LinearFactor::Matrix::Zero(1, kOffsets);
    on_state(0, kAccelBias) = 1.0 / m.sd_mps2;
    on_offsets(0, kAccelOffset) = 1.0 / m.sd_mps2;
    Add("wheel_bias_check",
        new LinearFactor({on_state, on_offsets},
                         Eigen::VectorXd::Constant(1, m.bias_mps2 / m.sd_mps2)),
        nullptr, x, offsets);
    ++counts->wheel_bias_checks;
  }

  // Weak constraints as soft priors, their densities scaled by the state's cycle time.
  const double dt_cycle =
      k + 1 < n ? times_[k + 1] - times_[k] : (k > 0 ? times_[k] - times_[k - 1] : 0.01);
  const double root_dt = std::sqrt(std::max(dt_cycle, 1e-6));
  const double still = options_.wheel_still_radps;
  const double vel_dir = DriveDirection(w[0], w[1], still);
  if (vel_dir != 0.0) {
    // The EKF's doubt of a large push (weak_constraints.cpp) as the loss's weight: Cauchy's
    // 1 / (1 + r^2 / b^2) at r = a_dist / sd equals 1 / (1 + (a_dist / scale)^2) at b = scale / sd.
    const double sd = wc.sd_oppose_motion / root_dt;
    const double scale = wc.oppose_motion_cauchy_scale_mps2;
    Add("oppose_motion", OpposeMotionPrior::Create(vel_dir, sd),
        scale > 0.0 ? new ceres::CauchyLoss(scale / sd) : nullptr, x);
    ++counts->oppose_motion;
    if (options_.no_pull_back_sd_density > 0.0 && PushesAlong(k, vel_dir, params)) {
      Add("no_pull_back",
          NoPullBackPrior::Create(vel_dir, options_.no_pull_back_sd_density / root_dt), nullptr, x);
      ++counts->no_pull_back;
    }
  }
  if (stop_timers_[k].AtRestFor(times_[k], wc.stop_time_s)) {
    Add("at_rest", AtRestPrior::Create(wc.sd_at_rest / root_dt, 0.1 * wc.sd_at_rest / root_dt),
        nullptr, x);
    ++counts->at_rest;
  }
  // Slip is meaningless on (nearly) stopped wheels: there the prior stays on.
  const double surface_mps = 0.5 * params_.wheel_radius_m * std::abs(w[0] + w[1]);
  const double gate_slip = options_.decay_gate_slip.size() == n ? options_.decay_gate_slip[k]
                                                                : initial_[k].slip.slip_ema;
  const bool slipping =
      gate_slip >= wc.slip_threshold && surface_mps > model_.immobilization.min_wheel_speed_mps;
  if (!slipping) {
    Add("act_quickly", DisturbanceDecayPrior::Create(options_.decay_sd_density / root_dt),
        new ceres::CauchyLoss(options_.decay_cauchy_sigmas), x);
    ++counts->act_quickly;
  }
  Add("bound",
      BoundPrior::Create(
          {wc.max_v_bx_mps, wc.max_accel_bias_mps2, wc.max_a_dist_mps2, wc.max_gyro_bias_radps},
          wc.sd_bound / root_dt),
      nullptr, x);
  ++counts->bounds;

  // Dynamics from state k-1 (none for the first state of a problem).
  if (k == 0 || previous == nullptr) return;
  const double dt = times_[k] - times_[k - 1];
  if (dt <= 0.0) return;
  // The attitude at t_{k-1}; the accelerometer sample that ends the interval (its mean over it).
  Context c = ContextAt(times_[k - 1]);
  c.accel_x = ContextAt(times_[k]).accel_x;
  const bool accel_driven =
      options_.velocity_model == VelocityModel::kAccelerometerDriven && std::isfinite(c.accel_x);
  const double sd_v = accel_driven
                          ? std::sqrt(AccelInputDensitySq(noise.imu_sd_accel_mps2, c.pitch_sd,
                                                          params.gravity_mps2, imu_period_s_) *
                                      dt)
                          : q.v_bx_mps2_per_sqrt_hz * std::sqrt(dt);
  const double omega_walk = std::isfinite(options_.omega_walk_radps2_per_sqrt_hz)
                                ? options_.omega_walk_radps2_per_sqrt_hz
                                : q.omega_radps2_per_sqrt_hz;
  const bool robust_omega = options_.omega_walk_huber_sigmas > 0.0;
  const auto gauss_markov = [dt](double sd, double tau) {
    return std::sqrt(GaussMarkovStepVariance(sd, tau, dt));
  };
  const std::array<double, WardDynamicsFactor::kResiduals> sd_step = {
      sd_v,
      gauss_markov(q.accel_bias_sd_mps2, q.accel_bias_tau_s),
      robust_omega ? 1e6 : omega_walk * std::sqrt(dt),
      robust_omega ? 1e6 : omega_walk * std::sqrt(dt),
      q.yaw_rate_radps2_per_sqrt_hz * std::sqrt(dt),
      gauss_markov(q.gyro_bias_sd_radps, q.gyro_bias_tau_s)};
  Add("dynamics",
      WardDynamicsFactor::Create(params, c.attitude, dt, accel_driven ? c.accel_x : std::nan(""),
                                 sd_step),
      nullptr, previous, x, offsets);
  if (robust_omega) {
    Add("wheel_speed_walk", WheelSpeedWalkFactor::Create(omega_walk * std::sqrt(dt)),
        new ceres::HuberLoss(options_.omega_walk_huber_sigmas), previous, x);
  }
  const double w3 = k - 1 < options_.disturbance_density_per_state.size()
                        ? options_.disturbance_density_per_state[k - 1]
                        : q.a_dist_mps3_per_sqrt_hz;
  Add("disturbance_walk", DisturbanceWalkFactor::Create(w3 * std::sqrt(dt)),
      new ceres::HuberLoss(options_.disturbance_huber_sigmas), previous, x);
  Add("rate_bound",
      RateBoundPrior::Create({wc.max_v_bx_rate_mps2, wc.max_accel_bias_rate_mps3}, dt,
                             wc.sd_bound / std::sqrt(dt)),
      nullptr, previous, x);
  ++counts->rate_bounds;
  ++counts->dynamics;
}

void WardFactorSource::AddLateBodyVelocity(size_t k, const std::function<double*(size_t)>& state_of,
                                           ceres::Problem* problem, std::vector<AddedFactor>* added,
                                           FactorCounts* counts) const {
  if (!options_.body_velocity_when_available || k == 0 || k >= times_.size() ||
      !options_.Builds("body_velocity")) {
    return;
  }
  const auto available = [&](size_t i) { return options_.body_velocity[i].available_t; };
  auto it = std::upper_bound(velocity_by_availability_.begin(), velocity_by_availability_.end(),
                             times_[k - 1], [&](double t, size_t i) { return t < available(i); });
  for (; it != velocity_by_availability_.end() && available(*it) <= times_[k]; ++it) {
    const BodyVelocityMeasurement& m = options_.body_velocity[*it];
    if (velocity_state_[*it] >= k) continue;  // on state k or later: AddStep has it
    if (!Usable(m)) continue;
    double* x = state_of(velocity_state_[*it]);
    if (x == nullptr) {
      ++counts->body_velocity_too_late;
      continue;
    }
    const ceres::ResidualBlockId id =
        problem->AddResidualBlock(GnssVelocityFactor::Create(m.v_mps, m.sd_mps), nullptr, x);
    added->push_back({"body_velocity", id});
    ++counts->body_velocity;
  }
}

}  // namespace slipgraph
