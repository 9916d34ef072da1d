// Immobilization on smoothed states: flagged where the wheels turn and the body does not, for at
// least the minimum duration; a shorter blip, ordinary driving slip and braking are not flagged.
#include "solvers/smoothed_detection.h"

#include <gtest/gtest.h>

#include <vector>

#include "model/model_config.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state indices

Vehicle Lagr() {
  Vehicle v;
  v.mass_kg = 117.0;
  v.wheel_radius_m = 0.25;
  v.track_width_m = 0.55;
  return v;
}

// 100 Hz states: driving at 1 m/s with 10 % slip, a hold-back (wheels at 4 rad/s, body still)
// from 1.0 to 1.4 s, a 0.05 s blip at 2.0 s, braking (body faster than the wheels) at 3 s.
std::vector<WardEstimate> States() {
  std::vector<WardEstimate> out;
  for (int k = 0; k < 400; ++k) {
    WardEstimate e;
    e.t = 0.01 * k;
    const bool hold = e.t >= 1.0 - 1e-9 && e.t < 1.4 - 1e-9;
    const bool blip = e.t >= 2.0 - 1e-9 && e.t < 2.05 - 1e-9;
    const bool braking = e.t >= 3.0 - 1e-9;
    const double omega = hold || blip ? 4.0 : 1.0 / 0.25 / 0.9;
    e.x[kVbx] = hold || blip ? 0.0 : braking ? 1.0 : 1.0;
    e.x[kOmegaLeft] = e.x[kOmegaRight] = braking ? 2.0 : omega;
    out.push_back(e);
  }
  return out;
}

TEST(SmoothedDetection, FlagsAHoldBackThatLastsAndNothingElse) {
  const Vehicle vehicle = Lagr();
  std::vector<WardEstimate> states = States();
  DetectImmobilizationOnSmoothedStates(DefaultModelConfig(vehicle), vehicle, 0.1, &states);
  for (const WardEstimate& e : states) {
    const bool hold = e.t >= 1.0 - 1e-9 && e.t < 1.4 - 1e-9;
    EXPECT_EQ(e.slip.immobilized, hold) << "t=" << e.t;
    // Smoothed: no EMA, the mean of the sides.
    EXPECT_DOUBLE_EQ(e.slip.slip_ema, 0.5 * (e.slip.slip_left + e.slip.slip_right));
  }
  EXPECT_NEAR(states[50].slip.slip_left, 0.1, 1e-12);  // driving: slip 1 - v / (r w)
  EXPECT_TRUE(states[350].slip.braking);
}

TEST(SmoothedDetection, TheMinimumDurationDropsShortRuns) {
  const Vehicle vehicle = Lagr();
  std::vector<WardEstimate> states = States();
  DetectImmobilizationOnSmoothedStates(DefaultModelConfig(vehicle), vehicle, 0.0, &states);
  EXPECT_TRUE(states[202].slip.immobilized);  // the 0.05 s blip, kept without a minimum
  states = States();
  DetectImmobilizationOnSmoothedStates(DefaultModelConfig(vehicle), vehicle, 0.5, &states);
  for (const WardEstimate& e : states) EXPECT_FALSE(e.slip.immobilized) << "t=" << e.t;
}

}  // namespace
}  // namespace slipgraph
