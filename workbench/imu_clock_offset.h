// How late the IMU's stamps are against the encoders', for `identify --clock`: the workbench's
// model-based test of the clock_offset effect (workbench/effect_signatures.h) at the batch
// smoother's solution on each log, combined over the logs. The model's yaw-rate
// state follows the wheels through the yaw dynamics, so the dynamics' lag is not read as the
// clock's, which a plain alignment of the gyro with the wheels' yaw rate does (docs/identify.md).
// A clock's offset is one number for the whole drive: the same test on each log's two halves,
// and where they disagree beyond their sd (Cochran's Q over every half, at 1 %), what the test
// reads is some other misfit, and the offset is not taken. (The halves' own readings are not
// used beyond that: each half loses the other's turns and is less precise.)
#pragma once

#include <cmath>
#include <vector>

#include "io/drive_log.h"
#include "model/model_config.h"

namespace slipgraph {

struct ImuClockOffset {
  // The logs' magnitudes, inverse-variance weighted (NaN: none could be tested).
  double offset_s = std::nan("");
  double sd_s = std::nan("");
  int logs = 0;              // logs tested
  int significant_logs = 0;  // logs whose own test finds it (diagnose's level, 0.01)
  // Cochran's Q of the halves about their combination, and its p-value (chi-square, halves - 1
  // dof; 1 with fewer than two halves).
  int halves = 0;
  double heterogeneity = 0.0;
  double heterogeneity_p = 1.0;
  bool consistent() const { return heterogeneity_p >= 0.01; }
  // Taken: significant on a log, beyond 3 sd of the combination, the halves consistent.
  bool significant() const {
    return significant_logs > 0 && std::abs(offset_s) > 3.0 * sd_s && consistent();
  }
};

// Each log as the model calibrates it (ApplyCalibration; its halves cut at the middle of its
// wheel data): the offset found is on top of the model's calibration.imu_time_offset.
ImuClockOffset EstimateImuClockOffset(const std::vector<DriveLog>& logs, const ModelConfig& model,
                                      int threads = 2);

}  // namespace slipgraph
