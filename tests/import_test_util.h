// Helpers for the importer and plausibility tests: a mapping file with one piece of text replaced
// (a deliberately wrong mapping), a reader's error message, and whether a plausibility report
// names a problem.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "io/input_error.h"
#include "io/plausibility.h"

namespace slipgraph {
namespace testing {

// Writes `mapping_path` with the first `from` replaced by `to` to a temporary file named `name`
// (prefixed with the running test's name: ctest runs tests side by side, each altering the same
// mapping its own way) and returns its path; fails the test when `from` is not there.
inline std::string AlteredMapping(const std::string& mapping_path, const std::string& from,
                                  const std::string& to, const std::string& name) {
  std::ifstream in(mapping_path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string prefix =
      test == nullptr ? "" : std::string(test->test_suite_name()) + "." + test->name() + ".";
  const std::string path = ::testing::TempDir() + "/" + prefix + name;
  std::ofstream(path) << text;
  return path;
}

// The report named `name` (a StreamReport, an InnovationReport: anything with a `name`); fails
// the test when there is none, so that an assertion on it cannot silently not run.
template <typename Reports>
const typename Reports::value_type& Named(const Reports& reports, const std::string& name) {
  for (const auto& report : reports) {
    if (report.name == name) return report;
  }
  ADD_FAILURE() << "no report named '" << name << "'";
  throw std::out_of_range(name);
}

// The message of the InputError `f` throws (empty, and a test failure, when it throws none).
template <typename F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

inline bool Mentions(const Plausibility& p, const std::string& text) {
  for (const std::string& problem : p.problems) {
    if (problem.find(text) != std::string::npos) return true;
  }
  return false;
}

}  // namespace testing
}  // namespace slipgraph
