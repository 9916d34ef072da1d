// The checks of an options struct's IsValid(std::string* error), as one expression that stops at
// the first failure and names the struct, the field and its value:
//
//   bool WindowSmootherOptions::IsValid(std::string* error) const {
//     return OptionCheck("WindowSmootherOptions", error)
//                .Positive("window_s", window_s)
//                .AtLeast("update_every", update_every, 1) &&
//            filter.IsValid(error);
//   }
//
// A NaN fails every check. Entry points throw std::invalid_argument with the message.
#pragma once

#include <cstdio>
#include <string>

namespace slipgraph {

class OptionCheck {
 public:
  OptionCheck(std::string owner, std::string* error) : owner_(std::move(owner)), error_(error) {}

  OptionCheck& Positive(const char* field, double value) {
    return Require(field, value > 0.0, value, "must be positive");
  }
  OptionCheck& NonNegative(const char* field, double value) {
    return Require(field, value >= 0.0, value, "must be non-negative");
  }
  OptionCheck& AtLeast(const char* field, double value, double least) {
    return Require(field, value >= least, value, "must be at least " + Format(least));
  }
  // Within [low, high].
  OptionCheck& Within(const char* field, double value, double low, double high) {
    return Require(field, value >= low && value <= high, value,
                   "must lie in [" + Format(low) + ", " + Format(high) + "]");
  }
  OptionCheck& Require(const char* field, bool holds, double value, const std::string& what) {
    if (ok_ && !holds) {
      ok_ = false;
      *error_ = owner_ + "." + field + " = " + Format(value) + ": " + what;
    }
    return *this;
  }

  operator bool() const { return ok_; }  // NOLINT: used as the IsValid result

 private:
  static std::string Format(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", value);
    return text;
  }

  std::string owner_;
  std::string* error_;
  bool ok_ = true;
};

}  // namespace slipgraph
