#include "solvers/identification_json.h"

#include <cmath>
#include <vector>

#include "evaluation/json_number.h"

namespace slipgraph {

nlohmann::json ToJson(const ModelScore& s) {
  return {{"gnss_fixes", s.gnss_fixes},
          {"gnss_nis_mean", JsonNumber(s.gnss_nis_mean)},
          {"flagged_fraction", s.flagged_fraction},
          {"velocity_rmse_mps", JsonNumber(s.velocity_rmse)},
          {"false_immobilized_fraction", JsonNumber(s.false_immobilized_fraction)},
          {"prediction_2s",
           {{"spans", s.prediction_spans},
            {"reference", s.prediction_spans == 0     ? "none"
                          : s.prediction_against_pose ? "pose"
                                                      : "gnss"},
            {"rms_m", JsonNumber(s.prediction_rms_m)},
            {"mean_m", JsonNumber(s.prediction_mean_m)},
            {"mean_se_m", JsonNumber(s.prediction_mean_se_m)},
            {"distance_m", JsonNumber(s.prediction_distance_m)},
            {"floor_m", JsonNumber(s.prediction_floor_m)}}}};
}

nlohmann::json ToJson(const IdentificationResult& r) {
  nlohmann::json j;
  for (const IdentifiedParameter& p : r.parameters) {
    j["parameters"].push_back({{"name", p.name},
                               {"nominal", p.nominal},
                               {"value", p.value},
                               {"sd", JsonNumber(p.sd)},
                               {"prior_sd", p.prior_sd},
                               {"identified", std::isfinite(p.sd) && p.identified()},
                               {"at_bound", p.at_bound}});
  }
  for (int i = 0; i < r.correlation.rows(); ++i) {
    std::vector<nlohmann::json> row;
    for (int k = 0; k < r.correlation.cols(); ++k) row.push_back(JsonNumber(r.correlation(i, k)));
    j["correlation"].push_back(row);
  }
  for (const NoiseEstimate& e : r.noise) {
    j["noise"].push_back({{"name", e.name},
                          {"nominal", e.nominal},
                          {"value", e.value},
                          {"samples", e.samples},
                          {"method", e.method}});
  }
  const WheelClockReading& c = r.wheel_clock;
  j["wheels_clock"] = {{"lag_s", JsonNumber(c.lag_s)},
                       {"sd_s", JsonNumber(c.sd_s)},
                       {"correlation", JsonNumber(c.correlation)},
                       {"correlation_at_zero", JsonNumber(c.correlation_at_zero)},
                       {"samples", c.samples},
                       {"parts", c.blocks},
                       {"taken", c.taken},
                       {"wheels_time_offset_s", r.model.calibration.wheels_time_offset_s}};
  j["effective_track_m"] = JsonNumber(r.effective_track_m);
  j["gnss_radius_error"] = {{"value", JsonNumber(r.gnss_radius_error)},
                            {"sd", JsonNumber(r.gnss_radius_error_sd)},
                            {"fixes", r.gnss_radius_fixes}};
  j["falling_branch_refused"] = r.falling_branch_refused;
  for (const auto& offsets : r.offsets) {
    j["imu_offsets"].push_back({{"accel_x_mps2", offsets[0]}, {"gyro_z_radps", offsets[1]}});
  }
  j["converged"] = r.converged;
  j["iterations"] = r.summary.iterations.size();
  j["notes"] = r.notes;
  return j;
}

}  // namespace slipgraph
