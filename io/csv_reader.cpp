#include "io/csv_reader.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "io/input_error.h"
#include "io/text_file.h"

namespace slipgraph {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) {
    s.remove_suffix(1);
  }
  return s;
}

void SplitCells(std::string_view line, std::vector<std::string_view>* cells) {
  cells->clear();
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    if (comma == std::string_view::npos) {
      cells->push_back(Trim(line.substr(start)));
      return;
    }
    cells->push_back(Trim(line.substr(start, comma - start)));
    start = comma + 1;
  }
}

// The characters after a number's decimal point (its exponent included), -1 without a point.
int CharactersAfterPoint(std::string_view cell) {
  const size_t point = cell.find('.');
  return point == std::string_view::npos ? -1 : static_cast<int>(cell.size() - point - 1);
}

bool IsMissing(std::string_view cell) {
  return cell.empty() || cell == "nan" || cell == "NaN" || cell == "NAN";
}

}  // namespace

CsvReader::CsvReader(std::string path, std::vector<CsvColumn> columns)
    : path_(std::move(path)), columns_(std::move(columns)), positions_(columns_.size(), -1) {
  owned_ = ReadTextFile(path_);
  text_ = owned_;
  ReadHeader();
}

CsvReader::CsvReader(std::string name, std::string_view text, std::vector<CsvColumn> columns)
    : path_(std::move(name)),
      columns_(std::move(columns)),
      positions_(columns_.size(), -1),
      text_(text) {
  ReadHeader();
}

void CsvReader::ReadHeader() {
  // A UTF-8 byte-order mark (spreadsheets write one) is not part of the first column's name.
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") cursor_ = 3;

  // The header is the first line that is neither blank nor a comment.
  std::vector<std::string_view> header;
  while (Next()) {
    header = cells_;
    break;
  }
  if (header.empty()) throw InputError(path_, 0, "", "", "no header line");
  for (std::string_view name : header) header_.emplace_back(name);
  for (size_t c = 0; c < columns_.size(); ++c) {
    for (size_t h = 0; h < header.size(); ++h) {
      if (header[h] == columns_[c].name) positions_[c] = static_cast<int>(h);
    }
    if (positions_[c] < 0 && columns_[c].required) {
      throw InputError(path_, line_number_, columns_[c].name, "",
                       "required column is missing from the header");
    }
  }
}

bool CsvReader::Next() {
  while (cursor_ < text_.size()) {
    size_t end = text_.find('\n', cursor_);
    const bool ends_the_file = end == std::string_view::npos;
    if (ends_the_file) end = text_.size();
    const std::string_view line = Trim(text_.substr(cursor_, end - cursor_));
    cursor_ = end + 1;
    ++line_number_;
    if (line.empty() || line.front() == '#') continue;
    if (rows_read_ > 0) previous_rows_[(rows_read_ - 1) % 3] = cells_;
    ++rows_read_;
    SplitCells(line, &cells_);
    cut_position_ = ends_the_file ? CutCell() : -1;
    return true;
  }
  return false;
}

int CsvReader::CutCell() const {
  if (rows_read_ < 4) return -1;  // the header and three rows before this one
  const auto tail_before = [&](size_t p, int row) {
    const std::vector<std::string_view>& cells = previous_rows_[row];
    return p < cells.size() ? CharactersAfterPoint(cells[p]) : -1;
  };
  for (size_t p = 0; p < cells_.size(); ++p) {
    const int before = tail_before(p, 0);
    if (before < 1 || tail_before(p, 1) != before || tail_before(p, 2) != before) continue;
    if (CharactersAfterPoint(cells_[p]) < before) return static_cast<int>(p);
  }
  return -1;
}

std::string_view CsvReader::Cell(int column) const {
  // More cells than the header: the columns no longer line up (a decimal comma, "2,93").
  if (cells_.size() > header_.size() && !header_.empty()) {
    Fail(column, "",
         "row has " + std::to_string(cells_.size()) + " cells, the header " +
             std::to_string(header_.size()) + " (a decimal comma?)");
  }
  const int position = positions_[column];
  if (position < 0 || position >= static_cast<int>(cells_.size())) return {};
  return cells_[position];
}

void CsvReader::Fail(int column, const std::string& value, const std::string& what) const {
  throw InputError(path_, line_number_, columns_[column].name, value, what);
}

double CsvReader::Number(int column) const {
  const std::string_view cell = Cell(column);
  if (positions_[column] >= 0 && positions_[column] >= static_cast<int>(cells_.size())) {
    Fail(column, "", "row has fewer cells than the header");
  }
  if (positions_[column] == cut_position_ && cut_position_ >= 0) {
    Fail(column, std::string(cell),
         "the file ends inside this row without a line end, and this number has fewer digits "
         "than the rows before: cut short? (end the file with a line end if the row is whole)");
  }
  if (IsMissing(cell)) {
    if (columns_[column].required)
      Fail(column, std::string(cell), "missing value in a required column");
    return std::numeric_limits<double>::quiet_NaN();
  }
  double value = 0.0;
  const char* begin = cell.data();
  const char* end = begin + cell.size();
  if (*begin == '+') ++begin;  // from_chars rejects a leading '+', which CSV writers may emit
  const auto result = std::from_chars(begin, end, value);
  if (result.ec != std::errc() || result.ptr != end)
    Fail(column, std::string(cell), "not a number");
  if (!std::isfinite(value)) Fail(column, std::string(cell), "not a finite number");
  return value;
}

std::string CsvReader::Text(int column) const {
  const std::string_view cell = Cell(column);
  if (cell.empty()) Fail(column, "", "missing value");
  return std::string(cell);
}

}  // namespace slipgraph
