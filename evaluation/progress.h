// Progress of a long run, for a person watching: what a solver reports as it goes
// (ProgressUpdate, through a ProgressCallback it is given), and a printer that shows it on a
// terminal as one line on stderr, rewritten at most four times a second and only once the run
// has taken ProgressPrinter::delay_s, so short runs print nothing.
#pragma once

#include <chrono>
#include <functional>
#include <limits>
#include <mutex>
#include <ostream>
#include <string>

namespace slipgraph {

struct ProgressUpdate {
  std::string stage;  // "batch smoother: iteration", "chunk"
  long done = 0;      // iterations or chunks done
  long total = 0;     // of this many; 0 when only a bound is known (iterations)
  double cost = std::numeric_limits<double>::quiet_NaN();  // the solver's, where there is one
};
// Called on the solver's thread after each step; may be empty (no progress wanted).
using ProgressCallback = std::function<void(const ProgressUpdate&)>;

class ProgressPrinter {
 public:
  // Seconds since some fixed point (a steady clock; a test's own).
  using Clock = std::function<double()>;
  static double SteadySeconds();

  // enabled false: the callback does nothing (not a terminal, --quiet, logs run at once).
  ProgressPrinter(bool enabled, std::ostream& out, Clock clock = SteadySeconds);
  // Clears the line it left, if any.
  ~ProgressPrinter();
  ProgressPrinter(const ProgressPrinter&) = delete;
  ProgressPrinter& operator=(const ProgressPrinter&) = delete;

  // Shows `update`: "smooth: batch smoother: iteration 12, cost 1.79e+03, 3.4 s"; with a total,
  // "chunk 3 of 20, 12 s, about 68 s left" (the time left from the mean per step so far).
  void Show(const ProgressUpdate& update);
  // A callback for a solver that shows each update (the printer must outlive the run).
  ProgressCallback callback() {
    return [this](const ProgressUpdate& update) { Show(update); };
  }
  // Clears the line, so that the next text starts on a clean one.
  void Finish();

  double delay_s = 2.0;
  double interval_s = 0.25;

 private:
  bool enabled_;
  std::ostream& out_;
  Clock clock_;
  double start_s_;
  double last_shown_s_ = -1e300;
  size_t shown_width_ = 0;  // of the line on the terminal now (0: none)
  std::mutex mutex_;
};

// Whether stderr is a terminal (progress lines make sense there, not in a file or a pipe).
bool StderrIsTerminal();

}  // namespace slipgraph
