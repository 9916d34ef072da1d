// `slipgraph effects`: the catalogue of physical effects (model/effect_catalogue.h): the names
// `diagnose` tests, `diagnose --with` adds and `simulate --effect` switches on.
#include <iostream>

#include "apps/commands.h"
#include "apps/json_output.h"
#include "workbench/diagnosis_json.h"

namespace slipgraph {

void RegisterEffectsCommand(CLI::App* app, int* status) {
  struct Options {
    JsonOutput json;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app->add_subcommand(
      "effects",
      "List the catalogue of physical effects: default magnitude, physics, the evidence of its "
      "absence, and whether diagnose tests it and --with can add it");
  options->json.Add(cmd);
  cmd->callback([options, status]() {
    std::ostream& text = options->json.text();
    const nlohmann::json effects = EffectCatalogueJson();
    for (const nlohmann::json& e : effects) {
      text << e["name"].get<std::string>() << " (";
      if (e["default_value"].is_null()) {
        text << "model term only, in " << e["unit"].get<std::string>();
      } else {
        text << "default " << e["default_value"].get<double>() << " "
             << e["unit"].get<std::string>();
      }
      text << ")"
           << (e["model_parameter"].get<bool>() ? ", a model parameter (diagnose --parameters)"
               : e["candidate"].get<bool>()     ? ""
                                                : ", not a diagnose candidate")
           << (e["can_add"].get<bool>() ? ", diagnose --with adds it" : "") << "\n"
           << "  physics: " << e["physics"].get<std::string>() << "\n";
      if (!e["evidence"].get<std::string>().empty()) {
        text << "  evidence: " << e["evidence"].get<std::string>() << "\n";
      }
    }
    if (options->json.enabled()) options->json.Write({{"effects", effects}});
    *status = 0;
  });
}

}  // namespace slipgraph
