#include "io/matlab_import.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/hdf5_matrix.h"
#include "io/input_error.h"
#include "io/mapping_file.h"
#include "io/yaml_errors.h"

namespace slipgraph {
namespace {

std::string Text(const YAML::Node& node, const std::string& key, const std::string& path) {
  if (!node[key]) throw InputError(path, 0, key, "", "missing key '" + key + "'");
  return node[key].as<std::string>();
}

double Number(const YAML::Node& node, const std::string& key, double fallback) {
  return node[key] ? node[key].as<double>() : fallback;
}

std::vector<std::string> Names(const YAML::Node& node, const std::string& key,
                               const std::string& path) {
  if (!node[key]) throw InputError(path, 0, key, "", "missing key '" + key + "'");
  if (node[key].IsScalar()) return {node[key].as<std::string>()};
  return node[key].as<std::vector<std::string>>();
}

}  // namespace

std::vector<SourceEntry> ListMatlab(const std::string& source) {
  std::vector<SourceEntry> out;
  for (const auto& [name, dims] : ListHdf5Datasets(source)) {
    SourceEntry e;
    e.name = name;
    long count = dims.empty() ? 0 : 1;
    for (size_t i = 0; i < dims.size(); ++i) {
      e.type += (i > 0 ? " x " : "") + std::to_string(dims[i]);
      count *= static_cast<long>(dims[i]);
    }
    e.count = count;
    out.push_back(e);
  }
  return out;
}

namespace {

DriveLog Import(const std::string& source, const std::string& mapping_path, const Vehicle& vehicle,
                ImportReport* report) {
  const YAML::Node mapping = LoadYamlFile(mapping_path);
  CheckMappingKeys(mapping, "", {"format", "imu", "wheels", "gps"}, mapping_path);
  if (mapping["imu"]) {
    CheckMappingKeys(mapping["imu"], "imu", {"t", "ax", "ay", "az", "gx", "gy", "gz", "frame"},
                     mapping_path);
  }
  if (mapping["wheels"]) {
    CheckMappingKeys(mapping["wheels"], "wheels", {"t", "left", "right", "left_sign", "right_sign"},
                     mapping_path);
  }
  if (mapping["gps"]) {
    CheckMappingKeys(mapping["gps"], "gps", {"t", "enu", "sd_xy", "sd_v"}, mapping_path);
  }
  if (Text(mapping, "format", mapping_path) != "matlab_v73") {
    throw InputError(mapping_path, 0, "format", mapping["format"].as<std::string>(),
                     "this importer reads format: matlab_v73");
  }
  const auto vec = [&](const std::string& name) {
    return ReadHdf5Matrix(source, name).Vector(source + ": " + name);
  };
  DriveLog log;
  log.directory = source;
  log.vehicle = vehicle;
  log.present_files = {"vehicle.yaml"};
  double t0 = std::numeric_limits<double>::infinity();

  // IMU.
  std::vector<double> imu_t;
  if (const YAML::Node imu = mapping["imu"]) {
    imu_t = vec(Text(imu, "t", mapping_path));
    std::vector<std::vector<double>> axes;
    for (const char* key : {"ax", "ay", "az", "gx", "gy", "gz"}) {
      axes.push_back(vec(Text(imu, key, mapping_path)));
      if (axes.back().size() != imu_t.size()) {
        throw InputError(source, 0, Text(imu, key, mapping_path), "",
                         "has " + std::to_string(axes.back().size()) + " values for " +
                             std::to_string(imu_t.size()) + " IMU stamps");
      }
    }
    const std::string frame = imu["frame"] ? imu["frame"].as<std::string>() : "z_up";
    if (frame != "z_up" && frame != "z_down") {
      throw InputError(mapping_path, 0, "imu.frame", frame, "expected z_up or z_down");
    }
    const double flip = frame == "z_down" ? -1.0 : 1.0;
    for (size_t i = 0; i < imu_t.size(); ++i) {
      log.imu.push_back({imu_t[i], axes[0][i], flip * axes[1][i], flip * axes[2][i], axes[3][i],
                         flip * axes[4][i], flip * axes[5][i]});
    }
    if (!imu_t.empty()) t0 = std::min(t0, imu_t.front());
    log.present_files.push_back("imu.csv");
    report->lines.push_back("imu: " + std::to_string(imu_t.size()) + " samples, frame " + frame +
                            (flip < 0.0 ? " (rotated 180 deg about x: y, z negated)" : ""));
  }
  // Wheels: each side the mean of its wheels, times its sign.
  if (const YAML::Node wheels = mapping["wheels"]) {
    const std::vector<double> t = vec(Text(wheels, "t", mapping_path));
    const auto side = [&](const char* key, double sign) {
      std::vector<double> sum(t.size(), 0.0);
      const std::vector<std::string> names = Names(wheels, key, mapping_path);
      for (const std::string& name : names) {
        const std::vector<double> v = vec(name);
        if (v.size() != t.size()) {
          throw InputError(source, 0, name, "",
                           "has " + std::to_string(v.size()) + " values for " +
                               std::to_string(t.size()) + " wheel stamps");
        }
        for (size_t i = 0; i < t.size(); ++i) sum[i] += sign * v[i] / names.size();
      }
      return sum;
    };
    const double left_sign = Number(wheels, "left_sign", 1.0);
    const double right_sign = Number(wheels, "right_sign", 1.0);
    const std::vector<double> left = side("left", left_sign);
    const std::vector<double> right = side("right", right_sign);
    for (size_t i = 0; i < t.size(); ++i) {
      WheelSample w;
      w.t = t[i];
      w.omega_radps.fill(kMissing);
      w.omega_radps[0] = left[i];
      w.omega_radps[1] = right[i];
      log.wheels.push_back(w);
    }
    if (!t.empty()) t0 = std::min(t0, t.front());
    log.present_files.push_back("wheels.csv");
    report->lines.push_back("wheels: " + std::to_string(t.size()) +
                            " samples, left = mean of its wheels x " + std::to_string(left_sign) +
                            ", right x " + std::to_string(right_sign));
  }
  // GNSS: ENU positions, velocity by central difference when the source has none.
  if (const YAML::Node gps = mapping["gps"]) {
    const std::vector<double> t = vec(Text(gps, "t", mapping_path));
    const Hdf5Matrix enu = ReadHdf5Matrix(source, Text(gps, "enu", mapping_path));
    const bool by_rows = enu.rows == t.size() && enu.columns == 3;
    const bool by_columns = enu.columns == t.size() && enu.rows == 3;
    if (!by_rows && !by_columns) {
      throw InputError(source, 0, Text(gps, "enu", mapping_path), "",
                       "expected 3 x " + std::to_string(t.size()) + " ENU positions");
    }
    const auto at = [&](size_t i, size_t axis) {
      return by_rows ? enu.At(i, axis) : enu.At(axis, i);
    };
    const double sd_xy = MappingSd(gps, "gps", "sd_xy", mapping_path);
    const double sd_v = MappingSd(gps, "gps", "sd_v", mapping_path);
    for (size_t i = 0; i < t.size(); ++i) {
      const size_t a = i > 0 ? i - 1 : i, b = i + 1 < t.size() ? i + 1 : i;
      const double dt = t[b] - t[a];
      GpsSample g;
      g.t = t[i];
      g.x = at(i, 0), g.y = at(i, 1), g.z = at(i, 2);
      g.vx = dt > 0.0 ? (at(b, 0) - at(a, 0)) / dt : kMissing;
      g.vy = dt > 0.0 ? (at(b, 1) - at(a, 1)) / dt : kMissing;
      g.vz = dt > 0.0 ? (at(b, 2) - at(a, 2)) / dt : kMissing;
      g.sd_xy = sd_xy, g.sd_z = sd_xy, g.sd_v = sd_v;
      log.gps.push_back(g);
    }
    if (!t.empty()) t0 = std::min(t0, t.front());
    log.present_files.push_back("gps.csv");
    report->lines.push_back("gps: " + std::to_string(t.size()) +
                            " fixes, velocity by central difference of the ENU positions");
  }
  // One clock starting at 0.
  if (std::isfinite(t0)) {
    for (ImuSample& s : log.imu) s.t -= t0;
    for (WheelSample& s : log.wheels) s.t -= t0;
    for (GpsSample& s : log.gps) s.t -= t0;
    report->lines.push_back("time: shifted by -" + std::to_string(t0) + " s (the earliest stamp)");
  }
  KeepReadableSamples(&log, report);
  return log;
}

}  // namespace

DriveLog ImportMatlab(const std::string& source, const std::string& mapping_path,
                      const Vehicle& vehicle, ImportReport* report) {
  return NamingYamlErrors(mapping_path,
                          [&] { return Import(source, mapping_path, vehicle, report); });
}

}  // namespace slipgraph
