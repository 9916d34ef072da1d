#include "problems/ward_batch_problem.h"

#include <ceres/loss_function.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "factors/at_rest_prior.h"
#include "factors/bound_prior.h"
#include "factors/diagonal_prior.h"
#include "factors/disturbance_decay_prior.h"
#include "factors/disturbance_walk_factor.h"
#include "factors/encoder_factor.h"
#include "factors/gnss_velocity_factor.h"
#include "factors/imu_factor.h"
#include "factors/oppose_motion_prior.h"
#include "factors/tire_law_uncertainty.h"
#include "factors/ward_dynamics_factor.h"
#include "io/measurement_stream.h"
#include "solvers/weak_constraints.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state indices

// Sensor context of one state: the latest attitude, accelerometer reading and IMU interval.
struct Context {
  Attitude<double> attitude{0.0, 0.0};
  double pitch_sd = 0.0;  // the attitude source's stated pitch sd (0 when not given)
  double yaw = 0.0;
  bool have_attitude = false;
  double accel_x = std::nan("");
  double imu_period_s = 0.01;
};

}  // namespace

std::unique_ptr<WardProblem> BuildWardBatchProblem(const DriveLog& log, const ModelConfig& model,
                                                   const FilterResult& ekf,
                                                   const WardProblemOptions& options) {
  if (ekf.estimates.empty()) throw std::invalid_argument("the EKF produced no estimates");
  auto out = std::make_unique<WardProblem>();
  const Params params = MakeParams(log.vehicle, model);
  const size_t n = ekf.estimates.size();
  out->times.resize(n);
  out->states.resize(n);
  out->wheel_speeds.resize(n);
  for (size_t k = 0; k < n; ++k) {
    out->times[k] = ekf.estimates[k].t;
    std::copy(ekf.estimates[k].x.begin(), ekf.estimates[k].x.end(), out->states[k].begin());
  }
  out->offsets = {ekf.estimates.back().accel_offset_mps2, ekf.estimates.back().gyro_offset_radps};

  ceres::Problem::Options problem_options;
  problem_options.enable_fast_removal = false;
  out->problem = std::make_unique<ceres::Problem>(problem_options);
  ceres::Problem& problem = *out->problem;
  const auto Add = [&](const char* kind, ceres::CostFunction* cost, ceres::LossFunction* loss,
                       auto... blocks) {
    out->blocks[kind].push_back(problem.AddResidualBlock(cost, loss, blocks...));
  };
  for (size_t k = 0; k < n; ++k) problem.AddParameterBlock(out->states[k].data(), kStateSize);
  problem.AddParameterBlock(out->offsets.data(), 2);

  const SensorNoise& noise = model.measurement;
  const ProcessNoiseConfig& q = model.process;
  const WeakConstraintConfig& wc = model.weak_constraints;
  // Priors: the first state from the EKF's initial estimate, the offsets weakly around the EKF's.
  {
    std::array<double, kStateSize> mean, sd;
    for (int i = 0; i < kStateSize; ++i) {
      mean[i] = ekf.estimates.front().x[i];
      sd[i] = std::max(ekf.estimates.front().sd[i], 1e-6);
    }
    Add("first_state_prior", DiagonalPrior<kStateSize>::Create(mean, sd), nullptr,
        out->states[0].data());
    Add("offset_prior",
        DiagonalPrior<2>::Create({out->offsets[0], out->offsets[1]},
                                 {noise.imu_sd_accel_mps2 + q.accel_bias_sd_mps2,
                                  noise.imu_sd_gyro_radps + q.gyro_bias_sd_radps}),
        nullptr, out->offsets.data());
  }

  // Measurements attach to the state nearest in time; inputs (attitude, accelerometer for the
  // dynamics) are the latest sample at or before a time, as the EKF holds them.
  const auto nearest_state = [&](double t) {
    const auto it = std::lower_bound(out->times.begin(), out->times.end(), t);
    if (it == out->times.begin()) return size_t{0};
    if (it == out->times.end()) return n - 1;
    const size_t after = static_cast<size_t>(it - out->times.begin());
    return (t - out->times[after - 1] <= out->times[after] - t) ? after - 1 : after;
  };
  const auto latest_index = [](const auto& samples, double t) -> long {
    const auto it = std::upper_bound(samples.begin(), samples.end(), t + 1e-9,
                                     [](double value, const auto& s) { return value < s.t; });
    return static_cast<long>(it - samples.begin()) - 1;
  };
  const auto context_at = [&](double t) {
    Context c;
    const long a = latest_index(log.attitude, t);
    if (a >= 0) {
      c.attitude = {log.attitude[a].roll, log.attitude[a].pitch};
      c.yaw = log.attitude[a].yaw;
      c.pitch_sd = std::isfinite(log.attitude[a].sd_pitch) ? log.attitude[a].sd_pitch : 0.0;
      c.have_attitude = true;
    }
    const long i = latest_index(log.imu, t);
    if (i >= 0) c.accel_x = log.imu[i].ax;
    if (log.imu.size() > 1) {
      c.imu_period_s = (log.imu.back().t - log.imu.front().t) / (log.imu.size() - 1);
    }
    return c;
  };
  for (size_t k = 0; k < n && k < log.wheels.size(); ++k) {
    const SideSpeeds s = DrivenSideSpeeds(log.wheels[k], log.vehicle.type);
    out->wheel_speeds[k] = {s.left_radps, s.right_radps};
    Add("encoder", EncoderFactor::Create(s.left_radps, s.right_radps, noise.wheels_sd_omega_radps),
        nullptr, out->states[k].data());
    ++out->encoders;
  }
  for (const ImuSample& imu : log.imu) {
    if (imu.t < out->times.front() - 0.5 || imu.t > out->times.back() + 0.5) continue;
    const size_t k = nearest_state(imu.t);
    const Context c = context_at(imu.t);
    double* x = out->states[k].data();
    double sd_a = noise.imu_sd_accel_mps2;
    if (options.velocity_model == VelocityModel::kAccelerometerDriven) {
      sd_a = std::sqrt(sd_a * sd_a + TireLawSampleVariance(ekf.estimates[k].x.data(), c.attitude,
                                                           params, model.tire_uncertainty,
                                                           c.imu_period_s));
    }
    if (std::isfinite(imu.ax)) {
      Add("accelerometer", AccelerometerFactor::Create(params, c.attitude, imu.ax, sd_a), nullptr,
          x, out->offsets.data());
      ++out->accelerometer;
    }
    if (std::isfinite(imu.gz)) {
      Add("gyro", YawGyroFactor::Create(imu.gz, noise.imu_sd_gyro_radps), nullptr, x,
          out->offsets.data());
      ++out->gyro;
    }
  }
  if (options.use_gps) {
    for (const GpsSample& g : log.gps) {
      if (!std::isfinite(g.vx) || !std::isfinite(g.vy) || !std::isfinite(g.vz)) continue;
      if (g.t < out->times.front() - 0.5 || g.t > out->times.back() + 0.5) continue;
      const size_t k = nearest_state(g.t);
      const Context c = context_at(g.t);
      double along;
      if (c.have_attitude) {
        const double cp = std::cos(c.attitude.pitch_rad);
        along = g.vx * std::cos(c.yaw) * cp + g.vy * std::sin(c.yaw) * cp -
                g.vz * std::sin(c.attitude.pitch_rad);
      } else {
        const auto& w = out->wheel_speeds[k];
        along = (w[0] + w[1] >= 0.0 ? 1.0 : -1.0) * std::hypot(g.vx, g.vy);
      }
      const double sd = std::isfinite(g.sd_v) && g.sd_v > 0.0 ? g.sd_v : noise.gps_sd_v_mps;
      Add("gnss", GnssVelocityFactor::Create(along, sd), nullptr, out->states[k].data());
      ++out->gnss;
    }
  }

  // Between consecutive states: dynamics, disturbance walk; on each: weak constraints.
  double stopped_since = -1.0;
  for (size_t k = 0; k < n; ++k) {
    const auto& w = out->wheel_speeds[k];
    const double still = options.wheel_still_radps;
    const bool stopped = std::abs(w[0]) < still && std::abs(w[1]) < still;
    if (!stopped) {
      stopped_since = -1.0;
    } else if (stopped_since < 0.0) {
      stopped_since = out->times[k];
    }
    const double dt_cycle = k + 1 < n ? out->times[k + 1] - out->times[k]
                                      : (k > 0 ? out->times[k] - out->times[k - 1] : 0.01);
    const double root_dt = std::sqrt(std::max(dt_cycle, 1e-6));
    double* x = out->states[k].data();
    const double vel_dir = DriveDirection(w[0], w[1], still);
    if (vel_dir != 0.0) {
      Add("oppose_motion", OpposeMotionPrior::Create(vel_dir, wc.sd_oppose_motion / root_dt),
          nullptr, x);
      ++out->oppose_motion;
    }
    if (stopped && out->times[k] - stopped_since >= wc.stop_time_s) {
      Add("at_rest", AtRestPrior::Create(wc.sd_at_rest / root_dt, 0.1 * wc.sd_at_rest / root_dt),
          nullptr, x);
      ++out->at_rest;
    }
    Add("act_quickly", DisturbanceDecayPrior::Create(options.decay_sd_density / root_dt),
        new ceres::CauchyLoss(options.decay_cauchy_sigmas), x);
    ++out->act_quickly;
    Add("bound",
        BoundPrior::Create(
            {wc.max_v_bx_mps, wc.max_accel_bias_mps2, wc.max_a_dist_mps2, wc.max_gyro_bias_radps},
            wc.sd_bound / root_dt),
        nullptr, x);
    ++out->bounds;
    if (k + 1 >= n) continue;
    const double dt = out->times[k + 1] - out->times[k];
    if (dt <= 0.0) continue;
    // The attitude at t_k; the accelerometer sample that ends the interval (its mean over it).
    Context c = context_at(out->times[k]);
    c.accel_x = context_at(out->times[k + 1]).accel_x;
    const bool accel_driven =
        options.velocity_model == VelocityModel::kAccelerometerDriven && std::isfinite(c.accel_x);
    const double sd_v = accel_driven
                            ? std::sqrt(AccelInputDensitySq(noise.imu_sd_accel_mps2, c.pitch_sd,
                                                            params.gravity_mps2, c.imu_period_s) *
                                        dt)
                            : q.v_bx_mps2_per_sqrt_hz * std::sqrt(dt);
    const auto gauss_markov = [dt](double sd, double tau) {
      return sd * std::sqrt(1.0 - std::exp(-2.0 * dt / tau));
    };
    const std::array<double, WardDynamicsFactor::kResiduals> sd_step = {
        sd_v,
        gauss_markov(q.accel_bias_sd_mps2, q.accel_bias_tau_s),
        q.omega_radps2_per_sqrt_hz * std::sqrt(dt),
        q.omega_radps2_per_sqrt_hz * std::sqrt(dt),
        q.yaw_rate_radps2_per_sqrt_hz * std::sqrt(dt),
        gauss_markov(q.gyro_bias_sd_radps, q.gyro_bias_tau_s)};
    Add("dynamics",
        WardDynamicsFactor::Create(params, c.attitude, dt, accel_driven ? c.accel_x : std::nan(""),
                                   sd_step),
        nullptr, x, out->states[k + 1].data(), out->offsets.data());
    Add("disturbance_walk",
        DisturbanceWalkFactor::Create(q.a_dist_mps3_per_sqrt_hz * std::sqrt(dt)),
        new ceres::HuberLoss(options.disturbance_huber_sigmas), x, out->states[k + 1].data());
    ++out->dynamics;
  }
  return out;
}

std::map<std::string, double> CostByKind(const WardProblem& problem) {
  std::map<std::string, double> costs;
  for (const auto& [kind, ids] : problem.blocks) {
    double total = 0.0;
    for (ceres::ResidualBlockId id : ids) {
      double cost = 0.0;
      problem.problem->EvaluateResidualBlock(id, true, &cost, nullptr, nullptr);
      total += cost;
    }
    costs[kind] = total;
  }
  return costs;
}

}  // namespace slipgraph
