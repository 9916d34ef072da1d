// The Ward & Iagnemma factor graph, one state at a time. A WardFactorSource reads a drive log once
// and knows, for every wheel sample k (a state), which factors belong to it: its encoder reading,
// the IMU and GNSS samples nearest to it in time, the weak-constraint soft priors on it, and for
// k > 0 the dynamics and disturbance random walk from state k-1. The whole-log problem adds every
// step; the sliding window adds steps as they arrive and marginalizes the oldest. One source of
// factors, so the batch and window problems cannot drift apart.
#pragma once

#include <ceres/problem.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "factors/drive_direction.h"
#include "factors/effect_term.h"
#include "factors/ward_state.h"
#include "io/drive_log.h"
#include "io/state_estimate.h"
#include "model/model_config.h"

namespace slipgraph {

// A velocity along body x measured by another estimator over an interval, e.g. a rover's
// advance per cycle from wheel-profile matching (solvers/wilcox_*): the mean velocity over
// [t - interval/2, t + interval/2], used as a measurement of v_bx at the state nearest t.
struct BodyVelocityMeasurement {
  double t = 0.0;
  double v_mps = 0.0;
  double sd_mps = 0.0;
  // When the estimate exists (the end of its interval, for an advance per cycle): an online
  // window takes it only from then (WardProblemOptions::body_velocity_when_available).
  double available_t = -std::numeric_limits<double>::infinity();
};

struct WardProblemOptions {
  VelocityModel velocity_model = VelocityModel::kAccelerometerDriven;
  bool use_gps = true;
  // A gate on GNSS velocity for gross outliers: a fix further from the front end's estimate than
  // this, in squared sd of the two together (10 sd), is left out (counted), unless the fixes
  // before it were left out max-consecutive times. The EKF's own gate (15.1, 3.9 sd) would also
  // leave out fixes that only disagree with a front end whose sd are too small under mismatch
  // (ward21m seeds 1-2: window v RMSE over the EKF's 0.688 -> 0.697 with it). Infinity: every
  // finite fix is taken (the workbench: a misfit is what it looks for). A fix at an infinite
  // distance (an absurd value) is never taken.
  double gnss_gate_chi2 = 100.0;
  int gnss_max_consecutive_rejections = 1;
  // Body-x velocity measurements from another estimator, sorted by t (empty: none).
  std::vector<BodyVelocityMeasurement> body_velocity;
  // The front end's wheels' checks on the accelerometer bias (EkfStats::wheel_bias_checks), sorted
  // by t (empty: none; the source throws std::invalid_argument on a t that is not finite or goes
  // back), each a factor on c_ax + b_ax at the state nearest its t (the interval's end: online,
  // it exists when the state does). The smoother's b_ax walks slowly (the paper's), so the checks
  // hold the bias a slow robot's velocity would otherwise integrate.
  std::vector<AccelBiasMeasurement> accel_bias;
  // Online: each body-velocity measurement enters at the first state at or after its
  // available_t, on the state nearest its t if that is still in the window (AddLateBodyVelocity;
  // otherwise it is counted as too late). Off for post-processing: each at its own state.
  bool body_velocity_when_available = false;
  // |w| below this reads as a stopped wheel (weak constraints 1 and 4), as in the EKF.
  double wheel_still_radps = kDefaultWheelStillRadps;
  // Huber scale of the disturbance random walk, in standard deviations of one step.
  double disturbance_huber_sigmas = 3.0;
  // Cauchy scale of the disturbance decay prior (weak constraint 2), in its standard deviations:
  // quadratic near zero (a creeping disturbance decays), nearly flat far out (a hold-back's
  // disturbance, which the accelerometer and the tire law insist on, is left alone).
  double decay_cauchy_sigmas = 1.0;
  // Density (m/s^2 sqrt(s)) of that prior. Like the EKF's WC2 it applies only while the slip is
  // small (Ward & Iagnemma Table I): it is left out where the wheels turn (above the detector's
  // min_wheel_speed) and the EKF's slip EMA is at or above WC2's thresh_i
  // (WeakConstraintConfig::slip_threshold). Without the gate the prior fights the tire law during
  // hold-backs and the velocity absorbs the difference (ward21 seed 1/2: 19/20 and 16/20
  // detected, v RMSE 0.023/0.020 m/s; with it 20/20 and 19/20, 0.019/0.017).
  double decay_sd_density = 0.1;
  // Density (m/s sqrt(s)) of weak constraint 3's velocity form (factors/no_pull_back_prior.h):
  // the body does not move against its wheels unless gravity pulls it back. 0: off.
  double no_pull_back_sd_density = 0.0;
  // The slip that gates that prior, one per state (empty: the EKF's slip EMA). The batch smoother
  // re-gates with its own first solution's slip (BatchSmootherOptions::regate_decay_prior).
  std::vector<double> decay_gate_slip;
  // Correlation time (s) of the tire law's error as the smoother weighs its accelerometer
  // factors (NaN: the model's TireLawUncertainty::correlation_time_s, which the EKF uses). The
  // smoother sees every sample of a stretch at once, so treating a terrain's persistent error as
  // independent at 100 Hz makes it trust the law a hundred-fold. ward21 seed 1/2, batch: 0 s ->
  // v RMSE 0.0185/0.0161, a_dist 0.342/0.313; 0.2 s -> 0.0164/0.0156, 0.336/0.315; 0.5 s ->
  // 0.0154/0.0153, 0.422/0.385 (docs/smoother.md).
  double tire_law_correlation_time_s = 0.2;
  // Density (rad/s^2 / sqrt(Hz)) of the wheel speeds' random walk in the smoother's dynamics
  // (NaN: the model's ProcessNoiseConfig::omega_radps2_per_sqrt_hz, 10, which the EKF uses), and
  // the Huber scale of that walk in sd of one step (0: a Gaussian walk inside the dynamics
  // factor; else a separate WheelSpeedWalkFactor with this loss, so the wheels' steps in turns
  // pass). Every wheel speed is a state seen by one encoder sample and tied to the velocity by a
  // concave tire law: the more each follows its own encoder noise, the more slip the joint
  // solution needs for the same force (a Neyman-Scott bias: it grows with the encoder noise
  // variance, white noise more than quantization, and vanishes with perfect encoders). Measured
  // on hidden/none with the encoders' real noise stated (0.066 rad/s; docs/smoother.md):
  //   walk 10 (the EKF's):  velocity 5.5 mm/s low while moving
  //   walk 1:               2.8 mm/s low, v RMSE 0.0042; the workbench then reads the bias as
  //                         drag (19 +- 8 on none; 55 for a true 40; 5/20 seeds false alarms)
  //   walk 0.3, Huber 3:    v RMSE 0.0032 (seeds 1-3), drag 40.7-42.6 for a true 40, no
  //                         failure segments; fig5 v 0.0045 -> 0.0031; ward21 seed 1 / 2 batch
  //                         0.0160 / 0.0155 -> 0.0165 / 0.0157 (terrain mismatch dominates)
  double omega_walk_radps2_per_sqrt_hz = 0.3;
  double omega_walk_huber_sigmas = 3.0;
  // The tire law's slip stiffness as a slowly varying unknown (the accelerometer factor's
  // stiffness blocks, factors/accelerometer_factor.h) with a prior of this sd around the user's law
  // on its first node; 0: off (the law's stiffness is taken as exact). Nodes every
  // stiffness_node_s, a random walk of density stiffness_walk_sd (1/sqrt(s)) between them: 0.1 per
  // minute. Not with effect terms unless stiffness_with_effects (below). Measured
  // (docs/smoother.md): the sensors see the stiffness only through a slip velocity of about 1 cm/s,
  // so its estimate is weak and pulled low by any velocity bias; a prior of 0.15 took ward21 batch
  // v RMSE from 0.0165/0.0157 to 0.0102/0.0121 (seeds 1/2) and cost fig5, where the law is right,
  // 0.0031 -> 0.0048; 0.5 gave 0.0122/0.0148 and fig5 0.0076. The library's default keeps the law
  // as given (the workbench and the window need that); the post-processing commands `smooth` and
  // `compare` estimate it where the model lists its soils (PostProcessingStiffnessPriorSd).
  double stiffness_prior_sd = 0.0;
  double stiffness_node_s = 60.0;
  double stiffness_walk_sd = 0.1 / std::sqrt(60.0);
  // The scale 1 + theta stays positive: theta is bounded below here (the law's slope at least a
  // tenth of the user's). On a real log whose law was guessed (WVU Pathfinder) the data pushed
  // theta to -1.01, a law with no slope at all.
  double stiffness_min = -0.9;
  // The walk beside the model's effect terms too (the workbench's null model with a law that
  // varies along the path, DiagnosisOptions::varying_law_prior_sd); by default a model with
  // effects takes the law as given, as it was fitted.
  bool stiffness_with_effects = false;
  // The tire and rolling law at each state (one per state; empty: the model's everywhere), e.g.
  // the law a bank of filters weighed at that sample (FilterResult::law): a window behind the
  // bank then holds the law the bank's estimate came from. The stiffness walk and the law
  // blocks scale or replace it as they do the model's.
  std::vector<LawSample> law_per_state;
  // The disturbance's random-walk density (m/s^3/sqrt(Hz)) from each state to the next (one per
  // state; empty: the model's w3 everywhere), e.g. the adaptive w3 a filter's prediction took
  // there (FilterResult::disturbance_density): a window behind the filter then lets the
  // disturbance move where the filter did.
  std::vector<double> disturbance_density_per_state;
  // The effect terms the model's `effects` may name (factors/effect_term.h); null: the
  // catalogue's (CatalogueTerms()). Not owned: it outlives the problem.
  const EffectTerms* effect_terms = nullptr;
  // The factor kinds to build (of WardFactorKinds()); empty: every kind. The law's consider
  // covariance builds only the kinds the law enters. FactorCounts describe a problem of every
  // kind.
  std::vector<std::string> only_kinds;
  bool Builds(const std::string& kind) const {
    return only_kinds.empty() ||
           std::find(only_kinds.begin(), only_kinds.end(), kind) != only_kinds.end();
  }
  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const;
};

// Every factor kind a Ward problem is built of (tests/ward_factor_source_test.cpp checks that a
// problem holds no other).
inline const std::vector<std::string>& WardFactorKinds() {
  static const std::vector<std::string> kinds = {"accelerometer",
                                                 "act_quickly",
                                                 "at_rest",
                                                 "body_velocity",
                                                 "bound",
                                                 "disturbance_walk",
                                                 "dynamics",
                                                 "effect_prior",
                                                 "encoder",
                                                 "first_state_prior",
                                                 "gnss",
                                                 "gyro",
                                                 "no_pull_back",
                                                 "offset_prior",
                                                 "oppose_motion",
                                                 "rate_bound",
                                                 "stiffness_prior",
                                                 "stiffness_walk",
                                                 "wheel_bias_check",
                                                 "wheel_speed_walk"};
  return kinds;
}

// The factor kinds the tire and rolling law (and the slip stiffness that scales it) enters; every
// other kind has the same residuals with any law (tests/ward_factor_source_test.cpp).
inline const std::vector<std::string>& TireLawFactorKinds() {
  static const std::vector<std::string> kinds = {"accelerometer", "dynamics"};
  return kinds;
}

// A residual block that went into a problem, with its factor kind ("dynamics", "gnss", ...).
struct AddedFactor {
  const char* kind;
  ceres::ResidualBlockId id;
};

// How many factors of each kind went in, for the report.
struct FactorCounts {
  long dynamics = 0, accelerometer = 0, gyro = 0, encoders = 0, gnss = 0, gnss_gated = 0,
       body_velocity = 0, body_velocity_too_late = 0, oppose_motion = 0, act_quickly = 0,
       no_pull_back = 0, at_rest = 0, bounds = 0, rate_bounds = 0, wheel_bias_checks = 0;
  std::string Describe() const;
};

// Whether t (log time, s) lies in the model's windows for `term` (EffectContext::window): 1 or 0,
// and 0 for a term that does not act on windows.
double EffectWindowWeight(const ModelConfig& model, const EffectTerm& term, double t);
// What an effect term sees at time t of the log (factors/effect_term.h): the latest attitude and
// IMU sample at or before t (level and NaN when there is none), the normal forces there for the
// model's params (ward::MakeParams(log.vehicle, model)), and its window weight.
EffectContext EffectContextAt(const DriveLog& log, const ModelConfig& model,
                              const ward::Params& params, const EffectTerm& term, double t);

// The parameter blocks a step's factors share with every other step.
struct GlobalBlocks {
  double* offsets = nullptr;  // [c_ax, c_gz]
  // The magnitudes of the effect terms the model names (effect_terms(), in that order), or null
  // for a model without any.
  double* effects = nullptr;
  // The slip-stiffness nodes (stiffness_node_count() contiguous blocks of one), or null when
  // the stiffness is the law's (WardProblemOptions::stiffness_prior_sd = 0).
  double* stiffness = nullptr;
  // The tire and rolling laws' coefficients (kLawCoefficientCount) and the two sides' radius
  // errors as unknowns (factors/tire_law_coefficients.h), or null when they are the model's.
  // Both or neither; not with effects or the stiffness walk.
  double* law = nullptr;
  double* radius_error = nullptr;
};

class WardFactorSource {
 public:
  // `initial`: one estimate per wheel sample (a front end's run over the log), the states'
  // times and initial values; kept by reference. Throws std::invalid_argument when it is empty
  // (no wheel data).
  WardFactorSource(const DriveLog& log, const ModelConfig& model,
                   const std::vector<WardEstimate>& initial, const WardProblemOptions& options);

  size_t size() const { return times_.size(); }
  const WardProblemOptions& options() const { return options_; }
  double time(size_t k) const { return times_[k]; }
  const std::vector<double>& times() const { return times_; }
  // The front end's estimate at state k: the initial value of the state.
  const WardEstimate& initial(size_t k) const { return initial_[k]; }
  // The measured driven-side wheel speeds [left, right] at state k.
  const std::array<double, 2>& wheel_speeds(size_t k) const { return wheel_speeds_[k]; }

  // Gaussian prior on state k from the EKF's estimate and standard deviation there: the start of
  // the whole-log problem, or of a window that has no marginal prior to carry.
  void AddStatePrior(size_t k, double* x, ceres::Problem* problem,
                     std::vector<AddedFactor>* added) const;
  // Weak prior on the constant IMU offsets [c_ax, c_gz] around the given values.
  void AddOffsetPrior(const std::array<double, 2>& mean, double* offsets, ceres::Problem* problem,
                      std::vector<AddedFactor>* added) const;
  // Every factor of state k: measurements nearest to it, weak-constraint priors on it and, for
  // k > 0, the dynamics and disturbance walk from state k-1 (previous; null for the first state
  // of a problem, which then has no dynamics factor), on the problem's global blocks.
  void AddStep(size_t k, double* previous, double* x, const GlobalBlocks& globals,
               ceres::Problem* problem, std::vector<AddedFactor>* added,
               FactorCounts* counts) const;
  // With body_velocity_when_available: the body-velocity measurements that become available at
  // state k (available_t in (t_{k-1}, t_k]) on earlier states, each on state_of(its state), or
  // counted too late when that returns null (the state has left the window).
  void AddLateBodyVelocity(size_t k, const std::function<double*(size_t)>& state_of,
                           ceres::Problem* problem, std::vector<AddedFactor>* added,
                           FactorCounts* counts) const;

  // The effect terms the model names, each once, in the order of the terms' collection; and the
  // names it gives that no term has (a sensor effect: the smoother has nothing to add for it).
  const std::vector<const EffectTerm*>& effect_terms() const { return effect_terms_; }
  const std::vector<std::string>& effects_without_term() const { return effects_without_term_; }
  // The slip-stiffness walk's nodes (WardProblemOptions::stiffness_prior_sd): how many, and which
  // two carry time t with the second's share u.
  size_t stiffness_node_count() const;
  void StiffnessNodesAt(double t, size_t* first, double* u) const;
  // Node j of that walk (nodes: stiffness_node_count() contiguous values) as a parameter block
  // bounded below by stiffness_min, with the prior around the user's law (j = 0) or the walk's
  // step from node j - 1, which must be in the problem. Throws std::invalid_argument when the
  // walk's density or spacing is not positive.
  void AddStiffnessNode(size_t j, double* nodes, ceres::Problem* problem,
                        std::vector<AddedFactor>* added) const;

 private:
  struct Context;
  Context ContextAt(double t) const;
  // GNSS fix g's velocity along body x at state k and its sd, the attitude's yaw corrected by
  // heading_offset_rad (io/gnss_heading_offsets.h): false when it has none (a non-finite
  // component).
  bool GnssAlong(size_t k, const GpsSample& g, double heading_offset_rad, double* along,
                 double* sd) const;
  // Weak constraint 3's condition at state k: the tires, with the body held still and the wheels
  // at their measured speeds, push along vel_dir harder than gravity pulls back.
  bool PushesAlong(size_t k, double vel_dir, const ward::Params& params) const;

  const DriveLog& log_;
  const ModelConfig& model_;
  const std::vector<WardEstimate>& initial_;
  WardProblemOptions options_;
  ward::Params params_;
  TireLawUncertainty tire_uncertainty_;  // the model's, with the options' correlation time
  std::vector<const EffectTerm*> effect_terms_;
  std::vector<std::string> effects_without_term_;
  std::vector<double> times_;
  std::vector<std::array<double, 2>> wheel_speeds_;
  std::vector<WheelStopTimer> stop_timers_;  // weak constraint 4's rule (WheelRestTimer) at state k
  // Per GNSS fix, once: its speed along body x at its state and sd (GnssAlong), and whether the
  // gross-outlier gate (WardProblemOptions::gnss_gate_chi2) took it.
  struct GnssFix {
    bool usable = false, admitted = true;
    double along_mps = 0.0, sd_mps = 0.0;
  };
  std::vector<GnssFix> gnss_;
  // IMU and GNSS samples attached to state k: [imu_begin_[k], imu_begin_[k + 1]), same for GNSS.
  std::vector<size_t> imu_begin_, gps_begin_, velocity_begin_, accel_bias_begin_;
  // With body_velocity_when_available: the measurements attached to a state, by available_t.
  std::vector<size_t> velocity_by_availability_;
  std::vector<size_t> velocity_state_;  // the state measurement i is attached to
  double imu_period_s_ = 0.01;
};

}  // namespace slipgraph
