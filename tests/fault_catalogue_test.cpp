// Faults a user meets, run through the program as a user runs it: each case asserts the exit
// status, the message, and that every estimate file written is complete and finite.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/estimate_file.h"

namespace slipgraph {
namespace {

namespace fs = std::filesystem;

const std::string kSample = std::string(SLIPGRAPH_SOURCE_DIR) + "/data/sample";

struct ProgramRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

ProgramRun RunProgram(const std::string& arguments, const std::string& name) {
  const std::string log = std::string(SLIPGRAPH_BINARY_DIR) + "/fault_" + name + ".log";
  const std::string command = std::string(SLIPGRAPH_APP) + " " + arguments + " > " + log + " 2>&1";
  const int status = std::system(command.c_str());
  ProgramRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  run.output = text.str();
  return run;
}

// A copy of the bundled sample log, for a fault to be put in.
std::string CopyOfSample(const std::string& name) {
  const fs::path dir = fs::path(SLIPGRAPH_BINARY_DIR) / ("fault_" + name);
  fs::remove_all(dir);
  fs::copy(kSample, dir);
  return dir.string();
}

// Replaces column `column` of data row `row` (0: the first after the header) of a CSV file.
void SetCell(const std::string& path, size_t row, const std::string& column,
             const std::string& value) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  in.close();
  ASSERT_GT(lines.size(), row + 1);
  std::vector<std::string> header, cells;
  std::stringstream h(lines[0]), r(lines[row + 1]);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  for (std::string cell; std::getline(r, cell, ',');) cells.push_back(cell);
  const auto at = std::find(header.begin(), header.end(), column);
  ASSERT_NE(at, header.end()) << column;
  cells[at - header.begin()] = value;
  std::string joined;
  for (size_t i = 0; i < cells.size(); ++i) joined += (i ? "," : "") + cells[i];
  lines[row + 1] = joined;
  std::ofstream out(path);
  for (const std::string& line : lines) out << line << "\n";
}

// Rows and non-finite values of an estimate file.
void ExpectCompleteAndFinite(const std::string& path, size_t rows) {
  const NumericTable table = ReadNumericTable(path);
  EXPECT_EQ(table.rows(), rows) << path;
  long bad = 0;
  for (const auto& [name, values] : table.columns) {
    for (double v : values) bad += std::isfinite(v) ? 0 : 1;
  }
  EXPECT_EQ(bad, 0) << path << ": non-finite values";
}

size_t WheelRows() { return ReadNumericTable(kSample + "/wheels.csv").rows(); }

// One GNSS velocity of 1e300 (every filter's gate refuses it at an infinite distance): the bank
// of filters weighed its laws with it and wrote NaN from there on; the smoother took the fix and
// failed.
TEST(FaultCatalogue, AnAbsurdGnssVelocityIsLeftOutEverywhere) {
  const std::string log = CopyOfSample("gnss_1e300");
  SetCell(log + "/gps.csv", 5, "vx", "1e300");
  for (const std::string command : {"filter", "smooth", "online"}) {
    SCOPED_TRACE(command);
    const std::string out = log + "_" + command + ".csv";
    const ProgramRun run =
        RunProgram(command + " " + log + " --out " + out, "gnss_1e300_" + command);
    EXPECT_EQ(run.exit_code, 0) << run.output;
    if (command == "filter") {
      EXPECT_NE(run.output.find("1 rejected by the gate"), std::string::npos) << run.output;
    } else {
      EXPECT_NE(run.output.find("(1 outliers left out)"), std::string::npos) << run.output;
      EXPECT_EQ(run.output.find("FALLBACK"), std::string::npos) << run.output;
    }
    EXPECT_NE(run.output.find("trust: no sign of trouble"), std::string::npos) << run.output;
    ExpectCompleteAndFinite(out, WheelRows());
  }
}

// A GNSS velocity outlier of 50 m/s pulled the batch smoother to 0.74 m/s RMSE; the smoothers'
// gate on gross outliers leaves it out.
TEST(FaultCatalogue, AGnssOutlierDoesNotPullTheSmoother) {
  const std::string log = CopyOfSample("gnss_50");
  SetCell(log + "/gps.csv", 8, "vx", "50");
  const std::string out = log + "_smooth.csv";
  const ProgramRun run = RunProgram("smooth " + log + " --out " + out, "gnss_50");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("(1 outliers left out)"), std::string::npos);
  ExpectCompleteAndFinite(out, WheelRows());
  // The sample's batch error without the outlier is 0.0088 m/s.
  const size_t at = run.output.find("velocity RMSE ");
  ASSERT_NE(at, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(at + 14)), 0.015) << run.output;
}

// Writes were not checked: `--out /dev/full` went on and the evaluation then read /dev/full
// until memory ran out.
TEST(FaultCatalogue, AFailedWriteIsAnErrorNamingThePath) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  const ProgramRun run = RunProgram("filter " + kSample + " --out /dev/full", "dev_full");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("/dev/full: write failed"), std::string::npos) << run.output;
}

TEST(FaultCatalogue, TheOutputMayNotBeAnInput) {
  const std::string log = CopyOfSample("out_is_input");
  const std::string imu = log + "/imu.csv";
  const auto size = fs::file_size(imu);
  const ProgramRun run = RunProgram("filter " + log + " --out " + imu, "out_is_input");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("refusing to overwrite it"), std::string::npos) << run.output;
  EXPECT_EQ(fs::file_size(imu), size);
}

TEST(FaultCatalogue, AReportThatCannotBeWrittenIsAnError) {
  const ProgramRun json = RunProgram("diagnose " + kSample + " --json /no/such/dir/d.json", "json");
  EXPECT_EQ(json.exit_code, 2) << json.output;
  EXPECT_NE(json.output.find("/no/such/dir/d.json: cannot open file for writing"),
            std::string::npos)
      << json.output;
  EXPECT_EQ(json.output.find("report:"), std::string::npos);
}

}  // namespace
}  // namespace slipgraph
