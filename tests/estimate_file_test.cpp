#include "io/estimate_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

TEST(EstimateFile, WritesTheTablesColumnsInOrderAndReadsBack) {
  const std::string path = testing::FreshDirectory("est") + "/estimates.csv";
  NumericTable written;
  written.names = {"t", "v_bx", "sd_v_bx", "immobilized"};
  written.columns = {{"t", {0.0, 0.01}},
                     {"v_bx", {1.25, std::nan("")}},
                     {"sd_v_bx", {0.1, 0.2}},
                     {"immobilized", {0.0, 1.0}}};
  WriteNumericTable(written, path);
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "t,v_bx,sd_v_bx,immobilized");
  const NumericTable table = ReadNumericTable(path);
  ASSERT_EQ(table.rows(), 2u);
  EXPECT_EQ(table.columns.at("v_bx")[0], 1.25);
  EXPECT_TRUE(std::isnan(table.columns.at("v_bx")[1]));
  EXPECT_EQ(table.columns.at("sd_v_bx")[1], 0.2);
  EXPECT_EQ(table.columns.at("t")[1], 0.01);
}

TEST(EstimateFile, AShortColumnIsAnErrorNotAShortFile) {
  NumericTable table;
  table.names = {"t", "v_bx"};
  table.columns = {{"t", {0.0, 0.01}}, {"v_bx", {1.0}}};
  EXPECT_THROW(WriteNumericTable(table, testing::FreshDirectory("est") + "/short.csv"),
               std::logic_error);
}

TEST(EstimateFile, EveryStateIsFollowedByItsSdAndTheVerdictsComeLast) {
  WardEstimate e;
  e.t = 2.5;
  for (int i = 0; i < ward::kStateSize; ++i) e.x[i] = i + 1.0, e.sd[i] = 0.1 * (i + 1);
  e.slip.slip_left = 0.3;
  e.slip.immobilized = true;
  e.gyro_offset_radps = -0.01;
  const NumericTable table = EstimateColumns({e}, {{"lag_s", {0.4}}});
  const std::vector<std::string> expected = {
      "t",           "v_bx",         "sd_v_bx",       "b_ax",        "sd_b_ax",        "a_dist",
      "sd_a_dist",   "omega_left",   "sd_omega_left", "omega_right", "sd_omega_right", "yaw_rate",
      "sd_yaw_rate", "b_gz",         "sd_b_gz",       "slip_left",   "slip_right",     "slip_ema",
      "immobilized", "accel_offset", "gyro_offset",   "lag_s"};
  EXPECT_EQ(table.names, expected);
  EXPECT_EQ(table.columns.at("a_dist")[0], 3.0);
  EXPECT_DOUBLE_EQ(table.columns.at("sd_b_gz")[0], 0.7);
  EXPECT_EQ(table.columns.at("slip_left")[0], 0.3);
  EXPECT_EQ(table.columns.at("immobilized")[0], 1.0);
  EXPECT_EQ(table.columns.at("gyro_offset")[0], -0.01);
  EXPECT_EQ(table.columns.at("lag_s")[0], 0.4);
  EXPECT_THROW(EstimateColumns({e, e}, {{"lag_s", {0.4}}}), std::logic_error);
}

}  // namespace
}  // namespace slipgraph
