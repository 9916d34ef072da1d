// Faults a user meets, run through the program as a user runs it: each case asserts the exit
// status, the message, and that every estimate file written is complete and finite.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "io/estimate_file.h"
#include "io/text_file.h"

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

// Rewrites every data row of a CSV file through `edit` (its cells by column name), dropping the
// rows for which it returns false.
void EditRows(const std::string& path,
              const std::function<bool(std::map<std::string, std::string>*)>& edit) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  in.close();
  ASSERT_FALSE(lines.empty());
  std::vector<std::string> header;
  std::stringstream h(lines[0]);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  std::ofstream out(path);
  out << lines[0] << "\n";
  for (size_t i = 1; i < lines.size(); ++i) {
    std::map<std::string, std::string> row;
    std::stringstream r(lines[i]);
    size_t c = 0;
    for (std::string cell; std::getline(r, cell, ',') && c < header.size(); ++c) {
      row[header[c]] = cell;
    }
    if (!edit(&row)) continue;
    for (size_t j = 0; j < header.size(); ++j) out << (j ? "," : "") << row[header[j]];
    out << "\n";
  }
}

double T(const std::map<std::string, std::string>& row) { return std::stod(row.at("t")); }

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

// --skip-bad drops at most 1 % of a file's rows by default; --max-bad sets the share. 40 bad IMU
// rows of 1818 (2.2 %): an error quoting the first, then a run with the share raised.
TEST(FaultCatalogue, SkipBadHasALimitTheUserCanSet) {
  const std::string log = CopyOfSample("max_bad");
  for (size_t row = 100; row < 140; ++row) SetCell(log + "/imu.csv", row, "ax", "x");
  const std::string out = log + "_filter.csv";
  const ProgramRun limited = RunProgram("filter " + log + " --skip-bad --out " + out, "max_bad");
  EXPECT_EQ(limited.exit_code, 2) << limited.output;
  EXPECT_NE(limited.output.find("40 of 1818 rows are bad, more than --skip-bad drops"),
            std::string::npos)
      << limited.output;
  const ProgramRun raised =
      RunProgram("filter " + log + " --skip-bad --max-bad 0.05 --out " + out, "max_bad_raised");
  EXPECT_EQ(raised.exit_code, 0) << raised.output;
  EXPECT_NE(raised.output.find("40 bad rows skipped in all"), std::string::npos) << raised.output;
  ExpectCompleteAndFinite(out, WheelRows());
  EXPECT_NE(RunProgram("filter " + log + " --skip-bad --max-bad 2", "max_bad_range")
                .output.find("--max-bad"),
            std::string::npos);
}

// What every estimator checks before it runs: a warning naming the stream and the time span where
// the estimates can still mean something, an error where they cannot; each through `filter`,
// whose estimates stay complete and finite.
struct LogFault {
  const char* name;
  std::function<void(const std::string& log)> make;
  int exit_code;
  const char* message;
};

void PrintTo(const LogFault& fault, std::ostream* os) { *os << fault.name; }

class LogFaults : public ::testing::TestWithParam<LogFault> {};

TEST_P(LogFaults, SaidBeforeTheEstimatorRuns) {
  const LogFault& fault = GetParam();
  const std::string log = CopyOfSample(fault.name);
  fault.make(log);
  const std::string out = log + "_filter.csv";
  const ProgramRun run = RunProgram("filter " + log + " --out " + out, fault.name);
  EXPECT_EQ(run.exit_code, fault.exit_code) << run.output;
  EXPECT_NE(run.output.find(fault.message), std::string::npos) << run.output;
  if (fault.exit_code == 0) {
    EXPECT_NE(run.output.find("warning: " + log + ": "), std::string::npos) << run.output;
    ExpectCompleteAndFinite(out, ReadNumericTable(log + "/wheels.csv").rows());
  } else {
    EXPECT_FALSE(fs::exists(out));
  }
}

INSTANTIATE_TEST_SUITE_P(
    FaultCatalogue, LogFaults,
    ::testing::Values(
        // A 10 s hole in the IMU: velocity RMSE 2.6 m/s (200 x) with nothing said.
        LogFault{"imu_gap",
                 [](const std::string& log) {
                   EditRows(log + "/imu.csv",
                            [](auto* row) { return T(*row) < 4.0 || T(*row) > 14.0; });
                 },
                 0, "imu: gap of 10.020 s from t=3.990"},
        // An IMU that ends 9 s before the wheels (a truncated file).
        LogFault{"imu_truncated",
                 [](const std::string& log) {
                   EditRows(log + "/imu.csv", [](auto* row) { return T(*row) < 9.0; });
                 },
                 0, "imu and wheels cover different times"},
        // Wheels stamped on another clock (+100 s): they share no time with the IMU.
        LogFault{"wheels_time_base",
                 [](const std::string& log) {
                   EditRows(log + "/wheels.csv", [](auto* row) {
                     (*row)["t"] = std::to_string(T(*row) + 100.0);
                     return true;
                   });
                 },
                 2, "share no time: are they stamped on different clocks?"},
        // Wheels with a header and no rows: a header-only estimate file, exit 0.
        LogFault{"wheels_empty",
                 [](const std::string& log) {
                   EditRows(log + "/wheels.csv", [](auto*) { return false; });
                 },
                 2, "wheels.csv: no rows"},
        // An IMU that repeats one sample for 5 s.
        LogFault{"imu_frozen",
                 [](const std::string& log) {
                   std::map<std::string, std::string> held;
                   EditRows(log + "/imu.csv", [&held](auto* row) {
                     if (T(*row) >= 5.0 && T(*row) < 10.0) {
                       if (held.empty()) held = *row;
                       const std::string t = (*row)["t"];
                       *row = held;
                       (*row)["t"] = t;
                     }
                     return true;
                   });
                 },
                 0, "imu: every channel frozen at one value for 4.990 s from t=5.000"},
        // A recorder that writes six decimals stopped inside the IMU's last number: "0.0037"
        // read as a whole sample.
        LogFault{"imu_cut_in_a_number",
                 [](const std::string& log) {
                   EditRows(log + "/imu.csv", [](auto* row) {
                     for (auto& [column, cell] : *row) {
                       char fixed[32];
                       std::snprintf(fixed, sizeof(fixed), "%.6f", std::stod(cell));
                       cell = fixed;
                     }
                     return true;
                   });
                   std::string text = ReadTextFile(log + "/imu.csv");
                   text.resize(text.size() - 4);  // the line end and three digits
                   std::ofstream(log + "/imu.csv", std::ios::binary) << text;
                 },
                 2, "this number has fewer digits than the rows before: cut short?"},
        // Encoders stuck at 0 while the robot drives (GNSS 1 m/s).
        LogFault{"wheels_stuck",
                 [](const std::string& log) {
                   EditRows(log + "/wheels.csv", [](auto* row) {
                     if (T(*row) >= 4.0 && T(*row) < 8.0) (*row)["left"] = "0";
                     return true;
                   });
                 },
                 0, "wheels: left unchanged at 0 rad/s for 3.990 s from t=4.000 while GNSS"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace slipgraph
