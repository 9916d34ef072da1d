#include "io/csv_writer.h"

#include <charconv>
#include <cmath>

#include "io/input_error.h"

namespace slipgraph {

std::string FormatNumber(double value) {
  if (std::isnan(value)) return "nan";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& header)
    : path_(path), out_(path) {
  if (!out_) throw InputError(path, 0, "", "", "cannot open file for writing");
  for (const std::string& name : header) *this << name;
  EndRow();
}

void CsvWriter::Separator() {
  if (row_started_) row_.push_back(',');
  row_started_ = true;
}

CsvWriter& CsvWriter::operator<<(double value) {
  Separator();
  row_ += FormatNumber(value);
  return *this;
}

CsvWriter& CsvWriter::operator<<(const std::string& text) {
  Separator();
  row_ += text;
  return *this;
}

void CsvWriter::EndRow() {
  row_.push_back('\n');
  out_ << row_;
  row_.clear();
  row_started_ = false;
  if (!out_) throw InputError(path_, 0, "", "", "write failed (a full disk, or not a file)");
}

void CsvWriter::Close() {
  out_.flush();
  if (!out_) throw InputError(path_, 0, "", "", "write failed (a full disk, or not a file)");
  out_.close();
  if (out_.fail()) throw InputError(path_, 0, "", "", "closing the file failed");
}

}  // namespace slipgraph
