// `slipgraph calibrate`: IPD slip-model identification (Rogers-Marcovitz et al.) on a log with
// measured poses: alpha and Q over time, the 2 s prediction errors of the no-slip and the
// calibrated model, and the paper's scatter figure in an HTML report.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "apps/json_output.h"
#include "evaluation/html_report.h"
#include "io/csv_writer.h"
#include "io/log_reader.h"
#include "solvers/ipd_calibration.h"
#include "solvers/ipd_graph_calibration.h"

namespace slipgraph {
namespace {

nlohmann::json StatsJson(const PredictionStats& s) {
  return {{"segments", s.segments},
          {"mean_position_error_m", s.mean_position_error_m},
          {"sd_along_m", s.sd_along_m},
          {"sd_cross_m", s.sd_cross_m},
          {"mean_heading_error_rad", s.mean_heading_error_rad},
          {"sd_heading_rad", s.sd_heading_rad},
          {"predicted_over_sample_variance",
           {s.predicted_over_sample[0], s.predicted_over_sample[1], s.predicted_over_sample[2]}}};
}

// The 3-sigma ellipse of a 2x2 covariance around (0, 0), as a closed line.
PlotSeries Ellipse(const std::string& label, const Eigen::Matrix2d& covariance,
                   const std::string& color, bool dashed) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance);
  PlotSeries s = NewSeries(label, color, dashed);
  for (int i = 0; i <= 100; ++i) {
    const double a = 2.0 * M_PI * i / 100.0;
    const Eigen::Vector2d unit(std::cos(a), std::sin(a));
    const Eigen::Vector2d p = eigen.eigenvectors() *
                              (3.0 * eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt()).asDiagonal() *
                              unit;
    s.t.push_back(p[0]);
    s.y.push_back(p[1]);
  }
  return s;
}

Plot Scatter(const std::string& title, const std::vector<PredictionError>& errors,
             const std::string& color) {
  Plot plot{title, "cross-track error (m)", {}, {}, "along-track error (m)", true};
  PlotSeries dots = NewSeries("2 s predictions", color);
  dots.points = true;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d predicted = Eigen::Matrix2d::Zero();
  for (const PredictionError& e : errors) {
    dots.t.push_back(e.along_m);
    dots.y.push_back(e.cross_m);
    mean += Eigen::Vector2d(e.along_m, e.cross_m);
    predicted += e.predicted_covariance.topLeftCorner<2, 2>();
  }
  const double n = std::max<double>(1.0, errors.size());
  mean /= n;
  predicted /= n;
  Eigen::Matrix2d sample = Eigen::Matrix2d::Zero();
  for (const PredictionError& e : errors) {
    const Eigen::Vector2d d = Eigen::Vector2d(e.along_m, e.cross_m) - mean;
    sample += d * d.transpose();
  }
  sample /= std::max(1.0, n - 1.0);
  plot.series = {dots, Ellipse("sample covariance (3 sd)", sample, "#000000", false),
                 Ellipse("mean predicted covariance (3 sd)", predicted, "#d62728", true)};
  return plot;
}

}  // namespace

void RegisterCalibrateCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log, out, method = "ekf";
    JsonOutput json;
    ReadOptions read;  // --skip-bad, --max-bad
    IpdOptions ipd;
    IpdGraphOptions graph;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app->add_subcommand(
      "calibrate", "Identify the IPD slip model (Rogers-Marcovitz et al.) from odometry and poses");
  cmd->add_option("LOG", options->log, "Log with wheels.csv, pose.csv and attitude.csv")
      ->required();
  cmd->add_option("--method", options->method,
                  "ekf: the paper's online identification EKF; window: Ceres, sliding window with "
                  "marginalization (online); batch: Ceres, whole log (post-processing)")
      ->check(CLI::IsMember({"ekf", "window", "batch"}))
      ->capture_default_str();
  cmd->add_option("--out", options->out,
                  "Directory for alpha.csv, predictions.csv and report.html (default "
                  "./<log>_calibrate)");
  cmd->add_option("--segment", options->ipd.segment_s, "Path segment length, s")
      ->capture_default_str();
  cmd->add_option("--spacing", options->ipd.spacing_s, "A new segment starts every, s")
      ->capture_default_str();
  cmd->add_option("--block", options->graph.block_s, "batch: seconds of driving per alpha block")
      ->capture_default_str();
  cmd->add_option("--window-block", options->graph.window_block_s,
                  "window: seconds of driving per alpha block (it solves after each)")
      ->capture_default_str();
  cmd->add_option("--window", options->graph.window_s, "window: seconds of alpha blocks kept")
      ->capture_default_str();
  options->json.Add(cmd);
  AddReadOptions(cmd, &options->read);
  cmd->callback([options, status]() {
    namespace fs = std::filesystem;
    const DriveLog log = ReadLogWithWarnings(options->log, options->read);
    const IpdCalibrationResult result =
        options->method == "ekf"      ? CalibrateIpdEkf(log, options->ipd)
        : options->method == "window" ? CalibrateIpdWindow(log, options->ipd, options->graph)
                                      : CalibrateIpdBatch(log, options->ipd, options->graph);
    const std::string out = options->out.empty()
                                ? fs::path(options->log).filename().string() + "_calibrate"
                                : options->out;
    fs::create_directories(out);
    {
      std::vector<std::string> header = {"t"};
      for (int i = 0; i < ipd::kAlphaSize; ++i) header.push_back("alpha_" + std::to_string(i));
      for (const char* q : {"q_vx", "q_vy", "q_yaw"}) header.push_back(q);
      CsvWriter csv((fs::path(out) / "alpha.csv").string(), header);
      for (size_t k = 0; k < result.update_t.size(); ++k) {
        std::vector<double> row = {result.update_t[k]};
        row.insert(row.end(), result.alpha[k].begin(), result.alpha[k].end());
        for (int i = 0; i < 3; ++i) row.push_back(result.q[k][i]);
        for (double v : row) csv << v;
        csv.EndRow();
      }
      CsvWriter predictions((fs::path(out) / "predictions.csv").string(),
                            {"t", "no_slip_along", "no_slip_cross", "no_slip_heading",
                             "calibrated_along", "calibrated_cross", "calibrated_heading",
                             "predicted_sd_along", "predicted_sd_cross", "predicted_sd_heading"});
      for (size_t k = 0; k < result.calibrated.size(); ++k) {
        const PredictionError& a = result.no_slip[k];
        const PredictionError& b = result.calibrated[k];
        for (double v :
             {b.t_start, a.along_m, a.cross_m, a.heading_rad, b.along_m, b.cross_m, b.heading_rad,
              std::sqrt(b.predicted_covariance(0, 0)), std::sqrt(b.predicted_covariance(1, 1)),
              std::sqrt(b.predicted_covariance(2, 2))}) {
          predictions << v;
        }
        predictions.EndRow();
      }
    }
    const PredictionStats no_slip = Summarize(result.no_slip);
    const PredictionStats calibrated = Summarize(result.calibrated);
    HtmlReport html("slipgraph calibrate: " + options->log);
    html.Paragraph(std::to_string(result.segments.size()) + " path segments of " +
                   std::to_string(options->ipd.segment_s) + " s, one every " +
                   std::to_string(options->ipd.spacing_s) +
                   " s; each predicted with the slip model known when it started (online).");
    const auto row = [](const std::string& name, const PredictionStats& s) {
      return std::vector<std::string>{name, std::to_string(s.mean_position_error_m),
                                      std::to_string(s.sd_along_m), std::to_string(s.sd_cross_m),
                                      std::to_string(s.mean_heading_error_rad)};
    };
    html.Table(
        {"model", "mean position error m", "sd along m", "sd cross m", "mean |heading error| rad"},
        {row("no slip", no_slip), row("calibrated (" + options->method + ")", calibrated)});
    html.Figure(Scatter("no-slip model: 2 s prediction errors", result.no_slip, "#7f7f7f"));
    html.Figure(Scatter("calibrated online: 2 s prediction errors", result.calibrated, "#1f77b4"));
    Plot alpha_plot{"slip parameters over time", "alpha", {}, {}};
    static const char* kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                    "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf",
                                    "#000000", "#aec7e8", "#ffbb78"};
    for (int i = 0; i < ipd::kAlphaSize; ++i) {
      PlotSeries s = NewSeries("alpha_" + std::to_string(i), kColors[i]);
      s.t = result.update_t;
      for (const auto& a : result.alpha) s.y.push_back(a[i]);
      alpha_plot.series.push_back(s);
    }
    html.Figure(alpha_plot);
    html.Paragraph(options->json.RecordText());
    html.Write((fs::path(out) / "report.html").string());
    if (options->json.enabled()) {
      nlohmann::json j = {{"method", options->method},
                          {"no_slip", StatsJson(no_slip)},
                          {"calibrated", StatsJson(calibrated)},
                          {"final_alpha", result.final_alpha},
                          {"final_alpha_sd", result.final_alpha_sd},
                          {"final_q", {result.final_q[0], result.final_q[1], result.final_q[2]}},
                          {"notes", result.notes},
                          {"report", (fs::path(out) / "report.html").string()}};
      options->json.Write(j);
    }
    {
      std::FILE* text = options->json.text_file();
      std::fprintf(
          text,
          "| model | mean position error m | sd along m | sd cross m | mean |heading| rad |\n");
      std::fprintf(text, "|---|---|---|---|---|\n");
      const std::string calibrated_name = "calibrated (" + options->method + ")";
      for (const auto& [name, s] : {std::pair<std::string, PredictionStats>{"no slip", no_slip},
                                    {calibrated_name, calibrated}}) {
        std::fprintf(text, "| %s | %.4f | %.4f | %.4f | %.4f |\n", name.c_str(),
                     s.mean_position_error_m, s.sd_along_m, s.sd_cross_m, s.mean_heading_error_rad);
      }
      std::fprintf(text, "predicted / sample variance (along, cross, heading): %.2f %.2f %.2f\n",
                   calibrated.predicted_over_sample[0], calibrated.predicted_over_sample[1],
                   calibrated.predicted_over_sample[2]);
      for (const std::string& note : result.notes) std::fprintf(text, "note: %s\n", note.c_str());
      std::fprintf(text, "report: %s\n", (fs::path(out) / "report.html").string().c_str());
    }
    *status = 0;
  });
}

}  // namespace slipgraph
