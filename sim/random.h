// Random draws that depend on the seed alone. The engine, std::mt19937_64, is fixed by the C++
// standard; its distributions are not (std::normal_distribution and uniform_real_distribution
// differ between standard libraries), so the simulator draws through these instead, and a log
// simulated from a seed is the same on every platform. The arithmetic is GNU libstdc++'s
// (generate_canonical with one 64-bit draw; Marsaglia's polar method, the pair's second value
// kept for the next call), so logs made through the standard library there are unchanged.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace slipgraph {
namespace sim {

// In [0, 1): one draw of a 64-bit engine scaled by 2^-64, kept below 1 where rounding to double
// reaches it.
template <typename Engine>
double Canonical(Engine& rng) {
  static_assert(Engine::min() == 0 && Engine::max() == ~std::uint64_t{0}, "a 64-bit engine");
  const double u = static_cast<double>(rng()) / 18446744073709551616.0;
  return u < 1.0 ? u : std::nextafter(1.0, 0.0);
}

// Uniform in [lo, hi).
class UniformReal {
 public:
  UniformReal(double lo, double hi) : lo_(lo), width_(hi - lo) {}
  double operator()(std::mt19937_64& rng) const { return Canonical(rng) * width_ + lo_; }

 private:
  double lo_, width_;
};

// Standard normal by Marsaglia's polar method: two uniforms in the unit disc give two independent
// normals; the second is returned by the next call.
class UnitNormal {
 public:
  double operator()(std::mt19937_64& rng) {
    if (saved_available_) {
      saved_available_ = false;
      return saved_;
    }
    double x, y, r2;
    do {
      x = 2.0 * Canonical(rng) - 1.0;
      y = 2.0 * Canonical(rng) - 1.0;
      r2 = x * x + y * y;
    } while (r2 > 1.0 || r2 == 0.0);
    const double mult = std::sqrt(-2.0 * std::log(r2) / r2);
    saved_ = x * mult;
    saved_available_ = true;
    return y * mult;
  }

 private:
  double saved_ = 0.0;
  bool saved_available_ = false;
};

// One step of a first-order Gauss-Markov process with stationary sd and correlation time tau
// (or correlation length, `dt_s` then the distance moved), driven by a unit normal draw.
inline double GaussMarkovStep(double value, double sd, double tau_s, double dt_s,
                              double unit_normal) {
  const double decay = std::exp(-dt_s / tau_s);
  return value * decay + sd * std::sqrt(1.0 - decay * decay) * unit_normal;
}

}  // namespace sim
}  // namespace slipgraph
