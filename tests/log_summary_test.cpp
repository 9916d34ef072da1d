#include "io/log_summary.h"

#include <gtest/gtest.h>

#include <sstream>

namespace slipgraph {
namespace {

DriveLog SteadyLog() {
  DriveLog log;
  log.directory = "mem";
  log.vehicle.name = "test";
  log.present_files = {"vehicle.yaml", "imu.csv", "wheels.csv"};
  for (int k = 0; k < 1000; ++k) {
    const double t = 0.01 * k;
    if (k < 400 || k > 450) log.imu.push_back({t, 0.0, 0.0, 9.81, 0.0, 0.0, 0.0});  // 0.5 s gap
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

}  // namespace
}  // namespace slipgraph
