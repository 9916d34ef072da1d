#include "io/estimate_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

TEST(EstimateFile, WritesStandardDeviationsBesideValuesAndReadsBack) {
  const std::string path = testing::FreshDirectory("est") + "/estimates.csv";
  {
    EstimateWriter writer(path, {{"v_bx", true}, {"immobilized", false}, {"a_dist", true}});
    writer.Write(0.0, {1.25, 0.0, -0.5}, {0.1, 0.0, 0.2});
    writer.Write(0.01, {1.5, 1.0, std::nan("")}, {0.1, 0.0, std::nan("")});
  }
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "t,v_bx,sd_v_bx,immobilized,a_dist,sd_a_dist");
  const NumericTable table = ReadNumericTable(path);
  ASSERT_EQ(table.rows(), 2u);
  EXPECT_EQ(table.columns.at("v_bx")[1], 1.5);
  EXPECT_EQ(table.columns.at("sd_a_dist")[0], 0.2);
  EXPECT_TRUE(std::isnan(table.columns.at("a_dist")[1]));
  EXPECT_EQ(table.columns.at("t")[1], 0.01);
}

}  // namespace
}  // namespace slipgraph
