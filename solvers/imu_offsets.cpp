#include "solvers/imu_offsets.h"

namespace slipgraph {

ImuOffsetEstimator::ImuOffsetEstimator(int init_samples, double ema_samples)
    : init_samples_(init_samples), accel_(ema_samples), gyro_(ema_samples) {}

void ImuOffsetEstimator::Add(double accel_x, double gyro_z, double gravity_along_x, bool at_rest) {
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
  if (at_rest) {
    accel_.Add(accel_offset);
    gyro_.Add(gyro_z);
  }
}

}  // namespace slipgraph
