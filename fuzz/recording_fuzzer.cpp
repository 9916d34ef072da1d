// Fuzzes the importers on the recordings' own bytes: the first byte picks a MATLAB v7.3 file
// (HDF5) or a ROS 1 bag, the rest is that file, imported with the tiny recordings' mapping
// (tests/tiny_recordings.h). Import must give a log that reads back, or throw InputError. The bytes
// are parsed by the HDF5 and rosbag libraries first, so a finding may be theirs: the importers must
// still turn what those libraries report into an InputError naming the file.
#include <cstdint>
#include <string>

#include "fuzz/fuzz_util.h"
#include "io/input_error.h"
#include "io/matlab_import.h"
#include "io/rosbag_import.h"
#include "tests/tiny_recordings.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string& dir = slipgraph::fuzz::ScratchDirectory();
  static const std::string mat_mapping =
      slipgraph::testing::WriteText(dir, "mat_mapping.yaml", slipgraph::testing::kMatMapping);
  static const std::string bag_mapping =
      slipgraph::testing::WriteText(dir, "bag_mapping.yaml", slipgraph::testing::kBagMapping);
  const bool bag = (data[0] & 1) != 0;
  const std::string recording = dir + (bag ? "/recording.bag" : "/recording.mat");
  slipgraph::fuzz::WriteFile(recording, data + 1, size - 1);
  slipgraph::ImportReport report;
  slipgraph::DriveLog log;
  try {
    log = bag ? slipgraph::ImportRosBag(recording, bag_mapping, slipgraph::testing::TinyVehicle(),
                                        &report)
              : slipgraph::ImportMatlab(recording, mat_mapping, slipgraph::testing::TinyVehicle(),
                                        &report);
  } catch (const slipgraph::InputError&) {
    return 0;
  }
  slipgraph::fuzz::CheckReadsBack(log);
  return 0;
}
