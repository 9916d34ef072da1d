#include "solvers/disturbance_imm.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/option_check.h"

namespace slipgraph {

bool DisturbanceImmOptions::IsValid(std::string* error) const {
  return OptionCheck("DisturbanceImmOptions", error)
      .Positive("quiet_a_dist_tau_s", quiet_a_dist_tau_s)
      .Positive("quiet_a_dist_sd_mps2", quiet_a_dist_sd_mps2)
      .Positive("held_a_dist_mps3_per_sqrt_hz", held_a_dist_mps3_per_sqrt_hz)
      .Positive("quiet_mean_s", quiet_mean_s)
      .Positive("change_mean_s", change_mean_s)
      .Positive("held_mean_s", held_mean_s)
      .NonNegative("mix_interval_s", mix_interval_s);
}

DisturbanceImm::DisturbanceImm(const Vehicle& vehicle, const ModelConfig& model,
                               const EkfOptions& ekf, const DisturbanceImmOptions& options)
    : options_(options),
      detector_(model.immobilization, vehicle.wheel_radius_m, vehicle.track_width_m),
      encoder_timeout_s_(ekf.encoder_timeout_s) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  EkfOptions scored = ekf;
  scored.track_log_likelihood = true;
  // The density w3 of the quiet process: sd = w3 sqrt(tau / 2).
  const double w3 = options.quiet_a_dist_sd_mps2 * std::sqrt(2.0 / options.quiet_a_dist_tau_s);
  ModelConfig quiet = model;
  quiet.process.a_dist_mps3_per_sqrt_hz = w3;
  quiet.process.a_dist_max_mps3_per_sqrt_hz = w3;
  quiet.process.a_dist_decay_tau_s = options.quiet_a_dist_tau_s;
  ModelConfig held = model;
  held.process.a_dist_mps3_per_sqrt_hz = options.held_a_dist_mps3_per_sqrt_hz;
  held.process.a_dist_max_mps3_per_sqrt_hz = options.held_a_dist_mps3_per_sqrt_hz;
  filters_[kQuiet] = std::make_unique<WardEkf>(vehicle, quiet, scored);
  filters_[kChanging] = std::make_unique<WardEkf>(vehicle, model, scored);
  filters_[kHeld] = std::make_unique<WardEkf>(vehicle, held, scored);
  rate_[kQuiet][kChanging] = 1.0 / options.quiet_mean_s;
  rate_[kChanging][kQuiet] = rate_[kChanging][kHeld] = 0.5 / options.change_mean_s;
  rate_[kHeld][kChanging] = 1.0 / options.held_mean_s;
  probability_ = {{1.0, 0.0, 0.0}};  // a drive starts without a disturbance
  predicted_ = probability_;
}

void DisturbanceImm::AddImu(const ImuSample& imu) {
  for (auto& f : filters_) f->AddImu(imu);
}

void DisturbanceImm::AddAttitude(const AttitudeSample& attitude) {
  for (auto& f : filters_) f->AddAttitude(attitude);
}

void DisturbanceImm::AddGps(const GpsSample& gps) {
  for (auto& f : filters_) f->AddGps(gps);
}

void DisturbanceImm::AddWheels(double t, double omega_left, double omega_right) {
  for (auto& f : filters_) f->AddWheels(t, omega_left, omega_right);
  // The mode probabilities by the likelihood of everything measured since the last mixing.
  for (int j = 0; j < kModeCount; ++j) log_likelihood_[j] += filters_[j]->TakeLogLikelihood();
  const double best = *std::max_element(log_likelihood_.begin(), log_likelihood_.end());
  probability_ = predicted_;
  if (std::isfinite(best)) {
    double sum = 0.0;
    for (int j = 0; j < kModeCount; ++j) {
      const double l = std::isnan(log_likelihood_[j]) ? 0.0 : std::exp(log_likelihood_[j] - best);
      probability_[j] = l * predicted_[j];
      sum += probability_[j];
    }
    if (sum > 0.0) {
      for (double& p : probability_) p /= sum;
    } else {
      probability_ = predicted_;
    }
  }
  if (std::isfinite(omega_left) && std::isfinite(omega_right)) last_wheels_t_ = t;
  const WardEstimate e = Estimate();
  slip_ = detector_.Update(e.x[ward::kVbx], e.x[ward::kYawRate], e.x[ward::kOmegaLeft],
                           e.x[ward::kOmegaRight], t - last_wheels_t_ <= encoder_timeout_s_);
  if (last_mix_t_ < 0.0) last_mix_t_ = t;
  // Interaction: over intervals of mix_interval_s the filters run apart, so that modes whose
  // predictions part slowly (a decaying disturbance against a held one) can be told apart.
  if (t - last_mix_t_ >= options_.mix_interval_s) {
    Mix(t - last_mix_t_);
    last_mix_t_ = t;
    log_likelihood_.fill(0.0);
  }
}

void DisturbanceImm::Mix(double dt) {
  // transition[i][j]: from mode i to mode j over dt. Mode i is left with probability
  // 1 - exp(-dt sum_j rate_ij), for the modes in proportion to their rates (at most one switch
  // per interval).
  double transition[kModeCount][kModeCount];
  for (int i = 0; i < kModeCount; ++i) {
    double total_rate = 0.0;
    for (int j = 0; j < kModeCount; ++j) total_rate += rate_[i][j];
    const double leave = -std::expm1(-dt * total_rate);
    for (int j = 0; j < kModeCount; ++j) {
      transition[i][j] = i == j ? 1.0 - leave : leave * rate_[i][j] / total_rate;
    }
  }
  for (int j = 0; j < kModeCount; ++j) {
    predicted_[j] = 0.0;
    for (int i = 0; i < kModeCount; ++i) predicted_[j] += transition[i][j] * probability_[i];
  }
  std::array<ekf::StateVector, kModeCount> x;
  std::array<ekf::StateMatrix, kModeCount> P;
  for (int j = 0; j < kModeCount; ++j) {
    double weight[kModeCount];
    x[j].setZero();
    for (int i = 0; i < kModeCount; ++i) {
      weight[i] = predicted_[j] > 0.0 ? transition[i][j] * probability_[i] / predicted_[j]
                                      : (i == j ? 1.0 : 0.0);
      x[j] += weight[i] * filters_[i]->state();
    }
    P[j].setZero();
    for (int i = 0; i < kModeCount; ++i) {
      if (weight[i] == 0.0) continue;
      const ekf::StateVector d = filters_[i]->state() - x[j];
      P[j] += weight[i] * (filters_[i]->covariance() + d * d.transpose());
    }
  }
  for (int j = 0; j < kModeCount; ++j) filters_[j]->ReplaceState(x[j], P[j]);
}

WardEstimate DisturbanceImm::Estimate() const {
  WardEstimate out = filters_[kChanging]->Estimate();
  for (int k = 0; k < ward::kStateSize; ++k) {
    double mean = 0.0, second_moment = 0.0;
    for (int j = 0; j < kModeCount; ++j) {
      const double value = filters_[j]->state()(k);
      mean += probability_[j] * value;
      second_moment += probability_[j] * (filters_[j]->covariance()(k, k) + value * value);
    }
    out.x[k] = mean;
    out.sd[k] = std::sqrt(std::max(0.0, second_moment - mean * mean));
  }
  out.slip = slip_;
  // Missing encoder data is never reported as immobilization.
  if (out.t - last_wheels_t_ > encoder_timeout_s_) out.slip.immobilized = false;
  return out;
}

}  // namespace slipgraph
