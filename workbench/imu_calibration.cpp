#include "workbench/imu_calibration.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <cassert>
#include <exception>
#include <stdexcept>
#include <vector>

#include "workbench/diagnosis.h"
#include "workbench/effect_signatures.h"

namespace slipgraph {
namespace {

// The effect's candidate on a log: its magnitude and weight (1 / sd^2), and whether its
// test finds it; untested where the test gives no sd.
struct Reading {
  double magnitude = 0.0, weight = 0.0;
  bool significant = false, tested = false;
};

Reading Read(const DriveLog& log, const ModelConfig& model, const std::string& effect,
             const DiagnosisOptions& options) {
  Reading r;
  for (const CandidateScore& c : Diagnose(log, model, options).candidates) {
    if (c.effect == effect && std::isfinite(c.magnitude) && c.magnitude_sd > 0.0) {
      r = {c.magnitude, 1.0 / (c.magnitude_sd * c.magnitude_sd), c.significant, true};
    }
  }
  return r;
}

// A half of a log: untested where it is too short for the front end to run on.
Reading ReadHalf(const DriveLog& half, const ModelConfig& model, const std::string& effect,
                 const DiagnosisOptions& options) {
  if (half.wheels.size() < 2) return Reading{};
  try {
    return Read(half, model, effect, options);
  } catch (const std::exception&) {
    return Reading{};
  }
}

// The readings' inverse-variance mean and the sum of their weights (0 for none).
struct Combined {
  double mean = std::nan("");
  double weight = 0.0;
};
Combined Combine(const std::vector<Reading>& readings) {
  Combined out;
  double weighted = 0.0;
  for (const Reading& r : readings) {
    out.weight += r.weight;
    weighted += r.weight * r.magnitude;
  }
  if (out.weight > 0.0) out.mean = weighted / out.weight;
  return out;
}

}  // namespace

bool ImuCalibrationOptions::IsValid(std::string* error) const {
  if (!(halves_level > 0.0 && halves_level < 1.0 && min_sigmas >= 0.0 && threads > 0)) {
    *error = "ImuCalibrationOptions: halves_level in (0, 1), min_sigmas >= 0, threads > 0";
    return false;
  }
  return true;
}

const std::vector<ImuCalibrationEffect>& ImuCalibrationEffects() {
  static const std::vector<ImuCalibrationEffect> kEffects = {
      {"clock_offset", &CalibrationConfig::imu_time_offset_s, "imu_time_offset",
       "IMU clock against the other streams", "s", 1000.0, "ms late", "imu_clock", "offset_s",
       "sd_s"},
      {"imu_mounting_pitch", &CalibrationConfig::imu_mounting_pitch_rad, "imu_mounting_pitch",
       "IMU mounting pitch", "rad", 1.0, "rad nose-down", "imu_mounting", "pitch_rad", "sd_rad"}};
  return kEffects;
}

const ImuCalibrationEffect& FindImuCalibrationEffect(const std::string& effect) {
  for (const ImuCalibrationEffect& e : ImuCalibrationEffects()) {
    if (effect == e.effect) return e;
  }
  throw std::invalid_argument("no IMU calibration for effect '" + effect + "'");
}

ModelConfig WithImuCalibration(const ModelConfig& model, const std::string& effect, double value) {
  ModelConfig out = model;
  out.calibration.*FindImuCalibrationEffect(effect).field += value;
  return out;
}

ImuCalibrationReading EstimateImuCalibration(const std::vector<DriveLog>& logs,
                                             const ModelConfig& model, const std::string& effect,
                                             const ImuCalibrationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  FindImuCalibrationEffect(effect);  // throws for an effect it does not read
  EffectRegistry effect_only;
  const EffectSignature* signature = EffectRegistry::Catalogue().FindSignature(effect);
  assert(signature != nullptr);  // the catalogue's own signature
  effect_only.Add(*signature);
  DiagnosisOptions diagnosis;
  diagnosis.effects = &effect_only;
  diagnosis.fit_candidates = 0;
  diagnosis.threads = options.threads;
  diagnosis.smoother.filter.use_gps = options.use_gps;
  ModelConfig plain = model;
  plain.effects.clear();  // the registry has no terms
  plain.effect_windows.clear();

  ImuCalibrationReading out;
  std::vector<Reading> wholes, halves;
  for (const DriveLog& raw : logs) {
    if (raw.wheels.size() < 2) continue;
    DriveLog log = raw;
    ApplyCalibration(plain, &log);
    const Reading whole = Read(log, plain, effect, diagnosis);
    if (!whole.tested) continue;
    wholes.push_back(whole);
    out.significant_logs += whole.significant ? 1 : 0;
    const double middle = 0.5 * (log.wheels.front().t + log.wheels.back().t);
    for (const DriveLog& half : {SliceLog(log, -1e300, middle), SliceLog(log, middle, 1e300)}) {
      const Reading r = ReadHalf(half, plain, effect, diagnosis);
      if (r.tested) halves.push_back(r);
    }
  }
  out.logs = static_cast<int>(wholes.size());
  const Combined combined = Combine(wholes);
  if (combined.weight > 0.0) {
    out.value = combined.mean;
    out.sd = 1.0 / std::sqrt(combined.weight);
  }
  out.halves = static_cast<int>(halves.size());
  if (halves.size() >= 2) {
    const double mean = Combine(halves).mean;
    out.heterogeneity = 0.0;
    for (const Reading& r : halves) {
      out.heterogeneity += r.weight * (r.magnitude - mean) * (r.magnitude - mean);
    }
    const boost::math::chi_squared chi2(static_cast<double>(halves.size() - 1));
    out.heterogeneity_p = boost::math::cdf(boost::math::complement(chi2, out.heterogeneity));
    out.halves_agree = out.heterogeneity_p >= options.halves_level;
  }
  out.taken = out.significant_logs > 0 && out.halves_agree &&
              std::abs(out.value) > options.min_sigmas * out.sd;
  return out;
}

}  // namespace slipgraph
