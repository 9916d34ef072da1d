#include "solvers/disturbance_imm.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "factors/ward_dynamics.h"
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

namespace imm {

Eigen::MatrixXd Transition(const Eigen::MatrixXd& rate_per_s, double dt_s) {
  const int n = rate_per_s.rows();
  Eigen::MatrixXd transition = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    double total_rate = 0.0;
    for (int j = 0; j < n; ++j) total_rate += j == i ? 0.0 : rate_per_s(i, j);
    const double leave = -std::expm1(-dt_s * total_rate);
    for (int j = 0; j < n; ++j) {
      if (j != i && total_rate > 0.0) transition(i, j) = leave * rate_per_s(i, j) / total_rate;
    }
    transition(i, i) = 1.0 - leave;
  }
  return transition;
}

Eigen::VectorXd Posterior(const Eigen::VectorXd& predicted, const Eigen::VectorXd& log_likelihood) {
  // The largest log posterior weight, so that the exponentials cannot all underflow.
  double best = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < predicted.size(); ++j) {
    if (predicted(j) > 0.0 && std::isfinite(log_likelihood(j))) {
      best = std::max(best, log_likelihood(j) + std::log(predicted(j)));
    }
  }
  if (!std::isfinite(best)) return predicted;
  Eigen::VectorXd posterior = Eigen::VectorXd::Zero(predicted.size());
  for (int j = 0; j < predicted.size(); ++j) {
    if (predicted(j) > 0.0 && std::isfinite(log_likelihood(j))) {
      posterior(j) = std::exp(log_likelihood(j) + std::log(predicted(j)) - best);
    }
  }
  return posterior / posterior.sum();  // the best term is 1: the sum is at least 1
}

void MixtureMoments(const std::vector<double>& weights,
                    const std::vector<const ekf::StateVector*>& means,
                    const std::vector<const ekf::StateMatrix*>& covariances, ekf::StateVector* mean,
                    ekf::StateMatrix* covariance) {
  mean->setZero();
  for (size_t i = 0; i < weights.size(); ++i) *mean += weights[i] * *means[i];
  covariance->setZero();
  for (size_t i = 0; i < weights.size(); ++i) {
    if (weights[i] == 0.0) continue;
    const ekf::StateVector d = *means[i] - *mean;
    *covariance += weights[i] * (*covariances[i] + d * d.transpose());
  }
}

}  // namespace imm

DisturbanceImm::DisturbanceImm(const Vehicle& vehicle, const ModelConfig& model,
                               const EkfOptions& ekf, const DisturbanceImmOptions& options)
    : options_(options),
      rate_per_s_(Eigen::MatrixXd::Zero(kModeCount, kModeCount)),
      log_likelihood_(Eigen::VectorXd::Zero(kModeCount)),
      detector_(model.immobilization, vehicle.wheel_radius_m, vehicle.track_width_m),
      encoder_timeout_s_(ekf.encoder_timeout_s) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  EkfOptions scored = ekf;
  scored.track_log_likelihood = true;
  // The quiet process's density: its stationary sd is GaussMarkovStationarySd(density, tau).
  const double quiet_density =
      options.quiet_a_dist_sd_mps2 / ward::GaussMarkovStationarySd(1.0, options.quiet_a_dist_tau_s);
  ModelConfig quiet = model;
  quiet.process.a_dist_mps3_per_sqrt_hz = quiet_density;
  quiet.process.a_dist_max_mps3_per_sqrt_hz = quiet_density;
  quiet.process.a_dist_decay_tau_s = options.quiet_a_dist_tau_s;
  ModelConfig held = model;
  held.process.a_dist_mps3_per_sqrt_hz = options.held_a_dist_mps3_per_sqrt_hz;
  held.process.a_dist_max_mps3_per_sqrt_hz = options.held_a_dist_mps3_per_sqrt_hz;
  filters_[kQuiet] = std::make_unique<WardEkf>(vehicle, quiet, scored);
  filters_[kChanging] = std::make_unique<WardEkf>(vehicle, model, scored);
  filters_[kHeld] = std::make_unique<WardEkf>(vehicle, held, scored);
  rate_per_s_(kQuiet, kChanging) = 1.0 / options.quiet_mean_s;
  rate_per_s_(kChanging, kQuiet) = rate_per_s_(kChanging, kHeld) = 0.5 / options.change_mean_s;
  rate_per_s_(kHeld, kChanging) = 1.0 / options.held_mean_s;
  probability_ = Eigen::VectorXd::Unit(kModeCount, kQuiet);  // a drive starts undisturbed
  predicted_probability_ = probability_;
  estimate_ = filters_[kChanging]->Estimate();
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
  for (int j = 0; j < kModeCount; ++j) log_likelihood_(j) += filters_[j]->TakeLogLikelihood();
  probability_ = imm::Posterior(predicted_probability_, log_likelihood_);
  if (std::isfinite(omega_left) && std::isfinite(omega_right)) last_wheels_t_ = t;
  Combine(t);
  if (!last_mix_t_) last_mix_t_ = t;
  if (t - *last_mix_t_ >= options_.mix_interval_s) {
    Mix(t - *last_mix_t_);
    last_mix_t_ = t;
    log_likelihood_.setZero();
  }
}

void DisturbanceImm::MixFilters(const std::vector<double>& weights, ekf::StateVector* mean,
                                ekf::StateMatrix* covariance) const {
  std::vector<const ekf::StateVector*> means;
  std::vector<const ekf::StateMatrix*> covariances;
  for (const auto& f : filters_) {
    means.push_back(&f->state());
    covariances.push_back(&f->covariance());
  }
  imm::MixtureMoments(weights, means, covariances, mean, covariance);
}

void DisturbanceImm::Combine(double t) {
  ekf::StateVector mean;
  ekf::StateMatrix covariance;
  MixFilters(std::vector<double>(probability_.data(), probability_.data() + kModeCount), &mean,
             &covariance);
  estimate_ = filters_[kChanging]->Estimate();  // time, offsets
  for (int k = 0; k < ward::kStateSize; ++k) {
    estimate_.x[k] = mean(k);
    estimate_.sd[k] = std::sqrt(std::max(0.0, covariance(k, k)));
  }
  const bool fresh = t - last_wheels_t_ <= encoder_timeout_s_;
  estimate_.slip = detector_.Update(mean(ward::kVbx), mean(ward::kYawRate), mean(ward::kOmegaLeft),
                                    mean(ward::kOmegaRight), fresh, estimate_.sd[ward::kVbx]);
  // Missing encoder data is never reported as immobilization.
  if (!fresh) estimate_.slip.immobilized = false;
}

void DisturbanceImm::Mix(double dt) {
  const Eigen::MatrixXd transition = imm::Transition(rate_per_s_, dt);
  predicted_probability_ = transition.transpose() * probability_;
  std::array<ekf::StateVector, kModeCount> x;
  std::array<ekf::StateMatrix, kModeCount> P;
  for (int j = 0; j < kModeCount; ++j) {
    // The probability that the system was in mode i, given that it is in mode j now.
    std::vector<double> weights(kModeCount, 0.0);
    for (int i = 0; i < kModeCount; ++i) {
      weights[i] = predicted_probability_(j) > 0.0
                       ? transition(i, j) * probability_(i) / predicted_probability_(j)
                       : (i == j ? 1.0 : 0.0);
    }
    MixFilters(weights, &x[j], &P[j]);
  }
  for (int j = 0; j < kModeCount; ++j) filters_[j]->ReplaceState(x[j], P[j]);
}

double DisturbanceImm::DisturbanceDensity() const {
  return WeighedDisturbanceDensity(filters_, probability_);
}

}  // namespace slipgraph
