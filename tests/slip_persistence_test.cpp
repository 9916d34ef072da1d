// The wheels' check on the accelerometer bias (solvers/slip_persistence.h), on synthetic cycles
// at 100 Hz: what it measures for a bias, for a slip that persists while the wheels speed up, for
// a stop the accelerometer feels, for a bias error that lasts beyond the gate and a force that
// lasts, and where it measures nothing.
#include "solvers/slip_persistence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace slipgraph {
namespace {

constexpr double kDt_s = 0.01;
constexpr double kBiasVarianceMps2Sq = 0.02 * 0.02;  // the filter's P(b_ax, b_ax), for the gate
constexpr double kRemovedBiasMps2 = 0.03;            // the c_ax + b_ax the prediction removes

SlipPersistenceConfig Config() {
  SlipPersistenceConfig c;
  c.interval_s = 0.3;
  c.sd_mps = 0.005;
  c.gate_sd = 3.0;
  c.smoothing_s = 0.1;
  c.min_rim_speed_mps = 0.03;
  c.max_rim_acceleration_mps2 = 0.01;
  c.lasting_intervals = 3;
  c.max_lasting_error_mps2 = 0.1;
  return c;
}

struct Closed {
  double t_s;
  SlipPersistence::Outcome outcome;
  SlipPersistence::Measurement measurement;
};

// Runs `seconds` of cycles: at each, the prediction's velocity change felt_dv(t) (with
// kRemovedBiasMps2 removed), then the rim speed rim(t) and body velocity v(t) after the cycle.
// Returns the intervals that closed.
std::vector<Closed> RunCycles(SlipPersistence* check, double seconds,
                              const std::function<double(double)>& felt_dv,
                              const std::function<double(double)>& rim,
                              const std::function<double(double)>& v) {
  std::vector<Closed> closed;
  for (int k = 0; k * kDt_s <= seconds + 1e-9; ++k) {
    const double t = k * kDt_s;
    if (k > 0) check->AddFeltVelocityChange(felt_dv(t), kRemovedBiasMps2 * kDt_s);
    SlipPersistence::Measurement m;
    const SlipPersistence::Outcome outcome =
        check->Cycle({t, rim(t), v(t), kBiasVarianceMps2Sq}, &m);
    if (outcome != SlipPersistence::Outcome::kNone) closed.push_back({t, outcome, m});
  }
  return closed;
}

TEST(SlipPersistence, OffMeasuresNothing) {
  SlipPersistenceConfig c = Config();
  c.interval_s = 0.0;
  SlipPersistence check(c);
  EXPECT_FALSE(check.enabled());
  const auto closed = RunCycles(
      &check, 5.0, [](double) { return 0.001; }, [](double) { return 0.5; },
      [](double) { return 0.5; });
  EXPECT_TRUE(closed.empty());
}

// At a steady 0.12 m/s with the bias estimate 0.04 m/s^2 below the true one, the prediction's
// velocity rises 0.04 m/s a second while the wheels hold theirs: each interval measures the
// bias's error, 0.04 m/s^2, with variance (sd / T)^2, inside the gate, once the smoothing has
// settled on the ramp (its lag's transient decays as exp(-t / 0.1 s)); the bias the prediction
// removed comes back through the same smoothing.
TEST(SlipPersistence, ASteadyDriveMeasuresTheBiasError) {
  SlipPersistence check(Config());
  const auto closed = RunCycles(
      &check, 5.0, [](double) { return 0.04 * kDt_s; }, [](double) { return 0.12; },
      [](double) { return 0.12; });
  ASSERT_GE(closed.size(), 15u);
  for (const Closed& c : closed) {
    EXPECT_EQ(c.outcome, SlipPersistence::Outcome::kMeasured);
    EXPECT_NEAR(c.measurement.variance_mps2_sq, (0.005 / 0.3) * (0.005 / 0.3), 1e-12);
    if (c.t_s > 1.5) {
      EXPECT_NEAR(c.measurement.innovation_mps2, 0.04, 1e-7) << "t " << c.t_s;
      EXPECT_NEAR(c.measurement.removed_bias_mps2, kRemovedBiasMps2, 1e-7) << "t " << c.t_s;
    }
  }
  EXPECT_NEAR(closed[1].t_s - closed[0].t_s, 0.3, 1e-9);  // back to back from the first cycle
}

// The wheels speed up from 0.2 to 0.6 m/s over 4 s at a slip of 10 %: the body follows at 0.9
// of the rim speed and the accelerometer feels exactly that. With the rim acceleration allowed,
// every interval is measured, and reads no bias: both series pass through the same linear
// smoothing, so the persisting slip cancels to rounding, bends of the ramp included.
TEST(SlipPersistence, APersistingSlipMeasuresNothing) {
  SlipPersistenceConfig c = Config();
  c.max_rim_acceleration_mps2 = 1.0;
  SlipPersistence check(c);
  const auto rim = [](double t) { return t < 1.0 ? 0.2 : t < 5.0 ? 0.2 + 0.1 * (t - 1.0) : 0.6; };
  const auto closed = RunCycles(
      &check, 8.0,
      [](double t) { return t > 1.0 + 1e-9 && t < 5.0 + 1e-9 ? 0.9 * 0.1 * kDt_s : 0.0; }, rim,
      [&](double t) { return 0.9 * rim(t); });
  ASSERT_GE(closed.size(), 20u);
  for (const Closed& c : closed) {
    EXPECT_EQ(c.outcome, SlipPersistence::Outcome::kMeasured) << "t " << c.t_s;
    EXPECT_NEAR(c.measurement.innovation_mps2, 0.0, 1e-9) << "t " << c.t_s;
  }
}

// A hold-back: at 3 s the body stops within 0.1 s (the accelerometer feels -1.2 m/s^2) while the
// wheels keep their speed. The interval that holds the stop measures about -v / T, far outside
// the gate, and is left out with the next one (the smoothed tail); after them a slip of 1
// persists and reads as no bias again.
TEST(SlipPersistence, AStopTheAccelerometerFeelsIsLeftOut) {
  SlipPersistence check(Config());
  const double v0 = 0.12;
  const auto closed = RunCycles(
      &check, 6.0, [&](double t) { return t > 3.0 + 1e-9 && t <= 3.1 + 1e-9 ? -v0 / 10.0 : 0.0; },
      [&](double) { return v0; }, [&](double t) { return t < 3.0   ? v0
                                                         : t < 3.1 ? 0.05
                                                                   : 0.0; });
  double most_negative = 0.0;
  int left_out = 0;
  for (const Closed& c : closed) {
    most_negative = std::min(most_negative, c.measurement.innovation_mps2);
    if (c.outcome == SlipPersistence::Outcome::kLeftOut) {
      ++left_out;
      EXPECT_GT(c.t_s, 3.0);
      EXPECT_LT(c.t_s, 3.7);
    } else if (c.t_s > 3.8) {
      // The smoothed stop's tail: exp(-5) of it one interval on, nothing two on.
      EXPECT_NEAR(c.measurement.innovation_mps2, 0.0, c.t_s < 4.0 ? 3e-3 : 1e-4) << "t " << c.t_s;
    }
  }
  // The stop, smoothed, falls mostly in one interval: there at least half of -v / T, ten times
  // the measurement's sd (0.005 / 0.3); it and the one after are left out.
  EXPECT_LT(most_negative, -0.5 * v0 / 0.3);
  EXPECT_EQ(left_out, 2);
}

// A wheel stalled with its held body spins up (0.04 to 0.16 m/s over 1.5 s) while the body stays
// still: its slip rises on its own. No interval over which the wheels sped up is measured; the
// ones before and after the spin-up are, and read no bias.
TEST(SlipPersistence, NothingWhileTheWheelsChangeSpeed) {
  SlipPersistence check(Config());
  const auto rim = [](double t) {
    return t < 2.0 ? 0.04 : t < 3.5 ? 0.04 + 0.08 * (t - 2.0) : 0.16;
  };
  const auto closed = RunCycles(
      &check, 6.0, [](double) { return 0.0; }, rim, [](double) { return 0.0; });
  ASSERT_FALSE(closed.empty());
  for (const Closed& c : closed) {
    EXPECT_FALSE(c.t_s > 2.05 && c.t_s < 3.8) << "measured while the wheels spun up, at " << c.t_s;
    EXPECT_EQ(c.outcome, SlipPersistence::Outcome::kMeasured);
    EXPECT_NEAR(c.measurement.innovation_mps2, 0.0, 1e-12);
  }
}

// Nothing is measured while the wheels are below the rim speed floor (just above it, every
// interval is), nor across a reversal.
TEST(SlipPersistence, NothingBelowTheFloorOrAcrossAReversal) {
  const auto steady = [](SlipPersistence* check, double rim_mps) {
    return RunCycles(
        check, 5.0, [](double) { return 0.0; }, [rim_mps](double) { return rim_mps; },
        [rim_mps](double) { return rim_mps; });
  };
  SlipPersistence slow(Config()), above(Config());
  EXPECT_TRUE(steady(&slow, 0.02).empty());
  EXPECT_GE(steady(&above, 0.04).size(), 15u);
  SlipPersistenceConfig c = Config();
  c.smoothing_s = 0.001;              // the rim speed's sign as given
  c.max_rim_acceleration_mps2 = 1.0;  // a reversal's speed change allowed: the sign decides
  c.interval_s = 1.0;
  SlipPersistence reversing(c);
  // Forward at 0.2 m/s, then backward from 1.5 s: the interval open at the reversal (opened at
  // 1 s) closes on the other side at 2 s and measures nothing; the next opens there.
  const auto closed = RunCycles(
      &reversing, 4.0, [](double) { return 0.0; }, [](double t) { return t < 1.5 ? 0.2 : -0.2; },
      [](double t) { return t < 1.5 ? 0.2 : -0.2; });
  ASSERT_FALSE(closed.empty());
  for (const Closed& closed_at : closed) {
    EXPECT_GT(std::abs(closed_at.t_s - 2.0), 0.005) << "measured across the reversal";
  }
}

// The bias estimate 0.09 m/s^2 below the true one at a steady 0.12 m/s: beyond the gate (3 x
// sqrt(0.02^2 + (0.005 / 0.3)^2) = 0.078 m/s^2), but lasting, and within the 0.1 m/s^2 a bias
// error may be. Its first two gated intervals are left out as a force's pulse and tail would be;
// the third is applied with the velocity the prediction gained over all three (v_bx's error
// -3 x 0.09 x 0.3 m/s, variance 3 sd^2), and each after it with its own interval's. Off, every
// gated interval is left out.
TEST(SlipPersistence, ALastingBiasErrorIsAppliedWithTheVelocityItMoved) {
  const auto run = [](int lasting_intervals) {
    SlipPersistenceConfig c = Config();
    c.lasting_intervals = lasting_intervals;
    SlipPersistence check(c);
    return RunCycles(
        &check, 5.0, [](double) { return 0.09 * kDt_s; }, [](double) { return 0.12; },
        [](double) { return 0.12; });
  };
  const auto closed = run(3);
  size_t first_applied = 0;
  while (first_applied < closed.size() &&
         closed[first_applied].measurement.velocity_variance_mps_sq == 0.0) {
    ++first_applied;
  }
  ASSERT_GE(first_applied, 2u);
  ASSERT_LT(first_applied + 2, closed.size());
  for (size_t i = first_applied - 2; i < first_applied; ++i) {
    EXPECT_EQ(closed[i].outcome, SlipPersistence::Outcome::kLeftOut) << "t " << closed[i].t_s;
    EXPECT_GT(closed[i].measurement.innovation_mps2, 0.078) << "t " << closed[i].t_s;
  }
  const Closed& first = closed[first_applied];
  EXPECT_EQ(first.outcome, SlipPersistence::Outcome::kMeasured);
  EXPECT_NEAR(first.measurement.innovation_mps2, 0.09, 0.005);
  // The run's first interval keeps a trace of the smoothing's start-up lag (well under 1 mm/s).
  EXPECT_NEAR(first.measurement.velocity_innovation_mps, -3 * 0.09 * 0.3, 0.001);
  EXPECT_NEAR(first.measurement.velocity_variance_mps_sq, 3 * 0.005 * 0.005, 1e-12);
  for (size_t i = first_applied + 1; i < closed.size(); ++i) {
    EXPECT_EQ(closed[i].outcome, SlipPersistence::Outcome::kMeasured) << "t " << closed[i].t_s;
    EXPECT_NEAR(closed[i].measurement.velocity_innovation_mps, -0.09 * 0.3, 1e-6);
    EXPECT_NEAR(closed[i].measurement.velocity_variance_mps_sq, 0.005 * 0.005, 1e-12);
  }
  for (const Closed& c : run(0)) {
    if (c.t_s > 1.0) {
      EXPECT_EQ(c.outcome, SlipPersistence::Outcome::kLeftOut) << "t " << c.t_s;
    }
    EXPECT_EQ(c.measurement.velocity_variance_mps_sq, 0.0);
  }
}

// A robot that speeds up after a hold-back while its wheels hold their speed (the slip falls from
// 1 to 0 over 2 s) feels 0.3 m/s^2 all that time: lasting, but more than a bias error may be, so
// every interval it fills is left out.
TEST(SlipPersistence, ALastingForceBeyondABiasErrorIsLeftOut) {
  SlipPersistence check(Config());
  const auto closed = RunCycles(
      &check, 4.0, [](double t) { return t > 1.0 && t <= 3.0 ? 0.3 * kDt_s : 0.0; },
      [](double) { return 0.6; }, [](double t) { return std::clamp(0.3 * (t - 1.0), 0.0, 0.6); });
  int left_out = 0;
  for (const Closed& c : closed) {
    EXPECT_EQ(c.measurement.velocity_variance_mps_sq, 0.0) << "t " << c.t_s;
    if (c.t_s > 1.3 && c.t_s < 3.0) {
      EXPECT_EQ(c.outcome, SlipPersistence::Outcome::kLeftOut) << "t " << c.t_s;
      ++left_out;
    }
  }
  EXPECT_GE(left_out, 5);
}

// Intervals at given bias errors (m/s^2, one per 0.3 s interval from 0 s on, 0 after), with
// the smoothing so short that each interval reads its own; the bias variance as in the others.
std::vector<Closed> RunIntervals(const std::vector<double>& errors_mps2) {
  SlipPersistenceConfig c = Config();
  c.smoothing_s = 0.001;
  SlipPersistence check(c);
  const auto rate = [errors_mps2](double t) {
    const int i = static_cast<int>(std::floor((t - 1e-9) / 0.3));
    return i >= 0 && i < static_cast<int>(errors_mps2.size()) ? errors_mps2[i] : 0.0;
  };
  const double seconds = 0.3 * (errors_mps2.size() + 1);
  return RunCycles(
      &check, seconds, [&](double t) { return rate(t) * kDt_s; }, [](double) { return 0.12; },
      [](double) { return 0.12; });
}

// Which runs make a lasting error (gate 0.078 m/s^2, bound 0.1): a gated interval, its tail back
// inside the gate (but beyond 3 of its own sd, 0.05 m/s^2) and a gated one continue a run (applied
// at the third, with all three's velocity); a change of sign ends one, and so does a tail that
// reads no error; the tail of a force beyond the bound starts none, so its next three gated
// intervals are a new run.
TEST(SlipPersistence, WhichIntervalsMakeALastingRun) {
  const auto lasting = [](const std::vector<Closed>& closed) {
    std::vector<int> at;  // the indices (from the first interval, 0) applied as lasting errors
    for (size_t i = 0; i < closed.size(); ++i) {
      if (closed[i].measurement.velocity_variance_mps_sq > 0.0) at.push_back(static_cast<int>(i));
    }
    return at;
  };
  const auto tail_inside = RunIntervals({0.0, 0.09, 0.07, 0.09});
  ASSERT_EQ(lasting(tail_inside), std::vector<int>{3});
  EXPECT_NEAR(tail_inside[3].measurement.velocity_innovation_mps, -(0.09 + 0.07 + 0.09) * 0.3,
              1e-6);
  EXPECT_EQ(tail_inside[2].outcome, SlipPersistence::Outcome::kLeftOut);
  EXPECT_TRUE(lasting(RunIntervals({0.0, 0.09, 0.09, -0.09, -0.09})).empty());
  EXPECT_EQ(lasting(RunIntervals({0.0, 0.09, 0.09, -0.09, -0.09, -0.09})), std::vector<int>{5});
  EXPECT_EQ(lasting(RunIntervals({0.0, 0.2, 0.09, 0.09, 0.09, 0.09})), std::vector<int>{5});
}

// A configuration with the check on and a smoothing of zero is refused, not run into 0 / 0.
TEST(SlipPersistence, AnInvalidConfigIsRefused) {
  SlipPersistenceConfig c = Config();
  c.smoothing_s = 0.0;
  std::string error;
  EXPECT_FALSE(c.IsValid(&error));
  EXPECT_NE(error.find("slip_persistence.smoothing"), std::string::npos) << error;
  EXPECT_THROW(SlipPersistence{c}, std::invalid_argument);
  c.interval_s = 0.0;  // off: the rest is not read
  EXPECT_TRUE(c.IsValid(&error));
  c = Config();
  c.lasting_intervals = -1;
  EXPECT_FALSE(c.IsValid(&error));
  EXPECT_NE(error.find("slip_persistence.lasting_intervals"), std::string::npos) << error;
  c = Config();
  c.max_lasting_error_mps2 = 0.0;
  EXPECT_FALSE(c.IsValid(&error));
  EXPECT_NE(error.find("slip_persistence.max_lasting_error"), std::string::npos) << error;
}

}  // namespace
}  // namespace slipgraph
