// The importers on tiny recordings written here, so that they are tested without the real logs in
// ../shared: a MATLAB v7.3 file (HDF5, written with the HDF5 library) and a ROS 1 bag (written
// with rosbag), each with a known motion. Checked: every stream's count, values, frame and sign
// conventions, the GNSS velocity by central difference, the shifted clock, and the errors that
// name the file and the variable, topic or key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/hdf5_matrix.h"
#include "io/input_error.h"
#include "io/matlab_import.h"
#include "io/rosbag_import.h"
#include "io/yaml_config.h"
#include "tests/import_test_util.h"
#include "tests/tiny_recordings.h"

namespace slipgraph {
namespace {

using testing::kBagMapping;
using testing::kMatMapping;
using testing::TinyVehicle;

std::string WriteText(const std::string& name, const std::string& text) {
  return testing::WriteText(::testing::TempDir(), name, text);
}

std::string WriteTinyMat(const std::string& name) {
  return testing::WriteTinyMat(::testing::TempDir(), name);
}

std::string WriteTinyBag(const std::string& name) {
  return testing::WriteTinyBag(::testing::TempDir(), name);
}

TEST(SyntheticImport, MatlabFileEveryStreamAndConvention) {
  const std::string mat = WriteTinyMat("tiny.mat");
  const std::string mapping = WriteText("tiny_mat.yaml", kMatMapping);
  ImportReport report;
  const DriveLog log = ImportMatlab(mat, mapping, TinyVehicle(), &report);
  ASSERT_EQ(log.imu.size(), 200u);
  ASSERT_EQ(log.wheels.size(), 20u);
  ASSERT_EQ(log.gps.size(), 10u);
  // The clock starts at the earliest stamp (the IMU's, 50 s).
  EXPECT_NEAR(log.imu.front().t, 0.0, 1e-12);
  EXPECT_NEAR(log.wheels.front().t, 0.05, 1e-9);
  EXPECT_NEAR(log.gps.front().t, 0.1, 1e-9);
  // z_down: rotated 180 deg about x, y and z negated (gravity +9.8 on z at rest).
  EXPECT_EQ(log.imu[7].ax, 0.2);
  EXPECT_EQ(log.imu[7].ay, -0.1);
  EXPECT_EQ(log.imu[7].az, 9.8);
  EXPECT_EQ(log.imu[7].gx, 0.01);
  EXPECT_EQ(log.imu[7].gy, -0.02);
  EXPECT_EQ(log.imu[7].gz, 0.3);
  // Each side the mean of its wheels times its sign.
  EXPECT_DOUBLE_EQ(log.wheels[3].omega_radps[0], 5.0);
  EXPECT_DOUBLE_EQ(log.wheels[3].omega_radps[1], 5.0);
  // ENU positions as stored; velocity by central difference (0.1 m per 0.2 s east).
  EXPECT_DOUBLE_EQ(log.gps[4].x, 0.4);
  EXPECT_DOUBLE_EQ(log.gps[4].y, 2.0);
  EXPECT_NEAR(log.gps[4].vx, 0.5, 1e-9);
  EXPECT_NEAR(log.gps[4].vy, 0.0, 1e-12);
  EXPECT_NEAR(log.gps.back().vx, 0.5, 1e-9);  // one-sided at the ends
  EXPECT_EQ(log.gps[4].sd_xy, 2.5);
  EXPECT_EQ(log.gps[4].sd_v, 0.2);
  ASSERT_EQ(report.lines.size(), 4u);
  EXPECT_NE(report.lines[0].find("frame z_down"), std::string::npos) << report.lines[0];

  // import --list: the variables and their HDF5 dimensions.
  bool listed = false;
  for (const SourceEntry& e : ListMatlab(mat)) {
    if (e.name == "ENUGPS") {
      EXPECT_EQ(e.type, "3 x 10");
      EXPECT_EQ(e.count, 30);
      listed = true;
    }
  }
  EXPECT_TRUE(listed);
}

using testing::ErrorOf;

TEST(SyntheticImport, MatlabErrorsNameTheFileAndTheVariable) {
  const std::string mat = WriteTinyMat("tiny_short_gps.mat");
  ImportReport report;
  const std::string missing =
      WriteText("missing_var.yaml",
                std::string(kMatMapping).replace(std::string(kMatMapping).find("Az"), 2, "Azz"));
  std::string e = ErrorOf([&] { ImportMatlab(mat, missing, TinyVehicle(), &report); });
  EXPECT_NE(e.find("tiny_short_gps.mat"), std::string::npos) << e;
  EXPECT_NE(e.find("no variable named 'Azz'"), std::string::npos) << e;

  const std::string wrong_t = WriteText(
      "wrong_t.yaml",
      std::string(kMatMapping).replace(std::string(kMatMapping).find("t: tTodom"), 9, "t: tTimu"));
  e = ErrorOf([&] { ImportMatlab(mat, wrong_t, TinyVehicle(), &report); });
  EXPECT_NE(e.find("frontLeftVel"), std::string::npos) << e;
  EXPECT_NE(e.find("has 20 values for 200 wheel stamps"), std::string::npos) << e;

  const std::string not_hdf5 = WriteText("not_hdf5.mat", "MATLAB 5.0 MAT-file\n");
  e = ErrorOf([&] { ReadHdf5Matrix(not_hdf5, "Ax"); });
  EXPECT_NE(e.find("cannot open as HDF5"), std::string::npos) << e;
  e = ErrorOf([&] { ReadHdf5Matrix(mat, "ENUGPS").Vector("ENUGPS"); });
  EXPECT_NE(e.find("expected a vector, found a 3 x 10 matrix"), std::string::npos) << e;
}

// A corrupted file's dimensions are not allocated as read: here a chunked dataset of more values
// than the reader takes, none of them written (HDF5 stores no chunk), in a small file.
TEST(SyntheticImport, AVariableLargerThanTheReaderTakesIsAnError) {
  const std::string path = ::testing::TempDir() + "/huge.mat";
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[2] = {2, kMaxHdf5Values / 2 + 1}, chunk[2] = {1, 1024};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t layout = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(layout, 2, chunk);
  const hid_t set =
      H5Dcreate2(file, "Huge", H5T_IEEE_F64LE, space, H5P_DEFAULT, layout, H5P_DEFAULT);
  ASSERT_GE(set, 0);
  H5Dclose(set), H5Pclose(layout), H5Sclose(space), H5Fclose(file);
  const std::string e = ErrorOf([&] { ReadHdf5Matrix(path, "Huge"); });
  EXPECT_NE(e.find("Huge"), std::string::npos) << e;
  EXPECT_NE(e.find("more than this reader takes"), std::string::npos) << e;
}

TEST(SyntheticImport, RosBagEveryStreamAndConvention) {
  const std::string bag = WriteTinyBag("tiny.bag");
  const std::string mapping = WriteText("tiny_bag.yaml", kBagMapping);
  ImportReport report;
  const DriveLog log = ImportRosBag(bag, mapping, TinyVehicle(), &report);
  ASSERT_EQ(log.imu.size(), 100u);
  ASSERT_EQ(log.attitude.size(), 100u);
  ASSERT_EQ(log.wheels.size(), 20u);
  ASSERT_EQ(log.gps.size(), 4u);  // the fix without a fix is skipped
  EXPECT_NEAR(log.imu.front().t, 0.0, 1e-9);
  EXPECT_NEAR(log.wheels.front().t, 0.01, 1e-6);
  EXPECT_NEAR(log.gps.front().t, 0.55, 1e-6);
  // The IMU rotated into the body frame.
  EXPECT_NEAR(log.imu[5].ax, 0.3, 1e-12);
  EXPECT_NEAR(log.imu[5].ay, 0.1, 1e-12);
  EXPECT_NEAR(log.imu[5].az, 9.8, 1e-12);
  EXPECT_NEAR(log.imu[5].gz, 0.2, 1e-12);
  // Attitude: the body's yaw plus the mapping's offset; level; the stated sd.
  EXPECT_NEAR(log.attitude[5].yaw, 0.7, 1e-9);
  EXPECT_NEAR(log.attitude[5].pitch, 0.0, 1e-9);
  EXPECT_NEAR(log.attitude[5].roll, 0.0, 1e-9);
  // Side speeds from the body twist: (v -+ track / 2 w) / r.
  EXPECT_NEAR(log.wheels[4].omega_radps[0], 9.5, 1e-12);
  EXPECT_NEAR(log.wheels[4].omega_radps[1], 10.5, 1e-12);
  // Local ENU at the first fix: north at 1 m/s, the stated position sd.
  EXPECT_NEAR(log.gps[0].y, 0.0, 1e-9);
  EXPECT_NEAR(log.gps[2].y, 1.0, 1e-6);
  EXPECT_NEAR(log.gps[2].vy, 1.0, 1e-6);
  EXPECT_NEAR(log.gps[2].vx, 0.0, 1e-9);
  EXPECT_EQ(log.gps[2].sd_xy, 2.0);
  EXPECT_EQ(log.gps[2].sd_v, 0.3);
  bool skipped_said = false;
  for (const std::string& line : report.lines) {
    skipped_said = skipped_said || line.find("skipped: 1 messages") != std::string::npos;
  }
  EXPECT_TRUE(skipped_said);
  // import --list: the topics, their types and rates.
  const std::vector<SourceEntry> topics = ListRosBag(bag);
  ASSERT_EQ(topics.size(), 3u);
  EXPECT_EQ(topics[1].name, "/imu");
  EXPECT_EQ(topics[1].type, "sensor_msgs/Imu");
  EXPECT_EQ(topics[1].count, 100);
  EXPECT_NEAR(topics[1].rate_hz, 50.0, 1e-6);
}

TEST(SyntheticImport, RosBagErrorsNameTheTopicAndTheKey) {
  const std::string bag = WriteTinyBag("tiny_errors.bag");
  ImportReport report;
  std::string mapping_text = kBagMapping;
  mapping_text.replace(mapping_text.find("topic: /fix"), 11, "topic: /gnss");
  const std::string no_topic = WriteText("no_topic.yaml", mapping_text);
  std::string e = ErrorOf([&] { ImportRosBag(bag, no_topic, TinyVehicle(), &report); });
  EXPECT_NE(e.find("gps.topic"), std::string::npos) << e;
  EXPECT_NE(e.find("no messages on this topic"), std::string::npos) << e;

  mapping_text = kBagMapping;
  mapping_text.replace(mapping_text.find("topic: /imu"), 11, "topic: /odom");
  const std::string wrong_type = WriteText("wrong_type.yaml", mapping_text);
  e = ErrorOf([&] { ImportRosBag(bag, wrong_type, TinyVehicle(), &report); });
  EXPECT_NE(e.find("not a sensor_msgs/Imu"), std::string::npos) << e;

  const std::string not_a_bag = WriteText("not_a.bag", "#ROSBAG V1.2\nnothing\n");
  e = ErrorOf(
      [&] { ImportRosBag(not_a_bag, WriteText("ok.yaml", kBagMapping), TinyVehicle(), &report); });
  EXPECT_NE(e.find("not a ROS bag of format 2.0"), std::string::npos) << e;
}

}  // namespace
}  // namespace slipgraph
