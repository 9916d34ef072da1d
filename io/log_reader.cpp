#include "io/log_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "io/csv_reader.h"
#include "io/csv_writer.h"
#include "io/input_error.h"
#include "io/text_file.h"
#include "io/yaml_config.h"
#include "model/option_check.h"

namespace slipgraph {

bool ReadOptions::IsValid(std::string* error) const {
  return OptionCheck("ReadOptions", error).Within("max_bad_fraction", max_bad_fraction, 0.0, 1.0);
}
namespace {

namespace fs = std::filesystem;

constexpr int kMaxWarningsPerFile = 10;

// Reads one CSV file of the log row by row. `parse(reader, samples_so_far, &sample)` fills a
// sample or throws InputError; a row is kept only when it parses whole.
template <typename Sample, typename Parse>
void ReadCsvFile(const LogFiles& files, const std::string& name, bool required,
                 std::vector<CsvColumn> columns, const ReadOptions& options, DriveLog* log,
                 std::vector<Sample>* samples, Parse parse) {
  const std::string path = (fs::path(files.directory) / name).string();
  const std::optional<std::string> text = files.read(name);
  if (!text) {
    if (required) throw InputError(path, 0, "", "", "required file is missing");
    return;
  }
  std::optional<CsvReader> reader;
  try {
    reader.emplace(path, *text, std::move(columns));
  } catch (const InputError& error) {
    if (required || !options.skip_bad) throw;
    log->warnings.push_back(std::string(error.what()) + " (optional file left out: --skip-bad)");
    return;
  }
  int skipped = 0, kept = 0;
  std::string first_bad;
  while (reader->Next()) {
    Sample sample;
    try {
      parse(*reader, *samples, &sample);
    } catch (const InputError& error) {
      if (!options.skip_bad) throw;
      if (first_bad.empty()) first_bad = error.what();
      if (++skipped <= kMaxWarningsPerFile) {
        log->warnings.push_back(std::string(error.what()) + " (row skipped: --skip-bad)");
      }
      continue;
    }
    samples->push_back(sample);
    ++kept;
  }
  if (skipped > kMaxWarningsPerFile &&
      skipped > options.max_bad_fraction * static_cast<double>(skipped + kept)) {
    throw InputError(
        path, 0, "", "",
        std::to_string(skipped) + " of " + std::to_string(skipped + kept) +
            " rows are bad, more than --skip-bad drops (--max-bad sets the share); the "
            "first: " +
            first_bad);
  }
  if (skipped > kMaxWarningsPerFile) {
    log->warnings.push_back(path + ": " + std::to_string(skipped) + " bad rows skipped in all");
  }
  log->present_files.push_back(name);
}

// Time stamps must be strictly increasing within a file (or within a side's rows).
void CheckIncreasing(const CsvReader& reader, int t_column, double t, double previous_t,
                     bool allow_equal = false) {
  if (std::isnan(previous_t)) return;
  if (t > previous_t || (allow_equal && t == previous_t)) return;
  char value[64];
  std::snprintf(value, sizeof(value), "%.9g", t);
  reader.Fail(t_column, value,
              std::string(t == previous_t ? "repeated" : "decreasing") + " time stamp (previous " +
                  std::to_string(previous_t) + ")");
}

// A standard deviation cell: missing, or positive (zero would weigh the row as exact; it was
// replaced silently by vehicle.yaml's).
double Sd(const CsvReader& r, int column) {
  const double sd = r.Number(column);
  if (sd <= 0.0) r.Fail(column, FormatNumber(sd), "a standard deviation must be positive");
  return sd;
}

template <typename Sample>
double LastTime(const std::vector<Sample>& samples) {
  return samples.empty() ? kMissing : samples.back().t;
}

Side ReadSide(const CsvReader& reader, int column) {
  const std::string side = reader.Text(column);
  if (side == "left") return Side::kLeft;
  if (side == "right") return Side::kRight;
  reader.Fail(column, side, "side must be 'left' or 'right'");
}

// Last time stamp of a side's rows, for the per-side monotonicity of articulation.csv.
template <typename Sample>
double LastTimeOfSide(const std::vector<Sample>& samples, Side side) {
  for (auto it = samples.rbegin(); it != samples.rend(); ++it) {
    if (it->side == side) return it->t;
  }
  return kMissing;
}

std::vector<CsvColumn> Columns(std::initializer_list<const char*> required,
                               std::initializer_list<const char*> optional = {}) {
  std::vector<CsvColumn> columns;
  for (const char* name : required) columns.push_back({name, true});
  for (const char* name : optional) columns.push_back({name, false});
  return columns;
}

}  // namespace

bool IsLogDirectory(const std::string& directory) {
  return fs::exists(fs::path(directory) / "vehicle.yaml");
}

std::vector<std::string> ListLogs(const std::string& path) {
  if (IsLogDirectory(path)) return {path};
  std::vector<std::string> logs;
  if (fs::is_directory(path)) {
    for (const auto& entry : fs::directory_iterator(path)) {
      if (entry.is_directory() && IsLogDirectory(entry.path().string())) {
        logs.push_back(entry.path().string());
      }
    }
  }
  std::sort(logs.begin(), logs.end());
  if (logs.empty()) {
    throw InputError(path, 0, "", "", "neither a log (no vehicle.yaml) nor a suite of logs");
  }
  return logs;
}

LogFiles LogFilesIn(const std::string& directory) {
  return {directory, [directory](const std::string& name) -> std::optional<std::string> {
            const std::string path = (fs::path(directory) / name).string();
            if (!fs::exists(path)) return std::nullopt;
            return ReadTextFile(path);
          }};
}

LogFiles LogFilesInMemory(std::string directory, std::map<std::string, std::string> files) {
  return {std::move(directory),
          [files = std::move(files)](const std::string& name) -> std::optional<std::string> {
            const auto file = files.find(name);
            if (file == files.end()) return std::nullopt;
            return file->second;
          }};
}

DriveLog ReadDriveLog(const std::string& directory, const ReadOptions& options) {
  if (!fs::is_directory(directory)) {
    throw InputError(directory, 0, "", "", "not a directory (a log is a directory of files)");
  }
  return ReadDriveLog(LogFilesIn(directory), options);
}

DriveLog ReadDriveLog(const LogFiles& files, const ReadOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  DriveLog log;
  const std::string& directory = files.directory;
  log.directory = directory;
  const std::string vehicle_path = (fs::path(directory) / "vehicle.yaml").string();
  const std::optional<std::string> vehicle_text = files.read("vehicle.yaml");
  if (!vehicle_text) throw InputError(vehicle_path, 0, "", "", "required file is missing");
  log.vehicle = ParseVehicleYaml(vehicle_path, *vehicle_text, &log.warnings);
  if (log.vehicle.name.empty()) log.vehicle.name = fs::path(directory).filename().string();
  for (const std::string& key : log.vehicle.defaulted_keys) {
    log.warnings.push_back(vehicle_path + ": '" + key + "' not given, nominal defaults used");
  }
  log.present_files.push_back("vehicle.yaml");

  ReadCsvFile(files, "imu.csv", true, Columns({"t", "ax", "ay", "az", "gx", "gy", "gz"}), options,
              &log, &log.imu,
              [](const CsvReader& r, const std::vector<ImuSample>& prev, ImuSample* s) {
                s->t = r.Number(0);
                CheckIncreasing(r, 0, s->t, LastTime(prev));
                s->ax = r.Number(1), s->ay = r.Number(2), s->az = r.Number(3);
                s->gx = r.Number(4), s->gy = r.Number(5), s->gz = r.Number(6);
              });

  const std::vector<std::string>& wheel_names = WheelNames(log.vehicle.type);
  std::vector<CsvColumn> wheel_columns = {{"t", true}};
  for (const std::string& name : wheel_names) wheel_columns.push_back({name, true});
  ReadCsvFile(files, "wheels.csv", true, wheel_columns, options, &log, &log.wheels,
              [&](const CsvReader& r, const std::vector<WheelSample>& prev, WheelSample* s) {
                s->t = r.Number(0);
                CheckIncreasing(r, 0, s->t, LastTime(prev));
                for (size_t w = 0; w < wheel_names.size(); ++w) {
                  s->omega_radps[w] = r.Number(static_cast<int>(w) + 1);
                }
              });

  ReadCsvFile(files, "attitude.csv", false,
              Columns({"t", "roll", "pitch", "yaw"}, {"sd_roll", "sd_pitch", "sd_yaw"}), options,
              &log, &log.attitude,
              [](const CsvReader& r, const std::vector<AttitudeSample>& prev, AttitudeSample* s) {
                s->t = r.Number(0);
                CheckIncreasing(r, 0, s->t, LastTime(prev));
                s->roll = r.Number(1), s->pitch = r.Number(2), s->yaw = r.Number(3);
                s->sd_roll = Sd(r, 4), s->sd_pitch = Sd(r, 5), s->sd_yaw = Sd(r, 6);
              });

  ReadCsvFile(files, "gps.csv", false,
              Columns({"t", "x", "y", "z", "vx", "vy", "vz"}, {"sd_xy", "sd_z", "sd_v"}), options,
              &log, &log.gps,
              [](const CsvReader& r, const std::vector<GpsSample>& prev, GpsSample* s) {
                s->t = r.Number(0);
                CheckIncreasing(r, 0, s->t, LastTime(prev));
                s->x = r.Number(1), s->y = r.Number(2), s->z = r.Number(3);
                s->vx = r.Number(4), s->vy = r.Number(5), s->vz = r.Number(6);
                s->sd_xy = Sd(r, 7), s->sd_z = Sd(r, 8), s->sd_v = Sd(r, 9);
              });

  ReadCsvFile(files, "pose.csv", false,
              Columns({"t", "x", "y", "z", "roll", "pitch", "yaw"}, {"sd_x", "sd_y", "sd_yaw"}),
              options, &log, &log.pose,
              [](const CsvReader& r, const std::vector<PoseSample>& prev, PoseSample* s) {
                s->t = r.Number(0);
                CheckIncreasing(r, 0, s->t, LastTime(prev));
                s->x = r.Number(1), s->y = r.Number(2), s->z = r.Number(3);
                s->roll = r.Number(4), s->pitch = r.Number(5), s->yaw = r.Number(6);
                s->sd_x = Sd(r, 7), s->sd_y = Sd(r, 8), s->sd_yaw = Sd(r, 9);
              });

  ReadCsvFile(
      files, "articulation.csv", false, Columns({"t", "side", "dz_mid", "dz_front"}), options, &log,
      &log.articulation,
      [](const CsvReader& r, const std::vector<ArticulationSample>& prev, ArticulationSample* s) {
        s->t = r.Number(0);
        s->side = ReadSide(r, 1);
        CheckIncreasing(r, 0, s->t, LastTimeOfSide(prev, s->side));
        s->dz_mid = r.Number(2), s->dz_front = r.Number(3);
      });

  // Several range rows share a time stamp: time must not decrease.
  ReadCsvFile(files, "range.csv", false, Columns({"t", "side", "d", "dz"}), options, &log,
              &log.range,
              [](const CsvReader& r, const std::vector<RangeSample>& prev, RangeSample* s) {
                s->t = r.Number(0);
                CheckIncreasing(r, 0, s->t, LastTime(prev), /*allow_equal=*/true);
                s->side = ReadSide(r, 1);
                s->d = r.Number(2), s->dz = r.Number(3);
              });

  ReadCsvFile(files, "commands.csv", false, Columns({"t", "v", "omega"}), options, &log,
              &log.commands,
              [](const CsvReader& r, const std::vector<CommandSample>& prev, CommandSample* s) {
                s->t = r.Number(0);
                CheckIncreasing(r, 0, s->t, LastTime(prev));
                s->v = r.Number(1), s->omega = r.Number(2);
              });

  std::vector<CsvColumn> truth_columns =
      Columns({"t", "x", "y", "z", "roll", "pitch", "yaw", "vx", "vy", "yaw_rate"},
              {"a_dist", "immobilized"});
  const int first_slip_column = static_cast<int>(truth_columns.size());
  for (const std::string& name : wheel_names) truth_columns.push_back({"slip_" + name, false});
  for (const std::string& name : wheel_names) truth_columns.push_back({"sinkage_" + name, false});
  const int wheel_count = static_cast<int>(wheel_names.size());
  ReadCsvFile(files, "truth.csv", false, truth_columns, options, &log, &log.truth,
              [&](const CsvReader& r, const std::vector<TruthSample>& prev, TruthSample* s) {
                s->t = r.Number(0);
                CheckIncreasing(r, 0, s->t, LastTime(prev));
                s->x = r.Number(1), s->y = r.Number(2), s->z = r.Number(3);
                s->roll = r.Number(4), s->pitch = r.Number(5), s->yaw = r.Number(6);
                s->vx = r.Number(7), s->vy = r.Number(8), s->yaw_rate = r.Number(9);
                s->a_dist = r.Number(10), s->immobilized = r.Number(11);
                s->slip.fill(kMissing);
                s->sinkage.fill(kMissing);
                for (int w = 0; w < wheel_count; ++w) {
                  s->slip[w] = r.Number(first_slip_column + w);
                  s->sinkage[w] = r.Number(first_slip_column + wheel_count + w);
                }
              });

  ReadCsvFile(files, "events.csv", false, {{"t_start", true}, {"t_end", true}, {"label", true}},
              options, &log, &log.events,
              [](const CsvReader& r, const std::vector<Event>&, Event* e) {
                e->t_start = r.Number(0);
                e->t_end = r.Number(1);
                if (e->t_end < e->t_start) {
                  r.Fail(1, std::to_string(e->t_end), "event ends before it starts");
                }
                e->label = r.Text(2);
              });
  return log;
}

}  // namespace slipgraph
