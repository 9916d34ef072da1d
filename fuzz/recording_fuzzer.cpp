// Fuzzes the importers on recordings. The first byte modulo 4 picks:
// - 1: a ROS 1 bag, the rest its bytes. CheckRosBagRecords and the rosbag library parse them;
//   what passes is decoded message by message.
// - 2: an MCAP file (a ROS 2 bag), the rest its bytes, imported with the tiny recording's
//   mapping: records, chunks (zstd, lz4) and CDR messages as the bytes say.
// - 3: one CDR message, the next byte picking its type: decoded, or a CdrError.
// - 0: a MATLAB v7.3 file whose content the rest chooses (FuzzedDataProvider): for each
//   variable the tiny recording's mapping names, present or not, a dataset or a group, its number
//   type, rank, dimensions and values (NaN, infinities and extremes among them), written with
//   the HDF5 library. The HDF5 format's own bytes are not fuzzed here: Debian's HDF5 allocates
//   what a corrupted file's metadata claims (terabytes, inside H5C_protect), a fault of that
//   library that no caller can guard against.
// Either way, import must give a log that reads back, or throw InputError.
#include <fuzzer/FuzzedDataProvider.h>
#include <hdf5.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "fuzz/fuzz_util.h"
#include "io/cdr_reader.h"
#include "io/input_error.h"
#include "io/matlab_import.h"
#include "io/ros2_messages.h"
#include "io/rosbag2_import.h"
#include "io/rosbag_import.h"
#include "tests/tiny_recordings.h"

namespace {

const char* const kVariables[] = {"tTimu",
                                  "Ax",
                                  "Ay",
                                  "Az",
                                  "Gx",
                                  "Gy",
                                  "Gz",
                                  "tTodom",
                                  "frontLeftVel",
                                  "rearLeftVel",
                                  "frontRightVel",
                                  "rearRightVel",
                                  "tTGPS",
                                  "ENUGPS"};

double Value(FuzzedDataProvider& input) {
  switch (input.ConsumeIntegralInRange(0, 7)) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return std::numeric_limits<double>::infinity();
    case 2:
      return -std::numeric_limits<double>::max();
    case 3:
      return 0.01 * input.ConsumeIntegralInRange(0, 400);  // a plausible clock
    default:
      return input.ConsumeFloatingPointInRange(-1e3, 1e3);
  }
}

// A MATLAB file the input describes, at `path`.
void WriteMatlab(FuzzedDataProvider& input, const std::string& path) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t types[] = {H5T_IEEE_F64LE, H5T_IEEE_F32LE, H5T_STD_I32LE, H5T_STD_U8LE,
                         H5T_STD_I64LE};
  for (const char* name : kVariables) {
    const int kind = input.ConsumeIntegralInRange(0, 9);
    if (kind == 0) continue;  // absent
    if (kind == 1) {          // a group (a MATLAB struct), not a dataset
      H5Gclose(H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
      continue;
    }
    const int rank = input.ConsumeIntegralInRange(1, 3);
    std::vector<hsize_t> dims(rank);
    hsize_t count = 1;
    for (hsize_t& d : dims) count *= (d = input.ConsumeIntegralInRange<hsize_t>(0, 40));
    std::vector<double> values(count);
    for (double& v : values) v = Value(input);
    const hid_t space = H5Screate_simple(rank, dims.data(), nullptr);
    const hid_t set = H5Dcreate2(file, name, types[input.ConsumeIntegralInRange(0, 4)], space,
                                 H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (count > 0) H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(set);
    H5Sclose(space);
  }
  H5Fclose(file);
}

}  // namespace

std::string RosBagMapping() {
  std::string text = slipgraph::testing::kBagMapping;
  text.replace(text.find("ros1_bag"), 8, "ros_bag");
  return text;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string& dir = slipgraph::fuzz::ScratchDirectory();
  static const std::string mat_mapping =
      slipgraph::testing::WriteText(dir, "mat_mapping.yaml", slipgraph::testing::kMatMapping);
  static const std::string bag_mapping =
      slipgraph::testing::WriteText(dir, "bag_mapping.yaml", RosBagMapping());
  const int kind = data[0] % 4;
  if (kind == 3) {
    if (size < 2) return 0;
    const char* types[] = {"sensor_msgs/msg/Imu", "nav_msgs/msg/Odometry",
                           "sensor_msgs/msg/NavSatFix", "sensor_msgs/msg/JointState",
                           "tf2_msgs/msg/TFMessage"};
    try {
      slipgraph::DecodeRos2Message(types[data[1] % 5], data + 2, size - 2);
    } catch (const slipgraph::CdrError&) {
    }
    return 0;
  }
  const std::string recording = dir + (kind == 1   ? "/recording.bag"
                                       : kind == 2 ? "/recording.mcap"
                                                   : "/recording.mat");
  if (kind == 0) {
    FuzzedDataProvider input(data + 1, size - 1);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    WriteMatlab(input, recording);
  } else {
    slipgraph::fuzz::WriteFile(recording, data + 1, size - 1);
  }
  slipgraph::ImportReport report;
  slipgraph::DriveLog log;
  const slipgraph::Vehicle vehicle = slipgraph::testing::TinyVehicle();
  try {
    log = kind == 1   ? slipgraph::ImportRosBag(recording, bag_mapping, vehicle, &report)
          : kind == 2 ? slipgraph::ImportRos2Bag(recording, bag_mapping, vehicle, &report)
                      : slipgraph::ImportMatlab(recording, mat_mapping, vehicle, &report);
  } catch (const slipgraph::InputError&) {
    return 0;
  }
  slipgraph::fuzz::CheckReadsBack(log);
  return 0;
}
