// The workbench's ranking over noise seeds (issue 6's Monte Carlo): for each catalogue effect
// hidden in the `hidden` scenario, and for nothing hidden, over N seeds, how often the hidden
// effect ranks first (and first and significant), how often anything at all is significant, and the
// mean and sd of the top candidate's fitted magnitude, and how often the verdict is "no candidate
// explains it". Prints a table (docs/workbench.md).
// Run: build/bench/diagnose_monte_carlo [--parameters] [--mismatch] [--gnss-fading] [SEEDS=20]
//      [EFFECT...]
// --parameters: "a parameter of the model is off" as candidates too (diagnose --parameters);
// --mismatch: the hiddenm suites (docs/mismatch.md) instead of hidden.
// --gnss-fading: the smoother starts from the default front end (GNSS fading memory), not from
// the paper's filter that DiagnosisOptions starts it from.
// --known-averaging: with --mismatch, every log's GNSS velocity averaging (one fix interval, an
// ingredient of the suite) corrected before the diagnosis, as a user who knows the receiver does
// (diagnose's measurement correction; not a candidate then);
// --varying-law P,N,W: the null model's tire law varies along the path (diagnose --varying-law;
// DiagnosisOptions::varying_law_*: prior sd P, nodes every N s, walk density W), for choosing
// them on seeds the figures are not reported on.
//
// With --detectable first: the minimum detectable magnitudes checked. For each effect and seed,
// the diagnosis of the drive with nothing hidden states the effect's detectable magnitude D
// (CandidateScore::detectable: significant with 80 % power); the same drive and seed is then
// simulated with the effect at D (the catalogue's sign) and diagnosed. If D is right, the effect
// is significant on about 80 % of seeds. --scale F hides it at F x D instead (the power curve).
// Run: build/bench/diagnose_monte_carlo --detectable [--scale F] [--parameters] [--gnss-fading]
//      [SEEDS=20] [EFFECT...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "model/effect_catalogue.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ward_ekf.h"
#include "workbench/diagnosis.h"

namespace {

using namespace slipgraph;  // NOLINT

const CandidateScore* Candidate(const Diagnosis& d, const std::string& effect) {
  for (const CandidateScore& c : d.candidates) {
    if (c.effect == effect) return &c;
  }
  return nullptr;
}

// The diagnosis of a log whose GNSS velocity is known to average over one fix interval: the
// averaging corrected in the log first (AddEffects with that magnitude), then not a candidate.
Diagnosis DiagnoseAveragingKnown(const DriveLog& log, DiagnosisOptions options) {
  Diagnosis known;
  CandidateScore averaging;
  averaging.effect = "gps_velocity_averaging";
  averaging.magnitude = 1.0;
  known.candidates.push_back(averaging);
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  const ExtendedModel corrected = AddEffects(log, model, known, {averaging.effect});
  options.corrected = corrected.corrected;
  return Diagnose(corrected.log, corrected.model, options);
}

int CheckDetectable(int seeds, double scale, std::vector<std::string> effects,
                    const DiagnosisOptions& options) {
  if (effects.empty()) {
    for (const EffectInfo& e : EffectCatalogue()) {
      if (e.in_model_catalogue) effects.push_back(e.name);
    }
  }
  std::printf(
      "| effect | seeds | detectable magnitude D, median (range) | significant at %g D | "
      "top-1 and significant |\n|---|---|---|---|---|\n",
      scale);
  for (const std::string& effect : effects) {
    const EffectInfo* info = FindEffect(effect);
    if (info == nullptr) {
      std::fprintf(stderr, "unknown effect '%s'\n", effect.c_str());
      return 2;
    }
    std::vector<double> detectable;
    int significant = 0, top1 = 0, tried = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      sim::ScenarioRun run = sim::ExpandScenario("hidden/none", seed).at(0);
      const DriveLog null_log = sim::Simulate(run.scenario, run.seed).log;
      const Diagnosis null_d = Diagnose(null_log, DefaultModelConfig(null_log.vehicle), options);
      const CandidateScore* c = Candidate(null_d, effect);
      if (c == nullptr || !std::isfinite(c->detectable)) continue;
      detectable.push_back(c->detectable);
      run.scenario.effects[effect] = std::copysign(scale * c->detectable, info->default_value);
      const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
      const Diagnosis d = Diagnose(log, DefaultModelConfig(log.vehicle), options);
      ++tried;
      const CandidateScore* found = Candidate(d, effect);
      significant += found != nullptr && found->significant;
      top1 += !d.candidates.empty() && d.candidates.front().effect == effect &&
              d.candidates.front().significant;
    }
    std::sort(detectable.begin(), detectable.end());
    char range[96] = "-";
    if (!detectable.empty()) {
      std::snprintf(range, sizeof(range), "%.3g (%.3g-%.3g)", detectable[detectable.size() / 2],
                    detectable.front(), detectable.back());
    }
    std::printf("| %s | %d | %s | %d/%d | %d/%d |\n", effect.c_str(), tried, range, significant,
                tried, top1, tried);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv_in) {
  // The flags, anywhere; the rest are the positional arguments.
  bool parameters = false, mismatch = false, fading = false, known_averaging = false;
  double varying_law[3] = {0.0, 0.0, 0.0};
  std::vector<char*> args = {argv_in[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv_in[i];
    if (a == "--parameters") {
      parameters = true;
    } else if (a == "--mismatch") {
      mismatch = true;
    } else if (a == "--gnss-fading") {
      fading = true;
    } else if (a == "--known-averaging") {
      known_averaging = true;
    } else if (a == "--varying-law" && i + 1 < argc) {
      if (std::sscanf(argv_in[++i], "%lf,%lf,%lf", &varying_law[0], &varying_law[1],
                      &varying_law[2]) != 3) {
        std::fprintf(stderr, "diagnose_monte_carlo: --varying-law PRIOR,NODE_S,WALK\n");
        return 2;
      }
    } else {
      args.push_back(argv_in[i]);
    }
  }
  argc = static_cast<int>(args.size());
  char** argv = args.data();
  DiagnosisOptions options;
  if (fading) options.smoother.filter.ekf.gnss_fading_fixes = kGnssFadingFixes;
  if (varying_law[0] > 0.0) {
    options.varying_law_prior_sd = varying_law[0];
    options.varying_law_node_s = varying_law[1];
    options.varying_law_walk_sd = varying_law[2];
  }
  options.effects =
      parameters ? &EffectRegistry::CatalogueWithParameters() : &EffectRegistry::Catalogue();
  const std::string suite = mismatch ? "hiddenm/" : "hidden/";
  const bool check_detectable = argc > 1 && std::string(argv[1]) == "--detectable";
  const bool scaled = check_detectable && argc > 3 && std::string(argv[2]) == "--scale";
  const double scale = scaled ? std::atof(argv[3]) : 1.0;
  const int first = check_detectable ? (scaled ? 4 : 2) : 1;
  const int seeds = argc > first ? std::atoi(argv[first]) : 20;
  std::vector<std::string> effects;
  for (int i = first + 1; i < argc; ++i) effects.push_back(argv[i]);
  if (check_detectable) return CheckDetectable(seeds, scale, effects, options);
  if (effects.empty()) {
    effects.push_back("none");
    for (const EffectInfo& e : EffectCatalogue()) {
      // Every mismatch log averages its GNSS velocity: hiddenm has no log of that name.
      if (!(mismatch && e.name == "gps_velocity_averaging")) effects.push_back(e.name);
    }
  }
  std::printf(
      "| hidden | seeds | top-1 | top-1 and significant | any significant | top candidate (most "
      "often) | its magnitude mean +- sd | true magnitude | unexplained "
      "|\n|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& effect : effects) {
    int ranked_first = 0, top1 = 0, any = 0, unexplained = 0;
    std::vector<double> magnitudes;
    std::string most;
    std::vector<std::pair<std::string, int>> counts;
    for (int seed = 1; seed <= seeds; ++seed) {
      const sim::ScenarioRun run = sim::ExpandScenario(suite + effect, seed).at(0);
      const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
      const Diagnosis d = known_averaging ? DiagnoseAveragingKnown(log, options)
                                          : Diagnose(log, DefaultModelConfig(log.vehicle), options);
      unexplained += !d.explained;
      if (d.candidates.empty()) continue;
      const CandidateScore& top = d.candidates.front();
      ranked_first += top.effect == effect;
      if (top.significant) {
        ++any;
        auto it = std::find_if(counts.begin(), counts.end(),
                               [&](const auto& c) { return c.first == top.effect; });
        if (it == counts.end())
          counts.push_back({top.effect, 1});
        else
          ++it->second;
      }
      if (top.effect == effect && top.significant) {
        ++top1;
        magnitudes.push_back(top.magnitude);
      }
    }
    int best = 0;
    for (const auto& [name, n] : counts) {
      if (n > best) best = n, most = name;
    }
    double mean = 0.0, sq = 0.0;
    for (double m : magnitudes) mean += m;
    if (!magnitudes.empty()) mean /= magnitudes.size();
    for (double m : magnitudes) sq += (m - mean) * (m - mean);
    const double sd = magnitudes.size() > 1 ? std::sqrt(sq / (magnitudes.size() - 1)) : 0.0;
    const EffectInfo* info = FindEffect(effect);
    std::printf(
        "| %s | %d | %d/%d | %d/%d | %d/%d | %s | %s | %s | %d/%d |\n", effect.c_str(), seeds,
        ranked_first, seeds, top1, seeds, any, seeds, most.empty() ? "-" : most.c_str(),
        magnitudes.empty() ? "-" : (std::to_string(mean) + " +- " + std::to_string(sd)).c_str(),
        info ? std::to_string(info->default_value).c_str() : "0", unexplained, seeds);
    std::fflush(stdout);
  }
  return 0;
}
