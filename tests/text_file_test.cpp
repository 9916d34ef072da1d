// Whole-file text output: written and read back, replaced, and errors naming the path for a
// missing directory and a full disk.
#include "io/text_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "io/input_error.h"

namespace slipgraph {
namespace {

std::string Read(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(TextFile, WrittenAndReplaced) {
  const std::string path = ::testing::TempDir() + "/text_file_test.txt";
  WriteTextFile(path, "first, longer text\n");
  WriteTextFile(path, "second\n");
  EXPECT_EQ(Read(path), "second\n");
}

TEST(TextFile, AMissingDirectoryIsAnErrorNamingThePath) {
  const std::string path = ::testing::TempDir() + "/no/such/dir/report.html";
  try {
    WriteTextFile(path, "x");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(TextFile, AFullDiskIsAnError) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  EXPECT_THROW(WriteTextFile("/dev/full", std::string(1 << 16, 'x')), InputError);
}

}  // namespace
}  // namespace slipgraph
