// The simulator's random draws: the same values from a seed on every standard library (golden
// values), the same as GNU libstdc++'s distributions where that is the library (so logs simulated
// before are unchanged), and the moments a normal and a uniform must have.
#include "sim/random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace slipgraph {
namespace {

TEST(Random, GoldenValuesFromASeed) {
  std::mt19937_64 rng(42);
  sim::UnitNormal normal;
  EXPECT_EQ(normal(rng), 0.70498826642085988);
  EXPECT_EQ(normal(rng), 1.2938204232729367);
  EXPECT_EQ(normal(rng), -0.5740948067202617);
  EXPECT_EQ(normal(rng), 0.39797739618378897);
  std::mt19937_64 rng2(42);
  const sim::UniformReal uniform(-1.0, 1.0);
  EXPECT_EQ(uniform(rng2), 0.51031106590907793);
  EXPECT_EQ(uniform(rng2), 0.27806278770939485);
}

#ifdef __GLIBCXX__
TEST(Random, SameDrawsAsLibstdcxx) {
  std::mt19937_64 a(7), b(7);
  std::normal_distribution<double> std_normal(0.0, 1.0);
  sim::UnitNormal normal;
  std::uniform_real_distribution<double> std_uniform(-3.0, 5.0);
  const sim::UniformReal uniform(-3.0, 5.0);
  for (int i = 0; i < 100000; ++i) {
    // Interleaved as the simulator draws: both distributions on one engine.
    ASSERT_EQ(normal(b), std_normal(a)) << i;
    ASSERT_EQ(uniform(b), std_uniform(a)) << i;
  }
}
#endif

TEST(Random, MomentsOfTheNormalAndTheUniform) {
  std::mt19937_64 rng(2026);
  sim::UnitNormal normal;
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
  int within_one = 0;
  for (int i = 0; i < n; ++i) {
    const double z = normal(rng);
    sum += z;
    sum2 += z * z;
    sum4 += z * z * z * z;
    within_one += std::abs(z) < 1.0;
  }
  // Bounds at about 4 standard errors of each statistic for n draws.
  EXPECT_NEAR(sum / n, 0.0, 4.0 / std::sqrt(n));
  EXPECT_NEAR(sum2 / n, 1.0, 4.0 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sum4 / n, 3.0, 4.0 * std::sqrt(96.0 / n));
  EXPECT_NEAR(static_cast<double>(within_one) / n, 0.682689, 4.0 * std::sqrt(0.2166 / n));

  const sim::UniformReal uniform(2.0, 5.0);
  double lo = 1e9, hi = -1e9, mean = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = uniform(rng);
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    mean += u / n;
  }
  EXPECT_GE(lo, 2.0);
  EXPECT_LT(hi, 5.0);
  EXPECT_GT(hi - lo, 2.99);
  EXPECT_NEAR(mean, 3.5, 4.0 * std::sqrt(0.75 / n));
}

TEST(Random, CanonicalStaysBelowOne) {
  // The engine's largest outputs round to 2^64 in double: the draw is kept below 1.
  struct MaxEngine {
    using result_type = std::uint64_t;
    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return ~result_type{0}; }
    result_type operator()() { return max() - 100; }
  } engine;
  const double u = sim::Canonical(engine);
  EXPECT_LT(u, 1.0);
  EXPECT_EQ(u, std::nextafter(1.0, 0.0));
}

}  // namespace
}  // namespace slipgraph
