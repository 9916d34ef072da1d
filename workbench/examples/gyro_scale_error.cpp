// An effect the catalogue does not have, added in one file: a yaw gyro whose scale factor is off,
// g_z = (1 + s) yaw_rate + offset + bias. The walkthrough is docs/adding-an-effect.md; the test
// that builds and checks this file is tests/effect_example_test.cpp.
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
#include <cmath>

#include "factors/ward_state.h"
#include "io/measurement_stream.h"
#include "workbench/effect_signatures.h"

namespace slipgraph {
namespace {

std::vector<SignatureSeries> GyroScaleSeries(const ModelResiduals& m, const DriveLog& log,
                                             const ModelConfig&) {
  SignatureSeries s;
  s.stream = "attitude_yaw";
  double psi_gyro = 0.0, psi_att = 0.0, previous_att = std::nan("");
  for (size_t k = 0; k < m.states.size(); ++k) {
    const StateContext& c = m.states[k];
    const double rate = c.gyro_z - m.gyro_offset - c.x[ward::kGyroBias];
    if (!std::isfinite(rate)) continue;
    if (k > 0) psi_gyro += rate * (c.t - m.states[k - 1].t);
    const long a = LatestAtOrBefore(log.attitude, c.t, 1e-6);
    if (a < 0 || std::abs(log.attitude[a].t - c.t) > 1e-3) continue;
    const double yaw = log.attitude[a].yaw;
    psi_att =
        std::isfinite(previous_att) ? psi_att + std::remainder(yaw - previous_att, 2 * M_PI) : yaw;
    previous_att = yaw;
    const double sd = log.attitude[a].sd_yaw > 0.0 ? log.attitude[a].sd_yaw : 0.01;
    s.t.push_back(c.t);
    s.y.push_back((psi_att - psi_gyro) / sd);
    s.g.push_back(-psi_gyro / sd);
  }
  s.y = HighPass(s.t, s.y, 20.0);
  s.g = HighPass(s.t, s.g, 20.0);
  return {s};
}

void UndoGyroScale(double scale_error, DriveLog* log) {
  for (ImuSample& imu : log->imu) imu.gz /= 1.0 + scale_error;
}

const EffectSignatureRegistration kGyroScaleError({
    "gyro_scale_error",
    "attitude heading minus integrated gyro against minus the integrated gyro, high-passed at 20 s",
    nullptr,  // no negligible magnitude: any scale error is an error
    GyroScaleSeries,
    UndoGyroScale,
});

}  // namespace
}  // namespace slipgraph
