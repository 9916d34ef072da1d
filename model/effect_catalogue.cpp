#include "model/effect_catalogue.h"

namespace slipgraph {

const std::vector<EffectInfo>& EffectCatalogue() {
  static const std::vector<EffectInfo> kCatalogue = {
      {"gps_velocity_averaging", 1.0, "fix intervals",
       "GNSS velocity is the mean over the previous fix interval (the position difference), as "
       "the Garmin receiver of Ward & Iagnemma did, so it lags truth by half an interval.",
       "GNSS-velocity residuals correlate with acceleration (negative while accelerating), and "
       "shifting the GNSS stamps back by half an interval whitens them.",
       true},
      {"wheel_radius_error", 0.05, "fraction",
       "The effective rolling radius is nominal x (1 + value): encoders over- or under-report "
       "ground speed in proportion to speed.",
       "Wheel and GNSS-velocity residuals grow linearly with speed with one sign; a constant "
       "apparent slip at steady speed on hard ground.",
       true},
      {"imu_mounting_pitch", 0.03, "rad",
       "The IMU is mounted pitched nose-down by value about body y: gravity leaks into the x "
       "accelerometer as g sin(value) and x acceleration into z.",
       "A constant accelerometer-x residual at rest that the constant-offset EMA absorbs, which "
       "then varies with terrain pitch as cos(pitch) changes; residual scales with g cos(pitch).",
       true},
      {"slope_slip", 4.0, "1/rad",
       "On a slope the traction coefficient C1 drops by a factor (1 - value |phi|), phi the grade "
       "angle (looser footing on inclines).",
       "Slip and disturbance residuals that appear on slopes only and grow with |grade|.", true},
      {"turn_slip", 0.15, "s/rad",
       "Turning scrubs the tires: an extra resistive force value x m g x |yaw rate| along body x, "
       "smoothed at zero speed.",
       "Disturbance/acceleration residuals proportional to |yaw rate| during turns, none when "
       "driving straight.",
       true},
      {"sinkage_resistance", 0.08, "fraction of weight",
       "Compaction resistance in soft terrain (mud, soft dirt, mulch): value x m g opposing "
       "motion, ramping in with sinkage.",
       "A persistent negative disturbance on soft terrain patches that vanishes on hard ground.",
       true},
      {"quadratic_drag", 40.0, "N s^2/m^2",
       "Aerodynamic / vegetation drag, value x v |v| opposing motion.",
       "Acceleration residuals proportional to v^2: small at low speed, large at top speed.", true},
      {"load_transfer", 1.0, "scale",
       "Longitudinal load transfer: the front normal forces change by -value x m a h / (a + b) "
       "under body acceleration a (the default model neglects acceleration in eqs. 3-5).",
       "Traction residuals correlated with longitudinal acceleration: too much modelled traction "
       "while accelerating, too little while braking.",
       true},
      {"terrain_change", 0.6, "C1 factor",
       "Halfway through the log the terrain's tire coefficients C1 and C2 are scaled by value "
       "(e.g. from hard soil to loose gravel).",
       "Residuals that are white before one moment and biased after it: a change point.", true},
      {"clock_offset", 0.05, "s",
       "IMU time stamps are late by value relative to the encoders (an unsynchronised clock).",
       "Accelerometer and gyro residuals correlated with the derivative of acceleration and yaw "
       "rate; cross-correlation of IMU and wheel signals peaks at a nonzero lag.",
       true},
      {"corrugation", 0.6, "m/s^2",
       "Washboard terrain: a periodic longitudinal force of amplitude value x m with a 0.8 m "
       "wavelength along the path. Deliberately outside the model catalogue.",
       "Periodic disturbance/acceleration residuals at a spatial frequency of 1/0.8 m.", false},
  };
  return kCatalogue;
}

const EffectInfo* FindEffect(const std::string& name) {
  for (const EffectInfo& effect : EffectCatalogue()) {
    if (effect.name == name) return &effect;
  }
  return nullptr;
}

}  // namespace slipgraph
