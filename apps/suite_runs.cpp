#include "apps/suite_runs.h"

#include <atomic>
#include <exception>
#include <mutex>
#include <sstream>

#include "solvers/run_concurrently.h"

namespace slipgraph {

void AddSuiteOptions(CLI::App* cmd, SuiteOptions* suite) {
  cmd->add_option("--jobs,-j", suite->jobs, "A suite: logs run at once (one thread each)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--keep-going", suite->keep_going,
                "A suite: a log that fails is reported and the others run; the run ends with a "
                "list of the failures and exit status 4");
}

namespace {

std::string Describe(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "an unknown error";
  }
}

}  // namespace

std::vector<LogFailure> RunOverLogs(const std::vector<std::string>& logs, const SuiteOptions& suite,
                                    const LogJob& job, std::ostream& out, std::ostream& err) {
  std::vector<LogFailure> failures;
  const auto failed = [&](size_t i, const std::exception_ptr& error) {
    if (!suite.keep_going) std::rethrow_exception(error);
    failures.push_back({i, logs[i], Describe(error)});
    err << "error: " << logs[i] << ": " << failures.back().error << "\n" << std::flush;
  };
  if (suite.jobs <= 1) {  // one at a time: the text as it comes (progress on long runs)
    for (size_t i = 0; i < logs.size(); ++i) {
      try {
        job(i, out, err);
      } catch (...) {
        failed(i, std::current_exception());
      }
    }
    return failures;
  }
  struct Outcome {
    std::ostringstream out, err;
    std::exception_ptr error;
    bool done = false;
  };
  std::vector<Outcome> outcomes(logs.size());
  // Without keep_going, the first log (by index) that failed: no log after it starts, as none
  // would have one at a time.
  std::atomic<size_t> first_failed{logs.size()};
  std::mutex print_mutex;
  size_t next_to_print = 0;
  // Prints every finished outcome from next_to_print on, in order (the caller holds the lock);
  // without keep_going, stops at the first failure.
  const auto flush = [&] {
    for (; next_to_print < outcomes.size() && outcomes[next_to_print].done; ++next_to_print) {
      Outcome& o = outcomes[next_to_print];
      err << o.err.str() << std::flush;
      out << o.out.str() << std::flush;
      if (o.error && !suite.keep_going) {
        next_to_print = outcomes.size();
        break;
      }
      if (o.error) failed(next_to_print, o.error);
    }
  };
  RunConcurrently(logs.size(), suite.jobs, [&](size_t i) {
    Outcome& o = outcomes[i];
    if (i < first_failed) {
      try {
        job(i, o.out, o.err);
      } catch (...) {
        o.error = std::current_exception();
        if (!suite.keep_going) {
          size_t seen = first_failed;
          while (i < seen && !first_failed.compare_exchange_weak(seen, i)) {
          }
        }
      }
    }
    std::lock_guard<std::mutex> lock(print_mutex);
    o.done = true;
    flush();
  });
  if (first_failed < logs.size()) std::rethrow_exception(outcomes[first_failed].error);
  return failures;
}

void PrintFailures(const std::string& name, const std::vector<LogFailure>& failures, size_t logs,
                   std::ostream& err) {
  if (failures.empty()) return;
  err << name << ": " << failures.size() << " of " << logs << " log(s) failed:\n";
  for (const LogFailure& f : failures) err << "  " << f.log << ": " << f.error << "\n";
}

}  // namespace slipgraph
