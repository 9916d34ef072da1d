// Reader for the drive-log CSV dialect (shared/log-format.md): '#' comment lines, first
// non-comment line is the header, columns matched by name in any order, unknown columns ignored,
// empty cells and "nan" are missing values; a leading UTF-8 byte-order mark is skipped, and a row
// with more cells than the header is an error. Plain numeric CSV without quoting, so this is a
// tokenizer over a memory buffer; Debian's libfccp needs the column count at compile time, which
// the vehicle-dependent columns (wheels, slip_<wheel>) rule out.
#pragma once

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

  // Advances to the next data row (comments and blank lines are skipped). False at the end.
  bool Next();

  // True when the (optional) column exists in the header.
  bool Has(int column) const { return positions_[column] >= 0; }
  // The number in `column` of the current row. Throws InputError naming file, line, column and
  // value when the cell is not a number, is infinite, or is missing in a required column.
  // A missing optional value (absent column, empty cell or "nan") is returned as NaN.
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
  std::string_view Cell(int column) const;

  std::string path_;
  std::vector<CsvColumn> columns_;
  std::vector<std::string> header_;
  std::vector<int> positions_;  // header position of each requested column, -1 when absent
  std::string buffer_;
  size_t cursor_ = 0;
  int line_number_ = 0;
  std::vector<std::string_view> cells_;
};

}  // namespace slipgraph
