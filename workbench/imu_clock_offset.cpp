#include "workbench/imu_clock_offset.h"

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
  ImuClockOffset out;
  double weight_sum = 0.0, weighted = 0.0;
  for (const DriveLog& raw : logs) {
    DriveLog log = raw;
    ApplyCalibration(plain, &log);
    const Diagnosis d = Diagnose(log, plain, options);
    for (const CandidateScore& c : d.candidates) {
      if (c.effect != "clock_offset" || !(c.magnitude_sd > 0.0)) continue;
      ++out.logs;
      out.significant_logs += c.significant ? 1 : 0;
      const double w = 1.0 / (c.magnitude_sd * c.magnitude_sd);
      weight_sum += w;
      weighted += w * c.magnitude;
    }
  }
  if (weight_sum > 0.0) {
    out.offset_s = weighted / weight_sum;
    out.sd_s = 1.0 / std::sqrt(weight_sum);
  }
  return out;
}

}  // namespace slipgraph
