// An effect the catalogue does not have, added by a program in one file: a yaw gyro whose scale
// factor is off, g_z = (1 + s) yaw_rate + offset + bias. A program adds it to the registry it
// hands to Diagnose (`registry.Add(GyroScaleError())`); the walkthrough is
// docs/adding-an-effect.md, the test that checks it tests/effect_example_test.cpp.
//
// Evidence: the gyro's integrated heading grows (1 + s) times as fast as the true heading, so
// against the attitude stream's heading (which the gyro does not feed here)
//
//   psi_att - psi_gyro = const - s psi_gyro,
//
// a straight line in the integrated heading itself. The gyro noise and the error of its bias
// estimate make the difference walk slowly, so both sides are high-passed at 20 s (turns take a
// few seconds; a 5 s window would cut the signal with the walk). The correction divides the
// gyro by (1 + s).
#pragma once

#include <vector>

#include "workbench/effect_signatures.h"

namespace slipgraph {

inline std::vector<SignatureSeries> GyroScaleSeries(const ModelResiduals& m, const DriveLog& log,
                                                    const ModelConfig&) {
  SignatureSeries s;
  s.stream = "attitude_yaw";
  const HeadingSeries h = AttitudeAndGyroHeadings(m, log);
  s.t = h.t;
  for (size_t i = 0; i < h.t.size(); ++i) {
    s.y.push_back((h.attitude[i] - h.gyro[i]) / h.sd[i]);
    s.g.push_back(-h.gyro[i] / h.sd[i]);
  }
  s.y = HighPass(s.t, s.y, 20.0);
  s.g = HighPass(s.t, s.g, 20.0);
  return {s};
}

inline void UndoGyroScale(double scale_error, DriveLog* log) {
  for (ImuSample& imu : log->imu) imu.gz /= 1.0 + scale_error;
}

inline EffectSignature GyroScaleError() {
  return {
      "gyro_scale_error",
      "attitude heading minus integrated gyro against minus the integrated gyro, high-passed at 20 "
      "s",
      nullptr,  // no negligible magnitude: any scale error is an error
      GyroScaleSeries,
      UndoGyroScale,
  };
}

}  // namespace slipgraph
