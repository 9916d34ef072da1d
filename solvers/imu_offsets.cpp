#include "solvers/imu_offsets.h"

namespace slipgraph {

ImuOffsetEstimator::ImuOffsetEstimator(int init_samples, double ema_samples, double rest_guard_s)
    : init_samples_(init_samples),
      rest_guard_s_(rest_guard_s),
      accel_(ema_samples),
      gyro_(ema_samples) {}

void ImuOffsetEstimator::Add(double t, double accel_x, double gyro_z, double gravity_along_x,
                             bool at_rest) {
  const double accel_offset = accel_x - gravity_along_x;
  if (count_ < init_samples_) {
    sum_accel_ += accel_offset;
    sum_gyro_ += gyro_z;
    ++count_;
    if (count_ == init_samples_) {
      accel_.Reset(sum_accel_ / count_);
      gyro_.Reset(sum_gyro_ / count_);
    }
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

}  // namespace slipgraph
