#include "io/log_writer.h"

#include <filesystem>
#include <sstream>

#include "io/csv_writer.h"
#include "io/text_file.h"
#include "io/yaml_config.h"

namespace slipgraph {
namespace {

namespace fs = std::filesystem;

bool ShouldWrite(const DriveLog& log, const std::string& name, bool has_samples) {
  return has_samples || log.Has(name);
}

}  // namespace

void WriteDriveLog(const DriveLog& log, const std::string& directory) {
  fs::create_directories(directory);
  const auto path = [&](const char* name) { return (fs::path(directory) / name).string(); };
  {
    std::ostringstream yaml;
    WriteVehicleYaml(log.vehicle, yaml);
    WriteTextFile(path("vehicle.yaml"), yaml.str());
  }
  const std::vector<std::string>& wheels = WheelNames(log.vehicle.type);
  const int wheel_count = static_cast<int>(wheels.size());

  {
    CsvWriter w(path("imu.csv"), {"t", "ax", "ay", "az", "gx", "gy", "gz"});
    for (const ImuSample& s : log.imu) {
      w << s.t << s.ax << s.ay << s.az << s.gx << s.gy << s.gz;
      w.EndRow();
    }
    w.Close();
  }
  {
    std::vector<std::string> header = {"t"};
    header.insert(header.end(), wheels.begin(), wheels.end());
    CsvWriter w(path("wheels.csv"), header);
    for (const WheelSample& s : log.wheels) {
      w << s.t;
      for (int i = 0; i < wheel_count; ++i) w << s.omega_radps[i];
      w.EndRow();
    }
    w.Close();
  }
  if (ShouldWrite(log, "attitude.csv", !log.attitude.empty())) {
    CsvWriter w(path("attitude.csv"),
                {"t", "roll", "pitch", "yaw", "sd_roll", "sd_pitch", "sd_yaw"});
    for (const AttitudeSample& s : log.attitude) {
      w << s.t << s.roll << s.pitch << s.yaw << s.sd_roll << s.sd_pitch << s.sd_yaw;
      w.EndRow();
    }
    w.Close();
  }
  if (ShouldWrite(log, "gps.csv", !log.gps.empty())) {
    CsvWriter w(path("gps.csv"), {"t", "x", "y", "z", "vx", "vy", "vz", "sd_xy", "sd_z", "sd_v"});
    for (const GpsSample& s : log.gps) {
      w << s.t << s.x << s.y << s.z << s.vx << s.vy << s.vz << s.sd_xy << s.sd_z << s.sd_v;
      w.EndRow();
    }
    w.Close();
  }
  if (ShouldWrite(log, "pose.csv", !log.pose.empty())) {
    CsvWriter w(path("pose.csv"),
                {"t", "x", "y", "z", "roll", "pitch", "yaw", "sd_x", "sd_y", "sd_yaw"});
    for (const PoseSample& s : log.pose) {
      w << s.t << s.x << s.y << s.z << s.roll << s.pitch << s.yaw << s.sd_x << s.sd_y << s.sd_yaw;
      w.EndRow();
    }
    w.Close();
  }
  if (ShouldWrite(log, "articulation.csv", !log.articulation.empty())) {
    CsvWriter w(path("articulation.csv"), {"t", "side", "dz_mid", "dz_front"});
    for (const ArticulationSample& s : log.articulation) {
      w << s.t << SideName(s.side) << s.dz_mid << s.dz_front;
      w.EndRow();
    }
    w.Close();
  }
  if (ShouldWrite(log, "range.csv", !log.range.empty())) {
    CsvWriter w(path("range.csv"), {"t", "side", "d", "dz"});
    for (const RangeSample& s : log.range) {
      w << s.t << SideName(s.side) << s.d << s.dz;
      w.EndRow();
    }
    w.Close();
  }
  if (ShouldWrite(log, "commands.csv", !log.commands.empty())) {
    CsvWriter w(path("commands.csv"), {"t", "v", "omega"});
    for (const CommandSample& s : log.commands) {
      w << s.t << s.v << s.omega;
      w.EndRow();
    }
    w.Close();
  }
  if (ShouldWrite(log, "truth.csv", !log.truth.empty())) {
    std::vector<std::string> header = {"t",   "x",  "y",  "z",        "roll",   "pitch",
                                       "yaw", "vx", "vy", "yaw_rate", "a_dist", "immobilized"};
    for (const std::string& name : wheels) header.push_back("slip_" + name);
    for (const std::string& name : wheels) header.push_back("sinkage_" + name);
    CsvWriter w(path("truth.csv"), header);
    for (const TruthSample& s : log.truth) {
      w << s.t << s.x << s.y << s.z << s.roll << s.pitch << s.yaw << s.vx << s.vy << s.yaw_rate
        << s.a_dist << s.immobilized;
      for (int i = 0; i < wheel_count; ++i) w << s.slip[i];
      for (int i = 0; i < wheel_count; ++i) w << s.sinkage[i];
      w.EndRow();
    }
    w.Close();
  }
  if (ShouldWrite(log, "events.csv", !log.events.empty())) {
    CsvWriter w(path("events.csv"), {"t_start", "t_end", "label"});
    for (const Event& e : log.events) {
      w << e.t_start << e.t_end << e.label;
      w.EndRow();
    }
    w.Close();
  }
}

}  // namespace slipgraph
