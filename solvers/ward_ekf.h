// The streaming EKF of Ward & Iagnemma (Sec. III): state [v_bx, b_ax, a_dist, w_l, w_r,
// yaw_rate, b_gz], process model eq. (10) discretized with the shared RK4 step
// (factors/ward_dynamics.h), measurement model eq. (11), Joseph-form covariance update, constant
// IMU offsets by mean-then-EMA (eq. 12), the six weak constraints of Table I as pseudo-
// measurements, and the slip-EMA immobilization detector. Jacobians by automatic differentiation
// of the same templated physics (in the accelerometer-driven prediction, its yaw acceleration's,
// carried through the RK4 stages by the chain rule: factors/ward_accel_driven_step.h).
//
// In parts: the prediction (solvers/ward_propagator.h), the sensors' rows and the GNSS fading
// memory (solvers/ward_updaters.h), the gated sequential update (solvers/ekf_update.h); this
// class holds the state and the clock, and runs offsets, gates, weak constraints, the detector
// and the divergence guard around them.
//
// Streaming: push measurements in time order (AddImu, AddWheels, ...); each does constant work.
// Any subset of streams works. A NaN component is dropped alone (as robot_localization does);
// process noise scales with the gap; innovations are gated and every rejection is counted; a
// stream whose measurements are all being rejected is re-admitted after a bounded run of
// rejections (a filter that silently rejects every GNSS fix is a known failure).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "factors/drive_direction.h"
#include "factors/gnss_heading_offset.h"
#include "factors/ward_dynamics.h"
#include "factors/ward_state.h"
#include "io/drive_log.h"
#include "io/gnss_heading_offsets.h"
#include "io/state_estimate.h"
#include "model/model_config.h"
#include "solvers/ekf_update.h"
#include "solvers/immobilization_detector.h"
#include "solvers/imu_offsets.h"
#include "solvers/slip_persistence.h"
#include "solvers/ward_propagator.h"
#include "solvers/ward_updaters.h"
#include "solvers/weak_constraints.h"

namespace slipgraph {

// The fading memory's EMA length, on by default (EkfOptions::gnss_fading_fixes; `filter
// --no-gnss-fading`: 0).
constexpr double kGnssFadingFixes = 8.0;

struct EkfOptions {
  VelocityModel velocity_model = VelocityModel::kAccelerometerDriven;
  // Innovation gates as chi-square thresholds on the Mahalanobis distance (per update);
  // infinity disables a gate. The IMU is not gated by default: the accelerometer is what first
  // sees a hold-back, and gating it would hide exactly the events the filter exists to find.
  double imu_gate_chi2 = std::numeric_limits<double>::infinity();
  double wheels_gate_chi2 = 18.4;  // 2 dof, 99.99 %
  double gps_gate_chi2 = 15.1;     // 1 dof, 99.99 %
  // After this many consecutive rejections a stream's next measurement is accepted (and counted
  // as re-admitted): 1 for 1 Hz GNSS means a second inconsistent fix in a row is believed.
  int imu_max_consecutive_rejections = 10;
  int wheels_max_consecutive_rejections = 10;
  int gps_max_consecutive_rejections = 1;
  double encoder_timeout_s = 0.25;  // older encoder data: no immobilization flag
  // |w| below this reads as a stopped wheel (factors/drive_direction.h).
  double wheel_still_radps = kDefaultWheelStillRadps;
  // Initial standard deviations of the state (the wheel speeds start at their first reading).
  std::array<double, ward::kStateSize> initial_sd = {0.2, 0.02, 0.5, 1.0, 1.0, 0.1, 0.002};
  // Keep every applied measurement's normalized innovation (EkfStats::innovations), for the
  // filter's consistency tests (NIS, whiteness). Off in the streaming front end.
  bool record_innovations = false;
  // Fading memory on GNSS (an adaptive filter, beyond the paper): the GNSS innovations
  // normalized by their predicted sd, z = nu / sqrt(h P h' + r), averaged over about
  // gnss_fading_fixes fixes (an EMA). A consistent filter's average is about 0; a velocity
  // drifting off (a tire law or an AHRS the model does not have) leaves a run of one sign. When
  // the average passes gnss_fading_threshold and a fix with |z| > 1 agrees with it (z times the
  // average above 1) and passes the gate, P is scaled by z^2 (at most gnss_fading_max) before
  // the update, so that the fix can pull the velocity back. Not in a bank of laws (which weighs
  // its filters by each fix's likelihood under their own covariance: AddGpsScored); in the
  // disturbance modes (solvers/disturbance_imm.h) each mode fades. 8 fixes and 0.5 (about 1.9
  // sd of a consistent filter's average) were chosen on seeds 1-20 and are reported on seeds
  // 21-40 (docs/mismatch.md); 0 fixes: off, the paper's filter.
  double gnss_fading_fixes = kGnssFadingFixes;
  double gnss_fading_threshold = 0.5;
  double gnss_fading_max = 100.0;
  // Sum the sensor measurements' log-likelihood for TakeLogLikelihood() (a bank of filters
  // weighing their models sets it); off, no logarithm is taken in the updates.
  bool track_log_likelihood = false;

  bool IsValid(std::string* error) const;
};

struct StreamCounters {
  long used = 0;                // measurements applied
  long rejected = 0;            // gated out
  long forced = 0;              // accepted after max_consecutive_rejections
  long dropped_components = 0;  // NaN fields left out
};

struct EkfStats {
  StreamCounters imu, wheels, gps, attitude;
  // The wheels' checks on the accelerometer bias (ModelConfig::slip_persistence): applied, and
  // left out by their gate (a force the accelerometer felt).
  StreamCounters slip_persistence;
  long slip_persistence_lasting = 0;  // of those applied, lasting errors (with the velocity moved)
  // Those applied, in time order, for a smoother behind the filter (about two a second while the
  // robot drives; a bank's and the disturbance modes' stats are their first filter's).
  std::vector<AccelBiasMeasurement> wheel_bias_checks;
  std::array<long, kWeakConstraintCount> weak_constraints{};  // applications per constraint
  long late_measurements = 0;  // stamped before the filter's time: applied at the filter time
  long offset_init_samples = 0;
  // The wheels turned during those samples: the offsets were motion-compensated from the wheels
  // (solvers/imu_offsets.h) and the bias states opened by their uncertainty.
  bool offset_moving_start = false;
  bool offset_implausible_start = false;  // ... and the compensation failed: started at zero
  // Times the state or covariance became non-finite (a model far from the data can make the
  // stiff tire law blow up): the filter went back to its last finite state, covariance inflated.
  long divergence_resets = 0;
  // GNSS fixes projected on a yaw corrected by the course (factors/gnss_heading_offset.h), and
  // the last correction applied (rad).
  long gnss_heading_corrected = 0;
  double gnss_heading_offset_rad = 0.0;
  long gnss_fading = 0;  // GNSS updates preceded by fading memory (EkfOptions::gnss_fading_*)
  double first_divergence_t = -1.0;
  // With EkfOptions::record_innovations: per measurement ("accelerometer", "gyro",
  // "encoder_left", "encoder_right", "gnss") the applied updates' times and normalized
  // innovations nu / sqrt(h P h^T + r) (of the sequential scalar updates, so the rows of one
  // update are decorrelated; their squares sum to its NIS). A consistent filter's are white with
  // unit variance. measurement_share: r / (h P h^T + r), the measurement noise's share of each
  // innovation's variance (what a scale on the stated noise moves). The gated_ series: the same
  // of the one-row measurements (GNSS) the gate left out (not in `normalized`: they did not
  // update).
  struct InnovationSeries {
    std::vector<double> t, normalized, measurement_share;
    std::vector<double> gated_t, gated_normalized, gated_measurement_share;
  };
  std::map<std::string, InnovationSeries> innovations;
};

class WardEkf {
 public:
  WardEkf(const Vehicle& vehicle, const ModelConfig& model, const EkfOptions& options = {});

  void AddImu(const ImuSample& imu);
  // Driven left/right side speeds (io/measurement_stream DrivenSideSpeeds). One filter cycle:
  // the update, then the weak constraints and the immobilization detector.
  void AddWheels(double t, double omega_left_radps, double omega_right_radps);
  void AddGps(const GpsSample& gps);
  void AddAttitude(const AttitudeSample& attitude);

  WardEstimate Estimate() const;
  // With EkfOptions::track_log_likelihood: the log-likelihood of the sensor measurements applied
  // (or gated out) since the last call, log N(nu; 0, H P H' + R) (weak constraints not counted),
  // and reset; 0 without. For a bank of filters weighing their models
  // (solvers/multiple_model_ekf.h).
  double TakeLogLikelihood() {
    const double l = log_likelihood_;
    log_likelihood_ = 0.0;
    return l;
  }
  // AddGps, returning that fix's log-likelihood under the filter's prediction (applied or gated
  // out) whether or not track_log_likelihood is set; the running sum is as AddGps leaves it. A
  // bank weighing its filters by GNSS alone (solvers/multiple_model_ekf.h) takes no logarithm in
  // the other streams' updates.
  double AddGpsScored(const GpsSample& gps);
  const EkfStats& stats() const { return stats_; }
  // The disturbance's random-walk density its next prediction takes (WardPropagator's adaptive
  // w3), for a smoother behind the filter.
  double DisturbanceDensity() const { return propagator_.DisturbanceDensity(); }
  bool started() const { return started_; }
  // The state and covariance, and their replacement by a mixture of several filters' (an
  // interacting multiple model, solvers/disturbance_imm.h); the offsets, gates, detector and
  // timers stay this filter's.
  const ekf::StateVector& state() const { return x_; }
  const ekf::StateMatrix& covariance() const { return P_; }
  // The previous cycle's state (for the rate bound) moves with it, so that the replacement is
  // not read as motion; the divergence guard's last sane state becomes this one.
  void ReplaceState(const ekf::StateVector& x, const ekf::StateMatrix& P) {
    x_previous_cycle_ += x - x_;
    x_ = x;
    P_ = P;
    last_good_x_ = x_;
    last_good_P_ = P_;
  }

 private:
  using StateVector = ekf::StateVector;
  using StateMatrix = ekf::StateMatrix;

  // A stream's gate: a chi-square threshold on the Mahalanobis distance, and re-admission after
  // a bounded run of rejections.
  struct StreamGate {
    double chi2;
    int max_consecutive_rejections;
    int consecutive_rejections = 0;
  };

  // Starts the filter clock at t on the first measurement; returns false for a stamp before
  // the filter time (then the measurement is applied at the filter time and counted as late).
  void Begin(double t);
  void PredictTo(double t);
  // A sensor's measurement through its gate (ekf_update.h); returns false when gated out. Its
  // log-likelihood is summed when a bank scores the filter, its rows' normalized innovations
  // recorded under their names with EkfOptions::record_innovations.
  bool Update(const ekf::MeasurementRows& rows, StreamGate* gate, StreamCounters* counters);
  void ApplyWeakConstraints(double dt_cycle);
  // The wheel cycle's step of the wheels' check on b_ax (solvers/slip_persistence.h): its
  // measurement, gated, when an interval closes.
  void CheckBiasAgainstWheels();
  // After every measurement: keep the last sane (x, P); on a diverged one (not finite, or a state
  // beyond kDivergedMagnitude) go back to it with the covariance inflated, and count it. Never a
  // silent NaN, nor a yaw rate of 1e46 rad/s that is still finite.
  void GuardDivergence();
  ward::Attitude<double> CurrentAttitude() const { return {roll_rad_, pitch_rad_}; }
  // Normal forces and gravity along x at the current attitude, updated with each attitude sample.
  ward::AttitudeLoads<double> loads_;
  WardPropagator propagator_;
  GnssFading gnss_fading_;
  GnssHeadingOffset gnss_heading_;  // the attitude's yaw against the GNSS course
  SlipPersistence slip_persistence_;
  // kAccelerometerDriven: the accelerometer x reading driving the current prediction (the mean
  // over the interval ending at its stamp) and the IMU sample interval, for the input noise.
  double accel_input_mps2_ = 0.0;
  bool have_accel_input_ = false;
  double imu_period_s_ = 0.01;
  double last_imu_t_ = -1.0;

  ward::Params params_;
  ModelConfig model_;
  EkfOptions options_;
  StateVector x_ = StateVector::Zero();
  StateMatrix P_ = StateMatrix::Zero();
  double t_ = 0.0;
  bool started_ = false;
  bool wheels_initialised_ = false;
  double roll_rad_ = 0.0, pitch_rad_ = 0.0, yaw_rad_ = 0.0;
  double pitch_sd_rad_ = 0.0;  // the attitude source's stated pitch sd (0 when not given)
  bool have_attitude_ = false;
  bool have_yaw_ = false;  // a finite yaw has been read
  ImuOffsetEstimator offsets_;
  ImmobilizationDetector detector_;
  StateVector x_previous_cycle_ = StateVector::Zero();
  double t_previous_cycle_ = 0.0;
  bool have_previous_cycle_ = false;
  double previous_slip_ema_ = 0.0;
  double last_wheels_t_ = -1e300;
  // Two at-rest timers: on each reading, for the IMU offsets (which must not take the first
  // samples of a start for rest), and weak constraint 4's (which an encoder's odd count while the
  // wheels stand must not restart).
  WheelStopTimer stop_timer_;
  WheelRestTimer rest_timer_;
  // The latest encoder reading: for the offsets' start and the GNSS heading's drive direction.
  WheelMotion last_wheel_motion_;
  EkfStats stats_;
  StreamGate imu_gate_, wheels_gate_, gps_gate_;
  double log_likelihood_ = 0.0;  // since the last TakeLogLikelihood()
  bool scoring_ = false;         // inside AddGpsScored: the updates sum their log-likelihood
  StateVector last_good_x_ = StateVector::Zero();
  StateMatrix last_good_P_ = StateMatrix::Zero();
  std::vector<PseudoMeasurement> pseudo_;  // reused buffer
};

// A mixture of filters' disturbance density for a smoother behind it (the bank's, the
// disturbance modes'): the root of the filters' squared WardEkf::DisturbanceDensity, weighed.
template <typename Filters, typename Weights>
double WeighedDisturbanceDensity(const Filters& filters, const Weights& weights) {
  double variance = 0.0;
  for (size_t i = 0; i < filters.size(); ++i) {
    const double q = filters[i]->DisturbanceDensity();
    variance += weights[i] * q * q;
  }
  return std::sqrt(variance);
}

}  // namespace slipgraph
