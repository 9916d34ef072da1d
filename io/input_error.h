// Typed error for bad external input (logs, YAML files): names the file, line, column and value
// so a user can go straight to the problem. Thrown at the boundary (readers) only; the library's
// solvers never throw for data problems.
#pragma once

#include <stdexcept>
#include <string>

namespace slipgraph {

class InputError : public std::runtime_error {
 public:
  // line and column are 1-based; 0 means "not applicable" (e.g. a missing file).
  InputError(std::string file, int line, std::string column, std::string value,
             const std::string& what);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& column() const { return column_; }
  const std::string& value() const { return value_; }

 private:
  std::string file_;
  int line_;
  std::string column_;
  std::string value_;
};

}  // namespace slipgraph
