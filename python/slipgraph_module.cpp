// slipgraph._core: the library for Python (pybind11). Logs as objects whose streams are numpy
// arrays; the EKF front end and the batch smoother as functions returning their estimates as
// columns (the estimate file's, io/estimate_file.h) with their report and trust check; the
// diagnosis, the identification and the evaluation as the JSON text the CLI writes (the package
// slipgraph/__init__.py turns them into dicts and tables).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "evaluation/evaluation.h"
#include "io/estimate_file.h"
#include "io/input_error.h"
#include "io/log_reader.h"
#include "io/log_summary.h"
#include "io/log_tables.h"
#include "io/yaml_config.h"
#include "solvers/batch_smoother.h"
#include "solvers/ekf_runner.h"
#include "solvers/identification_json.h"
#include "solvers/model_identification.h"
#include "solvers/trust_check.h"
#include "solvers/window_smoother.h"
#include "workbench/diagnosis.h"
#include "workbench/diagnosis_json.h"
#include "workbench/diagnosis_series.h"

namespace py = pybind11;

namespace slipgraph {
namespace {

// A log read once and shared by every call on it (estimators copy it where they calibrate it).
using LogPtr = std::shared_ptr<const DriveLog>;

py::array_t<double> ToArray(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

// A stream's columns by name, in the file's order (Python dicts keep it): numbers as float
// arrays, text columns as lists of str.
py::dict StreamColumns(const DriveLog& log, const std::string& name) {
  const std::string file = name.find('.') == std::string::npos ? name + ".csv" : name;
  const LogTable table = StreamTable(log, file);
  py::dict columns;
  for (const LogColumn& column : table.columns) {
    if (column.is_text) {
      columns[py::str(column.name)] = py::cast(column.texts);
    } else {
      columns[py::str(column.name)] = ToArray(column.numbers);
    }
  }
  return columns;
}

py::dict TableColumns(const NumericTable& table) {
  py::dict columns;
  for (const std::string& name : table.names) {
    columns[py::str(name)] = ToArray(table.columns.at(name));
  }
  return columns;
}

py::dict VehicleDict(const Vehicle& v) {
  py::dict d;
  d["name"] = v.name;
  d["type"] = VehicleTypeName(v.type);
  d["mass_kg"] = v.mass_kg;
  d["wheel_radius_m"] = v.wheel_radius_m;
  d["track_width_m"] = v.track_width_m;
  d["wheels"] = WheelNames(v.type);
  return d;
}

// The log with its model applied (as the CLI's --model does): the vehicle's nominal model, or
// the model file over it, its calibration (wheel radii, effective track, the IMU's and the
// encoders' time offsets) applied to a copy.
struct CalibratedLog {
  DriveLog log;
  ModelConfig model;
};
CalibratedLog Calibrate(const DriveLog& log, const std::string& model_path) {
  CalibratedLog out{log, {}};
  out.model = ModelForLog(&out.log, model_path);
  return out;
}

// An estimator's run as Python gets it: its estimates as the estimate file's columns (with the
// trust check's `suspect`, as the CLI writes it), its report, and the trust check.
py::dict RunDict(const DriveLog& log, const std::vector<WardEstimate>& estimates,
                 const std::string& report, bool used_fallback,
                 std::vector<ExtraColumn> extra = {}) {
  const TrustReport trust = CheckTrust(log, estimates);
  extra.push_back({"suspect", trust.suspect});
  py::dict run;
  run["columns"] = TableColumns(EstimateColumns(estimates, extra));
  run["report"] = report;
  run["trusted"] = trust.trusted;
  run["trust_warnings"] = trust.warnings;
  run["used_fallback"] = used_fallback;
  return run;
}

FilterRunOptions FrontEnd(bool use_gps, bool single_law, bool gnss_fading, bool disturbance_modes) {
  FilterRunOptions options;
  options.use_gps = use_gps;
  options.multiple_model = !single_law;
  options.ekf.gnss_fading_fixes = gnss_fading ? kGnssFadingFixes : 0.0;
  options.disturbance_modes = disturbance_modes;
  return options;
}

py::dict FilterRun(const LogPtr& log, const std::string& model, bool use_gps, bool single_law,
                   bool gnss_fading, bool disturbance_modes) {
  const CalibratedLog run = Calibrate(*log, model);
  FilterResult result;
  {
    py::gil_scoped_release release;
    result =
        RunEkf(run.log, run.model, FrontEnd(use_gps, single_law, gnss_fading, disturbance_modes));
  }
  return RunDict(run.log, result.estimates, DescribeFilterRun(result), false);
}

py::dict SmoothRun(const LogPtr& log, const std::string& model, bool use_gps, double stiffness_sd,
                   int threads) {
  const CalibratedLog run = Calibrate(*log, model);
  BatchSmootherOptions options;
  options.problem.stiffness_prior_sd = PostProcessingStiffnessPriorSd(run.model, stiffness_sd);
  options.filter.use_gps = use_gps;
  options.threads = threads;
  SmootherResult result;
  {
    py::gil_scoped_release release;
    result = SmoothBatch(run.log, run.model, options);
  }
  py::dict out = RunDict(run.log, DisturbanceWithEffects(result, run.log, run.model),
                         DescribeSmootherRun(result), result.used_fallback);
  out["converged"] = result.summary.termination_type == ceres::CONVERGENCE;
  out["final_cost"] = result.final_cost;
  out["iterations"] = result.summary.iterations.size();
  return out;
}

py::dict OnlineRun(const LogPtr& log, const std::string& model, bool use_gps, double window_s,
                   int update_every, int iterations, double stiffness_sd, bool covariance,
                   double reject_distance) {
  const CalibratedLog run = Calibrate(*log, model);
  WindowSmootherOptions options;
  options.filter.use_gps = use_gps;
  options.window_s = window_s;
  options.update_every = update_every;
  options.max_iterations = iterations;
  options.stiffness_prior_sd = stiffness_sd;
  options.covariance = covariance;
  options.reject_distance_sd = reject_distance;
  WindowSmootherResult result;
  {
    py::gil_scoped_release release;
    result = SmoothWindowed(run.log, run.model, options);
  }
  py::dict out =
      RunDict(run.log, result.estimates, DescribeWindowRun(result), false, OnlineColumns(result));
  std::vector<double> sorted = result.update_ms;
  std::sort(sorted.begin(), sorted.end());
  const auto percentile = [&](double p) {
    return sorted.empty() ? std::nan("")
                          : sorted[static_cast<size_t>(p * static_cast<double>(sorted.size() - 1))];
  };
  out["update_ms_p50"] = percentile(0.5);
  out["update_ms_p99"] = percentile(0.99);
  out["rejected_updates"] = result.rejected_updates;
  return out;
}

// The diagnosis as the CLI's JSON text, and its series (workbench/diagnosis_series.h) by file
// name as dicts of arrays.
py::tuple DiagnoseRun(const LogPtr& log, const std::string& model, bool use_gps,
                      const std::vector<std::string>& with, int threads, bool parameters) {
  const CalibratedLog run = Calibrate(*log, model);
  const EffectRegistry& registry =
      parameters ? EffectRegistry::CatalogueWithParameters() : EffectRegistry::Catalogue();
  DiagnosisOptions options;
  options.smoother.filter.use_gps = use_gps;
  options.threads = threads;
  options.effects = &registry;
  std::string json_text;
  std::vector<NamedTable> series;
  {
    py::gil_scoped_release release;
    const Diagnosis before = Diagnose(run.log, run.model, options);
    nlohmann::json json = ToJson(before);
    if (!with.empty()) {
      json["after"] = ToJson(DiagnoseWith(run.log, run.model, before, with, options).after);
    }
    json_text = json.dump();
    series = DiagnosisSeries(before);
  }
  py::dict tables;
  for (const NamedTable& named : series) tables[py::str(named.file)] = TableColumns(named.table);
  return py::make_tuple(json_text, tables);
}

std::string IdentifyJson(const std::vector<LogPtr>& logs, const std::string& model, bool use_gps,
                         bool fit_radius, int threads) {
  if (logs.empty()) throw std::invalid_argument("identify: no logs");
  std::vector<DriveLog> copies;
  for (const LogPtr& log : logs) copies.push_back(*log);
  const ModelConfig start = ReadModelOrNominal(model, copies.front().vehicle);
  IdentifyOptions options;
  options.use_gps = use_gps;
  options.fit_radius = fit_radius;
  options.threads = threads;
  py::gil_scoped_release release;
  const IdentificationResult result = IdentifyModel(copies, start, options);
  nlohmann::json json = ToJson(result);
  std::ostringstream yaml;
  WriteModelYaml(result.model, yaml);
  json["model_yaml"] = yaml.str();
  json["report"] = DescribeIdentification(result);
  return json.dump();
}

std::string ScoreModelJson(const LogPtr& log, const std::string& model, bool use_gps) {
  // ScoreModel applies the model's calibration to the log itself.
  const ModelConfig config = ReadModelOrNominal(model, log->vehicle);
  py::gil_scoped_release release;
  return ToJson(ScoreModel(*log, config, use_gps)).dump();
}

// A dict of 1-D arrays as a table, in the dict's order.
NumericTable ToTable(const py::dict& columns, const std::string& what) {
  NumericTable table;
  for (const auto& item : columns) {
    const std::string name = py::cast<std::string>(item.first);
    const py::array_t<double, py::array::c_style | py::array::forcecast> values =
        py::cast<py::array>(item.second);
    if (values.ndim() != 1) {
      throw std::invalid_argument(what + ": column '" + name + "' is not one-dimensional");
    }
    if (!table.names.empty() && static_cast<size_t>(values.size()) != table.rows()) {
      throw std::invalid_argument(what + ": column '" + name + "' has " +
                                  std::to_string(values.size()) + " values, not " +
                                  std::to_string(table.rows()));
    }
    table.names.push_back(name);
    table.columns[name].assign(values.data(), values.data() + values.size());
  }
  return table;
}

// The estimates' columns (a dict of arrays: t, v_bx, sd_v_bx, immobilized, a_dist at least)
// scored against the log's truth, as `evaluate` scores an estimate file.
std::string EvaluateJson(const LogPtr& log, const py::dict& columns) {
  return ToJson(Evaluate(*log, ToTable(columns, "evaluate"))).dump();
}

}  // namespace
}  // namespace slipgraph

PYBIND11_MODULE(_core, m) {
  using namespace slipgraph;
  m.doc() = "slipgraph: wheel slip, immobilization and sinkage estimation (C++ core)";
  m.attr("__version__") = SLIPGRAPH_VERSION;
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

  py::class_<DriveLog, std::shared_ptr<DriveLog>>(m, "Log", "A drive log (shared/log-format.md)")
      .def_property_readonly("path", [](const DriveLog& log) { return log.directory; })
      .def_property_readonly("vehicle",
                             [](const DriveLog& log) { return VehicleDict(log.vehicle); })
      .def_property_readonly("files", &LogTableFiles, "The log's CSV files, in the format's order")
      .def_property_readonly("warnings", [](const DriveLog& log) { return log.warnings; })
      .def_property_readonly("problems", &CheckLogForEstimation,
                             "What would make estimates on it mean less: gaps, frozen sensors")
      .def_property_readonly("has_truth", [](const DriveLog& log) { return !log.truth.empty(); })
      .def("stream", &StreamColumns, py::arg("name"),
           "A stream ('imu', 'wheels', 'gps', ..., or 'imu.csv') as a dict of its columns")
      .def(
          "slice",
          [](const DriveLog& log, double t_begin, double t_end) {
            return std::make_shared<DriveLog>(SliceLog(log, t_begin, t_end));
          },
          py::arg("t_begin"), py::arg("t_end"),
          "The samples with t in [t_begin, t_end), events clipped to it")
      .def("__repr__", [](const DriveLog& log) {
        return "<slipgraph.Log " + log.directory + ": " + log.vehicle.name + ", " +
               std::to_string(log.wheels.size()) + " wheel samples>";
      });

  m.def(
      "read_log",
      [](const std::string& path, bool skip_bad, double max_bad_fraction) {
        ReadOptions options;
        options.skip_bad = skip_bad;
        options.max_bad_fraction = max_bad_fraction;
        std::string error;
        if (!options.IsValid(&error)) throw std::invalid_argument(error);
        py::gil_scoped_release release;
        return std::make_shared<DriveLog>(ReadDriveLog(path, options));
      },
      py::arg("path"), py::arg("skip_bad") = false, py::arg("max_bad_fraction") = 0.01);
  m.def("list_logs", &ListLogs, py::arg("path"),
        "The logs at path: itself when it is a log, else its sub-directories that are logs");
  m.def("filter", &FilterRun, py::arg("log"), py::arg("model") = "", py::arg("use_gps") = true,
        py::arg("single_law") = false, py::arg("gnss_fading") = true,
        py::arg("disturbance_modes") = false);
  m.def("smooth", &SmoothRun, py::arg("log"), py::arg("model") = "", py::arg("use_gps") = true,
        py::arg("stiffness_sd") = std::nan(""), py::arg("threads") = 1);
  const WindowSmootherOptions window;
  m.def("online", &OnlineRun, py::arg("log"), py::arg("model") = "", py::arg("use_gps") = true,
        py::arg("window_s") = window.window_s, py::arg("update_every") = window.update_every,
        py::arg("iterations") = window.max_iterations,
        py::arg("stiffness_sd") = window.stiffness_prior_sd,
        py::arg("covariance") = window.covariance,
        py::arg("reject_distance") = window.reject_distance_sd);
  m.def("diagnose", &DiagnoseRun, py::arg("log"), py::arg("model") = "", py::arg("use_gps") = true,
        py::arg("with_effects") = std::vector<std::string>{}, py::arg("threads") = 2,
        py::arg("parameters") = false);
  m.def("identify", &IdentifyJson, py::arg("logs"), py::arg("model") = "",
        py::arg("use_gps") = true, py::arg("fit_radius") = false, py::arg("threads") = 1);
  m.def("score_model", &ScoreModelJson, py::arg("log"), py::arg("model") = "",
        py::arg("use_gps") = true);
  m.def("evaluate", &EvaluateJson, py::arg("log"), py::arg("columns"));
  m.def(
      "write_table",
      [](const py::dict& columns, const std::string& path) {
        WriteNumericTable(ToTable(columns, path), path);
      },
      py::arg("columns"), py::arg("path"),
      "Columns (a dict of 1-D arrays) as a CSV file in the log format's dialect");
  m.def(
      "effects", [] { return EffectCatalogueJson().dump(); },
      "The catalogue of physical effects (model/effect_catalogue.h), as JSON text");
}
