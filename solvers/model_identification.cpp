#include "solvers/model_identification.h"

#include <ceres/covariance.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "evaluation/evaluation.h"
#include "evaluation/outage_prediction.h"
#include "factors/traction.h"
#include "io/estimate_file.h"
#include "io/measurement_stream.h"
#include "solvers/batch_smoother.h"
#include "solvers/ekf_runner.h"
#include "solvers/trust_check.h"

namespace slipgraph {
namespace {

// The noise sd of a sampled signal from its second differences at lag `lag` (see the header): their
// RMS over those within 5 robust sd (1.4826 x the median absolute difference) of zero, so that
// spikes and steps do not count. Not the median itself: a quantized signal's differences take a
// few discrete values, and their median is one of them.
double SecondDifferenceSd(const std::vector<double>& x, size_t lag, long* used) {
  std::vector<double> d;
  for (size_t k = lag; k + lag < x.size(); ++k) {
    const double value = x[k + lag] - 2.0 * x[k] + x[k - lag];
    if (std::isfinite(value)) d.push_back(std::abs(value));
  }
  *used = 0;
  if (d.size() < 10) return std::nan("");
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double robust = 1.4826 * sorted[sorted.size() / 2];
  double sum_sq = 0.0;
  for (double v : d) {
    if (robust == 0.0 || v <= 5.0 * robust) sum_sq += v * v, ++*used;
  }
  return *used > 0 ? std::sqrt(sum_sq / *used / 6.0) : std::nan("");
}

// The driven sides' mean surface speed r |w_l + w_r| / 2 at the wheel sample at or within 0.05 s
// before t; NaN when there is none.
double WheelSurfaceSpeedAt(const DriveLog& log, double t) {
  const long i = LatestAtOrBefore(log.wheels, t);
  if (i < 0 || t - log.wheels[i].t > 0.05) return std::nan("");
  const SideSpeeds s = DrivenSideSpeeds(log.wheels[i], log.vehicle.type);
  return 0.5 * log.vehicle.wheel_radius_m * std::abs(s.left_radps + s.right_radps);
}

void EstimateSensorNoise(const std::vector<DriveLog>& logs, ModelConfig* model,
                         std::vector<NoiseEstimate>* out) {
  struct Signal {
    const char* name;
    double* value;
    size_t lag;  // 2 for speeds differenced from counts (see the header)
    std::vector<std::vector<double>> series;
  };
  Signal accel{"measurement_noise.imu_sd_accel", &model->measurement.imu_sd_accel_mps2, 1, {}};
  Signal gyro{"measurement_noise.imu_sd_gyro", &model->measurement.imu_sd_gyro_radps, 1, {}};
  Signal wheels{
      "measurement_noise.wheels_sd_omega", &model->measurement.wheels_sd_omega_radps, 2, {}};
  // GNSS at 1 Hz: lag 1 (two seconds) already holds some of the robot's own speed changes.
  Signal gnss{"measurement_noise.gps_sd_v", &model->measurement.gps_sd_v_mps, 1, {}};
  // A drive too slow for that (fewer than 30 fixes above 0.3 m/s): the velocity's components,
  // which a slow robot's turns hardly move.
  Signal gnss_components{"measurement_noise.gps_sd_v", &model->measurement.gps_sd_v_mps, 1, {}};
  for (const DriveLog& log : logs) {
    std::vector<double> ax, gz, left, right;
    for (const ImuSample& s : log.imu) ax.push_back(s.ax), gz.push_back(s.gz);
    for (const WheelSample& w : log.wheels) {
      // Stopped wheels read exactly 0 (a count difference of 0): no noise to see there.
      const SideSpeeds s = DrivenSideSpeeds(w, log.vehicle.type);
      const bool stopped = s.left_radps == 0.0 && s.right_radps == 0.0;
      left.push_back(stopped ? std::nan("") : s.left_radps);
      right.push_back(stopped ? std::nan("") : s.right_radps);
    }
    // GNSS: the ground speed while moving (its components turn with the robot; its noise along
    // the course is the components' sd; below 0.3 m/s the norm's noise is not Gaussian), less
    // the wheels' mean surface speed at the fix, which takes the robot's own speed changes out.
    std::vector<double> speed;
    for (const GpsSample& g : log.gps) {
      const double v = std::hypot(g.vx, g.vy);
      speed.push_back(v > 0.3 ? v - WheelSurfaceSpeedAt(log, g.t) : std::nan(""));
    }
    gnss.series.push_back(speed);
    std::vector<double> east, north;
    for (const GpsSample& g : log.gps) east.push_back(g.vx), north.push_back(g.vy);
    gnss_components.series.push_back(east);
    gnss_components.series.push_back(north);
    accel.series.push_back(ax);
    gyro.series.push_back(gz);
    wheels.series.push_back(left);
    wheels.series.push_back(right);
  }
  // Pooled over the series: the samples' weighted mean of the variances.
  const auto pooled = [](const Signal& signal, long* total) {
    double weighted = 0.0;
    *total = 0;
    for (const std::vector<double>& series : signal.series) {
      long used = 0;
      const double sd = SecondDifferenceSd(series, signal.lag, &used);
      if (std::isfinite(sd)) weighted += sd * sd * used, *total += used;
    }
    return *total > 0 ? weighted / *total : 0.0;
  };
  for (Signal* signal : {&accel, &gyro, &wheels, &gnss}) {
    long total = 0;
    double variance = pooled(*signal, &total);
    std::string method = "second difference";
    if (signal == &gnss && total < 30) {
      variance = pooled(gnss_components, &total);
      method = "second difference of the components (a slow drive)";
    } else if (signal == &gnss && total > 0) {
      // Less the wheels' share: r sd_w / sqrt(2) of the mean surface speed (estimated above).
      const double r = logs[0].vehicle.wheel_radius_m;
      const double wheel_sd = r * model->measurement.wheels_sd_omega_radps / std::sqrt(2.0);
      variance = std::max(0.25 * variance, variance - wheel_sd * wheel_sd);
    }
    NoiseEstimate e{signal->name, *signal->value, *signal->value, total,
                    total > 0 ? "kept (no spread seen)" : "kept (too few samples)"};
    // GNSS at 1-10 Hz: a few minutes of fixes; the others sample at 50-100 Hz.
    const long needed = signal == &gnss ? 30 : 100;
    if (total >= needed && variance > 0.0) {
      e.value = std::sqrt(variance);
      e.method = method;
      *signal->value = e.value;
    }
    out->push_back(e);
  }
}

// The wheels' rolling radius against GNSS ground speed: |v_gnss| = (1 + e) r |w_mean| through
// the origin, over the fixes while the wheels turn (mean surface speed above 0.3 m/s), with the
// wheel sample nearest each fix. e includes the mean slip (the law's steady slip, a percent or
// two on soft ground). sd from the fit's scatter. NaN with fewer than 10 fixes.
double GnssRadiusError(const std::vector<DriveLog>& logs, double* sd, long* used) {
  double suu = 0.0, suv = 0.0, svv = 0.0;
  long n = 0;
  for (const DriveLog& log : logs) {
    for (const GpsSample& g : log.gps) {
      const double u = WheelSurfaceSpeedAt(log, g.t);
      const double v = std::hypot(g.vx, g.vy);
      if (!std::isfinite(u) || !std::isfinite(v) || u < 0.3) continue;
      suu += u * u, suv += u * v, svv += v * v, ++n;
    }
  }
  *used = n;
  *sd = std::nan("");
  if (n < 10) return std::nan("");
  const double slope = suv / suu;
  const double residual_sq = std::max(0.0, svv - 2.0 * slope * suv + slope * slope * suu);
  *sd = std::sqrt(residual_sq / (n - 1) / suu);
  return slope - 1.0;
}

// The model with the fitted laws and radii in it.
ModelConfig WithFittedLaw(const ModelConfig& model, const IdentificationProblem& problem) {
  ModelConfig out = model;
  SetLawCoefficients(problem.law, &out.tire, &out.rolling);
  // The law is now the data's: its soils' spread no longer describes its error.
  out.law_samples.clear();
  out.calibration.wheel_radius_scale_left *= 1.0 + problem.radius_error[0];
  out.calibration.wheel_radius_scale_right *= 1.0 + problem.radius_error[1];
  return out;
}

void SolveIdentification(const IdentifyOptions& options, IdentificationProblem* problem,
                         ceres::Solver::Summary* summary) {
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = options.threads;
  // A relative cost change of 1e-5 is a tenth of a unit of log-likelihood on a minute's log: the
  // law's bounds and the robust losses make the last digits slow (tr_ratio about 0.3).
  solver.function_tolerance = 1e-5;
  ceres::Solve(solver, problem->problem.get(), summary);
}

// The first log (as read, ScoreModel calibrates it) whose velocity the default front end, run
// with `fitted`, takes off the wheels (solvers/trust_check.h) where with `start` it does not,
// said as "the fitted law sent the default front end off the wheels on X % of LOG"; empty when
// none.
std::string FallingBranchLeavesTheWheels(const std::vector<DriveLog>& logs,
                                         const ModelConfig& start, const ModelConfig& fitted,
                                         bool use_gps) {
  const double limit = TrustOptions{}.suspect_fraction;
  for (const DriveLog& log : logs) {
    const double off = ScoreModel(log, fitted, use_gps, /*gnss_fading=*/true, /*predict=*/false)
                           .off_wheels_fraction;
    if (off <= limit || ScoreModel(log, start, use_gps, /*gnss_fading=*/true, /*predict=*/false)
                                .off_wheels_fraction > limit) {
      continue;
    }
    std::ostringstream out;
    out << std::setprecision(3) << "the fitted law sent the default front end off the wheels on "
        << 100.0 * off << " % of " << log.directory;
    return out.str();
  }
  return "";
}

// The speed the driven wheels' rims reach on the logs (m/s): the 99th percentile of r |w| over
// both sides' samples (a spike in one encoder does not set it); NaN without wheel samples.
double FastRimSpeedMps(const std::vector<DriveLog>& logs) {
  std::vector<double> speeds;
  for (const DriveLog& log : logs) {
    for (const WheelSample& w : log.wheels) {
      const SideSpeeds s = DrivenSideSpeeds(w, log.vehicle.type);
      for (double omega : {s.left_radps, s.right_radps}) {
        const double speed = log.vehicle.wheel_radius_m * std::abs(omega);
        if (std::isfinite(speed)) speeds.push_back(speed);
      }
    }
  }
  if (speeds.empty()) return std::nan("");
  const size_t k = static_cast<size_t>(0.99 * (speeds.size() - 1));
  std::nth_element(speeds.begin(), speeds.begin() + k, speeds.end());
  return speeds[k];
}

// "the fitted law's traction reverses at X m/s of slip speed, below the wheels' rim speed Y m/s
// (...)" where it does (TractionReversalSpeedMps); empty where it keeps its sign.
std::string TractionReversesWithin(const TireParams& tire, double rim_speed_mps) {
  const double reversal_mps = TractionReversalSpeedMps(tire, rim_speed_mps);
  if (std::isnan(reversal_mps)) return "";
  std::ostringstream out;
  out << std::setprecision(3) << "the fitted law's traction reverses at " << reversal_mps
      << " m/s of slip speed, below the wheels' rim speed " << rim_speed_mps
      << " m/s (a stuck robot's wheels would pull it back)";
  return out.str();
}

// u = r (w_r - w_l) = c (yaw rate - a) over the wheel samples with the nearest IMU sample: least
// squares of u on the gyro with an intercept (a: the gyro's offset). That way round because the
// gyro is the precise one (encoder noise in a regressor would bias c up: 0.82 m for a 0.55 m
// track on the bundled log). NaN when the drive turns too little.
double EffectiveTrack(const std::vector<DriveLog>& logs, long* used) {
  double su = 0.0, sg = 0.0, sgg = 0.0, sug = 0.0;
  long n = 0, turning = 0;
  for (const DriveLog& log : logs) {
    const double r = log.vehicle.wheel_radius_m;
    for (const WheelSample& w : log.wheels) {
      const long i = LatestAtOrBefore(log.imu, w.t);
      if (i < 0 || w.t - log.imu[i].t > 0.05) continue;
      const SideSpeeds s = DrivenSideSpeeds(w, log.vehicle.type);
      const double u = r * (s.right_radps - s.left_radps);
      const double g = log.imu[i].gz;
      if (!std::isfinite(u) || !std::isfinite(g)) continue;
      su += u, sg += g, sgg += g * g, sug += u * g, ++n;
      if (std::abs(g) > 0.05) ++turning;
    }
  }
  *used = n;
  if (n < 100 || turning < 100) return std::nan("");
  const double cov_ug = sug - su * sg / n, var_g = sgg - sg * sg / n;
  if (!(var_g > 0.0) || !(cov_ug > 0.0)) return std::nan("");
  return cov_ug / var_g;
}

}  // namespace

bool IdentifyOptions::IsValid(std::string* error) const {
  for (int i = 0; i < kLawCoefficientCount; ++i) {
    if (!(priors.law_sd[i] > 0.0 && priors.law_min[i] < priors.law_max[i])) {
      *error = "IdentifyOptions: each law prior sd > 0 and its minimum below its maximum";
      return false;
    }
  }
  if (!(priors.radius_error_sd > 0.0 && priors.radius_error_bound > 0.0 && max_iterations > 0 &&
        threads > 0 && disturbance_walk_mps3_per_sqrt_hz > 0.0 && law_residual.relative_sd > 0.0 &&
        law_residual.floor_mps2 > 0.0)) {
    *error =
        "IdentifyOptions: radius prior sd and bound, iterations, threads, the disturbance walk "
        "and the law residual's relative sd and floor must be positive";
    return false;
  }
  return true;
}

IdentificationResult IdentifyModel(const std::vector<DriveLog>& input_logs,
                                   const ModelConfig& input_model, const IdentifyOptions& options) {
  if (input_logs.empty()) throw std::invalid_argument("identify needs at least one log");
  IdentificationResult result;
  ModelConfig model = input_model;
  model.effects.clear();  // an effect and the law would explain the same force
  model.effect_windows.clear();
  if (!input_model.effects.empty()) {
    result.notes.push_back("the model's effects are left out: the law is fitted without them");
  }
  for (const DriveLog& log : input_logs) {
    if (log.vehicle.type != input_logs[0].vehicle.type ||
        log.vehicle.wheel_radius_m != input_logs[0].vehicle.wheel_radius_m) {
      throw std::invalid_argument(log.directory + ": not the vehicle of " +
                                  input_logs[0].directory + " (one robot's logs only)");
    }
  }
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  std::vector<DriveLog> logs = input_logs;
  for (DriveLog& log : logs) ApplyCalibration(model, &log);

  // 1. The encoders' delay (before the noise, whose GNSS sd reads the wheels at the fixes'
  // stamps, and the track).
  if (options.wheel_clock) {
    result.wheel_clock = EstimateWheelClock(logs);
    if (result.wheel_clock.taken &&
        !(std::abs(model.calibration.wheels_time_offset_s + result.wheel_clock.lag_s) <= 1.0)) {
      result.wheel_clock.taken = false;
      result.notes.push_back(
          "the encoders' delay would put calibration.wheels_time_offset beyond 1 s: not taken");
    }
    if (result.wheel_clock.taken) {
      model.calibration.wheels_time_offset_s += result.wheel_clock.lag_s;
      for (DriveLog& log : logs) MoveWheelStampsBack(result.wheel_clock.lag_s, &log);
    }
  }

  // 2. Sensor noise, then the effective track.
  EstimateSensorNoise(logs, &model, &result.noise);
  const VehicleType type = logs[0].vehicle.type;
  result.effective_track_m = EffectiveTrack(logs, &result.track_samples);
  if (std::isfinite(result.effective_track_m) && type == VehicleType::kSkidSteer) {
    model.calibration.track_width_m = result.effective_track_m;
    for (DriveLog& log : logs) log.vehicle.track_width_m = result.effective_track_m;
    result.notes.push_back("skid-steer: the model takes the effective track");
  } else if (!std::isfinite(result.effective_track_m)) {
    result.notes.push_back("effective track: the drive turns too little to tell");
  }

  result.gnss_radius_error = std::nan("");
  if (options.use_gps) {
    result.gnss_radius_error =
        GnssRadiusError(logs, &result.gnss_radius_error_sd, &result.gnss_radius_fixes);
  }

  // 3. Laws, radii and offsets in one problem, from one EKF per log.
  std::vector<FilterResult> runs;
  FilterRunOptions filter;
  filter.use_gps = options.use_gps;
  filter.multiple_model = false;
  // The paper's filter, as the figures in docs/identify.md.
  filter.ekf.gnss_fading_fixes = 0.0;
  filter.papers_accel_bias = true;
  for (const DriveLog& log : logs) runs.push_back(RunEkf(log, model, filter));
  std::vector<const DriveLog*> log_pointers;
  std::vector<const std::vector<WardEstimate>*> initial;
  for (size_t i = 0; i < logs.size(); ++i) {
    if (runs[i].estimates.empty()) {
      throw std::invalid_argument(logs[i].directory + ": no wheel data to identify from");
    }
    log_pointers.push_back(&logs[i]);
    initial.push_back(&runs[i].estimates);
  }
  WardProblemOptions problem_options = WithFilterSettings(WardProblemOptions{}, filter);
  // The law is what is sought: the accelerometer factors carry the sensor's noise and a small
  // share of the law's error only (not the model's stated law uncertainty, which describes a law
  // taken as given), and the disturbance walks slowly, so the law, not a_dist, explains the
  // forces; the walk's Huber loss still lets a hold-back's step through.
  ModelConfig fit_model = model;
  fit_model.tire_uncertainty = options.law_residual;
  problem_options.tire_law_correlation_time_s = options.law_residual.correlation_time_s;
  fit_model.process.a_dist_mps3_per_sqrt_hz = options.disturbance_walk_mps3_per_sqrt_hz;
  IdentificationPriors priors = options.priors;
  std::unique_ptr<IdentificationProblem> problem =
      BuildIdentificationProblem(log_pointers, fit_model, initial, problem_options, priors);
  if (!options.fit_radius) {
    problem->problem->SetParameterBlockConstant(problem->radius_error.data());
  }
  SolveIdentification(options, problem.get(), &result.summary);

  // A law with a falling branch (C2 < 0) must still run in the front end that will use it: eq.
  // (8)'s linear falling branch makes the velocity's dynamics unstable at large slip, and the
  // default front end, whose GNSS fading widens its covariance, can settle on a wrong root there,
  // a disturbance holding the body far ahead of its wheels (docs/identify.md). Where the law's
  // traction reverses within the rim speeds the wheels reach (a hold-back's slip: the law must
  // still pull a stuck robot forward, and a held-out stretch may need it where the fitted one did
  // not), or it sends a fitted log's velocity off the wheels and the starting model does not,
  // C2's lower bound is raised to 0 and the problem solved again from where it stands.
  if (options.keep_front_end_on_wheels && problem->law[kLawC2] < 0.0) {
    const ModelConfig fitted = WithFittedLaw(model, *problem);
    std::string refused = TractionReversesWithin(fitted.tire, FastRimSpeedMps(logs));
    if (refused.empty()) {
      refused = FallingBranchLeavesTheWheels(input_logs, model, fitted, options.use_gps);
    }
    if (!refused.empty() && priors.law_max[kLawC2] <= 0.0) {
      result.notes.push_back(refused + ": kept, C2's upper bound allows no other");
    } else if (!refused.empty()) {
      std::ostringstream note;
      note << std::setprecision(3) << refused << " (C2 = " << problem->law[kLawC2] << ", "
           << result.summary.iterations.size() << " iterations): solved again with C2 >= 0";
      result.notes.push_back(note.str());
      result.falling_branch_refused = true;
      priors.law_min[kLawC2] = std::max(0.0, priors.law_min[kLawC2]);
      problem->law[kLawC2] = priors.law_min[kLawC2];  // C2 < 0 <= the new bound: start on it
      problem->problem->SetParameterLowerBound(problem->law.data(), kLawC2, priors.law_min[kLawC2]);
      SolveIdentification(options, problem.get(), &result.summary);
    }
  }
  result.converged = result.summary.termination_type == ceres::CONVERGENCE;
  if (!result.converged) {
    result.notes.push_back(
        "the solve did not converge (" +
        std::string(ceres::TerminationTypeToString(result.summary.termination_type)) +
        "): the values are the last iterate");
  }
  for (const IdentificationLogBlocks& blocks : problem->logs)
    result.offsets.push_back(blocks.offsets);

  // Their covariance.
  const int count = kLawCoefficientCount + 2;
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Constant(count, count, std::nan(""));
  {
    ceres::Covariance::Options covariance_options;
    covariance_options.num_threads = options.threads;
    covariance_options.algorithm_type = ceres::SPARSE_QR;
    ceres::Covariance estimator(covariance_options);
    double* law = problem->law.data();
    double* radius = problem->radius_error.data();
    const std::vector<std::pair<const double*, const double*>> pairs = {
        {law, law}, {law, radius}, {radius, radius}};
    if (estimator.Compute(pairs, problem->problem.get())) {
      Eigen::Matrix<double, kLawCoefficientCount, kLawCoefficientCount, Eigen::RowMajor> ll;
      Eigen::Matrix<double, kLawCoefficientCount, 2, Eigen::RowMajor> lr;
      Eigen::Matrix<double, 2, 2, Eigen::RowMajor> rr;
      estimator.GetCovarianceBlock(law, law, ll.data());
      estimator.GetCovarianceBlock(law, radius, lr.data());
      estimator.GetCovarianceBlock(radius, radius, rr.data());
      covariance.topLeftCorner<kLawCoefficientCount, kLawCoefficientCount>() = ll;
      covariance.topRightCorner<kLawCoefficientCount, 2>() = lr;
      covariance.bottomLeftCorner<2, kLawCoefficientCount>() = lr.transpose();
      covariance.bottomRightCorner<2, 2>() = rr;
      const Eigen::VectorXd sd = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
      result.correlation = covariance.cwiseQuotient(sd * sd.transpose());
    } else {
      result.notes.push_back("the parameters' covariance was not recovered: no sd");
    }
  }
  const std::array<double, kLawCoefficientCount> nominal_law =
      LawCoefficients(model.tire, model.rolling);
  for (int i = 0; i < kLawCoefficientCount; ++i) {
    const double bound_gap = 1e-6 * (priors.law_max[i] - priors.law_min[i]);
    result.parameters.push_back({LawCoefficientNames()[i], nominal_law[i], problem->law[i],
                                 std::sqrt(covariance(i, i)), priors.law_sd[i],
                                 problem->law[i] <= priors.law_min[i] + bound_gap ||
                                     problem->law[i] >= priors.law_max[i] - bound_gap});
  }
  for (int side = 0; side < 2 && options.fit_radius; ++side) {
    const int i = kLawCoefficientCount + side;
    result.parameters.push_back(
        {side == 0 ? "radius_error.left" : "radius_error.right", 0.0, problem->radius_error[side],
         std::sqrt(covariance(i, i)), options.priors.radius_error_sd,
         std::abs(problem->radius_error[side]) >= options.priors.radius_error_bound * (1 - 1e-6)});
  }
  if (result.correlation.size() > 0) {
    const int kept = static_cast<int>(result.parameters.size());
    result.correlation = result.correlation.topLeftCorner(kept, kept).eval();
  }
  model = WithFittedLaw(model, *problem);

  if (!model.IsValid(&error)) result.notes.push_back("the identified model is invalid: " + error);
  result.model = model;
  return result;
}

std::string DescribeIdentification(const IdentificationResult& r) {
  std::ostringstream out;
  out << std::setprecision(4);
  out << "parameters (prior sd: the data identify a parameter whose sd is under half of it):\n";
  for (const IdentifiedParameter& p : r.parameters) {
    out << "  " << std::left << std::setw(20) << p.name << std::right << " " << std::setw(9)
        << p.nominal << " -> " << std::setw(9) << p.value << " +- " << std::setw(9) << p.sd
        << "  (prior sd " << p.prior_sd << ") "
        << (std::isfinite(p.sd) ? (p.identified() ? "identified" : "NOT identified: the prior's")
                                : "no sd")
        << (p.at_bound ? ", AT ITS BOUND (its sd ignores the bound)" : "") << "\n";
  }
  if (r.correlation.size() > 0) {
    for (int i = 0; i < r.correlation.rows(); ++i) {
      for (int j = i + 1; j < r.correlation.cols(); ++j) {
        if (std::abs(r.correlation(i, j)) >= 0.8) {
          out << "  correlated: " << r.parameters[i].name << " and " << r.parameters[j].name << " ("
              << std::setprecision(2) << r.correlation(i, j) << std::setprecision(4)
              << "): the data see their combination, not each\n";
        }
      }
    }
  }
  out << "noise:\n";
  for (const NoiseEstimate& e : r.noise) {
    out << "  " << std::left << std::setw(36) << e.name << std::right << " " << std::setw(9)
        << e.nominal << " -> " << std::setw(9) << e.value << "  (" << e.method << ", " << e.samples
        << " samples)\n";
  }
  out << "wheel radius against GNSS ground speed: ";
  if (std::isfinite(r.gnss_radius_error)) {
    out << std::showpos << 100.0 * r.gnss_radius_error << std::noshowpos << " +- "
        << 100.0 * r.gnss_radius_error_sd << " % (" << r.gnss_radius_fixes
        << " fixes; the mean slip is in it: not applied)\n";
  } else {
    out << "too few fixes while driving\n";
  }
  const WheelClockReading& c = r.wheel_clock;
  if (std::isfinite(c.lag_s)) {
    out << "encoders against the IMU (the yaw channel): " << std::showpos << 1000.0 * c.lag_s
        << std::noshowpos << " +- " << 1000.0 * c.sd_s << " ms late (" << c.samples << " samples, "
        << c.blocks << " parts; correlation with the gyro " << c.correlation_at_zero << " at 0 -> "
        << c.correlation << ")";
    if (c.taken) {
      out << "; the model's calibration.wheels_time_offset takes it\n";
    } else if (c.lag_s < 0.0) {
      out << "; not taken (the gyro follows the wheels: the body's yaw response, or an IMU clock "
             "late: --clock)\n";
    } else if (c.at_grid_edge) {
      out << "; not taken (at the end of the lags searched: a bound)\n";
    } else if (!std::isfinite(c.sd_s)) {
      out << "; not taken (too few parts of the drive turn to give it an sd)\n";
    } else {
      out << "; not taken (under 3 sd or 50 ms, or the note below)\n";
    }
  }
  out << "effective track: ";
  if (std::isfinite(r.effective_track_m)) {
    out << r.effective_track_m << " m (" << r.track_samples << " samples)\n";
  } else {
    out << "not identified\n";
  }
  for (size_t i = 0; i < r.offsets.size(); ++i) {
    out << "log " << i + 1 << " IMU offsets: c_ax " << r.offsets[i][0] << " m/s^2, c_gz "
        << r.offsets[i][1] << " rad/s\n";
  }
  out << "solve: " << r.summary.iterations.size() << " iterations, "
      << (r.converged ? "converged" : "NOT converged") << ", " << r.summary.total_time_in_seconds
      << " s\n";
  for (const std::string& note : r.notes) out << "  note: " << note << "\n";
  return out.str();
}

ModelScore ScoreModel(const DriveLog& input_log, const ModelConfig& model, bool use_gps,
                      bool gnss_fading, bool predict) {
  DriveLog log = input_log;
  ApplyCalibration(model, &log);
  // As `filter --no-gnss-fading` runs it (a bank when the model has law samples): the paper's
  // filter, on which docs/identify.md's figures were measured; or as `filter` runs it by default.
  // With the fading memory the nominal model's held-out velocity error falls, and the identified
  // law's gain with it.
  FilterRunOptions run;
  run.use_gps = use_gps;
  run.ekf.gnss_fading_fixes = gnss_fading ? kGnssFadingFixes : 0.0;
  run.papers_accel_bias = !gnss_fading;  // the paper's filter, or the default front end
  run.ekf.record_innovations = true;
  const FilterResult result = RunEkf(log, model, run);
  ModelScore score;
  if (!result.estimates.empty()) {
    score.off_wheels_fraction = CheckTrust(log, result.estimates).off_wheels_fraction;
  }
  const auto it = result.stats.innovations.find("gnss");
  if (it != result.stats.innovations.end()) {
    double sum = 0.0;
    for (double z : it->second.normalized) {
      if (std::isfinite(z)) sum += z * z, ++score.gnss_fixes;
    }
    if (score.gnss_fixes > 0) score.gnss_nis_mean = sum / score.gnss_fixes;
  }
  long flagged = 0;
  for (const WardEstimate& e : result.estimates) flagged += e.slip.immobilized ? 1 : 0;
  if (!result.estimates.empty()) {
    score.flagged_fraction = static_cast<double>(flagged) / result.estimates.size();
  }
  if (!log.truth.empty() && !result.estimates.empty()) {
    const Evaluation ev = Evaluate(log, EstimateTable(result.estimates));
    score.velocity_rmse = ev.velocity_rmse;
    score.false_immobilized_fraction = ev.false_immobilized_fraction();
  }
  if (predict && use_gps && !log.gps.empty()) {
    // Two runs whose outages alternate, so that most of the drive is predicted once; the spans
    // planned on the log as read (the calibration scales the wheels, which choose them), so that
    // every model is scored on the same spans.
    PredictionError prediction;
    OutagePlanOptions plan;
    plan.stated_fix_sd_xy_m = model.measurement.gps_sd_xy_m;
    run.ekf.record_innovations = false;
    for (const double offset_s : {0.0, plan.horizon_s}) {
      plan.offset_s = offset_s;
      const std::vector<OutageSpan> spans = PlanOutages(input_log, plan);
      if (spans.empty()) continue;
      const FilterResult predicted = RunEkf(WithoutFixesInside(log, spans), model, run);
      AddPredictionErrors(log, spans, predicted.estimates, &prediction, plan);
    }
    score.prediction_spans = prediction.spans();
    score.prediction_against_pose = prediction.against_pose;
    score.prediction_rms_m = prediction.rms_m();
    score.prediction_mean_m = prediction.mean_m();
    score.prediction_mean_se_m = prediction.standard_error_m();
    score.prediction_distance_m = prediction.mean_distance_m();
    score.prediction_floor_m = prediction.floor_rms_m();
  }
  return score;
}

}  // namespace slipgraph
