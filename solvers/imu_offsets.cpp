#include "solvers/imu_offsets.h"

#include <algorithm>

namespace slipgraph {
namespace {

// How late the encoders see a start (their first counts): at-rest samples this close to the
// first motion are dropped.
constexpr double kStartSeenLateS = 0.1;
// A moving start's accelerometer offset is uncertain by at least this (the slip's change over the
// initial samples that the wheels do not show).
constexpr double kMovingStartSdMps2 = 0.03;
// The largest accelerometer offset taken as plausible: a MEMS offset plus about 1.5 degrees of
// mounting tilt.
constexpr double kMaxPlausibleOffsetMps2 = 0.3;

}  // namespace

ImuOffsetEstimator::ImuOffsetEstimator(int init_samples, double ema_samples, double rest_guard_s)
    : init_samples_(init_samples),
      rest_guard_s_(rest_guard_s),
      accel_(ema_samples),
      gyro_(ema_samples) {}

void ImuOffsetEstimator::Add(double t, double accel_x, double gyro_z, double gravity_along_x,
                             bool at_rest, const WheelMotion& wheels) {
  const double accel_offset = accel_x - gravity_along_x;
  if (count_ < init_samples_) {
    if (!wheels.still && !moving_start_) {
      // Motion before n samples: the rest so far, without its last tenth of a second, if long
      // enough; else the motion is compensated over n samples.
      size_t rest = init_.size();
      while (rest > 0 && init_[rest - 1].t > t - kStartSeenLateS) --rest;
      if (static_cast<int>(rest) >= std::max(1, init_samples_ / 4)) {
        FinishAtRest(rest);
        return;
      }
      moving_start_ = true;
    }
    init_.push_back({t, accel_offset, gyro_z, wheels});
    ++count_;
    if (count_ == init_samples_) FinishInitialisation();
    return;
  }
  if (!at_rest) {
    pending_.clear();  // the robot was moving, perhaps already during these
    return;
  }
  pending_.push_back({t, accel_offset, gyro_z});
  while (!pending_.empty() && pending_.front().t <= t - rest_guard_s_) {
    accel_.Add(pending_.front().accel_offset);
    gyro_.Add(pending_.front().gyro_z);
    pending_.pop_front();
  }
}

void ImuOffsetEstimator::FinishAtRest(size_t rest_samples) {
  double sum_accel = 0.0, sum_gyro = 0.0;
  for (size_t i = 0; i < rest_samples; ++i) {
    sum_accel += init_[i].accel_offset, sum_gyro += init_[i].gyro_z;
  }
  accel_.Reset(sum_accel / rest_samples);
  gyro_.Reset(sum_gyro / rest_samples);
  count_ = init_samples_;
  init_.clear();
  init_.shrink_to_fit();
}

void ImuOffsetEstimator::FinishInitialisation() {
  double sum_accel = 0.0, sum_gyro = 0.0;
  for (const InitSample& s : init_) sum_accel += s.accel_offset, sum_gyro += s.gyro_z;
  const double n = static_cast<double>(init_.size());
  double accel = sum_accel / n, gyro = sum_gyro / n;
  if (moving_start_) {
    // The body's mean acceleration over the samples: the wheels' forward speed, averaged over a
    // tenth of the interval at each end, differenced over the time between those means.
    const size_t end_count = std::max<size_t>(1, init_.size() / 10);
    const auto mean_over = [&](size_t begin, double* t, double* v) {
      double sum_t = 0.0, sum_v = 0.0;
      int used = 0;
      for (size_t i = begin; i < begin + end_count; ++i) {
        const WheelMotion& w = init_[i].wheels;
        const double speed = std::isfinite(w.speed_mps) ? w.speed_mps : 0.0;
        sum_t += init_[i].t, sum_v += speed, ++used;
      }
      *t = sum_t / used, *v = sum_v / used;
    };
    double t0, v0, t1, v1;
    mean_over(0, &t0, &v0);
    mean_over(init_.size() - end_count, &t1, &v1);
    const double body_accel = t1 > t0 ? (v1 - v0) / (t1 - t0) : 0.0;
    double sum_yaw = 0.0;
    for (const InitSample& s : init_) {
      if (std::isfinite(s.wheels.yaw_rate_radps)) sum_yaw += s.wheels.yaw_rate_radps;
    }
    const double yaw_rate = sum_yaw / n;
    accel -= body_accel;
    gyro -= yaw_rate;
    init_sd_ = {0.1 * std::abs(body_accel) + kMovingStartSdMps2, 0.2 * std::abs(yaw_rate)};
    if (std::abs(accel) > kMaxPlausibleOffsetMps2) {
      // The wheels' acceleration was not the body's (a slip that changed: a hold-back, a wheel
      // spinning up): no offset that large is plausible. Zero, with a typical offset's sd.
      accel = 0.0;
      init_sd_[0] = kMaxPlausibleOffsetMps2;
      implausible_ = true;
    }
  }
  accel_.Reset(accel);
  gyro_.Reset(gyro);
  init_.clear();
  init_.shrink_to_fit();
}

}  // namespace slipgraph
