// How late the IMU's stamps are against the encoders', for `identify --clock`: the workbench's
// model-based test of the clock_offset effect (workbench/effect_signatures.h) at the batch
// smoother's solution on each log, combined over the logs. The model's yaw-rate state follows the
// wheels through the yaw dynamics, so the dynamics' lag is not read as the clock's, which a plain
// alignment of the gyro with the wheels' yaw rate does (docs/identify.md).
#pragma once

#include <cmath>
#include <vector>

#include "io/drive_log.h"
#include "model/model_config.h"

namespace slipgraph {

struct ImuClockOffset {
  // The logs' magnitudes, inverse-variance weighted (NaN: no log could be tested).
  double offset_s = std::nan("");
  double sd_s = std::nan("");
  int logs = 0;              // logs tested
  int significant_logs = 0;  // logs whose own test finds it (diagnose's level, 0.01)
  // Taken: significant on a log and beyond 3 sd of the combination.
  bool significant() const { return significant_logs > 0 && std::abs(offset_s) > 3.0 * sd_s; }
};

// Each log as the model calibrates it (ApplyCalibration): the offset found is on top of the
// model's calibration.imu_time_offset.
ImuClockOffset EstimateImuClockOffset(const std::vector<DriveLog>& logs, const ModelConfig& model,
                                      int threads = 2);

}  // namespace slipgraph
