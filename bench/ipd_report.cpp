// IPD calibration figures on simulated tracked-vehicle logs (docs/ipd.md records them):
//
//   build/bench/ipd_report [--scenario ipd35|ipd35m] [--seed N] [--methods ekf,window,batch]
//                          [--errors PREFIX] [--no-matching]
//                                          the three methods (or those listed), recovery after
//                                          terrain changes; each prediction's errors and
//                                          predicted variances to PREFIX<method>.csv;
//                                          --no-matching: the predicted covariance as calibrated
//                                          (IpdOptions::match_covariance_segments = 0)
//   build/bench/ipd_report --holdout       the paper's Fig. 3: holdout error against calibration
//   time
//
// The "true alpha" row predicts every segment with the simulator's own slip model of the
// terrain under the segment's start and its true Q: the floor that the stochastic slip and the
// pose noise leave to any estimator.
//
// Terrain boundaries come from the simulated course (the estimators never see them): the time
// the robot's signed travel (the integral of its forward speed, as the simulator advances along
// the course) crosses a patch start. Recovery time after a boundary: the
// first moment after it from which the mean position error of the next 5 s of predictions is
// within 1.2 x the settled error (the mean from 20 s after the boundary to the next one);
// 30 s when it does not get there within 30 s. A second column measures it against the error
// the method's own settled model (its mean alpha from 20 s after the boundary to the next)
// makes on the same 5 s of predictions: how hard those seconds of driving are to predict is
// then taken out (the floor recovers at once by it).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ipd_calibration.h"
#include "solvers/ipd_graph_calibration.h"

namespace slipgraph {
namespace {

using Clock = std::chrono::steady_clock;

// Signed distance along the course at each truth sample, as the simulator advances it (the
// integral of the forward speed).
std::vector<double> SignedTravel(const DriveLog& log) {
  std::vector<double> s;
  double distance = 0.0;
  for (size_t k = 0; k < log.truth.size(); ++k) {
    if (k > 0) distance += log.truth[k].vx * (log.truth[k].t - log.truth[k - 1].t);
    s.push_back(distance);
  }
  return s;
}

std::vector<double> BoundaryTimes(const sim::Scenario& sc, const DriveLog& log) {
  const std::vector<double> s = SignedTravel(log);
  std::vector<double> times;
  size_t next = 1;
  for (size_t k = 1; k < log.truth.size() && next < sc.course.patches.size(); ++k) {
    if (s[k] >= sc.course.patches[next].s_start_m) {
      times.push_back(log.truth[k].t);
      ++next;
    }
  }
  return times;
}

// The course patch under each segment's start (by the signed travel at the truth sample then).
std::vector<size_t> SegmentPatches(const sim::Scenario& sc, const DriveLog& log,
                                   const std::vector<IpdSegment>& segments) {
  const std::vector<double> s = SignedTravel(log);
  std::vector<double> t;
  for (const TruthSample& sample : log.truth) t.push_back(sample.t);
  std::vector<size_t> patches;
  for (const IpdSegment& seg : segments) {
    const size_t k = std::min<size_t>(std::lower_bound(t.begin(), t.end(), seg.t_start) - t.begin(),
                                      t.size() - 1);
    const sim::TerrainPatch& patch = sc.course.PatchAt(s[k]);
    patches.push_back(static_cast<size_t>(&patch - sc.course.patches.data()));
  }
  return patches;
}

// Predictions with the simulator's slip model of the terrain under each segment's start.
IpdCalibrationResult TrueAlphaPredictions(const sim::Scenario& sc, const DriveLog& log) {
  const IpdOptions options;
  IpdCalibrationResult r;
  r.segments = BuildIpdSegments(log, options);
  const std::vector<size_t> patch_of = SegmentPatches(sc, log, r.segments);
  const std::array<double, ipd::kAlphaSize> zero{};
  for (size_t i = 0; i < r.segments.size(); ++i) {
    const IpdSegment& seg = r.segments[i];
    const sim::IpdSlip& slip = sc.course.patches[patch_of[i]].terrain.ipd;
    const Eigen::Vector3d q(slip.q_density[0], slip.q_density[1], slip.q_density[2]);
    r.no_slip.push_back(EvaluatePrediction(seg, zero.data(), options, q));
    r.calibrated.push_back(EvaluatePrediction(seg, slip.alpha.data(), options, q));
    r.update_t.push_back(seg.t_start);
    r.alpha.push_back(slip.alpha);
  }
  return r;
}

// Predictions with the best fixed slip model of each patch in hindsight (ipd35m, whose truth has
// no slip model): per patch, alpha by least squares over the patch's own segments (Gauss-Newton
// on the segments' end-pose residuals, heading weighted as 1 m per rad). What the 13-parameter
// model can do at best with the terrain known; q is not fitted (no covariance is reported).
IpdCalibrationResult HindsightAlphaPredictions(const sim::Scenario& sc, const DriveLog& log) {
  const IpdOptions options;
  IpdCalibrationResult r;
  r.segments = BuildIpdSegments(log, options);
  const std::vector<size_t> patch_of = SegmentPatches(sc, log, r.segments);
  std::vector<std::array<double, ipd::kAlphaSize>> alpha(sc.course.patches.size());
  for (size_t patch = 0; patch < alpha.size(); ++patch) {
    alpha[patch].fill(0.0);
    for (int iteration = 0; iteration < 5; ++iteration) {
      Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize> normal =
          1e-6 * Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize>::Identity();
      Eigen::Matrix<double, ipd::kAlphaSize, 1> gradient =
          Eigen::Matrix<double, ipd::kAlphaSize, 1>::Zero();
      for (size_t i = 0; i < r.segments.size(); ++i) {
        if (patch_of[i] != patch) continue;
        const SegmentLinearization lin =
            LinearizeSegment(r.segments[i], alpha[patch].data(), options);
        normal += lin.H.transpose() * lin.H;
        gradient += lin.H.transpose() * lin.residual;
      }
      const Eigen::Matrix<double, ipd::kAlphaSize, 1> step = normal.ldlt().solve(gradient);
      for (int j = 0; j < ipd::kAlphaSize; ++j) alpha[patch][j] += step[j];
    }
  }
  const std::array<double, ipd::kAlphaSize> zero{};
  for (size_t i = 0; i < r.segments.size(); ++i) {
    const IpdSegment& seg = r.segments[i];
    r.no_slip.push_back(EvaluatePrediction(seg, zero.data(), options, Eigen::Vector3d::Zero()));
    r.calibrated.push_back(
        EvaluatePrediction(seg, alpha[patch_of[i]].data(), options, Eigen::Vector3d::Zero()));
    r.update_t.push_back(seg.t_start);
    r.alpha.push_back(alpha[patch_of[i]]);
  }
  return r;
}

// The first moment after t_b from which the mean position error of the next 5 s of predictions
// is within 1.2 x `level(k, m)`, the reference over the same predictions k..m-1; 30 s when not
// within 30 s.
double RecoveryTime(const IpdCalibrationResult& r, const std::vector<double>& error, double t_b,
                    const std::function<double(size_t, size_t)>& level) {
  for (size_t k = 0; k < error.size(); ++k) {
    const double t = r.calibrated[k].t_start;
    if (t < t_b || t > t_b + 30.0) continue;
    double sum = 0.0;
    size_t m = k;
    for (; m < error.size() && r.calibrated[m].t_start < t + 5.0; ++m) sum += error[m];
    if (m > k && sum / (m - k) <= 1.2 * level(k, m)) return t - t_b;
  }
  return 30.0;
}

// One row per 2 s prediction: its start, errors (along, cross, heading) and predicted variances.
void WriteErrors(const std::string& path, const IpdCalibrationResult& r) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr) {
    std::fprintf(stderr, "ipd_report: cannot write %s\n", path.c_str());
    return;
  }
  std::fprintf(out, "t_start,along_m,cross_m,heading_rad,var_along,var_cross,var_heading\n");
  for (const PredictionError& e : r.calibrated) {
    std::fprintf(out, "%.3f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", e.t_start, e.along_m, e.cross_m,
                 e.heading_rad, e.predicted_covariance(0, 0), e.predicted_covariance(1, 1),
                 e.predicted_covariance(2, 2));
  }
  std::fclose(out);
}

// `covariance`: whether r's predicted covariance is the method's own (else "-" is printed).
void Report(const char* name, const IpdCalibrationResult& r, const std::vector<double>& boundaries,
            double seconds, bool covariance = true) {
  const PredictionStats a = Summarize(r.no_slip), b = Summarize(r.calibrated);
  // The same ratio without the first minute (AfterTheFirstMinute says why).
  const Eigen::Vector3d late = Summarize(AfterTheFirstMinute(r.calibrated)).predicted_over_sample;
  std::vector<double> error;
  for (const PredictionError& e : r.calibrated) error.push_back(std::hypot(e.along_m, e.cross_m));
  // Recovery after each boundary, against two references: the settled error (the mean from
  // 20 s after the boundary to the next one), and the error the method's own settled model (its
  // mean alpha over that stretch) makes on the same 5 s of predictions, which takes out how hard
  // those 5 s of driving are to predict (the floor recovers at once by this measure).
  const IpdOptions options;
  std::vector<double> recovery, own_recovery;
  for (size_t i = 0; i < boundaries.size(); ++i) {
    const double t_b = boundaries[i];
    const double t_next = i + 1 < boundaries.size() ? boundaries[i + 1] : 1e300;
    std::vector<double> settled;
    for (size_t k = 0; k < error.size(); ++k) {
      const double t = r.calibrated[k].t_start;
      if (t > t_b + 20.0 && t < t_next) settled.push_back(error[k]);
    }
    double settled_mean = 0.0;
    for (double x : settled) settled_mean += x / settled.size();
    recovery.push_back(RecoveryTime(r, error, t_b, [&](size_t, size_t) { return settled_mean; }));
    std::array<double, ipd::kAlphaSize> alpha{};
    int n = 0;
    for (size_t k = 0; k < r.update_t.size(); ++k) {
      if (r.update_t[k] <= t_b + 20.0 || r.update_t[k] >= t_next) continue;
      for (int j = 0; j < ipd::kAlphaSize; ++j) alpha[j] += r.alpha[k][j];
      ++n;
    }
    for (double& a : alpha) a /= std::max(n, 1);
    std::vector<double> own(error.size(), 0.0);
    for (size_t k = 0; k < error.size(); ++k) {
      const double t = r.calibrated[k].t_start;
      if (t < t_b || t > t_b + 35.0) continue;
      const PredictionError e =
          EvaluatePrediction(r.segments[k], alpha.data(), options, Eigen::Vector3d::Zero());
      own[k] = std::hypot(e.along_m, e.cross_m);
    }
    own_recovery.push_back(RecoveryTime(r, error, t_b, [&](size_t k, size_t m) {
      double sum = 0.0;
      for (size_t j = k; j < m; ++j) sum += own[j];
      return sum / (m - k);
    }));
  }
  double mean_recovery = 0.0, max_recovery = 0.0, mean_own = 0.0, max_own = 0.0;
  for (double x : recovery)
    mean_recovery += x / recovery.size(), max_recovery = std::max(max_recovery, x);
  for (double x : own_recovery) mean_own += x / own_recovery.size(), max_own = std::max(max_own, x);
  const auto reduction = [](double value, double reference) {
    return 100.0 * (1.0 - value / reference);
  };
  char ratios[96] = "- | -";
  if (covariance) {
    std::snprintf(ratios, sizeof(ratios), "%.2f %.2f %.2f | %.2f %.2f %.2f",
                  b.predicted_over_sample[0], b.predicted_over_sample[1],
                  b.predicted_over_sample[2], late[0], late[1], late[2]);
  }
  std::printf(
      "| %s | %.4f (%.0f %%) | %.4f (%.0f %%) | %.4f (%.0f %%) | %.4f (%.0f %%) | %.4f (%.0f %%) | "
      "%s | %.1f / %.1f | %.1f / %.1f | %.2f |\n",
      name, b.mean_position_error_m, reduction(b.mean_position_error_m, a.mean_position_error_m),
      b.sd_along_m, reduction(b.sd_along_m, a.sd_along_m), b.sd_cross_m,
      reduction(b.sd_cross_m, a.sd_cross_m), b.mean_heading_error_rad,
      reduction(b.mean_heading_error_rad, a.mean_heading_error_rad), b.sd_heading_rad,
      reduction(b.sd_heading_rad, a.sd_heading_rad), ratios, mean_recovery, max_recovery, mean_own,
      max_own, seconds);
}

// `scenario`: ipd35 (its floor: the simulator's own slip model) or ipd35m (the best fixed
// 13-parameter model per patch in hindsight).
// `methods_wanted`: the methods to run, by name (ekf, window, batch); `errors_prefix`: when
// not empty, each method's predictions are written to PREFIX<method>.csv; `options`: the
// calibrations' options.
int Ipd35(const std::string& scenario, uint64_t seed, const std::string& methods_wanted,
          const std::string& errors_prefix, const IpdOptions& options) {
  const sim::ScenarioRun run = sim::ExpandScenario(scenario, seed).at(0);
  const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  const std::vector<double> boundaries = BoundaryTimes(run.scenario, log);
  const bool has_slip_model = scenario == "ipd35";
  std::printf("%s seed %llu: %zu terrain boundaries\n\n", scenario.c_str(),
              static_cast<unsigned long long>(seed), boundaries.size());
  std::printf(
      "| method | mean position error m (reduction) | sd along m | sd cross m | mean heading "
      "error rad | sd heading rad | predicted / sample variance (along, cross, heading) | the "
      "same after the first minute | recovery after a boundary, mean / max s | recovery against "
      "its own settled model, mean / max s | time s |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
  const IpdCalibrationResult* no_slip = nullptr;
  const std::vector<std::pair<const char*, std::function<IpdCalibrationResult()>>> methods = {
      {"ekf", [&] { return CalibrateIpdEkf(log, options); }},
      {"window", [&] { return CalibrateIpdWindow(log, options); }},
      {"batch", [&] { return CalibrateIpdBatch(log, options); }}};
  for (const auto& [name, calibrate] : methods) {
    if (("," + methods_wanted + ",").find("," + std::string(name) + ",") == std::string::npos) {
      continue;
    }
    const Clock::time_point start = Clock::now();
    const IpdCalibrationResult r = calibrate();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (no_slip == nullptr) {
      const PredictionStats a = Summarize(r.no_slip);
      std::printf("| no slip | %.4f | %.4f | %.4f | %.4f | %.4f | | | | | |\n",
                  a.mean_position_error_m, a.sd_along_m, a.sd_cross_m, a.mean_heading_error_rad,
                  a.sd_heading_rad);
      if (has_slip_model) {
        Report("true alpha (floor)", TrueAlphaPredictions(run.scenario, log), boundaries, 0.0);
      } else {
        Report("best alpha per patch in hindsight", HindsightAlphaPredictions(run.scenario, log),
               boundaries, 0.0, false);
      }
      no_slip = &r;
    }
    Report(name, r, boundaries, seconds);
    if (!errors_prefix.empty()) WriteErrors(errors_prefix + name + ".csv", r);
  }
  return 0;
}

// Fig. 3: a 5-minute grass drive; calibrate on the first T seconds, evaluate the frozen model
// on the rest (holdout).
int Holdout() {
  sim::Scenario sc = sim::ExpandScenario("ipd35", 1).at(0).scenario;
  sc.course.patches = {{0.0, sim::FindTerrain("grass")}};
  double total = sc.rest_start_s;
  size_t keep = 0;
  while (keep < sc.commands.size() && total < 330.0 + 120.0)
    total += sc.commands[keep++].duration_s;
  sc.commands.resize(keep);
  const DriveLog log = sim::Simulate(sc, 3).log;
  const IpdOptions options;
  const IpdCalibrationResult full = CalibrateIpdEkf(log);
  std::printf(
      "| calibration time s | holdout mean position error m | holdout mean heading error rad "
      "|\n|---|---|---|\n");
  for (double T : {0.0, 5.0, 10.0, 20.0, 40.0, 80.0, 160.0, 330.0}) {
    // alpha as of T: the last update at or before T.
    std::array<double, ipd::kAlphaSize> alpha{};
    for (size_t k = 0; k < full.update_t.size() && full.update_t[k] <= sc.rest_start_s + T; ++k) {
      alpha = full.alpha[k];
    }
    std::vector<PredictionError> holdout;
    for (const IpdSegment& seg : full.segments) {
      if (seg.t_start >= sc.rest_start_s + 330.0) {
        holdout.push_back(EvaluatePrediction(seg, alpha.data(), options, full.final_q));
      }
    }
    const PredictionStats s = Summarize(holdout);
    std::printf("| %.0f | %.4f | %.4f |\n", T, s.mean_position_error_m, s.mean_heading_error_rad);
  }
  return 0;
}

}  // namespace
}  // namespace slipgraph

int main(int argc, char** argv) {
  std::string scenario = "ipd35", methods = "ekf,window,batch", errors_prefix;
  uint64_t seed = 1;
  slipgraph::IpdOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--holdout") return slipgraph::Holdout();
    if (arg == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--errors" && i + 1 < argc) {
      errors_prefix = argv[++i];
    } else if (arg == "--no-matching") {
      options.match_covariance_segments = 0.0;
    } else if (arg == "--methods" && i + 1 < argc) {
      methods = argv[++i];
    } else if (arg == "--scenario" && i + 1 < argc) {
      scenario = argv[++i];
      if (scenario != "ipd35" && scenario != "ipd35m") {
        std::fprintf(stderr, "ipd_report: --scenario is ipd35 or ipd35m, not '%s'\n",
                     scenario.c_str());
        return 2;
      }
    } else {
      std::fprintf(stderr,
                   "usage: ipd_report [--scenario ipd35|ipd35m] [--seed N] [--methods "
                   "ekf,window,batch] [--errors PREFIX] [--no-matching] | --holdout\n");
      return 2;
    }
  }
  return slipgraph::Ipd35(scenario, seed, methods, errors_prefix, options);
}
