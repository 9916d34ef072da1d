// The IMU's calibration from the workbench, for `identify --clock` and `identify --mounting`: the
// workbench's test of one measurement effect (workbench/effect_signatures.h) at the batch
// smoother's solution on each log, combined over the logs.
//   - clock_offset, how late the IMU's stamps are against the other streams' (s): the test reads
//     the IMU against the attitude stream (the AHRS heading against the integrated gyro) and
//     against the wheels (the force balance): where the attitude comes from the IMU itself, on its
//     own stamps, only the force balance speaks.
//   - imu_mounting_pitch, how far the IMU's axes are pitched nose-down about body y (rad): the
//     z accelerometer against the x one, both band-passed (gravity, which the body's
//     attitude gives, taken out).
// Each is one number for the whole drive, so the same test runs on each log's two halves too,
// and where they disagree beyond their sd (Cochran's Q over every half) what it reads is some
// other misfit, and the value is not taken. (The halves' own readings serve that check only:
// each loses the other's turns and is less precise.) Throws std::invalid_argument for invalid
// options or an effect not among those two.
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "io/drive_log.h"
#include "model/model_config.h"

namespace slipgraph {

struct ImuCalibrationOptions {
  double halves_level = 0.01;  // Cochran's Q over the halves: p below this, they disagree
  double min_sigmas = 3.0;     // taken only beyond this many sd of the combination
  bool use_gps = true;
  int threads = 2;
  bool IsValid(std::string* error) const;
};

struct ImuCalibrationReading {
  // The logs' magnitudes, inverse-variance weighted (NaN: no log could be tested), in the
  // effect's unit (clock_offset s, imu_mounting_pitch rad).
  double value = std::nan("");
  double sd = std::nan("");
  int logs = 0;              // logs tested
  int significant_logs = 0;  // logs whose own test finds it (the workbench's level, 0.01)
  // Cochran's Q of the halves about their combination, its p-value (chi-square, halves - 1
  // dof), and whether they agree (fewer than two halves tested: not known, so not).
  int halves = 0;
  double heterogeneity = std::nan("");
  double heterogeneity_p = std::nan("");
  bool halves_agree = false;
  // Significant on a log, beyond min_sigmas sd of the combination, the halves agreeing: the
  // model's calibration takes it.
  bool taken = false;
};

// An effect it reads and where the model keeps it: the calibration field and its model file
// key, what the terminal calls it and in which unit, the JSON's names.
struct ImuCalibrationEffect {
  const char* effect;  // the catalogue's name, e.g. "clock_offset"
  double CalibrationConfig::*field;
  const char* key;           // the model file's `calibration:` key
  const char* title;         // e.g. "IMU clock against the other streams"
  const char* unit;          // of the value in the model, e.g. "s"
  double display_scale;      // the terminal's figure = value x this ...
  const char* display_unit;  // ... in this, e.g. "ms late"
  const char* json_object;   // identify's JSON: the object's name, e.g. "imu_clock"
  const char* json_value;    // its value's and sd's names, e.g. "offset_s", "sd_s"
  const char* json_sd;
};
// clock_offset (calibration.imu_time_offset_s) and imu_mounting_pitch
// (calibration.imu_mounting_pitch_rad).
const std::vector<ImuCalibrationEffect>& ImuCalibrationEffects();
// The entry for `effect`; throws std::invalid_argument for an effect not among them.
const ImuCalibrationEffect& FindImuCalibrationEffect(const std::string& effect);

// Each log as the model calibrates it (ApplyCalibration; its halves cut at the middle of its
// wheel data): the value found is on top of the model's calibration (imu_time_offset or
// imu_mounting_pitch). A log with fewer than two wheel samples, or a half the front end cannot
// run on, is left out.
ImuCalibrationReading EstimateImuCalibration(const std::vector<DriveLog>& logs,
                                             const ModelConfig& model, const std::string& effect,
                                             const ImuCalibrationOptions& options = {});

// The model with `value` added to the effect's calibration field (throws std::invalid_argument
// for an effect not among ImuCalibrationEffects).
ModelConfig WithImuCalibration(const ModelConfig& model, const std::string& effect, double value);

}  // namespace slipgraph
