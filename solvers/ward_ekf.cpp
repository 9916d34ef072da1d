#include "solvers/ward_ekf.h"

#include <ceres/jet.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "factors/frames.h"
#include "factors/tire_law_uncertainty.h"
#include "factors/ward_accel_driven_step.h"
#include "factors/ward_dynamics.h"
#include "factors/ward_measurement.h"
#include "model/option_check.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state and measurement indices

bool IsFinite(double value) { return std::isfinite(value); }

// A P A^T for a transition matrix with few non-zeros per row: a_dist and the wheel speeds are
// random walks (identity rows) and the biases decay on their own, so in the accelerometer-driven
// form 12 of the 49 entries are non-zero. Symmetric by construction (the lower half is mirrored).
template <int N>
Eigen::Matrix<double, N, N> Sandwich(const Eigen::Matrix<double, N, N>& A,
                                     const Eigen::Matrix<double, N, N>& P) {
  int count[N];
  int column[N][N];
  for (int r = 0; r < N; ++r) {
    count[r] = 0;
    for (int c = 0; c < N; ++c) {
      if (A(r, c) != 0.0) column[r][count[r]++] = c;
    }
  }
  Eigen::Matrix<double, N, N> AP;
  for (int r = 0; r < N; ++r) {
    AP.row(r).setZero();
    for (int k = 0; k < count[r]; ++k) AP.row(r) += A(r, column[r][k]) * P.row(column[r][k]);
  }
  Eigen::Matrix<double, N, N> out;
  for (int r = 0; r < N; ++r) {
    for (int c = 0; c <= r; ++c) {
      double sum = 0.0;
      for (int k = 0; k < count[c]; ++k) sum += AP(r, column[c][k]) * A(c, column[c][k]);
      out(r, c) = out(c, r) = sum;
    }
  }
  return out;
}

}  // namespace

bool EkfOptions::IsValid(std::string* error) const {
  const double min_initial_sd = *std::min_element(initial_sd.begin(), initial_sd.end());
  return OptionCheck("EkfOptions", error)
      .Positive("wheels_gate_chi2", wheels_gate_chi2)
      .Positive("gps_gate_chi2", gps_gate_chi2)
      .Positive("imu_gate_chi2", imu_gate_chi2)
      .NonNegative("imu_max_consecutive_rejections", imu_max_consecutive_rejections)
      .NonNegative("wheels_max_consecutive_rejections", wheels_max_consecutive_rejections)
      .NonNegative("gps_max_consecutive_rejections", gps_max_consecutive_rejections)
      .Positive("encoder_timeout_s", encoder_timeout_s)
      .Positive("wheel_still_radps", wheel_still_radps)
      .Require("initial_sd", min_initial_sd > 0.0, min_initial_sd, "each entry must be positive")
      .Require("gnss_fading_fixes", gnss_fading_fixes == 0.0 || gnss_fading_fixes >= 1.0,
               gnss_fading_fixes, "must be 0 (off) or at least 1")
      .Positive("gnss_fading_threshold", gnss_fading_threshold)
      .AtLeast("gnss_fading_max", gnss_fading_max, 1.0);
}

WardEkf::WardEkf(const Vehicle& vehicle, const ModelConfig& model, const EkfOptions& options)
    : params_(MakeParams(vehicle, model)),
      model_(model),
      options_(options),
      offsets_(model.offset_init_samples, model.offset_ema_samples, model.offset_rest_guard_s,
               vehicle.type == VehicleType::kSkidSteer ? 1.0 : 0.2),
      detector_(model.immobilization, vehicle.wheel_radius_m, vehicle.track_width_m) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  for (int i = 0; i < kStateSize; ++i) P_(i, i) = options.initial_sd[i] * options.initial_sd[i];
  loads_ = ComputeAttitudeLoads(CurrentAttitude(), params_);
}

void WardEkf::Begin(double t) {
  if (!started_) {
    started_ = true;
    t_ = t;
    return;
  }
  if (t < t_) {
    ++stats_.late_measurements;
    return;
  }
  PredictTo(t);
}

void WardEkf::PredictTo(double t) {
  const double dt = t - t_;
  if (dt <= 0.0) return;
  const bool accel_driven =
      options_.velocity_model == VelocityModel::kAccelerometerDriven && have_accel_input_;
  StateMatrix A;
  if (accel_driven) {
    // The state and its transition matrix by the chain rule through the RK4 stages
    // (factors/ward_accel_driven_step.h): the same state as a 7-wide Jet pass, cheaper.
    StateVector next;
    PropagateAccelerometerDriven(x_.data(), accel_input_mps2_ - offsets_.accel_x_mps2(), loads_,
                                 params_, dt, next.data(), &A);
    x_ = next;
  } else {
    using Jet = ceres::Jet<double, kStateSize>;
    Jet x_jet[kStateSize], next[kStateSize];
    for (int i = 0; i < kStateSize; ++i) x_jet[i] = Jet(x_(i), i);
    Propagate(x_jet, loads_, params_, dt, next);
    for (int r = 0; r < kStateSize; ++r) {
      x_(r) = next[r].a;
      A.row(r) = next[r].v.transpose();
    }
  }
  // Discrete process noise of eq. (10): white-noise densities times dt, Gauss-Markov biases
  // with their exact discrete variance.
  const ProcessNoiseConfig& q = model_.process;
  StateVector q_diag;
  // Accelerometer-driven: the input's white noise (accelerometer and pitch through gravity).
  const double accel_density_sq = AccelInputDensitySq(
      model_.measurement.imu_sd_accel_mps2, pitch_sd_rad_, params_.gravity_mps2, imu_period_s_);
  q_diag(kVbx) =
      (accel_driven ? accel_density_sq : q.v_bx_mps2_per_sqrt_hz * q.v_bx_mps2_per_sqrt_hz) * dt;
  // The biases' exact Gauss-Markov variances, recomputed only when the step changes.
  if (dt != bias_noise_dt_) {
    bias_noise_dt_ = dt;
    accel_bias_q_ = GaussMarkovStepVariance(q.accel_bias_sd_mps2, q.accel_bias_tau_s, dt);
    gyro_bias_q_ = GaussMarkovStepVariance(q.gyro_bias_sd_radps, q.gyro_bias_tau_s, dt);
  }
  q_diag(kAccelBias) = accel_bias_q_;
  // Adaptive w3: the density scales with the recent accelerometer NIS (1 when consistent).
  const double q_adist =
      std::min(q.a_dist_max_mps3_per_sqrt_hz,
               q.a_dist_mps3_per_sqrt_hz * std::sqrt(std::max(1.0, accel_nis_ema_)));
  q_diag(kAdist) = q_adist * q_adist * dt;
  q_diag(kOmegaLeft) = q_diag(kOmegaRight) =
      q.omega_radps2_per_sqrt_hz * q.omega_radps2_per_sqrt_hz * dt;
  q_diag(kYawRate) = q.yaw_rate_radps2_per_sqrt_hz * q.yaw_rate_radps2_per_sqrt_hz * dt;
  q_diag(kGyroBias) = gyro_bias_q_;
  P_ = Sandwich(A, P_);
  P_.diagonal() += q_diag;
  t_ = t;
}

bool WardEkf::Update(const RowVector& nu, const RowMatrix& H, const RowVector& r, double gate_chi2,
                     int max_consecutive_rejections, StreamCounters* counters,
                     int* consecutive_rejections, const std::vector<const char*>* names) {
  const int m = static_cast<int>(nu.size());
  if (m == 0) return false;
  if (!std::isinf(gate_chi2)) {
    // Mahalanobis distance of the stacked innovation, S = H P H^T + R.
    using RowSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;
    RowSquare S(m, m);
    for (int i = 0; i < m; ++i) {
      const StateVector Ph = P_ * H.row(i).transpose();
      for (int j = 0; j <= i; ++j) S(j, i) = S(i, j) = H.row(j).dot(Ph);
      S(i, i) += r(i);
    }
    // One or two rows (every stream but a stacked custom one): closed form, no factorization.
    double mahalanobis, det;
    if (m == 1) {
      det = S(0, 0);
      mahalanobis = nu(0) * nu(0) / S(0, 0);
    } else if (m == 2) {
      det = S(0, 0) * S(1, 1) - S(0, 1) * S(1, 0);
      mahalanobis = (S(1, 1) * nu(0) * nu(0) - (S(0, 1) + S(1, 0)) * nu(0) * nu(1) +
                     S(0, 0) * nu(1) * nu(1)) /
                    det;
    } else {
      const auto ldlt = S.ldlt();
      det = ldlt.vectorD().prod();
      mahalanobis = nu.dot(ldlt.solve(nu));
    }
    if (mahalanobis > gate_chi2) {
      if (consecutive_rejections == nullptr ||
          ++*consecutive_rejections <= max_consecutive_rejections) {
        ++counters->rejected;
        // A measurement gated out still happened: it counts against the model in the likelihood.
        if ((options_.track_log_likelihood || scoring_) && consecutive_rejections != nullptr) {
          log_likelihood_ -= 0.5 * (mahalanobis + std::log(det) + m * std::log(2.0 * M_PI));
        }
        return false;
      }
      ++counters->forced;
    }
  }
  if (consecutive_rejections != nullptr) *consecutive_rejections = 0;
  // R is diagonal, so the rows are applied one after the other as scalar updates (the same
  // result as the stacked update), each in Joseph form P = A P A^T + r k k^T, A = I - k h^T,
  // evaluated in O(n^2): A P = P - k (P h)^T, (A P) A^T = A P - (A P h) k^T.
  const StateVector x_prior = x_;
  for (int i = 0; i < m; ++i) {
    const StateVector h = H.row(i).transpose();
    // The stacked update's linearization at x_prior: the innovation moves with the earlier rows.
    const double innovation = nu(i) - h.dot(x_ - x_prior);
    // Rows on one state (encoders, GNSS, weak constraints): P h is a column of P.
    int unit = -1;
    for (int j = 0; j < kStateSize && unit != -2; ++j) {
      if (h(j) != 0.0) unit = (unit == -1 && h(j) == 1.0) ? j : -2;
    }
    const StateVector Ph = unit >= 0 ? StateVector(P_.col(unit)) : StateVector(P_ * h);
    const double s = h.dot(Ph) + r(i);
    const StateVector k = Ph / s;
    // The stacked measurement's log-likelihood, one conditional row at a time (sensor rows only).
    if ((options_.track_log_likelihood || scoring_) && consecutive_rejections != nullptr) {
      log_likelihood_ -= 0.5 * (innovation * innovation / s + std::log(2.0 * M_PI * s));
    }
    if (options_.record_innovations && names != nullptr && i < static_cast<int>(names->size())) {
      EkfStats::InnovationSeries& series = stats_.innovations[(*names)[i]];
      series.t.push_back(t_);
      series.normalized.push_back(innovation / std::sqrt(s));
    }
    x_ += k * innovation;
    P_.noalias() -= k * Ph.transpose();  // A P
    const StateVector APh = unit >= 0 ? StateVector(P_.col(unit)) : StateVector(P_ * h);
    P_.noalias() -= (APh - r(i) * k) * k.transpose();  // (A P) A^T + r k k^T
  }
  ++counters->used;
  return true;
}

void WardEkf::GuardDivergence() {
  // No state of a ground robot (m/s, m/s^2, rad/s) comes near this: beyond it the filter has
  // diverged even while its numbers are still finite (an unstable yaw step grows ~10x per step).
  constexpr double kDivergedMagnitude = 1e6;
  if (x_.allFinite() && P_.allFinite() && x_.cwiseAbs().maxCoeff() < kDivergedMagnitude) {
    last_good_x_ = x_;
    last_good_P_ = P_;
    return;
  }
  if (stats_.divergence_resets++ == 0) stats_.first_divergence_t = t_;
  x_ = last_good_x_;
  P_ = last_good_P_ * 100.0;
}

double WardEkf::GravityAlongX() const { return loads_.gravity_along_x_mps2; }

void WardEkf::AddAttitude(const AttitudeSample& attitude) {
  if (!IsFinite(attitude.roll) || !IsFinite(attitude.pitch)) {
    ++stats_.attitude.dropped_components;
    return;
  }
  roll_rad_ = attitude.roll;
  pitch_rad_ = attitude.pitch;
  loads_ = ComputeAttitudeLoads(CurrentAttitude(), params_);
  pitch_sd_rad_ = std::isfinite(attitude.sd_pitch) ? attitude.sd_pitch : 0.0;
  if (IsFinite(attitude.yaw)) yaw_rad_ = attitude.yaw;
  have_attitude_ = true;
  ++stats_.attitude.used;
}

void WardEkf::AddImu(const ImuSample& imu) {
  struct Guard {
    WardEkf* ekf;
    ~Guard() { ekf->GuardDivergence(); }
  } guard{this};
  // The prediction up to this stamp is driven by the previous accelerometer sample (held): on
  // the simulated suites this did better than driving it with this sample, although this one is
  // the mean over exactly that interval (docs/ekf.md).
  Begin(imu.t);
  if (offsets_.ready() && std::isfinite(imu.ax)) {
    accel_input_mps2_ = imu.ax;
    have_accel_input_ = true;
  }
  if (last_imu_t_ >= 0.0 && imu.t > last_imu_t_) {
    imu_period_s_ += 0.05 * (imu.t - last_imu_t_ - imu_period_s_);  // slow average
  }
  last_imu_t_ = imu.t;
  const bool at_rest = stop_timer_.AtRestFor(t_, model_.weak_constraints.stop_time_s);
  const bool ax_ok = IsFinite(imu.ax), gz_ok = IsFinite(imu.gz);
  if (!offsets_.ready()) {
    if (ax_ok && gz_ok) {
      offsets_.Add(imu.t, imu.ax, imu.gz, GravityAlongX(), at_rest, last_wheel_motion_);
      ++stats_.offset_init_samples;
      if (offsets_.ready() && offsets_.moving_start()) {
        stats_.offset_moving_start = true;
        stats_.offset_implausible_start = offsets_.implausible_start();
        P_(kAccelBias, kAccelBias) += offsets_.init_sd()[0] * offsets_.init_sd()[0];
        P_(kGyroBias, kGyroBias) += offsets_.init_sd()[1] * offsets_.init_sd()[1];
      }
    }
    return;
  }
  if (ax_ok && gz_ok) offsets_.Add(imu.t, imu.ax, imu.gz, GravityAlongX(), at_rest);
  stats_.imu.dropped_components += (ax_ok ? 0 : 1) + (gz_ok ? 0 : 1);

  using Jet = ceres::Jet<double, kStateSize>;
  Jet x_jet[kStateSize], z[kMeasurementSize];
  for (int i = 0; i < kStateSize; ++i) x_jet[i] = Jet(x_(i), i);
  TireForces<Jet> forces;
  PredictMeasurements(x_jet, loads_,
                      ImuOffsets<double>{offsets_.accel_x_mps2(), offsets_.gyro_z_radps()}, params_,
                      z, &forces);
  RowVector nu(0), r(0);
  RowMatrix H(0, kStateSize);
  const auto add_row = [&](int index, double measured, double variance) {
    const int row = static_cast<int>(nu.size());
    nu.conservativeResize(row + 1);
    r.conservativeResize(row + 1);
    H.conservativeResize(row + 1, Eigen::NoChange);
    nu(row) = measured - z[index].a;
    H.row(row) = z[index].v.transpose();
    r(row) = variance;
  };
  const SensorNoise& noise = model_.measurement;
  if (ax_ok) {
    double variance = noise.imu_sd_accel_mps2 * noise.imu_sd_accel_mps2;
    if (options_.velocity_model == VelocityModel::kAccelerometerDriven) {
      // Eq. (11) as the tie between a_dist and the tire law: its noise is the tire law's,
      // persistent over correlation_time (a per-sample variance scaled by correlation_time/dt).
      // From the row's own forces (their Jets carry d/d w): no second tire-force evaluation.
      variance +=
          TireLawVarianceOf(forces, kOmegaLeft, kOmegaRight, params_, model_.tire_uncertainty) *
          TireLawSampleScale(model_.tire_uncertainty, imu_period_s_);
    }
    add_row(kZAccelX, imu.ax, variance);
    // Normalized innovation squared of the accelerometer alone, for the adaptive w3.
    const double s = H.row(0) * P_ * H.row(0).transpose() + r(0);
    const double weight = 2.0 / (1.0 + model_.process.a_dist_adapt_samples);
    accel_nis_ema_ += (nu(0) * nu(0) / s - accel_nis_ema_) * weight;
  }
  if (gz_ok) add_row(kZYawRate, imu.gz, noise.imu_sd_gyro_radps * noise.imu_sd_gyro_radps);
  std::vector<const char*> names;  // empty (no allocation) unless innovations are recorded
  if (options_.record_innovations) {
    if (ax_ok) names.push_back("accelerometer");
    if (gz_ok) names.push_back("gyro");
  }
  Update(nu, H, r, options_.imu_gate_chi2, options_.imu_max_consecutive_rejections, &stats_.imu,
         &imu_rejections_, &names);
}

void WardEkf::AddWheels(double t, double omega_left, double omega_right) {
  struct Guard {
    WardEkf* ekf;
    ~Guard() { ekf->GuardDivergence(); }
  } guard{this};
  const bool left_ok = IsFinite(omega_left), right_ok = IsFinite(omega_right);
  if (!wheels_initialised_ && left_ok && right_ok) {
    if (!started_) Begin(t);
    x_(kOmegaLeft) = omega_left;
    x_(kOmegaRight) = omega_right;
    wheels_initialised_ = true;
    if (std::abs(omega_left) >= options_.wheel_still_radps ||
        std::abs(omega_right) >= options_.wheel_still_radps) {
      // A log that starts in motion: the body moves as its wheels roll, give or take a slip of
      // up to a fifth (not the rest the initial state assumes).
      const double r = params_.wheel_radius_m;
      x_(kVbx) = 0.5 * r * (omega_left + omega_right);
      x_(kYawRate) = r * (omega_right - omega_left) / params_.track_width_m;
      P_(kVbx, kVbx) = std::max(P_(kVbx, kVbx), std::pow(0.2 * x_(kVbx), 2));
      P_(kYawRate, kYawRate) = std::max(P_(kYawRate, kYawRate), std::pow(0.3 * x_(kYawRate), 2));
    }
  }
  Begin(t);
  stats_.wheels.dropped_components += (left_ok ? 0 : 1) + (right_ok ? 0 : 1);
  RowVector nu(0), r(0);
  RowMatrix H(0, kStateSize);
  const double variance =
      model_.measurement.wheels_sd_omega_radps * model_.measurement.wheels_sd_omega_radps;
  const auto add_row = [&](int index, double measured) {
    const int row = static_cast<int>(nu.size());
    nu.conservativeResize(row + 1);
    r.conservativeResize(row + 1);
    H.conservativeResize(row + 1, Eigen::NoChange);
    nu(row) = measured - x_(index);
    H.row(row).setZero();
    H(row, index) = 1.0;
    r(row) = variance;
  };
  if (left_ok) add_row(kOmegaLeft, omega_left);
  if (right_ok) add_row(kOmegaRight, omega_right);
  std::vector<const char*> names;  // empty (no allocation) unless innovations are recorded
  if (options_.record_innovations) {
    if (left_ok) names.push_back("encoder_left");
    if (right_ok) names.push_back("encoder_right");
  }
  Update(nu, H, r, options_.wheels_gate_chi2, options_.wheels_max_consecutive_rejections,
         &stats_.wheels, &wheel_rejections_, &names);

  if (left_ok && right_ok) {
    last_wheels_t_ = t_;
    const bool still = std::abs(omega_left) < options_.wheel_still_radps &&
                       std::abs(omega_right) < options_.wheel_still_radps;
    last_wheel_motion_ = {
        0.5 * params_.wheel_radius_m * (omega_left + omega_right),
        params_.wheel_radius_m * (omega_right - omega_left) / params_.track_width_m, still};
    stop_timer_.Update(t_, still);
  }
  const double dt_cycle = have_previous_cycle_ ? t_ - t_previous_cycle_ : 0.0;
  if (offsets_.ready()) ApplyWeakConstraints(dt_cycle);
  const bool fresh = t_ - last_wheels_t_ <= options_.encoder_timeout_s;
  previous_slip_ema_ = detector_.latest().slip_ema;
  detector_.Update(x_(kVbx), x_(kYawRate), x_(kOmegaLeft), x_(kOmegaRight), fresh);
  x_previous_cycle_ = x_;
  t_previous_cycle_ = t_;
  have_previous_cycle_ = true;
}

void WardEkf::ApplyWeakConstraints(double dt_cycle) {
  WeakConstraintInputs in;
  in.dt_s = dt_cycle;
  in.vel_dir = DriveDirection(x_(kOmegaLeft), x_(kOmegaRight), options_.wheel_still_radps);
  in.slip_ema = detector_.latest().slip_ema;
  in.slip_ema_rate_per_s =
      dt_cycle > 0.0 ? (detector_.latest().slip_ema - previous_slip_ema_) / dt_cycle : 0.0;
  in.wheels_stopped_s = stop_timer_.StoppedFor(t_);
  if (MovingAgainstTheWheels(x_.data(), in.vel_dir)) {  // WC3 alone reads it
    // The tire forces on the body held still: the disturbance that would just hold the robot.
    // At the a priori v_bx (a few cm/s backwards) the rolling law, steep near v = 0, has turned
    // round and made the "holding" disturbance 0.35 m/s^2 too strong (fig5).
    StateVector held = x_;
    held(kVbx) = 0.0;
    in.f_tire_mps2 = ComputeTireForces(held.data(), loads_, params_).f_tire_mps2;
  }
  in.gravity_along_x_mps2 = GravityAlongX();
  pseudo_.clear();
  const StateVector x_prior = x_;
  CollectWeakConstraints(x_prior.data(), x_previous_cycle_.data(), in, model_.weak_constraints,
                         &pseudo_);
  // Densities to per-cycle variances (the first cycle uses the nominal 100 Hz).
  const double cycle_s = dt_cycle > 0.0 ? dt_cycle : 0.01;
  StreamCounters unused;
  for (const PseudoMeasurement& p : pseudo_) {
    RowVector nu(1), r(1);
    RowMatrix H = RowMatrix::Zero(1, kStateSize);
    nu(0) = p.z - x_(p.state_index);
    H(0, p.state_index) = 1.0;
    r(0) = p.density * p.density / cycle_s;
    Update(nu, H, r, std::numeric_limits<double>::infinity(), 0, &unused, nullptr);
    ++stats_.weak_constraints[static_cast<int>(p.constraint)];
  }
}

double WardEkf::AddGpsScored(const GpsSample& gps) {
  const double sum_before = log_likelihood_;
  log_likelihood_ = 0.0;
  scoring_ = true;
  AddGps(gps);
  scoring_ = false;
  const double fix = log_likelihood_;
  log_likelihood_ = sum_before + (options_.track_log_likelihood ? fix : 0.0);
  return fix;
}

void WardEkf::AddGps(const GpsSample& gps) {
  struct Guard {
    WardEkf* ekf;
    ~Guard() { ekf->GuardDivergence(); }
  } guard{this};
  Begin(gps.t);
  if (!IsFinite(gps.vx) || !IsFinite(gps.vy) || !IsFinite(gps.vz)) {
    ++stats_.gps.dropped_components;
    return;
  }
  const double along = GnssVelocityAlongBodyX(gps.vx, gps.vy, gps.vz, have_attitude_, pitch_rad_,
                                              yaw_rad_, x_(kOmegaLeft) + x_(kOmegaRight));
  const double sd = GnssVelocitySd(gps, model_.measurement.gps_sd_v_mps);
  RowVector nu(1), r(1);
  RowMatrix H = RowMatrix::Zero(1, kStateSize);
  nu(0) = along - x_(kVbx);
  H(0, kVbx) = 1.0;
  r(0) = sd * sd;
  // Fading memory (EkfOptions::gnss_fading_*): not for a fix the gate would reject (an
  // outlier must not open the covariance for itself), never shrinking P, and not in a bank of
  // filters, whose weights are each fix's likelihood under the filter's own covariance.
  if (options_.gnss_fading_fixes > 0.0 && !scoring_ && !options_.track_log_likelihood) {
    const double s = P_(kVbx, kVbx) + r(0);
    const double z = nu(0) / std::sqrt(s);
    const double weight = 1.0 / options_.gnss_fading_fixes;
    gnss_innovation_ema_ += weight * (z - gnss_innovation_ema_);
    if (std::abs(gnss_innovation_ema_) > options_.gnss_fading_threshold &&
        z * gnss_innovation_ema_ > 1.0 && std::abs(z) > 1.0 && z * z <= options_.gps_gate_chi2) {
      P_ *= std::min(options_.gnss_fading_max, z * z);
      ++stats_.gnss_fading;
    }
  }
  static const std::vector<const char*> kGnss = {"gnss"};
  Update(nu, H, r, options_.gps_gate_chi2, options_.gps_max_consecutive_rejections, &stats_.gps,
         &gps_rejections_, &kGnss);
}

WardEstimate WardEkf::Estimate() const {
  WardEstimate e;
  e.t = t_;
  for (int i = 0; i < kStateSize; ++i) {
    e.x[i] = x_(i);
    e.sd[i] = std::sqrt(std::max(0.0, P_(i, i)));
  }
  e.slip = detector_.latest();
  // Missing encoder data is never reported as immobilization.
  if (t_ - last_wheels_t_ > options_.encoder_timeout_s) e.slip.immobilized = false;
  e.accel_offset_mps2 = offsets_.accel_x_mps2();
  e.gyro_offset_radps = offsets_.gyro_z_radps();
  e.offsets_ready = offsets_.ready();
  return e;
}

}  // namespace slipgraph
