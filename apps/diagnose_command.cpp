// `slipgraph diagnose`: the model workbench. Smooths the log with the model, shows each stream's
// residuals against the model (RMS, chi-square consistency, whiteness), the segments where they
// fail, and the catalogue effects not in the model ranked by robust score tests. With `--with
// EFFECT`, the same report after switching the effects on, and the change (against truth when the
// log has it, always in residual terms).
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "apps/commands.h"
#include "apps/diagnosis_report.h"
#include "apps/estimator_runs.h"
#include "apps/json_output.h"
#include "apps/suite_runs.h"
#include "io/log_reader.h"
#include "io/text_file.h"
#include "io/yaml_config.h"
#include "model/effect_catalogue.h"
#include "workbench/diagnosis.h"
#include "workbench/diagnosis_series.h"
#include "workbench/effect_signatures.h"

namespace slipgraph {

void RegisterDiagnoseCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log, model, report, series;
    JsonOutput json;
    std::vector<std::string> with;
    bool no_gps = false, add_best = false, parameters = false;
    ReadOptions read;  // --skip-bad, --max-bad
    DiagnosisOptions diagnosis;
    SuiteOptions suite;  // --jobs, --keep-going
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app->add_subcommand(
      "diagnose",
      "Model vs measurements: residuals per stream, where the model fails, which catalogue "
      "effect is missing; --with EFFECT adds one and shows the change");
  cmd->add_option("LOG", options->log,
                  "Log or suite directory (default: the bundled hidden-effect log, "
                  "data/hidden_clock_offset)")
      ->check(NonEmptyPath());
  cmd->add_option("--model", options->model, "Model YAML over the vehicle's nominal model");
  cmd->add_option("--with", options->with,
                  "Switch a catalogue effect on in the model and report before and after "
                  "(repeatable): " +
                      EffectRegistry::CatalogueWithParameters().Names());
  cmd->add_flag("--add-best", options->add_best,
                "The whole loop: add the top-ranked significant candidate (if the smoother has a "
                "term or a correction for it) and report before and after");
  cmd->add_option("--report", options->report, "Write a self-contained HTML report");
  cmd->add_option("--series", options->series,
                  "Write the series behind the statistics to this directory (a suite: one "
                  "folder per log): per stream the smoother's normalized residuals "
                  "(residual_<stream>.csv: t, normalized, sd) and the front end's normalized "
                  "innovations (innovation_<stream>.csv: t, normalized)");
  options->json.Add(cmd);
  AddSuiteOptions(cmd, &options->suite);
  cmd->add_option("--alpha", options->diagnosis.alpha,
                  "Family-wise significance level of the tests")
      ->capture_default_str();
  cmd->add_option("--threads", options->diagnosis.threads,
                  "Candidates tested and fitted at once (the result does not depend on it)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--no-gps", options->no_gps, "Ignore GNSS");
  cmd->add_flag("--parameters", options->parameters,
                "Also test whether a parameter of the model is off: the tire law's traction level "
                "and slip stiffness, the rolling resistance");
  cmd->add_option("--varying-law", options->diagnosis.varying_law_prior_sd,
                  "A null model whose tire law varies slowly along the path (its slip stiffness "
                  "as a walk with this prior sd; nodes every 20 s): a patch of softer soil is "
                  "then not read as an effect; 0: the law as given")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  AddReadOptions(cmd, &options->read);
  cmd->callback([options, status]() {
    for (const std::string& effect : options->with) {
      if (FindEffect(effect) == nullptr &&
          EffectRegistry::CatalogueWithParameters().FindSignature(effect) == nullptr) {
        throw CLI::ValidationError(
            "--with", "unknown effect '" + effect +
                          "' (known: " + EffectRegistry::CatalogueWithParameters().Names() + ")");
      }
    }
    const EffectRegistry& registry = options->parameters ? EffectRegistry::CatalogueWithParameters()
                                                         : EffectRegistry::Catalogue();
    DiagnosisOptions diagnosis = options->diagnosis;
    diagnosis.smoother.filter.use_gps = !options->no_gps;
    diagnosis.effects = &registry;
    const std::string path = options->log.empty() ? DefaultHiddenEffectLogPath() : options->log;
    std::ostream& text = options->json.text();
    const std::vector<std::string> logs = ListLogs(path);
    // Per log: its JSON, its significant top candidate ("" for none) and whether its failures
    // were explained; the page is the first log's.
    std::vector<nlohmann::json> per_log(logs.size());
    std::vector<std::string> top(logs.size());
    std::vector<char> explained(logs.size(), 1);
    std::optional<HtmlReport> report;
    const std::vector<LogFailure> failures = RunOverLogs(
        logs, options->suite,
        [&](size_t i, std::ostream& out, std::ostream& err) {
          const std::string& log_dir = logs[i];
          DriveLog log = ReadLogWithWarnings(log_dir, options->read, err);
          const ModelConfig model = ModelForLog(&log, options->model);
          const Diagnosis before = Diagnose(log, model, diagnosis);
          PrintDiagnosis(before, out);
          nlohmann::json j = ToJson(before);
          if (!options->series.empty()) {
            const std::string directory = IsLogDirectory(path)
                                              ? options->series
                                              : (std::filesystem::path(options->series) /
                                                 std::filesystem::path(log_dir).filename())
                                                    .string();
            j["series"] = WriteSeries(DiagnosisSeries(before), directory);
            out << "series: " << directory << " (" << j["series"].size() << " files)\n";
          }
          std::vector<std::string> with = options->with;
          if (options->add_best && with.empty()) {
            const CandidateScore* best = BestExplanation(before.candidates);
            if (best == nullptr) {
              out << "--add-best: no significant, plausible candidate to add\n";
            } else if (!registry.CanAdd(best->effect)) {
              out << "--add-best: " << best->effect
                  << " has no smoother term or measurement correction yet\n";
            } else {
              out << "\n--add-best: adding " << best->effect << "\n";
              with.push_back(best->effect);
            }
          }
          const bool page = i == 0 && !options->report.empty();
          if (!with.empty()) {
            const ExtendedDiagnosis with_effects =
                DiagnoseWith(log, model, before, with, diagnosis);
            const Diagnosis& after = with_effects.after;
            out << "\nwith " << with.size() << " effect(s) added:\n";
            PrintDiagnosis(after, out);
            PrintComparison(before, after, out);
            j["after"] = ToJson(after);
            if (page) report = DiagnosisReport(log, before, &with_effects.extended.log, &after);
          } else if (page) {
            report = DiagnosisReport(log, before);
          }
          per_log[i] = j;
          if (const CandidateScore* best = BestExplanation(before.candidates)) {
            top[i] = best->effect;
          }
          explained[i] = before.explained;
        },
        text, std::cerr);
    // Suite totals: how often each effect was the significant top candidate, and how many logs
    // nothing explained.
    std::map<std::string, int> top_counts;
    int unexplained = 0;
    nlohmann::json all = nlohmann::json::array();
    for (const LogFailure& failure : failures) {
      per_log[failure.index] = {{"log", failure.log}, {"error", failure.error}};
    }
    for (size_t i = 0; i < logs.size(); ++i) {
      if (!per_log[i].contains("error")) {
        if (!top[i].empty()) ++top_counts[top[i]];
        unexplained += explained[i] ? 0 : 1;
      }
      all.push_back(per_log[i]);
    }
    if (all.size() > 1) {
      text << "\nsuite " << path << ": " << all.size() << " logs; significant top candidate:";
      if (top_counts.empty()) text << " none";
      for (const auto& [effect, count] : top_counts) text << " " << effect << " (" << count << ")";
      text << "; unexplained failures in " << unexplained << " log(s)\n";
    }
    if (!options->report.empty() && report) {
      report->Paragraph(options->json.RecordText());
      report->Write(options->report);
      text << "report: " << options->report << "\n";
    } else if (!options->report.empty()) {
      std::cerr << "diagnose: no report: the first log failed\n";
    }
    if (options->json.enabled()) {
      nlohmann::json out = all.size() == 1 ? all[0] : nlohmann::json{{"logs", all}};
      if (all.size() > 1) {
        out["total"] = {{"logs", all.size()},
                        {"failed", failures.size()},
                        {"top_candidates", top_counts},
                        {"unexplained", unexplained}};
      }
      options->json.Write(out);
    }
    PrintFailures("diagnose", failures, logs.size(), std::cerr);
    *status = failures.empty() ? 0 : kFailedLogsExit;
  });
}

}  // namespace slipgraph
