// The commanded velocity: zero while at rest, each segment in turn, ramped at the actuation's
// limits (a step takes target / limit seconds), back to zero after the last segment.
#include "sim/command_schedule.h"

#include <gtest/gtest.h>

namespace slipgraph {
namespace sim {
namespace {

TEST(CommandSchedule, RestSegmentsAndRamps) {
  Scenario sc;
  sc.rest_start_s = 1.0;
  sc.commands = {{3.0, 1.6, 0.0}, {2.0, 1.6, 0.5}};
  sc.actuation.accel_limit_mps2 = 0.8;
  sc.actuation.yaw_accel_limit_radps2 = 2.0;
  CommandSchedule s(sc);
  const double dt = 0.01;
  double t = 0.0;
  const auto run_to = [&](double end) {
    for (; t < end - 1e-9; t += dt) s.Step(t, dt);
  };
  run_to(1.0);
  EXPECT_EQ(s.v_mps(), 0.0);
  run_to(2.0);
  EXPECT_NEAR(s.v_mps(), 0.8, 1e-9);  // ramping at 0.8 m/s^2
  run_to(3.5);
  EXPECT_NEAR(s.v_mps(), 1.6, 1e-9);  // reached after 2 s
  EXPECT_EQ(s.yaw_rate_radps(), 0.0);
  run_to(4.1);
  // The second segment's turn, at 2 rad/s^2 (within a step: t is a sum of steps).
  EXPECT_NEAR(s.yaw_rate_radps(), 0.2, 2.0 * dt + 1e-9);
  run_to(6.0);
  EXPECT_NEAR(s.yaw_rate_radps(), 0.5, 1e-9);
  run_to(9.0);
  EXPECT_NEAR(s.v_mps(), 0.0, 1e-9);  // after the last segment: stopped
  EXPECT_NEAR(s.yaw_rate_radps(), 0.0, 1e-9);
}

}  // namespace
}  // namespace sim
}  // namespace slipgraph
