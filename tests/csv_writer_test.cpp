// CSV output in the drive-log dialect: header and rows, numbers that read back to the same
// double, missing values as nan, and write errors named.
#include "io/csv_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "io/input_error.h"

namespace slipgraph {
namespace {

TEST(CsvWriter, HeaderRowsAndRoundTripNumbers) {
  const std::string path = ::testing::TempDir() + "/csv_writer_test.csv";
  {
    CsvWriter w(path, {"t", "v", "label"});
    w << 0.1 << (1.0 / 3.0) << std::string("a");
    w.EndRow();
    w << 2.0 << std::nan("") << std::string("b");
    w.EndRow();
    w.Close();
  }
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "t,v,label\n0.1,0.3333333333333333,a\n2,nan,b\n");
  EXPECT_EQ(std::stod(FormatNumber(1.0 / 3.0)), 1.0 / 3.0);
  EXPECT_EQ(std::stod(FormatNumber(1e-300)), 1e-300);
  EXPECT_EQ(FormatNumber(std::nan("")), "nan");
}

TEST(CsvWriter, OpenAndWriteErrorsNameTheFile) {
  const std::string missing = ::testing::TempDir() + "/no/such/dir/out.csv";
  try {
    CsvWriter w(missing, {"t"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  EXPECT_THROW(
      {
        CsvWriter w("/dev/full", {"t"});
        for (int i = 0; i < 100000; ++i) {
          w << 1.0 * i;
          w.EndRow();
        }
        w.Close();
      },
      InputError);
}

}  // namespace
}  // namespace slipgraph
