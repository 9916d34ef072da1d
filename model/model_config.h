// The estimation model as data: physical parameters, noise, weak-constraint and detector
// settings, and which optional physical effects are on. Every solver (EKF, window and batch
// smoother) is built from one ModelConfig. Defaults are in-class; DefaultModelConfig() merges a
// vehicle's nominal values over them, and io/yaml_config applies a user's model file on top.
#pragma once

#include <string>
#include <vector>

#include "model/vehicle.h"

namespace slipgraph {

// Continuous-time process noise of Ward & Iagnemma eq. (10), as white-noise densities.
struct ProcessNoiseConfig {
  double v_bx_mps2_per_sqrt_hz = 0.3;    // w1: unmodelled longitudinal acceleration
  double a_dist_mps3_per_sqrt_hz = 5.0;  // w3: random walk of the disturbance acceleration
  // Adaptive w3 (innovation-based, beyond the paper): while the accelerometer's normalized
  // innovations are large (a force the model lacks has appeared, e.g. a hold-back), the density
  // of w3 grows up to this value; with the tire law's stiffness the disturbance and velocity
  // would otherwise drift together along an unobservable direction in normal driving.
  double a_dist_max_mps3_per_sqrt_hz = 40.0;
  double a_dist_adapt_samples = 5.0;         // EMA length (accelerometer samples) of the NIS
  double omega_radps2_per_sqrt_hz = 10.0;    // w4, w5: wheel acceleration (controller neglected)
  double yaw_rate_radps2_per_sqrt_hz = 1.0;  // w6: unmodelled yaw acceleration
  double accel_bias_sd_mps2 = 0.02;          // sigma_abx: stationary sd of the walking bias b_ax
  double accel_bias_tau_s = 300.0;           // tau_ax: correlation time of b_ax
  double gyro_bias_sd_radps = 0.002;         // sigma_gbz: stationary sd of the walking bias b_gz
  double gyro_bias_tau_s = 300.0;            // tau_gz: correlation time of b_gz
  // The attitude source's slow error, beyond the paper. An AHRS's attitude is its own filter's
  // output: its error is correlated over seconds to minutes, not white at the sample rate, and
  // where the accelerometer drives the velocity it removes gravity with an error g * d(pitch)
  // that acts as a bias. The front end's b_ax then also walks by g times the attitude's stated
  // pitch sd in this time (a density of g sd_pitch / sqrt(time); its mean reversion stays
  // accel_bias_tau). Chosen on ward21m and ward21 seeds 1-10, reported on 11-20
  // (docs/mismatch.md). 0: off, the paper's walk. The EKF's only: the smoothers' bias walk did
  // better without it (docs/mismatch.md).
  double attitude_error_walk_s = 60.0;
  // 0: a_dist is a random walk (the paper). Positive: a Gauss-Markov process decaying toward
  // zero with this correlation time (s), of stationary sd w3 sqrt(tau / 2) (the same density
  // over times short against tau): a disturbance that does not persist (the quiet mode of
  // solvers/disturbance_imm.h). The EKF's only: the smoothers' disturbance walk does not read it.
  double a_dist_decay_tau_s = 0.0;
};

// Ward & Iagnemma Table I. In the EKF these are pseudo-measurements applied under their
// conditions; in the smoother, smooth soft priors with the same sigmas. The sigmas are
// densities (unit x sqrt(s)): a constraint applied every cycle of length dt has variance
// sd^2 / dt, so its strength per second does not depend on the filter's rate (applied at 100 Hz
// with a plain 0.05 sigma, WC2 alone would pin a_dist to 5 mm/s^2 within a second).
struct WeakConstraintConfig {
  double sd_oppose_motion = 0.1;  // WC1, m/s^2 sqrt(s)
  // WC1 doubted as the push grows: its variance times 1 + (a_dist / scale)^2 (the weight of a
  // Cauchy loss of that scale, in m/s^2; the smoother's prior carries that loss). A forward push
  // of several m/s^2 is the tire law failing in a transient (a tread that relaxes, a body that
  // overtakes its wheels), not a disturbance the constraint should hold at zero through the
  // law's slope. 0: the paper's constraint.
  double oppose_motion_cauchy_scale_mps2 = 1.0;
  double sd_act_quickly = 0.2;   // WC2, m/s^2 sqrt(s)
  double sd_no_pull_back = 0.1;  // WC3, m/s^2 sqrt(s)
  double sd_at_rest = 0.02;      // WC4, on a_dist and b_ax (m/s^2 sqrt(s)); b_gz uses sd/10 rad/s
  double sd_bound = 0.05;        // WC5 and WC6, in the bounded state's unit x sqrt(s)
  double min_slip_rate_per_s = 0.05;  // WC2 min_delta_i: slow slip growth, per second
  double slip_threshold = 0.3;        // WC2 thresh_i: WC2 applies only below this EMA slip
  double decay_alpha = 0.995;         // WC2 alpha, 0 < alpha < 1, applied per filter cycle
  double stop_time_s = 1.0;           // WC4 t_stop: wheels at rest this long
  // The wheels read still when their speeds smoothed over this time constant are (WheelRestTimer
  // in factors/drive_direction.h), so that a standing encoder's odd count does not restart t_stop;
  // 0: each reading as it is, the paper's test; 0.1 s chosen in docs/mismatch.md.
  double still_smoothing_s = 0.1;
  double max_v_bx_mps = 3.0;              // WC5 bound on |v_bx|
  double max_accel_bias_mps2 = 0.5;       // WC5 bound on |b_ax|
  double max_a_dist_mps2 = 10.0;          // WC5 bound on |a_dist|
  double max_gyro_bias_radps = 0.1;       // WC5 bound on |b_gz|
  double max_v_bx_rate_mps2 = 5.0;        // WC6 bound on |d v_bx / dt|
  double max_accel_bias_rate_mps3 = 0.5;  // WC6 bound on |d b_ax / dt|
};

// Immobilization detector: EMA (eq. 12) of the mean driven-wheel slip over a threshold that
// rises at low wheel speed, where encoder noise makes slip noisy; never while braking.
struct ImmobilizationConfig {
  // The paper chose its threshold empirically. These were chosen on simulated ward21 suites 9-16
  // (the most detections with no false alarm there; ties to the higher threshold) and checked
  // on suites 17-40 (docs/ekf.md; the former 0.7 and 0.2: 790/806 against 803/806 over 1-40).
  double ema_samples = 20.0;              // p of eq. (12)
  double slip_threshold = 0.6;            // EMA slip above which the robot is immobilized
  double low_speed_threshold_add = 0.05;  // added to the threshold at zero wheel speed
  double low_speed_mps = 0.2;             // wheel surface speed below which the addition fades in
  double min_wheel_speed_mps = 0.05;      // never flagged below this wheel surface speed: the
                                          // wheels are not "spinning" (and slip is noise there)
  // Flag only when the slip is above the threshold also with the velocity moved this many of its
  // sd toward the wheels' surface speed (a second EMA of that slip; slip_ema, which the weak
  // constraints read, stays the estimate's). 0: the paper's detector on the estimate alone.
  double velocity_sd_margin = 0.0;
};

// The wheels' check on the front end's accelerometer bias, beyond the paper
// (solvers/slip_persistence.h): over each interval the body's speed changes as the wheels' rim
// speed does at the slip the interval started with, unless the accelerometer felt a force; the
// difference measures the error of the b_ax estimate. Chosen on ward21m and ward21 seeds 1-10,
// reported on 21-40 (docs/mismatch.md). The smoothers take the checks the front end applied
// (WardProblemOptions::accel_bias); UsePapersAccelBias turns it off.
struct SlipPersistenceConfig {
  double interval_s = 0.5;          // T; 0: off (the paper's filter)
  double sd_mps = 0.005;            // the slip's own change of the velocity over T, as an sd
  double gate_sd = 3.0;             // measurements beyond this many predicted sd are left out
  double smoothing_s = 0.1;         // time constant of the velocity and rim-speed smoothing
  double min_rim_speed_mps = 0.03;  // intervals only while the wheels' rim speed is above it
  // ... and only intervals over which the wheels held their speed: the mean rim acceleration
  // within this bound (a stalled wheel that spins up, or one that slips as it speeds up, changes
  // its slip on its own).
  double max_rim_acceleration_mps2 = 0.02;
  // A force the accelerometer feels at a hold-back is a pulse: the gate leaves out its interval
  // and the next (its smoothed tail). Intervals left out that go on, this many in a row with
  // innovations of one sign each within max_lasting_error_mps2, are the bias estimate's own
  // error instead: from the last of them on they are applied, and so is the velocity that error
  // moved the prediction by over them, either way (a robot whose velocity has run off its wheels
  // is otherwise held there by the slip the check then sees persist). 0: every gated interval left
  // out. Chosen on ward21m and ward21 seeds 1-20, reported on 21-40 (docs/mismatch.md).
  int lasting_intervals = 3;
  double max_lasting_error_mps2 = 0.1;  // a larger one is a force: a robot that speeds up
                                        // after a hold-back feels 0.2-0.5 m/s^2 for seconds
  // interval_s finite and non-negative; when on, lasting_intervals non-negative and the others
  // positive (the first bad one named).
  bool IsValid(std::string* error) const;
};

// How far the tire law (eqs. 8-9) with the nominal coefficients may be from the terrain's, as
// the sd of the modelled traction acceleration:
//   sd^2 = (relative_sd |traction|)^2 + sum_sides (d traction / d v_rel x
//          (slip_relative_sd |v_rel| + slip_floor))^2 + floor^2
// The first term is the uncertain saturation level (C1), the second the uncertain slip needed
// for a given force (the low-slip slope C1 At varies by a factor of two between soils). Used
// where the law ties the disturbance to the accelerometer (the accelerometer-driven EKF).
// The defaults keep only the first and last terms: on the ward21 suites the slip terms let
// v_bx drift more in normal driving than they help during hold-backs (docs/ekf.md).
struct TireLawUncertainty {
  double relative_sd = 0.3;       // fraction of the modelled traction
  double slip_relative_sd = 0.0;  // fraction of the relative velocity v_rel
  double slip_floor_mps = 0.0;    // m/s of v_rel
  double floor_mps2 = 0.1;        // m/s^2
  // The law's error persists (it is the terrain's): treated as independent per sample it would
  // accumulate 100 looks a second at 100 Hz. Its variance per sample of interval dt is therefore
  // sd^2 x correlation_time / dt (0: independent per sample).
  double correlation_time_s = 0.0;
};

// What the model file may correct in vehicle.yaml's geometry and the log's clocks (`slipgraph
// identify` writes it): each side's effective rolling radius as a scale of vehicle.yaml's
// wheel_radius, the effective track (a skid-steer turns as if its track were wider than its
// wheels are apart), how late the IMU's stamps are against the encoders', and how late the
// encoders' are against the IMU's (a controller's odometry averaged over a window, a driver
// stamping on receipt). Applied to a log by ApplyCalibration (io/drive_log.h) before any
// estimator sees it.
struct CalibrationConfig {
  double wheel_radius_scale_left = 1.0;
  double wheel_radius_scale_right = 1.0;
  double track_width_m = 0.0;         // 0: vehicle.yaml's
  double imu_time_offset_s = 0.0;     // subtracted from the IMU's stamps; within +- 1 s
  double wheels_time_offset_s = 0.0;  // subtracted from the encoders' stamps; within +- 1 s
  // The IMU's axes pitched nose-down by this about body y (rad; within +-
  // kMaxImuMountingPitchRad): its accelerometer and gyro rotated back (attitude.csv is taken as
  // the body's).
  double imu_mounting_pitch_rad = 0.0;
};

// The largest IMU mounting pitch taken (rad, 11 degrees): the calibration's bound and the
// workbench's plausible range.
constexpr double kMaxImuMountingPitchRad = 0.2;

// The largest tire_sd.slip_stiffness taken (error messages say [0, 2]): a slope uncertain by a
// factor e^2 either way.
constexpr double kMaxSlipStiffnessRelativeSd = 2.0;

struct ModelConfig {
  double gravity_mps2 = 9.80665;
  TireLawUncertainty tire_uncertainty;
  CalibrationConfig calibration;
  TireParams tire;        // from vehicle.yaml unless the model file overrides it
  RollingParams rolling;  // from vehicle.yaml unless the model file overrides it
  // The uncertainty (sd) of those coefficients, when the law is a fit that the terrain may not
  // follow (e.g. a mean over soils): the batch smoother's sd then include how far its estimate
  // would move with each coefficient one sd off (solvers/batch_smoother.h). 0: exact.
  TireParams tire_sd{0.0, 0.0, 0.0};
  RollingParams rolling_sd{0.0, 0.0, 0.0};
  // How far the tire law's slope at small slip (At and C2 together: the slip a force needs) may
  // be off: the sd of its logarithm (model file `tire_sd: slip_stiffness`; at most
  // kMaxSlipStiffnessRelativeSd). The single front end's sd then include how far its estimate
  // moves with the slope so moved (RunEkf; the window and the chunks add that share to their own),
  // and the batch smoother's consider covariance counts it with tire_sd and rolling_sd
  // (BatchSmootherOptions::consider_law_uncertainty, unless At's or C2's sd is stated); both at
  // exp(-sd) and exp(+sd) (SlipStiffnessSdScales). 0: the law is exact. Where law_samples are
  // listed the bank's spread and the batch's soils replace it (`--single-law` still takes it).
  // A law nobody fitted to this terrain is a guess: by default half or twice as steep at one sd
  // (chosen on ward21m seeds 1-10, docs/mismatch.md).
  double tire_slip_stiffness_relative_sd = 0.7;
  // Or the laws of the soils it was fitted over (from vehicle.yaml `law_samples`): with two or
  // more, their spread around the law (correlations included) replaces the three above in the
  // batch's consider covariance, and the front end is a bank whose spread counts the law.
  std::vector<LawSample> law_samples;
  // Whether the model lists its soils: two or more law_samples (one is no spread).
  bool ListsSoils() const { return law_samples.size() >= 2; }
  ProcessNoiseConfig process;
  SensorNoise measurement;  // from vehicle.yaml sensors unless the model file overrides it
  WeakConstraintConfig weak_constraints;
  ImmobilizationConfig immobilization;
  SlipPersistenceConfig slip_persistence;
  int offset_init_samples = 100;      // n: IMU samples averaged for the constant offsets
  double offset_ema_samples = 200.0;  // p of eq. (12) for the offsets at rest
  // An at-rest IMU sample updates the offsets only once the robot has stayed at rest this long
  // after it (the encoders see a start late; solvers/imu_offsets.h).
  double offset_rest_guard_s = 0.5;
  // Whether a GNSS velocity is projected on the attitude's yaw corrected by the fixes' course
  // where the two disagree (factors/gnss_heading_offset.h), in the front end and the smoothers
  // alike (model file `gnss_heading_from_course`); false: on the yaw as logged.
  bool gnss_heading_from_course = true;
  // Optional physical effects switched on, by the names of their terms (factors/effect_term.h;
  // io/yaml_config checks a model file's against the terms).
  std::vector<std::string> effects;
  // Where an effect that acts on part of a drive acts (EffectTerm::acts_on_windows): for
  // sinkage_resistance the time spans (log time, s) on soft ground, for terrain_change those on
  // the changed terrain, as `diagnose` found them. Required when such an effect is on.
  struct EffectWindow {
    std::string effect;
    double t_start_s = 0.0, t_end_s = 0.0;
  };
  std::vector<EffectWindow> effect_windows;
  // Whether t (log time, s) lies in one of `effect`'s windows.
  bool InEffectWindow(const std::string& effect, double t) const;

  // Ceres-style validity check: false with a message naming the first bad field.
  bool IsValid(std::string* error) const;
};

// In-class defaults with the vehicle's nominal tire, rolling and sensor values merged in.
ModelConfig DefaultModelConfig(const Vehicle& vehicle);

// The paper's accelerometer bias in the front end: its own walk alone, without the attitude's
// slow error in it (ProcessNoiseConfig::attitude_error_walk_s) and without the wheels' check on
// it (slip_persistence). The workbench and identify start from that filter (their figures were
// measured on it), and so do the tests of features measured before those two.
void UsePapersAccelBias(ModelConfig* model);

}  // namespace slipgraph
