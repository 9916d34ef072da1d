// Reader for the drive-log CSV dialect (shared/log-format.md): '#' comment lines, first
// non-comment line is the header, columns matched by name in any order, unknown columns ignored,
// empty cells and "nan" are missing values; a leading UTF-8 byte-order mark is skipped, and a row
// with more cells than the header is an error, and so is a last number that a file cut short
// has truncated (below). Plain numeric CSV without quoting, so this is a tokenizer over a memory
// buffer; Debian's libfccp needs the column count at compile time, which
// the vehicle-dependent columns (wheels, slip_<wheel>) rule out.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace slipgraph {

struct CsvColumn {
  std::string name;
  bool required = true;  // a required column must exist and hold a finite number on every row
};

class CsvReader {
 public:
  // Reads the file and its header. Throws InputError when the file cannot be read, has no
  // header, or lacks a required column (named in the error).
  CsvReader(std::string path, std::vector<CsvColumn> columns);
  // The same over `text` held by the caller (alive as long as the reader); `name` stands for the
  // file's path in errors.
  CsvReader(std::string name, std::string_view text, std::vector<CsvColumn> columns);
  CsvReader(const CsvReader&) = delete;  // cells_ view text_, which may view owned_
  CsvReader& operator=(const CsvReader&) = delete;

  // Advances to the next data row (comments and blank lines are skipped). False at the end.
  bool Next();

  // True when the (optional) column exists in the header.
  bool Has(int column) const { return positions_[column] >= 0; }
  // The number in `column` of the current row. Throws InputError naming file, line, column and
  // value when the cell is not a number, is infinite, or is missing in a required column, and
  // when the file ends inside it without a line end and it has fewer characters after its point
  // than the same column in each of the three rows before (a fixed-precision writer's file cut
  // short: "0.512345" read as "0.51"). A missing optional value (absent column, empty cell or
  // "nan") is returned as NaN.
  double Number(int column) const;
  // The raw text of a cell (for label columns such as `side`). Throws when missing.
  std::string Text(int column) const;
  // Throws InputError for the current row and `column` with the given message.
  [[noreturn]] void Fail(int column, const std::string& value, const std::string& what) const;

  int line() const { return line_number_; }
  // Every column name of the header, in file order.
  const std::vector<std::string>& header() const { return header_; }
  const std::string& path() const { return path_; }
  const std::string& column_name(int column) const { return columns_[column].name; }

 private:
  void ReadHeader();
  std::string_view Cell(int column) const;
  // The header position of a cell of the last row that a cut has likely shortened, or -1.
  int CutCell() const;

  std::string path_;
  std::vector<CsvColumn> columns_;
  std::vector<std::string> header_;
  std::vector<int> positions_;  // header position of each requested column, -1 when absent
  std::string owned_;           // the file's text, when the reader read it
  std::string_view text_;       // what it parses: owned_ or the caller's
  size_t cursor_ = 0;
  int line_number_ = 0;
  std::vector<std::string_view> cells_;
  // The three rows before the current one (any non-comment line), for CutCell.
  std::array<std::vector<std::string_view>, 3> previous_rows_;
  int rows_read_ = 0;
  int cut_position_ = -1;  // CutCell() of the current row
};

}  // namespace slipgraph
