#include "workbench/diagnosis_json.h"

#include "evaluation/json_number.h"
#include "model/effect_catalogue.h"

namespace slipgraph {

nlohmann::json ToJson(const Diagnosis& d) {
  nlohmann::json j;
  j["log"] = d.log;
  j["model_effects"] = d.model_effects;
  j["streams"] = nlohmann::json::object();
  for (const StreamReport& s : d.streams) {
    j["streams"][s.name] = {{"samples", s.samples},
                            {"rms", s.rms},
                            {"chi_square_p", s.chi_square_p},
                            {"consistent", s.consistent},
                            {"ljung_box_q", s.whiteness.q},
                            {"whiteness_p", s.whiteness.p_value},
                            {"white", s.white}};
  }
  j["filter"] = nlohmann::json::object();
  for (const InnovationReport& f : d.filter) {
    j["filter"][f.name] = {{"updates", f.updates},
                           {"nis_mean", f.nis_mean},
                           {"inside_95", f.inside_95},
                           {"ljung_box_q", f.whiteness.q},
                           {"whiteness_p", f.whiteness.p_value},
                           {"white", f.white}};
  }
  j["noise_scales"] = nlohmann::json::array();
  for (const NoiseScaleFinding& f : d.noise_scales) {
    j["noise_scales"].push_back({{"key", f.key},
                                 {"measurements", f.measurements},
                                 {"updates", f.updates},
                                 {"nis_mean", f.nis_mean},
                                 {"sd_scale", f.sd_scale()},
                                 {"statistic", f.statistic},
                                 {"p_value", f.p_value},
                                 {"significant", f.significant}});
  }
  j["failures"] = nlohmann::json::array();
  for (const FailureSegment& f : d.failures) {
    j["failures"].push_back({{"t_start", f.t_start},
                             {"t_end", f.t_end},
                             {"streams", f.streams},
                             {"speed_mps", f.speed_mps},
                             {"abs_pitch_rad", f.abs_pitch_rad},
                             {"abs_yaw_rate_radps", f.abs_yaw_rate_radps}});
  }
  j["candidates"] = nlohmann::json::array();
  for (const CandidateScore& c : d.candidates) {
    nlohmann::json cj = {{"effect", c.effect},
                         {"statistic", c.statistic},
                         {"dof", c.dof},
                         {"p_value", c.p_value},
                         {"significant", c.significant},
                         {"magnitude", c.magnitude},
                         {"magnitude_sd", c.magnitude_sd},
                         {"detectable", JsonNumber(c.detectable)},
                         {"plausible", c.implausible.empty()},
                         {"implausible", c.implausible},
                         {"test", c.test},
                         {"added_as", c.added_as}};
    if (!c.where.empty()) cj["where"] = c.where;
    if (c.fitted) {
      cj["fit"] = {
          {"likelihood_ratio", c.likelihood_ratio}, {"dispersion", c.dispersion},
          {"score_statistic", c.score_statistic},   {"score_p_value", c.score_p_value},
          {"score_magnitude", c.score_magnitude},   {"score_magnitude_sd", c.score_magnitude_sd}};
    }
    j["candidates"].push_back(cj);
  }
  j["explained"] = d.explained;
  if (d.path_force.tested) {
    nlohmann::json pf;
    pf["metre"] = d.path_force.metre;
    pf["statistic"] = d.path_force.statistic;
    pf["dof"] = d.path_force.dof;
    pf["p_value"] = d.path_force.p_value;
    if (!d.path_force.after_effect.empty()) {
      pf["after_effect"] = d.path_force.after_effect;
      pf["after_statistic"] = d.path_force.after_statistic;
      pf["after_dof"] = d.path_force.after_dof;
      pf["after_p_value"] = d.path_force.after_p_value;
    }
    j["path_force"] = pf;
  }
  j["corrected_effects"] = nlohmann::json::array();
  for (const EffectEstimate& e : d.corrected) {
    j["corrected_effects"].push_back({{"effect", e.name}, {"value", e.value}, {"sd", e.sd}});
  }
  j["fitted_effects"] = nlohmann::json::array();
  for (const EffectEstimate& e : d.fitted_effects) {
    j["fitted_effects"].push_back({{"effect", e.name}, {"value", e.value}, {"sd", e.sd}});
  }
  if (d.truth.available) {
    j["truth"] = {{"velocity_rmse", d.truth.velocity_rmse},
                  {"disturbance_rmse", d.truth.disturbance_rmse}};
  }
  j["used_fallback"] = d.used_fallback;
  j["trusted"] = d.trust.trusted;
  j["trust_warnings"] = d.trust.warnings;
  j["notes"] = d.notes;
  return j;
}

nlohmann::json EffectCatalogueJson() {
  const EffectRegistry& registry = EffectRegistry::Catalogue();
  nlohmann::json effects = nlohmann::json::array();
  for (const EffectInfo& e : EffectCatalogue()) {
    effects.push_back({{"name", e.name},
                       {"default_value", e.default_value},
                       {"unit", e.unit},
                       {"physics", e.physics},
                       {"evidence", e.evidence},
                       {"candidate", e.in_model_catalogue},
                       {"model_parameter", false},
                       {"can_add", registry.CanAdd(e.name)}});
  }
  // Model terms the simulator has no effect for (a model parameter off: diagnose --parameters
  // tests those).
  for (const EffectTerm& term : registry.terms().all()) {
    if (FindEffect(term.name) != nullptr) continue;
    effects.push_back({{"name", term.name},
                       {"default_value", nullptr},
                       {"unit", term.unit},
                       {"physics", term.physics},
                       {"evidence", ""},
                       {"candidate", !term.model_parameter},
                       {"model_parameter", term.model_parameter},
                       {"can_add", true}});
  }
  return effects;
}

}  // namespace slipgraph
