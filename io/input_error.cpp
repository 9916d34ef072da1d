#include "io/input_error.h"

#include <sstream>

namespace slipgraph {
namespace {

std::string FormatInputError(const std::string& file, int line, const std::string& column,
                             const std::string& value, const std::string& what) {
  std::ostringstream out;
  out << file;
  if (line > 0) out << ":" << line;
  out << ": ";
  if (!column.empty()) out << "column '" << column << "': ";
  if (!value.empty()) out << "value '" << value << "': ";
  out << what;
  return out.str();
}

}  // namespace

InputError::InputError(std::string file, int line, std::string column, std::string value,
                       const std::string& what)
    : std::runtime_error(FormatInputError(file, line, column, value, what)),
      file_(std::move(file)),
      line_(line),
      column_(std::move(column)),
      value_(std::move(value)) {}

}  // namespace slipgraph
