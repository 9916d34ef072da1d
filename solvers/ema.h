// Exponential moving average, Ward & Iagnemma eq. (12):
//   EMA_current = (measurement - EMA_prev) * 2 / (1 + p) + EMA_prev
// an approximation of the mean of the last p samples, weighted toward recent ones.
#pragma once

namespace slipgraph {

class ExponentialMovingAverage {
 public:
  explicit ExponentialMovingAverage(double samples_p) : weight_(2.0 / (1.0 + samples_p)) {}

  // The first sample initialises the average.
  double Add(double measurement) {
    value_ = initialised_ ? (measurement - value_) * weight_ + value_ : measurement;
    initialised_ = true;
    return value_;
  }
  void Reset(double value) {
    value_ = value;
    initialised_ = true;
  }
  double value() const { return value_; }
  bool initialised() const { return initialised_; }

 private:
  double weight_;
  double value_ = 0.0;
  bool initialised_ = false;
};

}  // namespace slipgraph
