// The stated-noise test (workbench/noise_scale.h) over seeds: each log of a suite run by the
// paper's filter (the workbench's front end) with every GNSS fix's sd as simulated, then
// divided by `factor`; how often each is flagged, the factor found, and any other measurement
// flagged.
//
// Run: build/bench/noise_scale_report [--suite hidden/none] [--seeds A-B] [--factor 10]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "model/model_config.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ekf_runner.h"
#include "workbench/noise_scale.h"

int main(int argc, char** argv) {
  using namespace slipgraph;  // NOLINT
  std::string suite = "hidden/none";
  unsigned long first = 1, last = 20;
  double factor = 10.0;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--suite") == 0 && has_value) {
      suite = argv[++i];
    } else if (std::strcmp(argv[i], "--seeds") == 0 && has_value &&
               std::sscanf(argv[++i], "%lu-%lu", &first, &last) == 2) {
    } else if (std::strcmp(argv[i], "--factor") == 0 && has_value) {
      factor = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "noise_scale_report: unknown argument '%s'\n", argv[i]);
      return 2;
    }
  }
  FilterRunOptions options;
  options.ekf.record_innovations = true;
  options.ekf.gnss_fading_fixes = 0.0;  // the paper's filter, as diagnose starts from
  int logs = 0, right = 0, small = 0;
  double found_factor = 0.0;
  std::vector<std::string> others;
  for (unsigned long seed = first; seed <= last; ++seed) {
    for (const sim::ScenarioRun& run : sim::ExpandScenario(suite, seed)) {
      DriveLog log = sim::Simulate(run.scenario, run.seed).log;
      const ModelConfig model = DefaultModelConfig(log.vehicle);
      for (int stated = 0; stated < 2; ++stated) {
        if (stated == 1) {
          for (GpsSample& fix : log.gps) fix.sd_v /= factor;
        }
        for (const NoiseScaleFinding& f : TestNoiseScales(RunEkf(log, model, options).stats)) {
          if (f.key != "measurement_noise.gps_sd_v") {
            if (f.significant) {
              others.push_back("seed " + std::to_string(seed) + ": " + f.key + " x" +
                               std::to_string(f.sd_scale()));
            }
            continue;
          }
          if (stated == 0) right += f.significant;
          if (stated == 1) small += f.significant, found_factor += f.sd_scale() / factor;
        }
      }
      ++logs;
    }
  }
  std::printf(
      "%s, seeds %lu-%lu, %d logs: GNSS sd as simulated flagged on %d; divided by %g "
      "flagged on %d (factor found / true, mean %.2f); other measurements flagged: %zu\n",
      suite.c_str(), first, last, logs, right, factor, small, logs > 0 ? found_factor / logs : 0.0,
      others.size());
  for (const std::string& o : others) std::printf("  %s\n", o.c_str());
  return 0;
}
