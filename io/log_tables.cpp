#include "io/log_tables.h"

#include <stdexcept>
#include <utility>

namespace slipgraph {
namespace {

// Stream files in log-format.md's order; the first two are required.
const std::vector<std::string>& StreamFiles() {
  static const std::vector<std::string> files = {
      "imu.csv",          "wheels.csv", "attitude.csv", "gps.csv",   "pose.csv",
      "articulation.csv", "range.csv",  "commands.csv", "truth.csv", "events.csv"};
  return files;
}

// Columns of samples of one type, added in the file's order.
template <typename Sample>
class Columns {
 public:
  Columns(LogTable* table, const std::vector<Sample>& samples) : table_(table), samples_(samples) {}

  template <typename Value>
  Columns& Number(const std::string& name, Value value_of) {
    LogColumn column;
    column.name = name;
    column.numbers.reserve(samples_.size());
    for (const Sample& s : samples_) column.numbers.push_back(value_of(s));
    table_->columns.push_back(std::move(column));
    return *this;
  }
  Columns& Member(const std::string& name, double Sample::*member) {
    return Number(name, [member](const Sample& s) { return s.*member; });
  }
  template <typename Value>
  Columns& Text(const std::string& name, Value value_of) {
    LogColumn column;
    column.name = name;
    column.is_text = true;
    column.texts.reserve(samples_.size());
    for (const Sample& s : samples_) column.texts.push_back(value_of(s));
    table_->columns.push_back(std::move(column));
    return *this;
  }
  // One column per wheel, `prefix` + the wheel's name, from a per-wheel array member.
  template <typename Array>
  Columns& PerWheel(const std::vector<std::string>& wheels, const std::string& prefix,
                    Array Sample::*member) {
    for (size_t i = 0; i < wheels.size(); ++i) {
      Number(prefix + wheels[i], [member, i](const Sample& s) { return (s.*member)[i]; });
    }
    return *this;
  }

 private:
  LogTable* table_;
  const std::vector<Sample>& samples_;
};

size_t SampleCount(const DriveLog& log, const std::string& file) {
  if (file == "imu.csv") return log.imu.size();
  if (file == "wheels.csv") return log.wheels.size();
  if (file == "attitude.csv") return log.attitude.size();
  if (file == "gps.csv") return log.gps.size();
  if (file == "pose.csv") return log.pose.size();
  if (file == "articulation.csv") return log.articulation.size();
  if (file == "range.csv") return log.range.size();
  if (file == "commands.csv") return log.commands.size();
  if (file == "truth.csv") return log.truth.size();
  return log.events.size();
}

}  // namespace

std::vector<std::string> LogTableFiles(const DriveLog& log) {
  std::vector<std::string> files = {StreamFiles()[0], StreamFiles()[1]};
  for (size_t i = 2; i < StreamFiles().size(); ++i) {
    const std::string& file = StreamFiles()[i];
    if (log.Has(file) || SampleCount(log, file) > 0) files.push_back(file);
  }
  return files;
}

LogTable StreamTable(const DriveLog& log, const std::string& file) {
  LogTable table;
  table.file = file;
  const std::vector<std::string>& wheels = WheelNames(log.vehicle.type);
  if (file == "imu.csv") {
    Columns<ImuSample>(&table, log.imu)
        .Member("t", &ImuSample::t)
        .Member("ax", &ImuSample::ax)
        .Member("ay", &ImuSample::ay)
        .Member("az", &ImuSample::az)
        .Member("gx", &ImuSample::gx)
        .Member("gy", &ImuSample::gy)
        .Member("gz", &ImuSample::gz);
  } else if (file == "wheels.csv") {
    Columns<WheelSample>(&table, log.wheels)
        .Member("t", &WheelSample::t)
        .PerWheel(wheels, "", &WheelSample::omega_radps);
  } else if (file == "attitude.csv") {
    Columns<AttitudeSample>(&table, log.attitude)
        .Member("t", &AttitudeSample::t)
        .Member("roll", &AttitudeSample::roll)
        .Member("pitch", &AttitudeSample::pitch)
        .Member("yaw", &AttitudeSample::yaw)
        .Member("sd_roll", &AttitudeSample::sd_roll)
        .Member("sd_pitch", &AttitudeSample::sd_pitch)
        .Member("sd_yaw", &AttitudeSample::sd_yaw);
  } else if (file == "gps.csv") {
    Columns<GpsSample>(&table, log.gps)
        .Member("t", &GpsSample::t)
        .Member("x", &GpsSample::x)
        .Member("y", &GpsSample::y)
        .Member("z", &GpsSample::z)
        .Member("vx", &GpsSample::vx)
        .Member("vy", &GpsSample::vy)
        .Member("vz", &GpsSample::vz)
        .Member("sd_xy", &GpsSample::sd_xy)
        .Member("sd_z", &GpsSample::sd_z)
        .Member("sd_v", &GpsSample::sd_v);
  } else if (file == "pose.csv") {
    Columns<PoseSample>(&table, log.pose)
        .Member("t", &PoseSample::t)
        .Member("x", &PoseSample::x)
        .Member("y", &PoseSample::y)
        .Member("z", &PoseSample::z)
        .Member("roll", &PoseSample::roll)
        .Member("pitch", &PoseSample::pitch)
        .Member("yaw", &PoseSample::yaw)
        .Member("sd_x", &PoseSample::sd_x)
        .Member("sd_y", &PoseSample::sd_y)
        .Member("sd_yaw", &PoseSample::sd_yaw);
  } else if (file == "articulation.csv") {
    Columns<ArticulationSample>(&table, log.articulation)
        .Member("t", &ArticulationSample::t)
        .Text("side", [](const ArticulationSample& s) { return SideName(s.side); })
        .Member("dz_mid", &ArticulationSample::dz_mid)
        .Member("dz_front", &ArticulationSample::dz_front);
  } else if (file == "range.csv") {
    Columns<RangeSample>(&table, log.range)
        .Member("t", &RangeSample::t)
        .Text("side", [](const RangeSample& s) { return SideName(s.side); })
        .Member("d", &RangeSample::d)
        .Member("dz", &RangeSample::dz);
  } else if (file == "commands.csv") {
    Columns<CommandSample>(&table, log.commands)
        .Member("t", &CommandSample::t)
        .Member("v", &CommandSample::v)
        .Member("omega", &CommandSample::omega);
  } else if (file == "truth.csv") {
    Columns<TruthSample>(&table, log.truth)
        .Member("t", &TruthSample::t)
        .Member("x", &TruthSample::x)
        .Member("y", &TruthSample::y)
        .Member("z", &TruthSample::z)
        .Member("roll", &TruthSample::roll)
        .Member("pitch", &TruthSample::pitch)
        .Member("yaw", &TruthSample::yaw)
        .Member("vx", &TruthSample::vx)
        .Member("vy", &TruthSample::vy)
        .Member("yaw_rate", &TruthSample::yaw_rate)
        .Member("a_dist", &TruthSample::a_dist)
        .Member("immobilized", &TruthSample::immobilized)
        .PerWheel(wheels, "slip_", &TruthSample::slip)
        .PerWheel(wheels, "sinkage_", &TruthSample::sinkage);
  } else if (file == "events.csv") {
    Columns<Event>(&table, log.events)
        .Member("t_start", &Event::t_start)
        .Member("t_end", &Event::t_end)
        .Text("label", [](const Event& e) { return e.label; });
  } else {
    std::string known;
    for (const std::string& name : StreamFiles()) known += (known.empty() ? "" : ", ") + name;
    throw std::invalid_argument("'" + file + "' is not a stream file of a drive log (" + known +
                                ")");
  }
  return table;
}

}  // namespace slipgraph
