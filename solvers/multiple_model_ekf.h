// A bank of Ward EKFs over the tire laws a user's law was fitted from, weighed by how well each
// predicts the GNSS velocity: multiple-model adaptive estimation (Magill 1965; Bar-Shalom, Li &
// Kirubarajan, "Estimation with Applications to Tracking and Navigation", Sec. 11.6), with the
// weights relaxing toward uniform so that they can follow a change of soil.
//
// Why: the user's law is a mean over soils (vehicle.yaml `law_samples`); on a soil whose slip
// differs by tens of percent one filter holds v_bx at the mean law's equilibrium, 2-5 cm/s off
// at slow speed on mud, and misses hold-backs there (docs/ekf.md). The bank runs one filter on the
// user's law and one on each soil's, every filter fed every measurement. After each GNSS fix,
// filter i's weight is multiplied by the likelihood of that fix under its prediction
// (WardEkf::AddGpsScored); at each wheel cycle the weights mix with the uniform weight at rate
// dt / switch_time. The estimate is the weighted mean (sd: the weighted variances plus the spread
// of the means), and the immobilization detector runs on it. Until GNSS tells the laws apart the
// estimate is their average: the posterior mean over the soils the user named.
//
// Only GNSS weighs: the accelerometer row's noise is the law's own tuning (30 % of the traction,
// each 100 Hz sample as if independent), so its likelihood compares variance models rather than
// laws. Weighed by every measurement, the mud law took 0.99 of the weight within two seconds, at
// rest, on every run of ward21 seed 1, gravel and grass included. GNSS sees v_bx, the quantity the
// laws disagree on, with a stated white noise.
//
// Without law samples the bank is the one filter, the paper's.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "solvers/ward_ekf.h"

namespace slipgraph {

struct MultipleModelOptions {
  // The weights relax toward uniform with this time constant (s), so that after a change of soil
  // a law the fixes had ruled out can come back.
  double switch_time_s = 30.0;

  bool IsValid(std::string* error) const;
};

class MultipleModelEkf {
 public:
  MultipleModelEkf(const Vehicle& vehicle, const ModelConfig& model, const EkfOptions& ekf,
                   const MultipleModelOptions& options = {});

  void AddImu(const ImuSample& imu);
  void AddWheels(double t, double omega_left_radps, double omega_right_radps);
  void AddGps(const GpsSample& gps);
  void AddAttitude(const AttitudeSample& attitude);

  // With law_spread_sd: also the sd of the filters' means about their weighted mean, the share
  // of the estimate's sd that is the tire law's uncertainty (zero with one filter).
  WardEstimate Estimate(std::array<double, ward::kStateSize>* law_spread_sd = nullptr) const;
  // The user's-law filter's counters (every filter is fed the same measurements).
  const EkfStats& stats() const { return filters_.front()->stats(); }
  // The filters: [0] on the user's law, then one per law sample.
  size_t size() const { return filters_.size(); }
  const std::vector<double>& weights() const { return weights_; }
  // The filters' laws weighed as the estimate is: each coefficient of the tire and rolling laws
  // averaged with the filters' weights (the user's law with one filter).
  LawSample Law() const;
  // The filters' disturbance densities (WardEkf::DisturbanceDensity) weighed as the estimate
  // is: the root of their squares' weighted mean.
  double DisturbanceDensity() const;

 private:
  MultipleModelOptions options_;
  std::vector<std::unique_ptr<WardEkf>> filters_;
  std::vector<LawSample> laws_;  // filter i's law
  std::vector<double> weights_;
  ImmobilizationDetector detector_;
  double encoder_timeout_s_;
  double last_wheels_t_ = -1e300;  // the last cycle with both wheel speeds
  double last_cycle_t_ = -1.0;
  SlipEstimate slip_;
};

}  // namespace slipgraph
