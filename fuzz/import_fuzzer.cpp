// Fuzzes the importers' mapping files: the first byte picks the tiny MATLAB v7.3 file or the tiny
// ROS bag (tests/tiny_recordings.h), the rest is the mapping. Import must give a log that reads
// back, or throw InputError. (The recordings' own bytes are parsed by the HDF5 and rosbag
// libraries.)
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
  static const std::string mat = slipgraph::testing::WriteTinyMat(dir, "tiny.mat");
  static const std::string bag = slipgraph::testing::WriteTinyBag(dir, "tiny.bag");
  const std::string mapping = dir + "/mapping.yaml";
  slipgraph::fuzz::WriteFile(mapping, data + 1, size - 1);
  slipgraph::ImportReport report;
  slipgraph::DriveLog log;
  try {
    log = (data[0] & 1)
              ? slipgraph::ImportRosBag(bag, mapping, slipgraph::testing::TinyVehicle(), &report)
              : slipgraph::ImportMatlab(mat, mapping, slipgraph::testing::TinyVehicle(), &report);
  } catch (const slipgraph::InputError&) {
    return 0;
  }
  slipgraph::fuzz::CheckReadsBack(log);
  return 0;
}
