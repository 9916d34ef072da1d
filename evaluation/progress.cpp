#include "evaluation/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace slipgraph {

double ProgressPrinter::SteadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

ProgressPrinter::ProgressPrinter(bool enabled, std::ostream& out, Clock clock)
    : enabled_(enabled), out_(out), clock_(std::move(clock)), start_s_(clock_()) {}

ProgressPrinter::~ProgressPrinter() { Finish(); }

void ProgressPrinter::Show(const ProgressUpdate& update) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const double now = clock_();
  const double elapsed = now - start_s_;
  const bool last = update.total > 0 && update.done >= update.total;
  if (elapsed < delay_s || (now - last_shown_s_ < interval_s && !last)) return;
  last_shown_s_ = now;
  char text[200];
  int n = std::snprintf(text, sizeof(text), "%s %ld", update.stage.c_str(), update.done);
  if (update.total > 0) n += std::snprintf(text + n, sizeof(text) - n, " of %ld", update.total);
  if (std::isfinite(update.cost)) {
    n += std::snprintf(text + n, sizeof(text) - n, ", cost %.3g", update.cost);
  }
  n += std::snprintf(text + n, sizeof(text) - n, ", %.0f s", elapsed);
  if (update.total > 0 && update.done > 0 && !last) {
    const double left = elapsed / update.done * (update.total - update.done);
    std::snprintf(text + n, sizeof(text) - n, ", about %.0f s left", left);
  }
  std::string line(text);
  const size_t width = line.size();
  if (width < shown_width_) line.append(shown_width_ - width, ' ');  // cover the longer line
  out_ << '\r' << line << std::flush;
  shown_width_ = width;
}

void ProgressPrinter::Finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (shown_width_ == 0) return;
  out_ << '\r' << std::string(shown_width_, ' ') << '\r' << std::flush;
  shown_width_ = 0;
}

bool StderrIsTerminal() { return isatty(STDERR_FILENO) == 1; }

}  // namespace slipgraph
