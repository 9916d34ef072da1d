#include "solvers/trust_check.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "factors/frames.h"
#include "io/gnss_heading_offsets.h"
#include "io/measurement_stream.h"
#include "io/nearest_time.h"
#include "model/model_config.h"

namespace slipgraph {

bool TrustOptions::IsValid(std::string* error) const {
  if (!(wheel_scale >= 1.0 && wheel_margin_mps >= 0.0 && min_speed_mps >= 0.0)) {
    *error = "TrustOptions: wheel_scale >= 1, wheel_margin_mps and min_speed_mps >= 0";
    return false;
  }
  if (!(scale_window_s > 0.0 && min_mean_slip < 0.0 && flat_pitch_rad > 0.0 &&
        moving_flag_fraction >= 0.0 && moving_flag_fraction <= 1.0)) {
    *error =
        "TrustOptions: scale_window_s > 0, min_mean_slip < 0, flat_pitch_rad > 0 and "
        "moving_flag_fraction in [0, 1]";
    return false;
  }
  if (!(stretch_z_limit > 0.0 && stretch_min_fixes >= 2 && stretch_start_margin_s >= 0.0 &&
        stretch_end_margin_s >= 0.0)) {
    *error =
        "TrustOptions: stretch_z_limit > 0, stretch_min_fixes >= 2, stretch_start_margin_s and "
        "stretch_end_margin_s >= 0";
    return false;
  }
  if (!(suspect_fraction >= 0.0 && suspect_fraction <= 1.0 && gnss_run_limit > 0.0 &&
        gnss_window >= 1 && gnss_window_limit > 0.0 && min_gnss_fixes >= 1)) {
    *error =
        "TrustOptions: suspect_fraction in [0, 1], gnss_run_limit and gnss_window_limit > 0, "
        "gnss_window and min_gnss_fixes >= 1";
    return false;
  }
  return true;
}

namespace {

// The largest |z| one GNSS fix adds to the speed check (CheckTrust).
constexpr double kFixZLimit = 10.0;

bool OffTheWheels(const WardEstimate& e, double radius_m, const TrustOptions& o) {
  const double v = e.x[ward::kVbx];
  if (!std::isfinite(v)) return true;  // no velocity at all: nothing to trust
  const double left = radius_m * e.x[ward::kOmegaLeft];
  const double right = radius_m * e.x[ward::kOmegaRight];
  const double faster = std::max(std::abs(left), std::abs(right));
  if (std::abs(v) > o.wheel_scale * faster + o.wheel_margin_mps) return true;
  const bool both_turn =
      std::abs(left) > o.min_speed_mps && std::abs(right) > o.min_speed_mps && left * right > 0.0;
  return both_turn && std::abs(v) > o.min_speed_mps && v * left < 0.0;
}

// A fix's squared speed, in 3-D when it has a vertical velocity (the body's speed on a grade),
// less its noise's bias (sd^2 per axis), and the variance of that noise (2 sd^4 per axis): zero
// mean at rest.
struct SquaredSpeed {
  double less_noise_m2ps2;
  double noise_variance;
};
SquaredSpeed SquaredSpeedLessNoise(const GpsSample& fix, double sd_mps) {
  const bool vertical = std::isfinite(fix.vz);
  const double axes = vertical ? 3.0 : 2.0;
  const double speed_sq = fix.vx * fix.vx + fix.vy * fix.vy + (vertical ? fix.vz * fix.vz : 0.0);
  const double variance = sd_mps * sd_mps;
  return {speed_sq - axes * variance, 2.0 * axes * variance * variance};
}

// Flags this close in time belong to one stretch (the slip's EMA may dip under its threshold
// for a moment inside one stop).
constexpr double kFlagGapS = 1.0;

// An attitude sample older than this does not give a fix its heading.
constexpr double kAttitudeMaxAgeS = 1.0;

// The attitude sample that gives a fix at t its heading, or null.
const AttitudeSample* HeadingAt(const DriveLog& log, double t) {
  const long a = LatestAtOrBefore(log.attitude, t);
  if (a < 0 || t - log.attitude[a].t > kAttitudeMaxAgeS) return nullptr;
  const AttitudeSample& attitude = log.attitude[a];
  return std::isfinite(attitude.pitch) && std::isfinite(attitude.yaw) ? &attitude : nullptr;
}

// What the fixes between t0 and t1 say against a robot at rest: z of the mean of each fix's
// velocity along the body's heading (the yaw corrected by heading_offsets, one per log.gps
// fix), |mean| sqrt(n) / sd, the robot moving either way; or, when
// any of them has no heading (no attitude within kAttitudeMaxAgeS), of all their squared speeds
// less the noise's share (k sd^2 over k axes, zero-mean at rest with sd sqrt(2k) sd^2), signed:
// fixes quieter than their stated sd are a robot at rest. sd is the larger of the stated and the
// fixes' own scatter. NaN with fewer than min_fixes fixes.
double RestZ(const DriveLog& log, const std::vector<double>& heading_offsets, double t0, double t1,
             int min_fixes) {
  std::vector<const GpsSample*> fixes;
  std::vector<const AttitudeSample*> headings;
  std::vector<double> offsets_rad;
  bool headed = true;
  for (long i = std::max(0L, LatestAtOrBefore(log.gps, t0)); i < static_cast<long>(log.gps.size());
       ++i) {
    const GpsSample& fix = log.gps[i];
    if (fix.t < t0 || !std::isfinite(fix.vx) || !std::isfinite(fix.vy)) continue;
    if (fix.t > t1) break;
    fixes.push_back(&fix);
    headings.push_back(HeadingAt(log, fix.t));
    offsets_rad.push_back(heading_offsets[i]);
    headed = headed && headings.back() != nullptr;
  }
  const size_t n = fixes.size();
  if (n < static_cast<size_t>(std::max(2, min_fixes))) return std::nan("");
  // One quantity for the whole stretch: m/s along the heading, or m^2/s^2 of squared speed.
  std::vector<double> values(n), stated_variance(n);
  for (size_t i = 0; i < n; ++i) {
    const GpsSample& fix = *fixes[i];
    const double sd_mps = GnssVelocitySd(fix, log.vehicle.sensors.gps_sd_v_mps);
    if (headed) {
      const double vz = std::isfinite(fix.vz) ? fix.vz : 0.0;
      values[i] = GnssVelocityAlongBodyX(fix.vx, fix.vy, vz, true, headings[i]->pitch,
                                         headings[i]->yaw + offsets_rad[i], 1.0);
      stated_variance[i] = sd_mps * sd_mps;
    } else {
      const SquaredSpeed squared = SquaredSpeedLessNoise(fix, sd_mps);
      values[i] = squared.less_noise_m2ps2;
      stated_variance[i] = squared.noise_variance;
    }
  }
  double mean = 0.0, stated = 0.0;
  for (size_t i = 0; i < n; ++i) mean += values[i] / n, stated += stated_variance[i] / n;
  double scatter = 0.0;
  for (const double v : values) scatter += (v - mean) * (v - mean) / (n - 1);
  const double sd = std::sqrt(std::max(stated, scatter));
  if (!(sd > 0.0)) return std::nan("");
  return (headed ? std::abs(mean) : mean) * std::sqrt(static_cast<double>(n)) / sd;
}

// The stretches of flags (flags within kFlagGapS of each other) whose fixes together say the
// robot moves (RestZ beyond options.stretch_z_limit): every flag in them is set in *moving and
// marked in *suspect (their test needs seconds of fixes, which a hold-back's edges do not give).
// Returns the largest stretch z (NaN: none tested).
double FlaggedStretchesThatMove(const DriveLog& log, const std::vector<WardEstimate>& estimates,
                                const TrustOptions& options, std::vector<char>* moving,
                                std::vector<double>* suspect) {
  // Each fix on the yaw corrected by the course, as the estimators project it.
  ModelConfig model = DefaultModelConfig(log.vehicle);
  model.gnss_heading_from_course = options.gnss_heading_from_course;
  const std::vector<double> heading_offsets = GnssHeadingOffsets(log, model);
  double worst = std::nan("");
  for (size_t first = 0; first < estimates.size();) {
    if (!estimates[first].slip.immobilized) {
      ++first;
      continue;
    }
    size_t last = first;  // the stretch's last flag
    for (size_t j = first + 1;
         j < estimates.size() && estimates[j].t - estimates[last].t <= kFlagGapS; ++j) {
      if (estimates[j].slip.immobilized) last = j;
    }
    const double z =
        RestZ(log, heading_offsets, estimates[first].t + options.stretch_start_margin_s,
              estimates[last].t - options.stretch_end_margin_s, options.stretch_min_fixes);
    if (std::isfinite(z) && !(z <= worst)) worst = z;
    if (z > options.stretch_z_limit) {
      for (size_t j = first; j <= last; ++j) {
        if (!estimates[j].slip.immobilized) continue;
        (*moving)[j] = 1;
        (*suspect)[j] = 1.0;
      }
    }
    first = last + 1;
  }
  return worst;
}

}  // namespace

TrustReport CheckTrust(const DriveLog& log, const std::vector<WardEstimate>& estimates,
                       const TrustOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  TrustReport report;
  report.suspect.assign(estimates.size(), 0.0);
  if (estimates.empty()) return report;
  long off = 0;
  for (size_t k = 0; k < estimates.size(); ++k) {
    if (!OffTheWheels(estimates[k], log.vehicle.wheel_radius_m, options)) continue;
    report.suspect[k] = 1.0;
    ++off;
  }
  report.off_wheels_fraction = static_cast<double>(off) / estimates.size();

  // Flagged immobilized while the GNSS fixes on both sides (each within 1.5 s) move: a held
  // robot's fixes stop, and a fix from before a hold-back's onset does not count alone.
  std::vector<char> flagged_moving(estimates.size(), 0);
  const auto moving = [&](const GpsSample& fix) {
    return std::hypot(fix.vx, fix.vy) >
           std::max(0.3, 3.0 * GnssVelocitySd(fix, log.vehicle.sensors.gps_sd_v_mps));
  };
  for (size_t j = 0; j < estimates.size(); ++j) {
    if (!estimates[j].slip.immobilized) continue;
    const long i = LatestAtOrBefore(log.gps, estimates[j].t);
    if (i < 0 || i + 1 >= static_cast<long>(log.gps.size())) continue;
    const GpsSample& before = log.gps[i];
    const GpsSample& after = log.gps[i + 1];
    if (estimates[j].t - before.t > 1.5 || after.t - estimates[j].t > 1.5) continue;
    if (moving(before) && moving(after)) flagged_moving[j] = 1;
  }
  // Stretches of flags whose fixes, taken together, say the robot moves.
  report.worst_stretch_z =
      FlaggedStretchesThatMove(log, estimates, options, &flagged_moving, &report.suspect);
  const long flagged_moving_count = std::count(flagged_moving.begin(), flagged_moving.end(), 1);
  report.flagged_moving_fraction = static_cast<double>(flagged_moving_count) / estimates.size();
  const bool flags_failed = report.flagged_moving_fraction > options.moving_flag_fraction;
  if (flags_failed) {
    for (size_t j = 0; j < estimates.size(); ++j) {
      if (flagged_moving[j]) report.suspect[j] = 1.0;
    }
  }

  // The wheels' scale: consecutive windows of scale_window_s, over their samples that move on
  // the flat (a robot may run ahead of its wheels braking downhill).
  const double radius = log.vehicle.wheel_radius_m;
  const auto on_the_flat = [&](double t) {
    const long i = LatestAtOrBefore(log.attitude, t);
    return i < 0 || !(std::abs(log.attitude[i].pitch) > options.flat_pitch_rad);
  };
  bool scale_failed = false;
  for (size_t first = 0; first < estimates.size();) {
    size_t end = first;
    double sum = 0.0;
    long moving = 0;
    while (end == first || (end < estimates.size() &&
                            estimates[end].t < estimates[first].t + options.scale_window_s)) {
      const WardEstimate& e = estimates[end];
      const double left = radius * e.x[ward::kOmegaLeft], right = radius * e.x[ward::kOmegaRight];
      const double surface = 0.5 * (left + right);
      if (left * right > 0.0 && std::min(std::abs(left), std::abs(right)) > options.min_speed_mps &&
          std::isfinite(e.x[ward::kVbx]) && on_the_flat(e.t)) {
        sum += (surface - e.x[ward::kVbx]) / surface, ++moving;
      }
      ++end;
    }
    if (2 * moving > static_cast<long>(end - first)) {
      const double mean = sum / moving;
      if (!(mean >= report.lowest_window_slip)) report.lowest_window_slip = mean;
      if (mean < options.min_mean_slip) {
        scale_failed = true;
        for (size_t j = first; j < end; ++j) report.suspect[j] = 1.0;
      }
    }
    first = end;
  }

  // The GNSS fixes' z and the estimate each is compared with.
  std::vector<double> z;
  std::vector<size_t> at;
  for (const GpsSample& fix : log.gps) {
    if (!std::isfinite(fix.vx) || !std::isfinite(fix.vy) || fix.t < estimates.front().t ||
        fix.t > estimates.back().t) {
      continue;
    }
    const size_t nearest =
        NearestInTime(estimates, fix.t, [](const WardEstimate& e) { return e.t; });
    const WardEstimate& e = estimates[nearest];
    const double sd_gnss_mps = GnssVelocitySd(fix, log.vehicle.sensors.gps_sd_v_mps);
    const double v_mps = e.x[ward::kVbx], sd_v_mps = e.sd[ward::kVbx];
    const SquaredSpeed squared = SquaredSpeedLessNoise(fix, sd_gnss_mps);
    const double var_g = sd_gnss_mps * sd_gnss_mps;
    const double scale =
        std::sqrt(4.0 * v_mps * v_mps * (var_g + sd_v_mps * sd_v_mps) + squared.noise_variance);
    if (!(scale > 0.0) || !std::isfinite(scale)) continue;
    // One fix cannot carry a run or a window: its z is clipped at kFixZLimit (an outlier of
    // 50 m/s is one fix at the limit; a drift is many fixes beyond 2).
    const double fix_z = (squared.less_noise_m2ps2 - v_mps * v_mps) / scale;
    if (!std::isfinite(fix_z)) continue;  // an absurd value, e.g. 1e300 m/s
    z.push_back(std::clamp(fix_z, -kFixZLimit, kFixZLimit));
    at.push_back(nearest);
  }
  report.gnss_fixes = z.size();
  if (z.size() >= static_cast<size_t>(options.min_gnss_fixes)) {
    double sum = 0.0;
    for (double value : z) sum += value;
    report.gnss_run_z = sum / std::sqrt(static_cast<double>(z.size()));
  }
  const size_t window = static_cast<size_t>(options.gnss_window);
  for (size_t first = 0; first + window <= z.size(); ++first) {
    double mean = 0.0;
    for (size_t i = first; i < first + window; ++i) mean += z[i] / window;
    if (!(std::abs(mean) <= report.gnss_worst_window)) report.gnss_worst_window = std::abs(mean);
    if (std::abs(mean) <= options.gnss_window_limit) continue;
    for (size_t j = at[first]; j <= at[first + window - 1]; ++j) report.suspect[j] = 1.0;
  }

  char line[256];
  if (report.off_wheels_fraction > options.suspect_fraction) {
    std::snprintf(line, sizeof(line),
                  "the velocity is off both wheels' speeds (beyond %.1f x the faster + %.2f m/s, "
                  "or against both) on %.1f %% of the samples",
                  options.wheel_scale, options.wheel_margin_mps,
                  100.0 * report.off_wheels_fraction);
    report.warnings.push_back(line);
  }
  if (flags_failed) {
    std::snprintf(line, sizeof(line),
                  "%.1f %% of the samples are flagged immobilized while GNSS says the robot moves "
                  "(limit %.1f %%): the detector's model does not fit this robot",
                  100.0 * report.flagged_moving_fraction, 100.0 * options.moving_flag_fraction);
    report.warnings.push_back(line);
  }
  if (scale_failed) {
    std::snprintf(line, sizeof(line),
                  "the body runs ahead of its wheels: mean apparent slip %.0f %% over %.0f s "
                  "(limit %.0f %%): a wheel radius or twist conversion is off, or the velocity",
                  100.0 * report.lowest_window_slip, options.scale_window_s,
                  100.0 * options.min_mean_slip);
    report.warnings.push_back(line);
  }
  if (std::abs(report.gnss_run_z) > options.gnss_run_limit ||
      report.gnss_worst_window > options.gnss_window_limit) {
    std::snprintf(line, sizeof(line),
                  "the speed disagrees with GNSS: over the run z %.1f (limit %.1f), over %d fixes "
                  "at worst %.2f (limit %.2f): the velocity has drifted or its sd are too small",
                  report.gnss_run_z, options.gnss_run_limit, options.gnss_window,
                  report.gnss_worst_window, options.gnss_window_limit);
    report.warnings.push_back(line);
  }
  report.trusted = report.warnings.empty();
  return report;
}

std::string DescribeTrust(const TrustReport& report) {
  std::ostringstream out;
  char slip[64] = "no window moving";
  if (std::isfinite(report.lowest_window_slip)) {
    std::snprintf(slip, sizeof(slip), "a window %.0f %%", 100.0 * report.lowest_window_slip);
  }
  char stretch[64] = "no flagged stretch long enough to test";
  if (std::isfinite(report.worst_stretch_z)) {
    std::snprintf(stretch, sizeof(stretch), "a flagged stretch's fixes at worst z %.1f from rest",
                  report.worst_stretch_z);
  }
  char figures[448];
  std::snprintf(figures, sizeof(figures),
                "off the wheels %.2f %% of samples; flagged while GNSS moves %.2f %% (%s); lowest "
                "apparent slip over %s; GNSS speed z over the run %.1f, over a window at worst "
                "%.2f (%zu fixes)",
                100.0 * report.off_wheels_fraction, 100.0 * report.flagged_moving_fraction, stretch,
                slip, report.gnss_run_z, report.gnss_worst_window, report.gnss_fixes);
  out << "trust: " << (report.trusted ? "no sign of trouble" : "NOT TRUSTED") << " (" << figures
      << ")\n";
  for (const std::string& warning : report.warnings) out << "  WARNING: " << warning << "\n";
  return out.str();
}

}  // namespace slipgraph
