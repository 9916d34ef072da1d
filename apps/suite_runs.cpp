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

std::vector<LogFailure> RunOverLogs(const std::vector<std::string>& logs, const SuiteOptions& suite,
                                    const LogJob& job, std::ostream& out, std::ostream& err) {
  struct Outcome {
    std::ostringstream out, err;
    std::exception_ptr error;
    bool done = false;
  };
  std::vector<Outcome> outcomes(logs.size());
  std::atomic<bool> stop{false};
  std::mutex print_mutex;
  size_t next_to_print = 0;
  std::vector<LogFailure> failures;
  const auto describe = [](const std::exception_ptr& error) -> std::string {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      return e.what();
    } catch (...) {
      return "an unknown error";
    }
  };
  // Prints every finished outcome from next_to_print on, in order (the caller holds the lock).
  const auto flush = [&] {
    for (; next_to_print < outcomes.size() && outcomes[next_to_print].done; ++next_to_print) {
      Outcome& o = outcomes[next_to_print];
      out << o.out.str() << std::flush;
      err << o.err.str();
      err << std::flush;
      if (o.error && !suite.keep_going) {  // the suite ends here: nothing after it is printed
        next_to_print = outcomes.size();
        break;
      }
      if (o.error) {
        failures.push_back({logs[next_to_print], describe(o.error)});
        err << "error: " << logs[next_to_print] << ": " << failures.back().error << "\n"
            << std::flush;
      }
    }
  };
  RunConcurrently(logs.size(), suite.jobs, [&](size_t i) {
    Outcome& o = outcomes[i];
    if (!stop) {
      try {
        job(i, o.out, o.err);
      } catch (...) {
        o.error = std::current_exception();
        if (!suite.keep_going) stop = true;
      }
    }
    std::lock_guard<std::mutex> lock(print_mutex);
    o.done = true;
    flush();
  });
  if (!suite.keep_going) {
    for (const Outcome& o : outcomes) {
      if (o.error) std::rethrow_exception(o.error);
    }
  }
  return failures;
}

void PrintFailures(const std::string& name, const std::vector<LogFailure>& failures, size_t logs,
                   std::ostream& err) {
  if (failures.empty()) return;
  err << name << ": " << failures.size() << " of " << logs << " log(s) failed:\n";
  for (const LogFailure& f : failures) err << "  " << f.log << ": " << f.error << "\n";
}

}  // namespace slipgraph
