// A suite's logs run one job each, on --jobs threads, with --keep-going: what the subcommands
// that take a suite (filter, smooth, online, diagnose) share. On more than one thread each log's
// text is held until the logs before it are printed, so the output reads in the suite's order
// whatever the threads do.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace slipgraph {

struct SuiteOptions {
  int jobs = 1;             // logs run at once
  bool keep_going = false;  // a log that fails is reported and the others run
};

// --jobs N and --keep-going on a subcommand.
void AddSuiteOptions(CLI::App* cmd, SuiteOptions* suite);

// The exit status when --keep-going ran a suite in which some logs failed.
constexpr int kFailedLogsExit = 4;

struct LogFailure {
  size_t index = 0;  // in the suite's order
  std::string log;
  std::string error;
};

// One log's job: `out` and `err` stand for stdout and stderr (printed in the suite's order).
using LogJob = std::function<void(size_t index, std::ostream& out, std::ostream& err)>;

// Runs job(i) for each of `logs` on suite.jobs threads (one: in turn, on `out` and `err` as the
// text comes; more: each log's text held and printed in the suite's order, its stderr first). A
// job's exception fails its log: with keep_going the failure is printed after the log's text and
// the rest run; without, no later log starts, and once the logs before it are printed its
// exception is rethrown. Returns the failures (keep_going), in the suite's order.
std::vector<LogFailure> RunOverLogs(const std::vector<std::string>& logs, const SuiteOptions& suite,
                                    const LogJob& job, std::ostream& out, std::ostream& err);

// "NAME: K of N log(s) failed:" and one line per failure.
void PrintFailures(const std::string& name, const std::vector<LogFailure>& failures, size_t logs,
                   std::ostream& err);

}  // namespace slipgraph
