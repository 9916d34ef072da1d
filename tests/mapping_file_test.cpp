// The importers' mapping files: a parse error names the file and line, an unknown key (a typo)
// is an error naming it with its section, a missing file is an error naming it, a stated sd must
// be a positive number.
#include "io/mapping_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "io/input_error.h"
#include "io/yaml_errors.h"
#include "tests/import_test_util.h"

namespace slipgraph {
namespace {

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

using testing::ErrorOf;

TEST(MappingFile, LoadsAndChecksKnownKeys) {
  const std::string path = Write("mapping_ok.yaml", "format: x\nimu: {topic: /imu, frame: z_up}\n");
  const YAML::Node m = LoadYamlFile(path);
  EXPECT_EQ(m["imu"]["topic"].as<std::string>(), "/imu");
  EXPECT_NO_THROW(CheckMappingKeys(m, "", {"format", "imu"}, path));
  EXPECT_NO_THROW(CheckMappingKeys(m["imu"], "imu", {"topic", "frame"}, path));
}

TEST(MappingFile, AnUnknownKeyIsNamedWithItsSection) {
  const std::string path = Write("mapping_typo.yaml", "imu: {topic: /imu, frmae: z_up}\n");
  const std::string e = ErrorOf([&] {
    CheckMappingKeys(LoadYamlFile(path)["imu"], "imu", {"topic", "frame"}, path);
  });
  EXPECT_NE(e.find("mapping_typo.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("imu.frmae"), std::string::npos) << e;
}

TEST(MappingFile, ADuplicateKeyIsNamed) {
  const std::string path =
      Write("mapping_duplicate.yaml", "imu:\n  topic: /imu\n  frame: z_up\n  frame: z_down\n");
  const std::string e = ErrorOf([&] { LoadYamlFile(path); });
  EXPECT_NE(e.find("mapping_duplicate.yaml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("imu.frame"), std::string::npos) << e;
  EXPECT_NE(e.find("duplicate key"), std::string::npos) << e;
}

TEST(MappingFile, AStatedSdIsAPositiveNumberOrAnErrorNamingIt) {
  const std::string ok = Write("mapping_sd.yaml", "gps: {topic: /fix, sd_v: 0.3}\n");
  EXPECT_EQ(MappingSd(LoadYamlFile(ok)["gps"], "gps", "sd_v", ok), 0.3);
  EXPECT_TRUE(std::isnan(MappingSd(LoadYamlFile(ok)["gps"], "gps", "sd_xy", ok)));  // kMissing
  // Found by the import fuzzer: a negative sd was written into gps.csv, which the reader refuses.
  for (const char* value : {"-.3", "0", "nan", "fast"}) {
    const std::string path =
        Write("mapping_bad_sd.yaml", std::string("gps:\n  topic: /fix\n  sd_v: ") + value + "\n");
    const std::string e =
        ErrorOf([&] { MappingSd(LoadYamlFile(path)["gps"], "gps", "sd_v", path); });
    EXPECT_NE(e.find("mapping_bad_sd.yaml:3"), std::string::npos) << value << ": " << e;
    EXPECT_NE(e.find("gps.sd_v"), std::string::npos) << value << ": " << e;
  }
}

TEST(MappingFile, ParseErrorsAndMissingFilesAreNamed) {
  const std::string bad = Write("mapping_bad.yaml", "imu:\n  topic: [unclosed\n");
  std::string e = ErrorOf([&] { LoadYamlFile(bad); });
  EXPECT_NE(e.find("mapping_bad.yaml"), std::string::npos) << e;
  const std::string missing = ::testing::TempDir() + "/no_such_mapping.yaml";
  e = ErrorOf([&] { LoadYamlFile(missing); });
  EXPECT_NE(e.find("no_such_mapping.yaml"), std::string::npos) << e;
  const std::string scalar = Write("mapping_scalar.yaml", "just text\n");
  e = ErrorOf([&] { CheckMappingKeys(LoadYamlFile(scalar), "", {"format"}, scalar); });
  EXPECT_NE(e.find("mapping_scalar.yaml"), std::string::npos) << e;
}

}  // namespace
}  // namespace slipgraph
