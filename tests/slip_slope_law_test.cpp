// The advance prior's slip-versus-slope law (solvers/slip_slope_law.h): the prior's information
// is taken out of each MAP before the fit (a Gaussian MAP gives back the data's own estimate
// exactly), a known law is recovered from noise-free looks, cycles without information leave it
// alone, and forgetting follows a change of soil.
#include "solvers/slip_slope_law.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace slipgraph {
namespace {

// The MAP and its chi-square curvature for a Gaussian prior (mean m, sd sp) and a Gaussian
// measurement of the advance (value d, sd sd_data).
struct Map {
  double advance, curvature;
};
Map GaussianMap(double m, double sp, double d, double sd_data) {
  const double p_prior = 1.0 / (sp * sp), p_data = 1.0 / (sd_data * sd_data);
  return {(p_prior * m + p_data * d) / (p_prior + p_data), 2.0 * (p_prior + p_data)};
}

TEST(SlipSlopeLaw, TakesThePriorOutOfTheMap) {
  // One look with a strong measurement: the law moves towards the data's slip (0.3), not the
  // MAP's compromise with the prior's 0.
  SlipSlopeLawOptions options;
  options.slip_noise_sd = 0.0;
  options.slip_sd = 1e3;  // an uninformative start: the fit is the look itself
  SlipSlopeLaw law(0.0, 0.0, options);
  const double rim = 0.05, prior_sd = 0.005;
  const Map map = GaussianMap(rim, prior_sd, rim * (1.0 - 0.3), 0.002);
  ASSERT_TRUE(law.AddCycle(0.0, rim, rim, prior_sd, map.advance, map.curvature));
  EXPECT_NEAR(law.Slip(0.0), 0.3, 1e-6);
  EXPECT_EQ(law.cycles_used(), 1);
}

TEST(SlipSlopeLaw, RecoversAKnownLawAndIgnoresCyclesWithoutInformation) {
  SlipSlopeLaw law(0.0, 0.0);
  const double rim = 0.0625, prior_sd = 0.1 * rim;
  for (int k = 0; k < 200; ++k) {
    const double slope = 0.15 * std::sin(0.1 * k);
    const double true_slip = 0.2 + 1.0 * slope;
    const double mean = rim * (1.0 - law.Slip(slope));
    const Map map = GaussianMap(mean, prior_sd, rim * (1.0 - true_slip), 0.002);
    law.AddCycle(slope, rim, mean, prior_sd, map.advance, map.curvature);
  }
  EXPECT_NEAR(law.slip(), 0.2, 0.01);
  EXPECT_NEAR(law.slip_per_slope(), 1.0, 0.05);
  // Smooth ground: the MAP is the prior (curvature of the prior alone): nothing learned.
  const double before = law.slip();
  EXPECT_FALSE(law.AddCycle(0.0, rim, rim, prior_sd, rim * 0.5, 2.0 / (prior_sd * prior_sd)));
  EXPECT_NEAR(law.slip(), before, 0.01);  // only the forgetting moved it
}

TEST(SlipSlopeLaw, ForgettingFollowsAChangeOfSoil) {
  SlipSlopeLawOptions options;
  options.memory_cycles = 20.0;
  SlipSlopeLaw law(0.0, 0.0, options);
  const double rim = 0.0625, prior_sd = 0.1 * rim;
  const auto drive = [&](double true_slip, int cycles) {
    for (int k = 0; k < cycles; ++k) {
      const double mean = rim * (1.0 - law.Slip(0.0));
      const Map map = GaussianMap(mean, prior_sd, rim * (1.0 - true_slip), 0.002);
      law.AddCycle(0.0, rim, mean, prior_sd, map.advance, map.curvature);
    }
  };
  drive(0.1, 100);
  EXPECT_NEAR(law.slip(), 0.1, 0.01);
  drive(0.4, 60);  // three memories later
  EXPECT_NEAR(law.slip(), 0.4, 0.03);
}

TEST(SlipSlopeLaw, ItsSdIsTheSpreadOfItsEstimates) {
  // 300 independent drives of 150 cycles on a law that does not change, each look's noise as the
  // law models it: the reported sd against the spread of the estimates over the drives. With the
  // forgetting the reported sd is that of a law that may drift, so for this constant one it may
  // exceed the spread by up to sqrt(2), never fall short of it.
  SlipSlopeLawOptions options;
  const double rim = 0.0625, prior_sd = 0.1 * rim, sd_data = 0.004;
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  double sum = 0.0, sum_sq = 0.0, sum_per = 0.0, sum_per_sq = 0.0, sd = 0.0, sd_per = 0.0;
  const int drives = 300;
  for (int d = 0; d < drives; ++d) {
    SlipSlopeLaw law(0.0, 0.0, options);
    for (int k = 0; k < 150; ++k) {
      const double slope = 0.15 * std::sin(0.1 * k);
      const double slip = 0.2 + 1.0 * slope + options.slip_noise_sd * gauss(random);
      const double mean = rim * (1.0 - law.Slip(slope));
      const Map map =
          GaussianMap(mean, prior_sd, rim * (1.0 - slip) + sd_data * gauss(random), sd_data);
      law.AddCycle(slope, rim, mean, prior_sd, map.advance, map.curvature);
    }
    sum += law.slip(), sum_sq += law.slip() * law.slip();
    sum_per += law.slip_per_slope(), sum_per_sq += law.slip_per_slope() * law.slip_per_slope();
    sd += law.slip_sd() / drives, sd_per += law.slip_per_slope_sd() / drives;
  }
  const double spread = std::sqrt(sum_sq / drives - (sum / drives) * (sum / drives));
  const double spread_per =
      std::sqrt(sum_per_sq / drives - (sum_per / drives) * (sum_per / drives));
  std::printf("slip sd %.4f spread %.4f; per slope sd %.3f spread %.3f\n", sd, spread, sd_per,
              spread_per);
  EXPECT_NEAR(sum / drives, 0.2, 0.01);
  EXPECT_GT(sd, 0.9 * spread);
  EXPECT_LT(sd, 1.6 * spread);
  EXPECT_GT(sd_per, 0.9 * spread_per);
  EXPECT_LT(sd_per, 1.6 * spread_per);
}

}  // namespace
}  // namespace slipgraph
