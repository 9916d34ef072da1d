#include "evaluation/evaluation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/input_error.h"

namespace slipgraph {
namespace {

// Truth: 10 s at 10 Hz, v = 1 except immobilized in [4, 6].
DriveLog TruthLog() {
  DriveLog log;
  log.directory = "synthetic";
  for (int k = 0; k <= 100; ++k) {
    TruthSample s;
    s.t = 0.1 * k;
    const bool held = s.t >= 4.0 && s.t <= 6.0;
    s.vx = held ? 0.0 : 1.0;
    s.a_dist = held ? -2.0 : 0.0;
    s.immobilized = held ? 1.0 : 0.0;
    log.truth.push_back(s);
  }
  log.events.push_back({4.0, 6.0, "immobilized"});
  return log;
}

TEST(Evaluation, HandComputedScores) {
  const DriveLog log = TruthLog();
  NumericTable est;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.1 * k;
    const bool held = t >= 4.0 && t <= 6.0;
    est.columns["t"].push_back(t);
    est.columns["v_bx"].push_back((held ? 0.0 : 1.0) + 0.1);  // biased by 0.1 m/s
    // sd 0.1 on even samples (NEES 1, inside the bound), 0.01 on odd ones (NEES 100, outside).
    est.columns["sd_v_bx"].push_back(k % 2 == 0 ? 0.1 : 0.01);
    est.columns["a_dist"].push_back(held ? -2.0 : 0.0);
    // Flags from 4.3 s (delay 0.3 s) to 6.0 s, plus a false alarm at 8.0 and 8.1 s.
    const bool flag = (t >= 4.3 - 1e-9 && t <= 6.0 + 1e-9) || std::abs(t - 8.0) < 1e-9 ||
                      std::abs(t - 8.1) < 1e-9;
    est.columns["immobilized"].push_back(flag ? 1.0 : 0.0);
  }
  const Evaluation ev = Evaluate(log, est);
  EXPECT_EQ(ev.samples, 101u);
  EXPECT_NEAR(ev.velocity_rmse, 0.1, 1e-9);
  EXPECT_NEAR(ev.disturbance_rmse, 0.0, 1e-9);
  EXPECT_EQ(ev.detected(), 1);
  EXPECT_NEAR(ev.mean_detection_delay_s(), 0.3, 1e-9);
  EXPECT_EQ(ev.false_immobilized_samples, 2);
  EXPECT_NEAR(ev.false_immobilized_fraction(), 2.0 / 101.0, 1e-12);
  EXPECT_NEAR(ev.nees_within_95_fraction(), 51.0 / 101.0, 1e-12);
  EXPECT_NEAR(ev.velocity_mean_nees, (51.0 * 1.0 + 50.0 * 100.0) / 101.0, 1e-6);
  const nlohmann::json json = ToJson(ev);
  for (const char* key : {"velocity_rmse", "disturbance_rmse", "events", "detected",
                          "mean_detection_delay_s", "false_immobilized_fraction"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
}

// A flag raised 1.2 s before the event and held into it: its samples before t_start - 0.5 are
// false alarms, and it detects the event at -0.5 s, not at -1.2.
TEST(Evaluation, EarlyFlagIsFalseUntilHalfASecondBeforeTheEvent) {
  const DriveLog log = TruthLog();
  NumericTable est;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.1 * k;
    est.columns["t"].push_back(t);
    est.columns["v_bx"].push_back(t >= 4.0 && t <= 6.0 ? 0.0 : 1.0);
    est.columns["immobilized"].push_back(t >= 2.8 - 1e-9 && t <= 6.0 + 1e-9 ? 1.0 : 0.0);
  }
  const Evaluation ev = Evaluate(log, est);
  EXPECT_EQ(ev.detected(), 1);
  EXPECT_NEAR(ev.mean_detection_delay_s(), -0.5, 1e-9);
  // 2.8, 2.9, ..., 3.4 s: seven samples before 3.5 s.
  EXPECT_EQ(ev.false_immobilized_samples, 7);
}

TEST(Evaluation, MissedEventAndSuiteTotals) {
  const DriveLog log = TruthLog();
  NumericTable est;
  for (int k = 0; k <= 100; ++k) {
    est.columns["t"].push_back(0.1 * k);
    est.columns["v_bx"].push_back(1.0);
    est.columns["immobilized"].push_back(0.0);
  }
  const Evaluation missed = Evaluate(log, est);
  EXPECT_EQ(missed.detected(), 0);
  EXPECT_TRUE(std::isnan(missed.mean_detection_delay_s()));
  EXPECT_TRUE(std::isnan(missed.disturbance_rmse));  // no a_dist column
  const Evaluation total = Combine({missed, missed}, "two");
  EXPECT_EQ(total.events.size(), 2u);
  EXPECT_EQ(total.samples, 202u);
  EXPECT_NEAR(total.velocity_rmse, missed.velocity_rmse, 1e-12);
}

}  // namespace
}  // namespace slipgraph

namespace slipgraph {
namespace {

// Estimates shifted by 1000 s were scored against the truth's last sample, and one NaN made the
// RMSE NaN (JSON null): both are errors naming the row.
TEST(Evaluation, EstimatesOffTheTruthOrNotFiniteAreErrors) {
  const DriveLog log = TruthLog();
  NumericTable est;
  est.path = "est.csv";
  for (int k = 0; k <= 100; ++k) {
    est.columns["t"].push_back(1000.0 + 0.1 * k);
    est.columns["v_bx"].push_back(1.0);
    est.columns["immobilized"].push_back(0.0);
  }
  try {
    Evaluate(log, est);
    FAIL() << "shifted estimates scored";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "est.csv");
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.column(), "t");
  }
  for (int k = 0; k <= 100; ++k) est.columns["t"][k] = 0.1 * k;
  EXPECT_NO_THROW(Evaluate(log, est));
  est.columns["v_bx"][7] = std::nan("");
  try {
    Evaluate(log, est);
    FAIL() << "a NaN estimate scored";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 9);
    EXPECT_EQ(e.column(), "v_bx");
  }
}

}  // namespace
}  // namespace slipgraph
