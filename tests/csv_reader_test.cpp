#include "io/csv_reader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/input_error.h"
#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

std::string WriteCsv(const std::string& text) {
  const std::string dir = testing::FreshDirectory("csv");
  testing::WriteText(dir, "f.csv", text);
  return dir + "/f.csv";
}

TEST(CsvReader, SkipsCommentsAndBlankLinesAndHandlesCrlfAndSpaces) {
  CsvReader r(WriteCsv("# a comment\n\nt, b ,a\r\n# mid comment\n1, 2 ,+3\r\n\n4,5,6\n"),
              {{"a", true}, {"t", true}, {"z", false}});
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.line(), 5);
  EXPECT_EQ(r.Number(0), 3.0);
  EXPECT_EQ(r.Number(1), 1.0);
  EXPECT_FALSE(r.Has(2));
  EXPECT_TRUE(std::isnan(r.Number(2)));
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.line(), 7);
  EXPECT_EQ(r.Number(0), 6.0);
  EXPECT_FALSE(r.Next());
  EXPECT_EQ(r.header(), (std::vector<std::string>{"t", "b", "a"}));
}

TEST(CsvReader, ShortRowIsAnErrorNamingTheColumn) {
  CsvReader r(WriteCsv("t,a,b\n1,2\n"), {{"t", true}, {"b", true}});
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.Number(0), 1.0);
  try {
    r.Number(1);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.column(), "b");
  }
}

// A decimal comma ("2,93") splits a cell in two and shifts every column after it: the row was
// read with the wrong values in the right-hand columns.
TEST(CsvReader, LongRowIsAnErrorNamingTheLine) {
  CsvReader r(WriteCsv("t,a,b\n1,2,3\n2,2,93,4\n"), {{"t", true}, {"b", true}});
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.Number(1), 3.0);
  ASSERT_TRUE(r.Next());
  try {
    r.Number(1);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("4 cells, the header 3"), std::string::npos) << e.what();
  }
}

// A spreadsheet's UTF-8 byte-order mark made the first column "\xEF\xBB\xBFt": "required column
// 't' is missing".
TEST(CsvReader, AByteOrderMarkIsNotPartOfTheHeader) {
  CsvReader r(WriteCsv("\xEF\xBB\xBFt,a\n1,2\n"), {{"t", true}, {"a", true}});
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.Number(0), 1.0);
  EXPECT_EQ(r.Number(1), 2.0);
}

TEST(CsvReader, TrailingGarbageIsNotANumber) {
  CsvReader r(WriteCsv("t\n1.5x\n"), {{"t", true}});
  ASSERT_TRUE(r.Next());
  EXPECT_THROW(r.Number(0), InputError);
}

TEST(CsvReader, ReadsTextHeldInMemoryNamingItInErrors) {
  const std::string text = "t,a\n1,2\n2,x\n";
  CsvReader r("memory/f.csv", text, {{"t", true}, {"a", true}});
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.Number(1), 2.0);
  ASSERT_TRUE(r.Next());
  try {
    r.Number(1);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "memory/f.csv");
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.value(), "x");
  }
}

// The last row of `text` with the reader positioned on it.
double LastNumber(const std::string& text, int column) {
  CsvReader r("f.csv", text, {{"t", true}, {"a", true}});
  while (r.Next()) {
    if (r.line() == 5) return r.Number(column);
  }
  ADD_FAILURE() << "no fifth line";
  return 0.0;
}

// A recorder stopped while writing: the file ends inside its last number, which still parses.
// A fixed-precision writer's three rows before show the number was cut.
TEST(CsvReader, ANumberCutByTheFilesEndIsAnError) {
  const std::string rows = "t,a\n0.100,1.2500\n0.200,1.2510\n0.300,1.2520\n";
  try {
    LastNumber(rows + "0.400,1.25", 1);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 5);
    EXPECT_EQ(e.column(), "a");
    EXPECT_EQ(e.value(), "1.25");
    EXPECT_NE(std::string(e.what()).find("cut short"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LastNumber(rows + "0.4", 0), InputError);  // cut in the first cell
  EXPECT_EQ(LastNumber(rows + "0.400,1.25", 0), 0.4);     // its whole cells read
}

// A last row without a line end is allowed by the format: whole numbers read, and so does a
// shorter number with its line end, or where the rows before vary in length (a "%g" writer).
TEST(CsvReader, ALastRowWithoutALineEndIsReadWhenNothingShowsACut) {
  const std::string rows = "t,a\n0.100,1.2500\n0.200,1.2510\n0.300,1.2520\n";
  EXPECT_EQ(LastNumber(rows + "0.400,1.2530", 1), 1.253);
  EXPECT_EQ(LastNumber(rows + "0.400,1.25\n", 1), 1.25);
  EXPECT_EQ(LastNumber("t,a\n0.1,1.5\n0.2,1.25\n0.3,1.125\n0.4,1", 1), 1.0);
  EXPECT_EQ(LastNumber("t,a\n0.1,1\n0.2,2\n0.3,3\n0.4,4", 1), 4.0);
}

TEST(CsvReader, EmptyFileHasNoHeader) {
  EXPECT_THROW(CsvReader(WriteCsv("# only a comment\n"), {{"t", true}}), InputError);
}

}  // namespace
}  // namespace slipgraph
