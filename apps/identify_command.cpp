// `slipgraph identify LOG...`: the robot's model from its own logs (solvers/model_identification.h)
// fitted on the first part of each log and scored on the rest, written as a model file that
// every other subcommand takes with --model.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "apps/json_output.h"
#include "evaluation/json_number.h"
#include "io/text_file.h"
#include "io/yaml_config.h"
#include "solvers/identification_json.h"
#include "solvers/model_identification.h"
#include "workbench/imu_calibration.h"

namespace slipgraph {
namespace {

std::string Figure(double value, int precision = 3) {
  if (!std::isfinite(value)) return "-";
  std::ostringstream out;
  out << std::setprecision(precision) << value;
  return out.str();
}

void PrintScores(const std::string& name, const ModelScore& nominal, const ModelScore& fitted,
                 std::ostream& out) {
  out << "  " << name << ": GNSS NIS mean " << Figure(nominal.gnss_nis_mean) << " -> "
      << Figure(fitted.gnss_nis_mean) << " (" << fitted.gnss_fixes << " fixes), flagged "
      << Figure(100.0 * nominal.flagged_fraction) << " % -> "
      << Figure(100.0 * fitted.flagged_fraction) << " %";
  if (fitted.prediction_spans > 0) {
    out << ", 2-s prediction error against "
        << (fitted.prediction_against_pose ? "the reference pose" : "GNSS") << " RMS "
        << Figure(nominal.prediction_rms_m) << " -> " << Figure(fitted.prediction_rms_m)
        << " m, mean " << Figure(nominal.prediction_mean_m) << " -> "
        << Figure(fitted.prediction_mean_m) << " +- " << Figure(fitted.prediction_mean_se_m)
        << " m (" << fitted.prediction_spans << " spans of " << Figure(fitted.prediction_distance_m)
        << " m; the reference's stated sd alone would give " << Figure(fitted.prediction_floor_m)
        << " m)";
  }
  if (std::isfinite(fitted.velocity_rmse)) {
    out << "; against truth: v RMSE " << Figure(nominal.velocity_rmse) << " -> "
        << Figure(fitted.velocity_rmse) << " m/s, false immobilized "
        << Figure(100.0 * nominal.false_immobilized_fraction) << " % -> "
        << Figure(100.0 * fitted.false_immobilized_fraction) << " %";
  }
  out << "\n";
}

// `--clock`, `--mounting`: the workbench's test of the effect on the fitted logs
// (workbench/imu_calibration.h), said on the terminal; the model's calibration takes what it
// finds where it is told from zero and the logs' halves agree. Its JSON.
nlohmann::json ReadImuCalibration(const ImuCalibrationEffect& effect,
                                  const std::vector<DriveLog>& train,
                                  const ImuCalibrationOptions& options, ModelConfig* model,
                                  std::ostream& text) {
  const ImuCalibrationReading found = EstimateImuCalibration(train, *model, effect.effect, options);
  text << effect.title << " (the workbench's test on " << found.logs << " log(s), significant on "
       << found.significant_logs << "): ";
  if (std::isfinite(found.value)) {
    text << std::showpos << effect.display_scale * found.value << std::noshowpos << " +- "
         << effect.display_scale * found.sd << " " << effect.display_unit;
  } else {
    text << "not tested";
  }
  if (found.taken) *model = WithImuCalibration(*model, effect.effect, found.value);
  const double kept = model->calibration.*effect.field;
  if (found.taken) {
    text << "; the model's calibration." << effect.key << " takes it: " << kept << " "
         << effect.unit << "\n";
  } else if (found.significant_logs > 0 && !found.halves_agree) {
    text << "; the logs' halves do not agree (" << found.halves << " tested, Cochran's Q "
         << found.heterogeneity << ", p " << found.heterogeneity_p << "): not taken, left at "
         << kept << " " << effect.unit << "\n";
  } else {
    text << "; not told from zero, left at " << kept << " " << effect.unit << "\n";
  }
  return {{effect.json_value, JsonNumber(found.value)},
          {effect.json_sd, JsonNumber(found.sd)},
          {"logs", found.logs},
          {"significant_logs", found.significant_logs},
          {"halves", found.halves},
          {"heterogeneity", JsonNumber(found.heterogeneity)},
          {"heterogeneity_p", JsonNumber(found.heterogeneity_p)},
          {"taken", found.taken},
          {std::string(effect.key) + "_" + effect.unit, kept}};
}

}  // namespace

void RegisterIdentifyCommand(CLI::App* app, int* status) {
  struct Options {
    std::vector<std::string> logs, validate;
    std::string model, out;
    JsonOutput json;
    double train = 0.5;
    std::string part = "first";
    bool no_gps = false, clock_offset = false, mounting = false;
    ReadOptions read;  // --skip-bad, --max-bad
    IdentifyOptions identify;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app->add_subcommand(
      "identify",
      "Identify the robot's model from its logs: tire and rolling laws, wheel radii, effective "
      "track, IMU offsets, sensor noise; fitted on the first part of each log, scored on the rest");
  cmd->add_option("LOG", options->logs, "One or more logs of the same robot")
      ->check(NonEmptyPath())
      ->required();
  cmd->add_option("--model", options->model, "Model YAML to start from (default: the nominal)");
  cmd->add_option("--out", options->out, "Model YAML to write (default ./<first log>_model.yaml)");
  cmd->add_option("--train", options->train,
                  "Fraction of each log (from its start) to fit on; the rest is held out and "
                  "scored. 1: fit on everything (only --validate logs scored)")
      ->check(CLI::Range(0.05, 1.0))
      ->capture_default_str();
  cmd->add_option("--train-part", options->part,
                  "Which part of each log to fit on: the first (default) or the last --train "
                  "fraction; the other part is scored")
      ->check(CLI::IsMember({"first", "last"}))
      ->capture_default_str();
  cmd->add_option("--validate", options->validate,
                  "Further logs of the same robot, not fitted on: each scored whole (e.g. another "
                  "day's drive, with --train 1)")
      ->check(NonEmptyPath());
  cmd->add_flag("--no-gps", options->no_gps, "Leave GNSS out");
  cmd->add_flag("--fit-radius", options->identify.fit_radius,
                "Fit each side's rolling radius with the law (seen only against GNSS ground "
                "speed, where it is one with the mean slip)");
  cmd->add_flag_callback(
      "--no-wheels-clock", [options] { options->identify.wheel_clock = false; },
      "Leave the encoders' stamps as the model has them. By default how late they are against "
      "the IMU's is read from the yaw channel (the sides' speed difference against the gyro) and "
      "the model's calibration.wheels_time_offset takes it where it is told from zero and at "
      "least 50 ms (solvers/wheel_clock.h)");
  cmd->add_flag("--clock", options->clock_offset,
                "First, how late the IMU's stamps are against the other streams': the "
                "workbench's clock_offset test on each fitted log and on its two halves (three "
                "batch solves a log); the model's calibration.imu_time_offset takes it where it "
                "is told from zero and the halves agree");
  cmd->add_flag("--mounting", options->mounting,
                "First, how far the IMU is pitched nose-down on the body: the workbench's "
                "imu_mounting_pitch test, as --clock; the model's calibration.imu_mounting_pitch "
                "takes it where it is told from zero and the halves agree");
  cmd->add_option("--threads", options->identify.threads, "Solver threads")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  AddReadOptions(cmd, &options->read);
  options->json.Add(cmd);
  cmd->callback([options, status]() {
    namespace fs = std::filesystem;
    std::vector<DriveLog> train, held_out;
    std::vector<std::string> held_out_names;
    ModelConfig model;
    for (size_t i = 0; i < options->logs.size(); ++i) {
      const DriveLog log = ReadLogWithWarnings(options->logs[i], options->read);
      if (i == 0) {
        model = ReadModelOrNominal(options->model, log.vehicle);
      }
      if (log.wheels.size() < 2) {
        std::cerr << "identify: " << options->logs[i] << ": no wheel data\n";
        *status = 1;
        return;
      }
      const double t0 = log.wheels.front().t, t1 = log.wheels.back().t;
      const bool first = options->part == "first";
      const double fraction = first ? options->train : 1.0 - options->train;
      if (options->train >= 1.0) {
        train.push_back(log);
        continue;
      }
      const double split = t0 + fraction * (t1 - t0);
      DriveLog before = SliceLog(log, -1e300, split), after = SliceLog(log, split, 1e300);
      train.push_back(first ? before : after);
      held_out.push_back(first ? after : before);
      held_out_names.push_back(options->logs[i]);
    }
    for (const std::string& path : options->validate) {
      DriveLog log = ReadLogWithWarnings(path, options->read);
      if (log.wheels.size() < 2) {
        std::cerr << "identify: " << path << ": no wheel data\n";
        *status = 1;
        return;
      }
      if (!train.empty() && log.vehicle.name != train.front().vehicle.name) {
        std::cerr << "identify: warning: " << path << " is vehicle '" << log.vehicle.name
                  << "', the fitted logs '" << train.front().vehicle.name
                  << "': scored with their model all the same\n";
      }
      held_out.push_back(std::move(log));
      held_out_names.push_back(path + " (whole)");
    }
    options->identify.use_gps = !options->no_gps;
    std::cerr << "identify: fitting on " << train.size() << " log(s)"
              << (options->train < 1.0 ? " (the " + options->part + " " +
                                             Figure(100.0 * options->train) + " % of each)"
                                       : "")
              << "\n";
    std::ostream& text = options->json.text();
    ModelConfig start = model;
    nlohmann::json calibration_json;
    for (const ImuCalibrationEffect& effect : ImuCalibrationEffects()) {
      const bool clock = effect.effect == std::string("clock_offset");
      if (!(clock ? options->clock_offset : options->mounting)) continue;
      ImuCalibrationOptions calibration_options;
      calibration_options.use_gps = !options->no_gps;
      calibration_options.threads = options->identify.threads;
      calibration_json[effect.json_object] =
          ReadImuCalibration(effect, train, calibration_options, &start, text);
    }
    const IdentificationResult result = IdentifyModel(train, start, options->identify);
    text << DescribeIdentification(result);
    nlohmann::json json = ToJson(result);
    for (const auto& [key, value] : calibration_json.items()) json[key] = value;
    if (!held_out.empty()) {
      // Scored without the GNSS fading memory and by the default front end (the fading takes out
      // part of what a better law would: docs/identify.md).
      for (const bool fading : {false, true}) {
        text << "held out, "
             << (fading ? "the default front end (GNSS fading memory, as `filter --model` runs it)"
                        : "without the fading memory (`filter --no-gnss-fading`)")
             << " (the model file's values -> the identified):\n";
        const char* key = fading ? "held_out_default_front_end" : "held_out";
        for (size_t i = 0; i < held_out.size(); ++i) {
          const ModelScore nominal = ScoreModel(held_out[i], model, !options->no_gps, fading);
          const ModelScore identified =
              ScoreModel(held_out[i], result.model, !options->no_gps, fading);
          PrintScores(held_out_names[i], nominal, identified, text);
          json[key].push_back({{"log", held_out_names[i]},
                               {"nominal", ToJson(nominal)},
                               {"identified", ToJson(identified)}});
        }
      }
    }
    const std::string out = options->out.empty()
                                ? fs::path(options->logs[0]).filename().string() + "_model.yaml"
                                : options->out;
    std::ostringstream model_text;
    WriteModelYaml(result.model, model_text);
    WriteTextFile(out, model_text.str());
    text << "model: " << out << " (use it with --model)\n";
    json["model_file"] = out;
    json["model"] = ModelRecord(options->model, model);
    if (options->json.enabled()) options->json.Write(json);
    *status = 0;
  });
}

}  // namespace slipgraph
