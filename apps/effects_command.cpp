// `slipgraph effects`: the catalogue of physical effects (model/effect_catalogue.h): the names
// `diagnose` tests, `diagnose --with` adds and `simulate --effect` switches on.
#include <iostream>

#include "apps/commands.h"
#include "apps/json_output.h"
#include "model/effect_catalogue.h"
#include "workbench/diagnosis.h"

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
    nlohmann::json effects = nlohmann::json::array();
    for (const EffectInfo& e : EffectCatalogue()) {
      const bool can_add = CanAddEffect(e.name);
      text << e.name << " (default " << e.default_value << " " << e.unit << ")"
           << (e.in_model_catalogue ? "" : ", not a diagnose candidate")
           << (can_add ? ", diagnose --with adds it" : "") << "\n"
           << "  physics: " << e.physics << "\n"
           << "  evidence: " << e.evidence << "\n";
      effects.push_back({{"name", e.name},
                         {"default_value", e.default_value},
                         {"unit", e.unit},
                         {"physics", e.physics},
                         {"evidence", e.evidence},
                         {"candidate", e.in_model_catalogue},
                         {"can_add", can_add}});
    }
    if (options->json.enabled()) options->json.Write({{"effects", effects}});
    *status = 0;
  });
}

}  // namespace slipgraph
