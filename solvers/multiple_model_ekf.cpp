#include "solvers/multiple_model_ekf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/option_check.h"

namespace slipgraph {

bool MultipleModelOptions::IsValid(std::string* error) const {
  return OptionCheck("MultipleModelOptions", error).Positive("switch_time_s", switch_time_s);
}

MultipleModelEkf::MultipleModelEkf(const Vehicle& vehicle, const ModelConfig& model,
                                   const EkfOptions& ekf, const MultipleModelOptions& options)
    : options_(options),
      detector_(model.immobilization, vehicle.wheel_radius_m, vehicle.track_width_m),
      encoder_timeout_s_(ekf.encoder_timeout_s) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  filters_.push_back(std::make_unique<WardEkf>(vehicle, model, ekf));
  laws_.push_back({model.tire, model.rolling});
  if (model.ListsSoils()) {
    for (const LawSample& sample : model.law_samples) {
      ModelConfig soil = model;
      soil.tire = sample.tire;
      soil.rolling = sample.rolling;
      filters_.push_back(std::make_unique<WardEkf>(vehicle, soil, ekf));
      laws_.push_back(sample);
    }
  }
  weights_.assign(filters_.size(), 1.0 / filters_.size());
}

void MultipleModelEkf::AddImu(const ImuSample& imu) {
  for (auto& f : filters_) f->AddImu(imu);  // not weighed (see the header)
}

void MultipleModelEkf::AddAttitude(const AttitudeSample& attitude) {
  for (auto& f : filters_) f->AddAttitude(attitude);
}

void MultipleModelEkf::AddGps(const GpsSample& gps) {
  std::vector<double> log_likelihood(filters_.size());
  for (size_t i = 0; i < filters_.size(); ++i) {
    log_likelihood[i] = filters_[i]->AddGpsScored(gps);
  }
  const double best = *std::max_element(log_likelihood.begin(), log_likelihood.end());
  // A fix no filter can score (an absurd value: every filter's gate refused it with an infinite
  // distance) says nothing about the laws: the weights stay.
  if (!std::isfinite(best)) return;
  double sum = 0.0;
  for (size_t i = 0; i < filters_.size(); ++i) {
    weights_[i] *= std::isnan(log_likelihood[i]) ? 0.0 : std::exp(log_likelihood[i] - best);
    sum += weights_[i];
  }
  for (double& w : weights_) w /= sum;
}

void MultipleModelEkf::AddWheels(double t, double omega_left, double omega_right) {
  for (auto& f : filters_) f->AddWheels(t, omega_left, omega_right);
  // Forgetting: the weights relax toward uniform, so a law that fits again can come back.
  if (last_cycle_t_ >= 0.0 && t > last_cycle_t_) {
    const double mix = std::min(1.0, (t - last_cycle_t_) / options_.switch_time_s);
    for (double& w : weights_) w = (1.0 - mix) * w + mix / weights_.size();
  }
  last_cycle_t_ = t;
  if (std::isfinite(omega_left) && std::isfinite(omega_right)) last_wheels_t_ = t;
  const WardEstimate e = Estimate();
  slip_ = detector_.Update(e.x[ward::kVbx], e.x[ward::kYawRate], e.x[ward::kOmegaLeft],
                           e.x[ward::kOmegaRight], t - last_wheels_t_ <= encoder_timeout_s_,
                           e.sd[ward::kVbx]);
}

LawSample MultipleModelEkf::Law() const {
  if (laws_.size() == 1) return laws_.front();
  LawSample law{{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  for (size_t i = 0; i < laws_.size(); ++i) {
    const double w = weights_[i];
    law.tire.C1 += w * laws_[i].tire.C1;
    law.tire.At += w * laws_[i].tire.At;
    law.tire.C2 += w * laws_[i].tire.C2;
    law.rolling.R1 += w * laws_[i].rolling.R1;
    law.rolling.A_roll += w * laws_[i].rolling.A_roll;
    law.rolling.R2 += w * laws_[i].rolling.R2;
  }
  return law;
}

double MultipleModelEkf::DisturbanceDensity() const {
  return WeighedDisturbanceDensity(filters_, weights_);
}

WardEstimate MultipleModelEkf::Estimate(std::array<double, ward::kStateSize>* law_spread_sd) const {
  WardEstimate out = filters_.front()->Estimate();
  if (law_spread_sd != nullptr) law_spread_sd->fill(0.0);
  if (filters_.size() == 1) return out;
  std::array<double, ward::kStateSize> mean{}, within{}, second_moment{};
  for (size_t i = 0; i < filters_.size(); ++i) {
    const WardEstimate e = filters_[i]->Estimate();
    for (int j = 0; j < ward::kStateSize; ++j) {
      mean[j] += weights_[i] * e.x[j];
      within[j] += weights_[i] * e.sd[j] * e.sd[j];
      second_moment[j] += weights_[i] * e.x[j] * e.x[j];
    }
  }
  for (int j = 0; j < ward::kStateSize; ++j) {
    const double spread = std::max(0.0, second_moment[j] - mean[j] * mean[j]);
    out.x[j] = mean[j];
    out.sd[j] = std::sqrt(within[j] + spread);
    if (law_spread_sd != nullptr) (*law_spread_sd)[j] = std::sqrt(spread);
  }
  out.slip = slip_;
  // Missing encoder data is never reported as immobilization.
  if (out.t - last_wheels_t_ > encoder_timeout_s_) out.slip.immobilized = false;
  return out;
}

}  // namespace slipgraph
