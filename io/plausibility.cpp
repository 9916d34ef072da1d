#include "io/plausibility.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "io/measurement_stream.h"

namespace slipgraph {
namespace {

constexpr double kStillRadps = 0.05;
constexpr double kMovingMps = 0.3;
// Gravity over a log that is never still: the norm of the mean over stretches this long.
constexpr double kWholeLogStretchS = 1.0;
// The wheels' yaw rate against the gyro's: a scale is read where the gyro's rate varies by more
// than this sd (a turn, not its noise) and the two correlate by more than kScaleMinCorrelation;
// it is named as a problem only where they correlate by more than kScaleFlagCorrelation.
constexpr double kScaleTurnRadps = 0.05;
constexpr double kScaleMinCorrelation = 0.5;
constexpr double kScaleFlagCorrelation = 0.8;
// Any drive: the wheels cannot turn the body much faster than they imply; slip and a wheel radius
// off by a few percent move the scale by as much. A gyro in deg/s read as rad/s gives 1/57.3.
constexpr double kMinWheelOverGyroYaw = 0.7;
// A differential drive on castors turns as its wheels imply, give or take their slip.
constexpr double kMaxDiffDriveWheelOverGyroYaw = 1.4;
// A skid-steer's tracks or wheels skid sideways in a turn (and a rocker-bogie rover's six), so
// they imply more yaw than the body makes: an effective track of 1.2-3 times the geometric one is
// common (higher on high friction); beyond this a unit is more likely wrong (rad/s converted as
// if deg/s gives 57.3).
constexpr double kMaxWheelOverGyroYaw = 6.0;

std::string Format(double v) {
  std::ostringstream out;
  out.precision(3);
  out << v;
  return out.str();
}

double Median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

Plausibility CheckPlausibility(const DriveLog& log) {
  Plausibility out;
  PlausibilityFigures& f = out.figures;
  const double r = log.vehicle.wheel_radius_m, c = log.vehicle.track_width_m;
  // Wheel-still intervals: every wheel's speed, averaged over about ten samples (quantized
  // encoders read +-one count at rest), below kStillRadps for at least a second.
  std::vector<std::pair<double, double>> still;
  {
    double start = -1.0;
    std::array<double, kMaxWheels> mean{};
    for (size_t k = 0; k < log.wheels.size(); ++k) {
      bool all_still = true;
      for (size_t i = 0; i < kMaxWheels; ++i) {
        const double w = log.wheels[k].omega_radps[i];
        if (!std::isfinite(w)) continue;
        mean[i] += 0.1 * (w - mean[i]);
        if (std::abs(mean[i]) > kStillRadps) all_still = false;
      }
      if (all_still && start < 0.0) start = log.wheels[k].t;
      if ((!all_still || k + 1 == log.wheels.size()) && start >= 0.0) {
        if (log.wheels[k].t - start >= 1.0) still.emplace_back(start + 0.3, log.wheels[k].t);
        start = -1.0;
      }
    }
  }
  // Gravity at rest.
  {
    // The norm of the mean specific force over each stretch, weighted by its samples: not the
    // mean of the norms, which vibration raises by about its variance over 2 g (a tracked
    // vehicle's engine at rest: 2-3 m/s^2 sd on x and y), nor the norm of one mean over stretches
    // at different tilts, which shrinks by their mean cosine (parked up and down a hill).
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), stretch = Eigen::Vector3d::Zero();
    double norm_sum = 0.0;
    long n = 0;
    const auto end_stretch = [&]() {
      norm_sum += stretch.norm();
      stretch.setZero();
    };
    const auto add = [&](const ImuSample& s) {
      if (!std::isfinite(s.ax) || !std::isfinite(s.ay) || !std::isfinite(s.az)) return;
      const Eigen::Vector3d a(s.ax, s.ay, s.az);
      sum += a, stretch += a;
      ++n;
    };
    size_t i = 0;
    for (const auto& [a, b] : still) {
      while (i < log.imu.size() && log.imu[i].t < a) ++i;
      const long before = n;
      for (; i < log.imu.size() && log.imu[i].t <= b; ++i) add(log.imu[i]);
      if (n > before) f.rest_seconds += b - a;
      end_stretch();
    }
    f.gravity_at_rest = n > 0;
    if (!f.gravity_at_rest && !log.imu.empty()) {
      // Never still: the whole log in stretches of a second (motion averages out over a drive).
      double stretch_start = log.imu.front().t;
      for (const ImuSample& s : log.imu) {
        if (s.t - stretch_start >= kWholeLogStretchS) {
          end_stretch();
          stretch_start = s.t;
        }
        add(s);
      }
      end_stretch();
    }
    const std::string where = f.gravity_at_rest ? "gravity at rest" : "gravity over the whole log";
    if (n > 0) {
      f.rest_az_mps2 = sum.z() / n;
      f.rest_norm_mps2 = norm_sum / n;
      if (std::abs(f.rest_norm_mps2 - 9.81) > 0.5) {
        out.problems.push_back(where + ": the specific force is " + Format(f.rest_norm_mps2) +
                               " m/s^2, not about 9.81: wrong units or scale (g instead of "
                               "m/s^2?)");
      } else if (std::abs(f.rest_az_mps2) < 0.9 * f.rest_norm_mps2) {
        // Gravity mostly on x or y: a sensor frame rotated by 90 deg (or mounted sideways).
        const double mx = sum.x() / n, my = sum.y() / n;
        const char* axis = std::abs(mx) > std::abs(my) ? "x" : "y";
        const double along = std::abs(mx) > std::abs(my) ? mx : my;
        out.problems.push_back(where + ": gravity is along " + (along < 0.0 ? "-" : "+") + axis +
                               " (ax " + Format(mx) + ", ay " + Format(my) + ", az " +
                               Format(f.rest_az_mps2) +
                               " m/s^2), not +z: the IMU frame is rotated against the body; map "
                               "it with a rotation (body_from_sensor)");
      } else if (f.rest_az_mps2 < 0.0) {
        out.problems.push_back(where + ": az is " + Format(f.rest_az_mps2) +
                               " m/s^2, expected about +9.81: the IMU's z axis points down "
                               "(flip z and y, or rotate the frame by 180 deg about x)");
      }
    }
  }
  // Wheels against GNSS speed.
  {
    std::vector<double> ratios;
    for (const GpsSample& g : log.gps) {
      const double speed = std::hypot(g.vx, g.vy);
      if (!std::isfinite(speed) || speed < kMovingMps) continue;
      const long k = LatestAtOrBefore(log.wheels, g.t);
      if (k < 0) continue;
      const SideSpeeds s = DrivenSideSpeeds(log.wheels[k], log.vehicle.type);
      const double surface = 0.5 * r * (s.left_radps + s.right_radps);
      if (std::isfinite(surface)) ratios.push_back(surface / speed);
    }
    if (ratios.size() >= 5) {
      f.wheel_over_gnss_speed = Median(ratios);
      if (std::abs(f.wheel_over_gnss_speed) < 0.3) {
        out.problems.push_back(
            "wheels against GNSS: while GNSS shows the robot moving, the wheels' mean surface "
            "speed is only " +
            Format(f.wheel_over_gnss_speed) +
            " of it: one side reads backwards (left wheels negative forward?) or the wheel "
            "units are wrong");
      } else if (f.wheel_over_gnss_speed < 0.0) {
        out.problems.push_back(
            "wheels against GNSS: the wheels read backwards while the robot "
            "moves (ratio " +
            Format(f.wheel_over_gnss_speed) + "): both sides' signs flipped?");
      } else if (f.wheel_over_gnss_speed > 3.0) {
        out.problems.push_back("wheels against GNSS: the wheels' surface speed is " +
                               Format(f.wheel_over_gnss_speed) +
                               " x the GNSS speed: wheel radius or units wrong?");
      }
    }
  }
  // Wheels against the gyro's yaw rate: each wheel cycle's against the gyro's mean over that
  // cycle (a wheel sample at 10 Hz against one of a 250 Hz gyro's would set noise against it).
  {
    double sxy = 0.0, sxx = 0.0, syy = 0.0, sx = 0.0, sy = 0.0;
    long n = 0;
    size_t i = 0;
    for (size_t k = 1; k < log.wheels.size(); ++k) {
      const double t0 = log.wheels[k - 1].t, t1 = log.wheels[k].t;
      while (i < log.imu.size() && log.imu[i].t <= t0) ++i;
      double gz_sum = 0.0;
      long gz_n = 0;
      for (size_t j = i; j < log.imu.size() && log.imu[j].t <= t1; ++j) {
        if (std::isfinite(log.imu[j].gz)) gz_sum += log.imu[j].gz, ++gz_n;
      }
      if (gz_n == 0) continue;
      const SideSpeeds s = DrivenSideSpeeds(log.wheels[k], log.vehicle.type);
      const double yaw = r * (s.right_radps - s.left_radps) / c;
      if (!std::isfinite(yaw)) continue;
      const double g = gz_sum / gz_n;
      sx += yaw, sy += g, sxx += yaw * yaw, syy += g * g, sxy += yaw * g;
      ++n;
    }
    if (n > 10) {
      const double cov = sxy / n - sx / n * sy / n;
      const double vx = sxx / n - sx / n * sx / n, vy = syy / n - sy / n * sy / n;
      // Only meaningful when the robot turned: the gyro's yaw rate must vary.
      if (vx > 1e-6 && vy > 1e-4) {
        f.wheel_gyro_yaw_correlation = cov / std::sqrt(vx * vy);
        if (f.wheel_gyro_yaw_correlation < -0.3) {
          out.problems.push_back(
              "wheels against the gyro: the yaw rate the wheels imply runs against the gyro's "
              "(correlation " +
              Format(f.wheel_gyro_yaw_correlation) +
              "): left and right wheels swapped, or the gyro's z axis flipped");
        }
      }
      // The scale, where the two move together and the robot turned by more than the gyro's
      // noise: the slope of the wheels' yaw rate on the gyro's (the gyro's bias in the
      // intercept). What scatters about the line (slip, the gyro's noise) pulls the slope towards
      // zero by up to the squared correlation: only a close fit is named.
      if (vy > kScaleTurnRadps * kScaleTurnRadps &&
          f.wheel_gyro_yaw_correlation > kScaleMinCorrelation) {
        f.wheel_over_gyro_yaw = cov / vy;
        const double scale = f.wheel_over_gyro_yaw;
        const char* cause = nullptr;
        if (scale < kMinWheelOverGyroYaw) {
          cause =
              "track_width too large, the wheel radius too small, or the gyro's unit or scale "
              "wrong (deg/s read as rad/s?)";
        } else if (log.vehicle.type == VehicleType::kDiffDriveCastor &&
                   scale > kMaxDiffDriveWheelOverGyroYaw) {
          cause =
              "on a differential drive with castors the wheels turn the body as they roll; "
              "track_width too small, the wheel radius too large, or the gyro's unit or scale "
              "wrong";
        } else if (scale > kMaxWheelOverGyroYaw) {
          cause =
              "more than a skid-steer's or a rover's wheels skid in a turn; track_width too "
              "small, or the gyro's unit or scale wrong (rad/s converted as if deg/s?)";
        }
        if (cause != nullptr && f.wheel_gyro_yaw_correlation > kScaleFlagCorrelation) {
          out.problems.push_back(
              "wheels against the gyro: the wheels' yaw rate is " + Format(scale) +
              " x the gyro's (the track that makes them agree: " + Format(c * scale) +
              " m against track_width " + Format(c) + " m): " + cause);
        }
      }
    }
  }
  return out;
}

std::string DescribePlausibility(const PlausibilityFigures& f) {
  std::vector<std::string> parts;
  if (std::isfinite(f.rest_norm_mps2)) {
    parts.push_back(f.gravity_at_rest ? "gravity at rest " + Format(f.rest_norm_mps2) +
                                            " m/s^2 over " + Format(f.rest_seconds) + " s"
                                      : "gravity over the whole log (never still) " +
                                            Format(f.rest_norm_mps2) + " m/s^2");
  }
  if (std::isfinite(f.wheel_over_gnss_speed)) {
    parts.push_back("wheels' speed " + Format(f.wheel_over_gnss_speed) + " x GNSS's");
  }
  if (std::isfinite(f.wheel_gyro_yaw_correlation)) {
    parts.push_back(std::isfinite(f.wheel_over_gyro_yaw)
                        ? "wheels' yaw rate " + Format(f.wheel_over_gyro_yaw) +
                              " x the gyro's (correlation " + Format(f.wheel_gyro_yaw_correlation) +
                              ")"
                        : "wheels' yaw rate against the gyro's: correlation " +
                              Format(f.wheel_gyro_yaw_correlation));
  }
  std::string line;
  for (const std::string& part : parts) line += (line.empty() ? "" : "; ") + part;
  return line;
}

}  // namespace slipgraph
