#include "workbench/imu_clock_offset.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <stdexcept>

#include "workbench/diagnosis.h"
#include "workbench/effect_signatures.h"

namespace slipgraph {

ImuClockOffset EstimateImuClockOffset(const std::vector<DriveLog>& logs, const ModelConfig& model,
                                      int threads) {
  EffectRegistry clock_only;
  const EffectSignature* signature = EffectRegistry::Catalogue().FindSignature("clock_offset");
  if (signature == nullptr) throw std::logic_error("the catalogue has no clock_offset signature");
  clock_only.Add(*signature);
  DiagnosisOptions options;
  options.effects = &clock_only;
  options.fit_candidates = 0;
  options.threads = threads;
  ModelConfig plain = model;
  plain.effects.clear();  // the registry has no terms
  plain.effect_windows.clear();
  // The clock_offset candidate's magnitude and sd on a log, and whether its test finds it.
  struct Reading {
    double magnitude = 0.0, weight = 0.0;
    bool significant = false, tested = false;
  };
  const auto read = [&](const DriveLog& log) {
    Reading r;
    for (const CandidateScore& c : Diagnose(log, plain, options).candidates) {
      if (c.effect != "clock_offset" || !(c.magnitude_sd > 0.0)) continue;
      r = {c.magnitude, 1.0 / (c.magnitude_sd * c.magnitude_sd), c.significant, true};
    }
    return r;
  };
  ImuClockOffset out;
  double weight_sum = 0.0, weighted = 0.0;
  std::vector<Reading> halves;
  for (const DriveLog& raw : logs) {
    if (raw.wheels.size() < 2) continue;
    DriveLog log = raw;
    ApplyCalibration(plain, &log);
    const Reading whole = read(log);
    if (!whole.tested) continue;
    ++out.logs;
    out.significant_logs += whole.significant ? 1 : 0;
    weight_sum += whole.weight;
    weighted += whole.weight * whole.magnitude;
    const double middle = 0.5 * (log.wheels.front().t + log.wheels.back().t);
    for (const DriveLog& half : {SliceLog(log, -1e300, middle), SliceLog(log, middle, 1e300)}) {
      const Reading r = read(half);
      if (r.tested) halves.push_back(r);
    }
  }
  if (weight_sum > 0.0) {
    out.offset_s = weighted / weight_sum;
    out.sd_s = 1.0 / std::sqrt(weight_sum);
  }
  // The halves about their own combination.
  double half_weights = 0.0, half_weighted = 0.0;
  for (const Reading& r : halves) half_weights += r.weight, half_weighted += r.weight * r.magnitude;
  if (halves.size() > 1) {
    const double mean = half_weighted / half_weights;
    for (const Reading& r : halves) {
      out.heterogeneity += r.weight * (r.magnitude - mean) * (r.magnitude - mean);
    }
    const boost::math::chi_squared chi2(static_cast<double>(halves.size() - 1));
    out.heterogeneity_p = boost::math::cdf(boost::math::complement(chi2, out.heterogeneity));
    out.halves = static_cast<int>(halves.size());
  }
  return out;
}

}  // namespace slipgraph
