#include "io/log_summary.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "io/input_error.h"

namespace slipgraph {
namespace {

DriveLog SteadyLog() {
  DriveLog log;
  log.directory = "mem";
  log.vehicle.name = "test";
  log.present_files = {"vehicle.yaml", "imu.csv", "wheels.csv"};
  for (int k = 0; k < 1000; ++k) {
    const double t = 0.01 * k;
    // A 0.5 s gap; each sample a little different, as a live sensor's are.
    if (k < 400 || k > 450) log.imu.push_back({t, 0.0, 0.0, 9.81 + 1e-4 * (k % 7), 0.0, 0.0, 0.0});
    WheelSample w;
    w.t = t;
    log.wheels.push_back(w);
  }
  return log;
}

TEST(LogSummary, ReportsRatesDurationAndGaps) {
  const LogSummary s = SummarizeLog(SteadyLog());
  ASSERT_EQ(s.streams.size(), 2u);
  EXPECT_NEAR(s.streams[0].rate_hz, 100.0, 1e-6);
  ASSERT_EQ(s.streams[0].gaps.size(), 1u);
  EXPECT_NEAR(s.streams[0].gaps[0].first, 3.99, 1e-9);
  EXPECT_NEAR(s.streams[0].gaps[0].second, 4.51, 1e-9);
  EXPECT_TRUE(s.streams[1].gaps.empty());
  EXPECT_NEAR(s.t_end_s - s.t_start_s, 9.99, 1e-9);
  ASSERT_EQ(s.problems.size(), 1u);
  EXPECT_NE(s.problems[0].find("imu: gap of 0.520 s"), std::string::npos);
  std::ostringstream out;
  PrintLogSummary(SteadyLog(), s, out);
  EXPECT_NE(out.str().find("(no gps.csv)"), std::string::npos);
}

TEST(LogSummary, FlagsAZDownImu) {
  DriveLog log = SteadyLog();
  for (ImuSample& s : log.imu) s.az = -9.81;
  const LogSummary s = SummarizeLog(log);
  bool flagged = false;
  for (const std::string& p : s.problems)
    flagged = flagged || p.find("z axis points down") != std::string::npos;
  EXPECT_TRUE(flagged);
}

bool Mentions(const std::vector<std::string>& problems, const std::string& text) {
  for (const std::string& p : problems) {
    if (p.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(LogSummary, AFrozenImuIsNamedWithItsSpan) {
  DriveLog log = SteadyLog();
  for (ImuSample& s : log.imu) {
    if (s.t >= 6.0 && s.t < 8.0) s.az = 9.5, s.ax = 0.1;  // 2 s of one value
  }
  EXPECT_TRUE(Mentions(SummarizeLog(log).problems,
                       "imu: every channel frozen at one value for 1.990 s from t=6.000"));
}

// GNSS fixes at 1 Hz, sd 0.5 m, driving east at `speed` (or standing, with 2 m of noise).
void AddGnss(DriveLog* log, double speed, double noise_m) {
  log->present_files.push_back("gps.csv");
  for (int k = 0; k < 10; ++k) {
    GpsSample g;
    g.t = k;
    g.x = speed * k + noise_m * ((k * 7) % 5 - 2) / 2.0;
    g.y = noise_m * ((k * 3) % 5 - 2) / 2.0;
    g.vx = speed, g.vy = 0.0;
    g.sd_xy = 0.5;
    log->gps.push_back(g);
  }
}

TEST(LogSummary, AWheelStuckWhileGnssMovesIsNamed) {
  DriveLog log = SteadyLog();
  for (size_t k = 0; k < log.wheels.size(); ++k) {
    log.wheels[k].omega_radps[0] = log.wheels[k].t < 3.0 ? 0.0 : 4.0 + 1e-3 * (k % 5);
    log.wheels[k].omega_radps[1] = 4.0 + 1e-3 * (k % 3);
  }
  DriveLog moving = log;
  AddGnss(&moving, 1.5, 0.0);
  EXPECT_TRUE(Mentions(SummarizeLog(moving).problems,
                       "wheels: left unchanged at 0 rad/s for 2.990 s from t=0.000 while GNSS "
                       "moves at 1.50 m/s"));
  // Standing still with noisy fixes (differences of several metres): not evidence of motion.
  DriveLog standing = log;
  AddGnss(&standing, 0.0, 1.0);
  EXPECT_FALSE(Mentions(SummarizeLog(standing).problems, "stuck encoder"));
}

// The reader's warnings are kept apart from what the summary finds: `info` lists both, an
// estimator shows its reader's warnings once and the summary's findings beside them.
TEST(LogSummary, ReaderWarningsAreKeptApartFromWhatTheDataShows) {
  DriveLog log = SteadyLog();
  log.warnings = {"imu.csv:7: column 'ax': value 'x': not a number (row skipped: --skip-bad)"};
  const LogSummary s = SummarizeLog(log);
  EXPECT_EQ(s.reader_warnings, log.warnings);
  ASSERT_EQ(s.problems.size(), 1u);
  EXPECT_NE(s.problems[0].find("imu: gap"), std::string::npos);
  const std::vector<std::string> found = CheckLogForEstimation(log);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0], s.problems[0]);
  std::ostringstream out;
  PrintLogSummary(log, s, out);
  EXPECT_NE(out.str().find("problems: 2\n  - imu.csv:7"), std::string::npos) << out.str();
}

TEST(LogSummary, EstimationNeedsImuAndWheelsOnOneClock) {
  DriveLog log = SteadyLog();
  EXPECT_TRUE(CheckLogForEstimation(log)[0].find("imu: gap") != std::string::npos);
  DriveLog shifted = SteadyLog();
  for (WheelSample& w : shifted.wheels) w.t += 100.0;
  EXPECT_THROW(CheckLogForEstimation(shifted), InputError);
  DriveLog no_wheels = SteadyLog();
  no_wheels.wheels.clear();
  EXPECT_THROW(CheckLogForEstimation(no_wheels), InputError);
}

}  // namespace
}  // namespace slipgraph
