#include "solvers/ipd_calibration.h"

#include <ceres/jet.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/measurement_stream.h"
#include "model/option_check.h"
#include "solvers/ipd_covariance_matching.h"
#include "solvers/ipd_terrain_memory.h"

namespace slipgraph {

bool IpdOptions::IsValid(std::string* error) const {
  return OptionCheck("IpdOptions", error)
      .Positive("segment_s", segment_s)
      .Positive("spacing_s", spacing_s)
      .Positive("gravity_mps2", gravity_mps2)
      .Positive("alpha_prior_sd", alpha_prior_sd)
      .NonNegative("alpha_walk_sd", alpha_walk_sd)
      .Require("q_initial", (q_initial.array() > 0.0).all(), q_initial.minCoeff(),
               "each entry must be positive")
      .Positive("q_prior_sd", q_prior_sd)
      .NonNegative("q_walk_sd", q_walk_sd)
      .Positive("min_pose_sd_m", min_pose_sd_m)
      .NonNegative("readmit_after", readmit_after)
      .NonNegative("match_covariance_segments", match_covariance_segments)
      .NonNegative("terrain_memory.capacity", terrain_memory.capacity)
      .Positive("terrain_memory.settle_s", terrain_memory.settle_s)
      .Positive("terrain_memory.search_s", terrain_memory.search_s)
      .AtLeast("terrain_memory.window", terrain_memory.window, 1)
      .Positive("terrain_memory.log_bayes_factor", terrain_memory.log_bayes_factor)
      .Positive("jump.jump_sd", jump.jump_sd)
      .Positive("jump.log_bayes_factor", jump.log_bayes_factor)
      .Positive("jump.window_s", jump.window_s);
}
namespace {

using ipd::kAlphaSize;
using AlphaVector = Eigen::Matrix<double, kAlphaSize, 1>;
using AlphaMatrix = Eigen::Matrix<double, kAlphaSize, kAlphaSize>;

double PoseSd(double stated, double floor) {
  return std::isfinite(stated) && stated > floor ? stated : floor;
}

// The six unique entries of a symmetric 3x3 (xx, xy, xt, yy, yt, tt), eq. (24).
Eigen::Matrix<double, 6, 1> Unique(const Eigen::Matrix3d& m) {
  Eigen::Matrix<double, 6, 1> v;
  v << m(0, 0), m(0, 1), m(0, 2), m(1, 1), m(1, 2), m(2, 2);
  return v;
}

// Covariance of the scatter matrix's unique entries for a zero-mean Gaussian residual with
// covariance R, eqs. (26)-(27): C(ab, cd) = C(a,c) C(b,d) + C(a,d) C(b,c).
Eigen::Matrix<double, 6, 6> ScatterCovariance(const Eigen::Matrix3d& R) {
  static const int kPairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  Eigen::Matrix<double, 6, 6> out;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const int a = kPairs[i][0], b = kPairs[i][1], c = kPairs[j][0], d = kPairs[j][1];
      out(i, j) = R(a, c) * R(b, d) + R(a, d) * R(b, c);
    }
  }
  return out;
}

// Rotation from the segment's start frame into (along, cross, heading) axes: along the predicted
// displacement (px, py), or the start heading when it is shorter than 1 cm.
Eigen::Matrix3d AlongCrossFrame(double px, double py) {
  const double length = std::hypot(px, py);
  const double ux = length > 0.01 ? px / length : 1.0;
  const double uy = length > 0.01 ? py / length : 0.0;
  Eigen::Matrix3d rotation;
  rotation << ux, uy, 0.0, -uy, ux, 0.0, 0.0, 0.0, 1.0;
  return rotation;
}

}  // namespace

std::vector<IpdSegment> BuildIpdSegments(const DriveLog& log, const IpdOptions& options) {
  if (log.wheels.size() < 2) throw std::invalid_argument(log.directory + ": no wheel data");
  if (log.pose.size() < 2) {
    throw std::invalid_argument(log.directory +
                                ": no pose.csv (IPD calibration needs measured poses)");
  }
  const double r = log.vehicle.wheel_radius_m, c = log.vehicle.track_width_m;
  std::vector<IpdSegment> segments;
  size_t next_start = 0;
  size_t wheel = 0, attitude = 0;
  double last_start = -1e300;
  for (size_t i = 0; i < log.pose.size(); ++i) {
    const PoseSample& p0 = log.pose[i];
    if (p0.t < last_start + options.spacing_s - 1e-9) continue;
    // The end: the pose sample nearest t0 + segment_s.
    size_t j = std::max(i + 1, next_start);
    while (j + 1 < log.pose.size() && std::abs(log.pose[j + 1].t - (p0.t + options.segment_s)) <
                                          std::abs(log.pose[j].t - (p0.t + options.segment_s))) {
      ++j;
    }
    next_start = j;
    if (j >= log.pose.size() || log.pose[j].t - p0.t < 0.5 * options.segment_s) break;
    const PoseSample& p1 = log.pose[j];
    last_start = p0.t;
    IpdSegment seg;
    seg.t_start = p0.t;
    seg.t_end = p1.t;
    seg.measured = ipd::RelativePose(p0.x, p0.y, p0.yaw, p1.x, p1.y, p1.yaw);
    const auto sigma = [&](const PoseSample& p) {
      const double sxy =
          std::max(PoseSd(p.sd_x, options.min_pose_sd_m), PoseSd(p.sd_y, options.min_pose_sd_m));
      const double syaw = PoseSd(p.sd_yaw, 1e-4);
      return Eigen::Vector3d(sxy * sxy, sxy * sxy, syaw * syaw).asDiagonal().toDenseMatrix();
    };
    seg.sigma_start = sigma(p0);
    seg.sigma_end = sigma(p1);
    while (wheel > 0 && log.wheels[wheel].t > seg.t_start) --wheel;
    while (wheel + 1 < log.wheels.size() && log.wheels[wheel + 1].t <= seg.t_start) ++wheel;
    for (size_t k = wheel; k < log.wheels.size() && log.wheels[k].t < seg.t_end; ++k) {
      const double t_from = std::max(log.wheels[k].t, seg.t_start);
      const double t_to =
          k + 1 < log.wheels.size() ? std::min(log.wheels[k + 1].t, seg.t_end) : seg.t_end;
      if (t_to <= t_from) continue;
      const SideSpeeds w = DrivenSideSpeeds(log.wheels[k], log.vehicle.type);
      ipd::OdometryStep step{t_to - t_from, 0.5 * r * (w.left_radps + w.right_radps),
                             r * (w.right_radps - w.left_radps) / c, 0.0, 0.0};
      while (attitude + 1 < log.attitude.size() && log.attitude[attitude + 1].t <= t_from) {
        ++attitude;
      }
      if (!log.attitude.empty() && log.attitude[attitude].t <= t_from + 1e-9) {
        step.roll_rad = log.attitude[attitude].roll;
        step.pitch_rad = log.attitude[attitude].pitch;
      }
      if (std::isfinite(step.v_x_mps) && std::isfinite(step.v_yaw_radps)) seg.steps.push_back(step);
    }
    if (!seg.steps.empty()) segments.push_back(std::move(seg));
  }
  return segments;
}

PredictionError EvaluatePrediction(const IpdSegment& segment, const double* alpha,
                                   const IpdOptions& options, const Eigen::Vector3d& q) {
  double predicted[3];
  ipd::PredictSegment(segment.steps, alpha, options.gravity_mps2, predicted);
  const Eigen::Matrix3d frame = AlongCrossFrame(predicted[0], predicted[1]);
  const Eigen::Vector3d error = frame * Eigen::Vector3d(segment.measured[0] - predicted[0],
                                                        segment.measured[1] - predicted[1], 0.0);
  PredictionError e;
  e.t_start = segment.t_start;
  e.along_m = error[0];
  e.cross_m = error[1];
  e.heading_rad = std::remainder(segment.measured[2] - predicted[2], 2.0 * M_PI);
  e.predicted_covariance = frame *
                           ipd::PredictionCovariance(segment.steps, alpha, options.gravity_mps2,
                                                     segment.sigma_start, segment.sigma_end)
                               .Total(q) *
                           frame.transpose();
  return e;
}

SegmentLinearization LinearizeSegment(const IpdSegment& seg, const double* alpha,
                                      const IpdOptions& options) {
  using Jet = ceres::Jet<double, kAlphaSize>;
  Jet alpha_jet[kAlphaSize];
  for (int i = 0; i < kAlphaSize; ++i) alpha_jet[i] = Jet(alpha[i], i);
  Jet predicted[3];
  ipd::PredictSegment(seg.steps, alpha_jet, options.gravity_mps2, predicted);
  SegmentLinearization out;
  for (int r = 0; r < 3; ++r) {
    out.predicted[r] = predicted[r].a;
    out.H.row(r) = predicted[r].v.transpose();
  }
  out.residual = seg.measured - out.predicted;
  out.residual[2] = std::remainder(out.residual[2], 2.0 * M_PI);
  return out;
}

Eigen::Matrix3d ParameterCovariance(const IpdSegment& seg, const double* alpha,
                                    const AlphaMatrix& P, const IpdOptions& options) {
  const SegmentLinearization l = LinearizeSegment(seg, alpha, options);
  const Eigen::Matrix3d frame = AlongCrossFrame(l.predicted[0], l.predicted[1]);
  return frame * l.H * P * l.H.transpose() * frame.transpose();
}

std::vector<PredictionError> AfterTheFirstMinute(const std::vector<PredictionError>& all) {
  std::vector<PredictionError> late;
  for (const PredictionError& e : all) {
    if (e.t_start >= all.front().t_start + 60.0) late.push_back(e);
  }
  return late;
}

PredictionStats Summarize(const std::vector<PredictionError>& errors) {
  PredictionStats s;
  s.segments = errors.size();
  if (errors.empty()) return s;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d predicted = Eigen::Matrix3d::Zero();
  for (const PredictionError& e : errors) {
    s.mean_position_error_m += std::hypot(e.along_m, e.cross_m);
    s.mean_heading_error_rad += std::abs(e.heading_rad);
    mean += Eigen::Vector3d(e.along_m, e.cross_m, e.heading_rad);
    predicted += e.predicted_covariance;
  }
  const double n = static_cast<double>(errors.size());
  s.mean_position_error_m /= n;
  s.mean_heading_error_rad /= n;
  mean /= n;
  predicted /= n;
  Eigen::Matrix3d sample = Eigen::Matrix3d::Zero();
  for (const PredictionError& e : errors) {
    const Eigen::Vector3d d = Eigen::Vector3d(e.along_m, e.cross_m, e.heading_rad) - mean;
    sample += d * d.transpose();
  }
  sample /= std::max(1.0, n - 1.0);
  s.sd_along_m = std::sqrt(sample(0, 0));
  s.sd_cross_m = std::sqrt(sample(1, 1));
  s.sd_heading_rad = std::sqrt(sample(2, 2));
  for (int i = 0; i < 3; ++i) s.predicted_over_sample[i] = predicted(i, i) / sample(i, i);
  return s;
}

StochasticCalibrator::StochasticCalibrator(const IpdOptions& options)
    : options_(options),
      q_(options.q_initial),
      P_(Eigen::Matrix3d::Identity() * options.q_prior_sd * options.q_prior_sd) {}

void StochasticCalibrator::Update(const Eigen::Vector3d& residual,
                                  const ipd::PredictionCovarianceTerms& terms,
                                  const Eigen::Matrix3d& parameter_covariance, double elapsed_s) {
  P_ += Eigen::Matrix3d::Identity() * options_.q_walk_sd * options_.q_walk_sd * elapsed_s;
  // Observation: the scatter matrix less what the poses and alpha's uncertainty explain.
  const Eigen::Matrix<double, 6, 1> z =
      Unique(residual * residual.transpose()) - Unique(terms.measurement + parameter_covariance);
  Eigen::Matrix<double, 6, 3> J;  // eq. (21)
  for (int i = 0; i < 3; ++i) J.col(i) = Unique(terms.input[i]);
  const Eigen::Matrix<double, 6, 6> Rz =
      ScatterCovariance(terms.Total(q_) + parameter_covariance);  // eqs. (26)-(27)
  const Eigen::Matrix<double, 6, 6> S = J * P_ * J.transpose() + Rz;
  const Eigen::Matrix<double, 3, 6> K =
      P_ * J.transpose() * S.ldlt().solve(Eigen::Matrix<double, 6, 6>::Identity());
  q_ += K * (z - J * q_);
  P_ = (Eigen::Matrix3d::Identity() - K * J) * P_;
  q_ = q_.cwiseMax(1e-9);  // densities stay positive
}

JumpDetectorOptions IpdJumpDetectorOptions(const IpdOptions& options) {
  JumpDetectorOptions o;
  o.jump_sd = options.jump.jump_sd;
  o.log_bayes_factor = options.jump.log_bayes_factor;
  o.window = std::max(1, static_cast<int>(std::lround(options.jump.window_s / options.spacing_s)));
  o.overlap = std::max(1.0, options.segment_s / options.spacing_s);
  return o;
}

IpdCalibrationResult CalibrateIpdEkf(const DriveLog& log, const IpdOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  IpdCalibrationResult result;
  result.segments = BuildIpdSegments(log, options);
  const std::vector<IpdSegment>& segments = result.segments;
  AlphaVector alpha = AlphaVector::Zero();
  AlphaMatrix P = AlphaMatrix::Identity() * options.alpha_prior_sd * options.alpha_prior_sd;
  StochasticCalibrator stochastic(options);
  Eigen::Vector3d q = stochastic.q();
  double last_update_t = segments.empty() ? 0.0 : segments.front().t_start;
  const std::array<double, kAlphaSize> zero{};
  size_t next_update = 0;
  IpdCovarianceMatching matching(options.match_covariance_segments);
  IpdTerrainMemory memory(options);
  double model_since_t = last_update_t;  // the current model's start: the last misfit or recall
  long rejected = 0, readmitted = 0, recalled = 0, jumps = 0;
  int gated_in_a_row = 0;
  JumpDetector<kAlphaSize, 3> detector(IpdJumpDetectorOptions(options));

  const auto record = [&](double t) {
    std::array<double, kAlphaSize> a;
    for (int i = 0; i < kAlphaSize; ++i) a[i] = alpha[i];
    result.update_t.push_back(t);
    result.alpha.push_back(a);
    result.q.push_back(q);
  };
  // Segment j's update, applied once its end pose is measured.
  const auto update = [&](const IpdSegment& seg) {
    const double elapsed = std::max(0.0, seg.t_end - last_update_t);
    last_update_t = std::max(last_update_t, seg.t_end);
    P += AlphaMatrix::Identity() * options.alpha_walk_sd * options.alpha_walk_sd * elapsed;  // (29)
    // h(alpha) and H = dh/dalpha by automatic differentiation (30)-(31).
    SegmentLinearization l;
    ipd::PredictionCovarianceTerms terms;
    Eigen::Matrix3d R, HPH;  // HPH: the prior's share of the residual
    Eigen::LDLT<Eigen::Matrix3d> S_ldlt;
    SegmentLikelihood score;
    const auto linearize = [&] {
      l = LinearizeSegment(seg, alpha.data(), options);
      terms = ipd::PredictionCovariance(seg.steps, alpha.data(), options.gravity_mps2,
                                        seg.sigma_start, seg.sigma_end);
      R = terms.Total(q);
      HPH = l.H * P * l.H.transpose();
      S_ldlt.compute(HPH + R);
      score = Likelihood(l.residual, S_ldlt);
    };
    linearize();
    IpdSlipModel stored;
    if (memory.Score(seg, score.log_likelihood, &stored)) {
      // Back on a terrain driven before: its model replaces the current one.
      ++recalled;
      alpha = stored.alpha;
      P = stored.P;
      stochastic.Recall(stored.q);
      q = stored.q;
      model_since_t = seg.t_end;
      gated_in_a_row = 0;
      detector.Restart();
      linearize();
    }
    JumpDetector<kAlphaSize, 3>::Jump jump;
    if (options.jump.enabled && detector.Measure(seg.t_end, l.residual, l.H, HPH + R, &jump)) {
      // A jump in alpha before jump.t: the model before it is remembered, alpha corrected by the
      // jump's estimate (which already holds this segment).
      ++jumps;
      memory.Misfit({alpha, P, q}, model_since_t, seg.t_end);
      model_since_t = seg.t_end;
      alpha += jump.correction;
      P += jump.covariance;
      detector.Restart();
      gated_in_a_row = 0;
      record(seg.t_end);
      return;
    }
    double nis = score.nis;
    const Eigen::Vector3d& residual = l.residual;
    const Eigen::Matrix<double, 3, kAlphaSize>& H = l.H;
    if (nis > kSegmentGateChi2) {
      ++rejected;
      if (options.readmit_after <= 0 || ++gated_in_a_row <= options.readmit_after) return;
      // Persistent: the terrain changed. Remember the model that has ended (it may be needed
      // again), then scale alpha's covariance until the residual is plausible.
      ++readmitted;
      memory.Misfit({alpha, P, q}, model_since_t, seg.t_end);
      model_since_t = seg.t_end;
      for (int iteration = 0; iteration < 30 && nis > kSegmentGateChi2; ++iteration) {
        P *= 2.0;
        HPH *= 2.0;
        S_ldlt.compute(HPH + R);
        nis = residual.dot(S_ldlt.solve(residual));
      }
    }
    gated_in_a_row = 0;
    const Eigen::Matrix<double, kAlphaSize, 3> K =
        P * H.transpose() * S_ldlt.solve(Eigen::Matrix3d::Identity());
    alpha += K * residual;  // (33)
    const AlphaMatrix I_KH = AlphaMatrix::Identity() - K * H;
    P = I_KH * P * I_KH.transpose() + K * R * K.transpose();  // (34), Joseph form
    detector.Updated(K, H);

    if (options.calibrate_q) stochastic.Update(residual, terms, HPH, elapsed);
    q = stochastic.q();
    record(seg.t_end);
  };

  for (size_t i = 0; i < segments.size(); ++i) {
    // Updates from every segment that has ended by the time this one starts.
    while (next_update < i && segments[next_update].t_end <= segments[i].t_start + 1e-9) {
      update(segments[next_update++]);
    }
    result.no_slip.push_back(EvaluatePrediction(segments[i], zero.data(), options, q));
    PredictionError e = EvaluatePrediction(segments[i], alpha.data(), options, q);
    e.parameter_covariance = ParameterCovariance(segments[i], alpha.data(), P, options);
    e.predicted_covariance += e.parameter_covariance;
    matching.Apply(segments[i].t_end, &e);
    result.calibrated.push_back(e);
  }
  while (next_update < segments.size()) update(segments[next_update++]);
  for (int i = 0; i < kAlphaSize; ++i) {
    result.final_alpha[i] = alpha[i];
    result.final_alpha_sd[i] = std::sqrt(P(i, i));
  }
  result.final_q = q;
  if (rejected > 0) {
    result.notes.push_back(std::to_string(rejected) +
                           " segment(s) failed the 99.99 % innovation gate, " +
                           std::to_string(readmitted) +
                           " of them taken with alpha's covariance inflated (a persistent "
                           "misfit: the terrain changed)");
  }
  if (jumps > 0) {
    result.notes.push_back(std::to_string(jumps) +
                           " jump(s) in the slip model detected from the segments' innovations "
                           "(a terrain change); alpha corrected by each jump's estimate");
  }
  const std::string memory_note = memory.Describe(recalled);
  if (!memory_note.empty()) result.notes.push_back(memory_note);
  return result;
}

}  // namespace slipgraph
