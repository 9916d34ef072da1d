// The attitude's yaw against the GNSS course over a whole log: each fix's offset is from the
// fixes before it, never from itself; fixes without a fresh encoder reading or a finite yaw are
// not read; the model's switch turns it off.
#include "io/gnss_heading_offsets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace slipgraph {
namespace {

// 20 s straight ahead at 1 m/s on an attitude yaw of 0 whose course is 0.4 rad: encoders and
// attitude at 10 Hz, fixes at 1 Hz from t = 0.5 s.
DriveLog StraightLog() {
  DriveLog log;
  log.vehicle.type = VehicleType::kDiffDriveCastor;
  log.vehicle.wheel_radius_m = 0.2;
  log.vehicle.track_width_m = 0.8;
  const double omega = 1.0 / log.vehicle.wheel_radius_m;
  for (int i = 0; i < 200; ++i) {
    const double t = 0.1 * i;
    WheelSample w;
    w.t = t;
    w.omega_radps.fill(omega);
    log.wheels.push_back(w);
    log.attitude.push_back({t, 0.0, 0.0, 0.0});
  }
  for (int i = 0; i < 20; ++i) {
    GpsSample g;
    g.t = 0.5 + i;
    g.vx = std::cos(0.4), g.vy = std::sin(0.4), g.sd_v = 0.05;
    log.gps.push_back(g);
  }
  return log;
}

TEST(GnssHeadingOffsets, EachFixIsReadOnTheFixesBeforeIt) {
  const DriveLog log = StraightLog();
  const std::vector<double> offsets = GnssHeadingOffsets(log, DefaultModelConfig(log.vehicle));
  ASSERT_EQ(offsets.size(), log.gps.size());
  // min_fixes (5) before the first applied: fix 5 is the first, and it did not count itself.
  for (int i = 0; i < 5; ++i) EXPECT_EQ(offsets[i], 0.0) << i;
  for (size_t i = 5; i < offsets.size(); ++i) EXPECT_NEAR(offsets[i], 0.4, 1e-12) << i;
}

TEST(GnssHeadingOffsets, ReadsNoFixWithoutFreshEncodersOrAYaw) {
  DriveLog stale = StraightLog();
  stale.wheels.resize(1);  // the encoders stop at t = 0
  DriveLog no_yaw = StraightLog();
  for (AttitudeSample& a : no_yaw.attitude) a.yaw = std::numeric_limits<double>::quiet_NaN();
  for (const DriveLog* log : {&stale, &no_yaw}) {
    for (double offset : GnssHeadingOffsets(*log, DefaultModelConfig(log->vehicle))) {
      EXPECT_EQ(offset, 0.0);
    }
  }
}

TEST(GnssHeadingOffsets, TheModelsSwitchTurnsItOff) {
  const DriveLog log = StraightLog();
  ModelConfig model = DefaultModelConfig(log.vehicle);
  model.gnss_heading_from_course = false;
  for (double offset : GnssHeadingOffsets(log, model)) EXPECT_EQ(offset, 0.0);
}

}  // namespace
}  // namespace slipgraph
