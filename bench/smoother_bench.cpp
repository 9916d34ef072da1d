// Batch smoother time and peak memory against log length, and the window smoother's update
// latency. Prints figures (docs/benchmarks.md records them with this command):
//
//   build/bench/smoother_bench batch MINUTES [--no-covariance] [--ceres] [--threads N]
//                                  [--function-tolerance F] [--step-sd S] [--against F2]
//                                  [--stiffness-sd SD]     the stiffness estimated at 0.15, as
//                                                          `smooth` runs a model with soils (SD
//                                                          0: the law as given, as it runs this
//                                                          one-law log; one solve, no border)
//                                                                 one length per process (peak
//                                                                 RSS); the chain solver or Ceres
//   build/bench/smoother_bench window [--ceres] [--length S] [ITERATIONS...]
//                                              a window of S s (default 2) at 100 Hz (chain
//                                              Gauss-Newton, or ceres::Solve)
//   build/bench/smoother_bench chunked MINUTES CHUNK_MINUTES [--threads N]
//                                                                 chunked mode, 60 s overlap
//
// For the batch it also times a hand-written block-tridiagonal Cholesky of a system with the
// same number of 7-dimensional states: the floor one Gauss-Newton step could reach. --against F2
// solves the log again to a relative cost change of F2 and prints how far the first solve's
// states and sd are from that solution's.
#include <sys/resource.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "bench/long_drive.h"
#include "evaluation/evaluation.h"
#include "io/estimate_file.h"
#include "sim/simulation.h"
#include "solvers/batch_smoother.h"
#include "solvers/window_smoother.h"

namespace slipgraph {
namespace {

using Clock = std::chrono::steady_clock;
using Block = Eigen::Matrix<double, 7, 7>;

double Seconds(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux: kilobytes
}

// Cholesky of a block-tridiagonal SPD matrix (n diagonal 7x7 blocks), in place: the floor for
// one Gauss-Newton step on a chain of n states. Returns seconds.
double BlockTridiagonalCholesky(size_t n) {
  std::mt19937 rng(1);
  std::normal_distribution<double> normal;
  std::vector<Block> diagonal(n), lower(n);  // lower[i]: block (i+1, i)
  for (size_t i = 0; i < n; ++i) {
    Block a;
    for (int r = 0; r < 7; ++r)
      for (int c = 0; c < 7; ++c) a(r, c) = normal(rng);
    diagonal[i] = a * a.transpose() + 30.0 * Block::Identity();
    for (int r = 0; r < 7; ++r)
      for (int c = 0; c < 7; ++c) lower[i](r, c) = 0.5 * normal(rng);
  }
  const Clock::time_point start = Clock::now();
  for (size_t i = 0; i < n; ++i) {
    if (i > 0) diagonal[i] -= lower[i - 1] * lower[i - 1].transpose();
    Eigen::LLT<Block> llt(diagonal[i]);
    diagonal[i] = llt.matrixL();
    if (i + 1 < n) {
      // L_{i+1,i} = A_{i+1,i} L_ii^{-T}
      lower[i] = llt.matrixL().solve(lower[i].transpose()).transpose();
    }
  }
  const double seconds = Seconds(start);
  volatile double sink = diagonal.back()(0, 0);
  (void)sink;
  return seconds;
}

int Batch(double minutes, const BatchSmootherOptions& given, double against_tolerance) {
  const sim::SimResult sim = sim::Simulate(LongDrive(minutes), 1);
  const double rss_log = PeakRssMb();
  BatchSmootherOptions options = given;
  options.max_iterations = 50;
  long iterations = 0;  // over both solves (the second re-gates weak constraint 2)
  options.progress = [&](const ProgressUpdate& update) { iterations += update.done > 0; };
  const Clock::time_point start = Clock::now();
  const SmootherResult result = SmoothBatch(sim.log, DefaultModelConfig(sim.log.vehicle), options);
  const double total = Seconds(start);
  double iteration_s = 0.0;  // the last solve's mean
  for (const ceres::IterationSummary& it : result.summary.iterations) {
    iteration_s += it.iteration_time_in_seconds;
  }
  iteration_s /= std::max<size_t>(1, result.summary.iterations.size());
  const double floor_s = BlockTridiagonalCholesky(result.estimates.size());
  std::printf(
      "| %s | %d | %5.1f | %8zu | %7.2f | %3ld | %s | %7.3f | %8.4f | %6.1f | %7.0f | %7.0f | %s "
      "| %.5f |\n",
      options.solver == BatchSolver::kChain ? "chain" : "Ceres", options.threads, minutes,
      result.estimates.size(), total, iterations,
      result.summary.termination_type == ceres::CONVERGENCE ? "yes" : "no", iteration_s, floor_s,
      iteration_s / floor_s, rss_log, PeakRssMb(),
      result.used_fallback ? "fallback" : (result.covariance_ok ? "cov" : "no cov"),
      Evaluate(sim.log, EstimateTable(result.estimates)).velocity_rmse);
  if (against_tolerance > 0.0) {
    // The same log solved to another relative cost change: how far the stop leaves each state
    // from that solution, in that solution's sd, and how far its sd.
    BatchSmootherOptions reference_options = options;
    reference_options.function_tolerance = against_tolerance;
    reference_options.progress = nullptr;
    const SmootherResult reference =
        SmoothBatch(sim.log, DefaultModelConfig(sim.log.vehicle), reference_options);
    std::printf(
        "against a relative cost change of %g: | state | max |dx|/sd | RMS |dx|/sd | "
        "max |d sd|/sd |\n",
        against_tolerance);
    for (int i = 0; i < ward::kStateSize; ++i) {
      double largest = 0.0, squares = 0.0, sd_change = 0.0;
      for (size_t k = 0; k < reference.estimates.size(); ++k) {
        const WardEstimate& a = result.estimates[k];
        const WardEstimate& b = reference.estimates[k];
        const double z = std::abs(a.x[i] - b.x[i]) / b.sd[i];
        largest = std::max(largest, z);
        squares += z * z;
        sd_change = std::max(sd_change, std::abs(a.sd[i] / b.sd[i] - 1.0));
      }
      std::printf("| %s | %.4f | %.4f | %.4f |\n", kStateColumns[i], largest,
                  std::sqrt(squares / reference.estimates.size()), sd_change);
    }
    long flags = 0;
    for (size_t k = 0; k < reference.estimates.size(); ++k) {
      flags += reference.estimates[k].slip.immobilized != result.estimates[k].slip.immobilized;
    }
    std::printf("immobilized flags that differ: %ld\n", flags);
  }
  return 0;
}

// Chunked mode on a long log: chunks of chunk_min minutes, 60 s of look-ahead.
int Chunked(double minutes, double chunk_min, int threads) {
  const Clock::time_point sim_start = Clock::now();
  const sim::SimResult sim = sim::Simulate(LongDrive(minutes), 1);
  const double sim_s = Seconds(sim_start);
  const Clock::time_point start = Clock::now();
  BatchSmootherOptions batch;
  batch.threads = threads;
  const WindowSmootherResult result = SmoothWindowed(sim.log, DefaultModelConfig(sim.log.vehicle),
                                                     ChunkedOptions(chunk_min, 60.0, 100.0, batch));
  const double total = Seconds(start);
  const long from_filter = std::count(result.from_filter.begin(), result.from_filter.end(), true);
  std::printf("| %.0f | %zu | %.1f | %ld | %.0f | %.0f | %.0f | %ld | %ld |\n", minutes,
              result.estimates.size(), chunk_min, result.updates, sim_s, total, PeakRssMb(),
              result.failed_updates, from_filter);
  return 0;
}

double Percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

int Window(const std::vector<int>& iterations, bool chain, double window_s) {
  const sim::SimResult sim = sim::Simulate(LongDrive(2.0), 1);
  const ModelConfig model = DefaultModelConfig(sim.log.vehicle);
  std::printf(
      "| solver | window s | iterations | updates | solve+marg. p50 ms | p99 ms | covariance p50 "
      "ms | p99 ms | update with the covariance p50 ms | p99 ms | fallbacks to Ceres | v RMSE m/s "
      "|\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int n : iterations) {
    WindowSmootherOptions options;
    options.max_iterations = n;
    options.window_s = window_s;
    options.solver = chain ? WindowSolver::kChainGaussNewton : WindowSolver::kCeres;
    const WindowSmootherResult r = SmoothWindowed(sim.log, model, options);
    std::vector<double> total = r.update_ms;  // with kChainGaussNewton it holds the covariance
    for (size_t i = 0; i < total.size() && i < r.covariance_ms.size(); ++i) {
      total[i] += r.covariance_ms[i];
    }
    const auto cov = [&](double p) {
      return r.covariance_ms.empty() ? std::nan("") : Percentile(r.covariance_ms, p);
    };
    std::printf("| %s | %g | %d | %zu | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %ld | %.4f |\n",
                chain ? "chain Gauss-Newton" : "Ceres", window_s, n, r.update_ms.size(),
                Percentile(r.update_ms, 0.5), Percentile(r.update_ms, 0.99), cov(0.5), cov(0.99),
                Percentile(total, 0.5), Percentile(total, 0.99), r.chain_fallbacks,
                Evaluate(sim.log, EstimateTable(r.estimates)).velocity_rmse);
  }
  return 0;
}

}  // namespace
}  // namespace slipgraph

int main(int argc, char** argv) {
  if (argc >= 3 && std::strcmp(argv[1], "batch") == 0) {
    // As `smooth` runs a model that lists its soils.
    slipgraph::BatchSmootherOptions options;
    options.problem.stiffness_prior_sd = slipgraph::kPostProcessingStiffnessPriorSd;
    options.threads = 1;
    double against = 0.0;
    for (int i = 3; i < argc; ++i) {
      const bool value = i + 1 < argc;
      if (std::strcmp(argv[i], "--no-covariance") == 0) options.covariance = false;
      if (std::strcmp(argv[i], "--ceres") == 0) options.solver = slipgraph::BatchSolver::kCeres;
      if (std::strcmp(argv[i], "--threads") == 0 && value) {
        options.threads = std::max(1, std::atoi(argv[++i]));
      }
      if (std::strcmp(argv[i], "--function-tolerance") == 0 && value) {
        options.function_tolerance = std::atof(argv[++i]);
      }
      if (std::strcmp(argv[i], "--step-sd") == 0 && value) {
        options.step_sd_tolerance = std::atof(argv[++i]);
      }
      if (std::strcmp(argv[i], "--against") == 0 && value) against = std::atof(argv[++i]);
      if (std::strcmp(argv[i], "--stiffness-sd") == 0 && value) {
        options.problem.stiffness_prior_sd = std::atof(argv[++i]);
      }
    }
    return slipgraph::Batch(std::atof(argv[2]), options, against);
  }
  if (argc >= 4 && std::strcmp(argv[1], "chunked") == 0) {
    const int threads =
        argc >= 6 && std::strcmp(argv[4], "--threads") == 0 ? std::atoi(argv[5]) : 1;
    return slipgraph::Chunked(std::atof(argv[2]), std::atof(argv[3]), std::max(1, threads));
  }
  if (argc >= 2 && std::strcmp(argv[1], "window") == 0) {
    std::vector<int> iterations;
    bool chain = true;
    double window_s = slipgraph::WindowSmootherOptions{}.window_s;
    for (int i = 2; i < argc; ++i) {
      if (std::strcmp(argv[i], "--ceres") == 0) {
        chain = false;
      } else if (std::strcmp(argv[i], "--length") == 0 && i + 1 < argc) {
        window_s = std::atof(argv[++i]);
      } else {
        iterations.push_back(std::atoi(argv[i]));
      }
    }
    if (iterations.empty()) iterations = {1, 2, 5};
    return slipgraph::Window(iterations, chain, window_s);
  }
  std::fprintf(
      stderr,
      "usage: smoother_bench batch MINUTES [--no-covariance] [--ceres] [--threads N] "
      "[--function-tolerance F] [--step-sd S] [--against F2] [--stiffness-sd SD] | "
      "window [--ceres] [--length S] [ITERATIONS...] | "
      "chunked MINUTES CHUNK_MINUTES [--threads N]\n"
      "chunked prints: | minutes | states | chunk min | chunks | simulation s | smoothing s "
      "| peak RSS MB | failed chunks | samples left at the EKF |\n"
      "batch prints: | solver | threads | minutes | states | total s | iterations (both solves) | "
      "converged | s/iteration | block-tridiagonal Cholesky s | ratio | RSS after simulation MB | "
      "peak RSS MB | covariance | v RMSE m/s |\n");
  return 2;
}
