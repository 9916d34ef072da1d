#include <filesystem>
#include <iostream>

#include "apps/commands.h"
#include "apps/json_output.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"

namespace slipgraph {

void RegisterSimulateCommand(CLI::App* app, int* status) {
  struct Options {
    std::string scenario;
    uint64_t seed = 1;
    std::string out;
    std::vector<std::string> effects;
    JsonOutput json;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app->add_subcommand(
      "simulate", "Write simulated drive logs with ground truth (truth.csv, events.csv, sim.yaml)");
  cmd->add_option("--scenario", options->scenario, sim::ScenarioHelp())->required();
  cmd->add_option("--seed", options->seed, "Random seed (same seed, same bytes)");
  cmd->add_option("--out", options->out, "Output log directory (a suite: one folder per run)")
      ->required();
  cmd->add_option("--effect", options->effects,
                  "Switch a physical effect on, NAME or NAME=VALUE (repeatable)");
  options->json.Add(cmd);
  cmd->callback([options, status]() {
    sim::EffectSet extra;
    for (const std::string& text : options->effects) {
      std::string error;
      if (!sim::ParseEffect(text, &extra, &error)) throw CLI::ValidationError("--effect", error);
    }
    const std::vector<sim::ScenarioRun> runs =
        sim::ExpandScenario(options->scenario, options->seed);
    nlohmann::json logs = nlohmann::json::array();
    for (const sim::ScenarioRun& run : runs) {
      sim::Scenario scenario = run.scenario;
      for (const auto& [name, value] : extra) scenario.effects[name] = value;
      const std::string dir =
          (std::filesystem::path(options->out) / run.relative_directory).string();
      const sim::SimResult result = sim::Simulate(scenario, run.seed);
      sim::WriteSimulation(scenario, run.seed, result, dir);
      std::cerr << "simulate: " << scenario.name << " -> " << dir << " (" << result.log.imu.size()
                << " IMU samples, " << result.log.events.size() << " immobilized events)\n";
      logs.push_back({{"scenario", scenario.name},
                      {"seed", run.seed},
                      {"log", dir},
                      {"imu_samples", result.log.imu.size()},
                      {"events", result.log.events.size()},
                      {"effects", scenario.effects}});
    }
    if (options->json.enabled()) options->json.Write({{"logs", logs}});
    *status = 0;
  });
}

}  // namespace slipgraph
