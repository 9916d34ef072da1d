// Immobilization detection on smoothed states (batch or window smoother): the slip of the driven
// sides above the detector's speed-dependent threshold while the wheels turn and the robot is not
// braking, kept only where it lasts at least min_duration_s. Smoothed states have no EKF lag, so
// no EMA is applied (slip_ema is the plain mean of the two sides).
#pragma once

#include <vector>

#include "model/model_config.h"
#include "model/vehicle.h"
#include "solvers/immobilization_detector.h"
#include "solvers/ward_ekf.h"

namespace slipgraph {

void DetectImmobilizationOnSmoothedStates(const ModelConfig& model, const Vehicle& vehicle,
                                          double min_duration_s,
                                          std::vector<WardEstimate>* estimates);

}  // namespace slipgraph
