#include "solvers/imu_offsets.h"

#include <algorithm>
#include <vector>

namespace slipgraph {
namespace {

// How late the encoders see a start (their first counts): at-rest samples this close to the
// first motion are dropped.
constexpr double kStartSeenLateS = 0.1;
// A moving start's accelerometer offset is uncertain by at least this (the slip's change over the
// initial samples that the wheels do not show).
constexpr double kMovingStartSdMps2 = 0.1;
// The largest accelerometer offset taken as plausible: a MEMS offset plus about 1.5 degrees of
// mounting tilt.
constexpr double kMaxPlausibleOffsetMps2 = 0.3;

}  // namespace

ImuOffsetEstimator::ImuOffsetEstimator(int init_samples, double ema_samples, double rest_guard_s,
                                       double yaw_rate_relative_sd)
    : init_samples_(init_samples),
      rest_guard_s_(rest_guard_s),
      yaw_rate_relative_sd_(yaw_rate_relative_sd),
      accel_(ema_samples),
      gyro_(ema_samples) {}

void ImuOffsetEstimator::Add(double t, double accel_x, double gyro_z, double gravity_along_x,
                             bool at_rest, const WheelMotion& wheels) {
  const double accel_offset = accel_x - gravity_along_x;
  if (count_ < init_samples_) {
    if (!wheels.still && !moving_start_) {
      // Motion before n samples: the rest so far (the samples the wheels read still, without
      // the last tenth of a second), if long enough; else the motion is compensated over n
      // samples. A sample before the wheels' first reading is not known to be at rest.
      size_t end = init_.size();
      while (end > 0 && init_[end - 1].t > t - kStartSeenLateS) --end;
      const long rest = std::count_if(init_.begin(), init_.begin() + end, [](const InitSample& s) {
        return std::isfinite(s.wheels.speed_mps);
      });
      if (rest >= std::max(1, init_samples_ / 4)) {
        FinishAtRest(end);
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

void ImuOffsetEstimator::FinishAtRest(size_t end) {
  double sum_accel = 0.0, sum_gyro = 0.0;
  long n = 0;
  for (size_t i = 0; i < end; ++i) {
    if (!std::isfinite(init_[i].wheels.speed_mps)) continue;
    sum_accel += init_[i].accel_offset, sum_gyro += init_[i].gyro_z, ++n;
  }
  accel_.Reset(sum_accel / n);
  gyro_.Reset(sum_gyro / n);
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
    // Over the samples the wheels saw (those before their first reading are left out): the
    // IMU's mean less the body's mean acceleration, the wheels' forward speed averaged over a
    // tenth of them at each end and differenced over the time between those means, and less
    // the wheels' mean yaw rate.
    std::vector<const InitSample*> seen;
    for (const InitSample& s : init_) {
      if (std::isfinite(s.wheels.speed_mps) && std::isfinite(s.wheels.yaw_rate_radps)) {
        seen.push_back(&s);
      }
    }
    if (seen.size() < 10) {
      accel = 0.0;
      init_sd_ = {kMaxPlausibleOffsetMps2, std::abs(gyro)};
      implausible_ = true;
    } else {
      const size_t end_count = std::max<size_t>(1, seen.size() / 10);
      const auto mean_over = [&](size_t begin, double* t, double* v) {
        double sum_t = 0.0, sum_v = 0.0;
        for (size_t i = begin; i < begin + end_count; ++i) {
          sum_t += seen[i]->t, sum_v += seen[i]->wheels.speed_mps;
        }
        *t = sum_t / end_count, *v = sum_v / end_count;
      };
      double t0, v0, t1, v1;
      mean_over(0, &t0, &v0);
      mean_over(seen.size() - end_count, &t1, &v1);
      const double body_accel = t1 > t0 ? (v1 - v0) / (t1 - t0) : 0.0;
      double seen_accel = 0.0, seen_gyro = 0.0, seen_yaw = 0.0;
      for (const InitSample* s : seen) {
        seen_accel += s->accel_offset;
        seen_gyro += s->gyro_z;
        seen_yaw += s->wheels.yaw_rate_radps;
      }
      const double n_seen = static_cast<double>(seen.size());
      const double mean_yaw = seen_yaw / n_seen;
      accel = seen_accel / n_seen - body_accel;
      gyro = seen_gyro / n_seen - mean_yaw;
      init_sd_ = {0.1 * std::abs(body_accel) + kMovingStartSdMps2,
                  yaw_rate_relative_sd_ * std::abs(mean_yaw)};
      if (std::abs(accel) > kMaxPlausibleOffsetMps2) {
        // The wheels' acceleration was not the body's (a slip that changed: a hold-back, a
        // wheel spinning up): no offset that large is plausible. Zero, with a typical offset's
        // sd.
        accel = 0.0;
        init_sd_[0] = kMaxPlausibleOffsetMps2;
        implausible_ = true;
      }
    }
  }
  accel_.Reset(accel);
  gyro_.Reset(gyro);
  init_.clear();
  init_.shrink_to_fit();
}

}  // namespace slipgraph
