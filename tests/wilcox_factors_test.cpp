// Wilcox measurement factors on profile nodes: residuals at a hand-computed point and Jacobians
// against numeric differentiation (the position moves the interpolation weights).
#include "factors/wilcox_factors.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "tests/factor_check.h"

namespace slipgraph {
namespace {

// Nodes every 1 cm; y a ramp of slope 0.1 plus a bump, s constant 3 mm.
struct Profiles {
  std::vector<double> y, s;
  explicit Profiles(int n) : y(n), s(n, 0.003) {
    for (int i = 0; i < n; ++i) y[i] = 0.1 * 0.01 * i + (i == 52 ? 0.002 : 0.0);
  }
};

// Prepares the factor for blocks of block_size nodes and lists its parameter blocks.
std::vector<const double*> Blocks(WilcoxMeasurementFactor* f, const double* x, const Profiles& p,
                                  int block_size = 1) {
  f->block_size = block_size;
  f->Prepare();
  std::vector<const double*> blocks = {x};
  for (int c : f->y_blocks) blocks.push_back(&p.y[c * block_size]);
  for (int c : f->s_blocks) blocks.push_back(&p.s[c * block_size]);
  return blocks;
}

TEST(WilcoxFactors, RangeResidualByHandAndJacobian) {
  const Profiles p(120);
  const double x = 0.1037;
  // Point contact: ride at the rear = y(x) - s = 0.01037 - 0.003; y(x + 0.5) = 0.06037.
  WilcoxMeasurementFactor f{WilcoxMeasurementFactor::kRange,
                            0.5,
                            0.06037 - (0.01037 - 0.003) + 0.001,  // 1 mm above the prediction
                            0.002,
                            0.0,
                            wilcox::RunCovering(x, x, 0.03, 0.01, 120),
                            wilcox::RunCovering(x + 0.5, x + 0.5, 0.03, 0.01, 120),
                            wilcox::RunCovering(x, x, 0.03, 0.01, 120),
                            wilcox::GridRun{0, 0, 0.01}};
  const std::vector<const double*> blocks = Blocks(&f, &x, p);
  const std::unique_ptr<ceres::CostFunction> cost(WilcoxMeasurementFactor::Create(f));
  EXPECT_NEAR(testing::Residuals(*cost, blocks)[0], 0.5, 1e-9);
  testing::ExpectJacobiansMatchNumeric(*cost, blocks);
  // The same factor on blocks of 8 nodes (the graph's default): same residual, same derivatives.
  const std::vector<const double*> blocks8 = Blocks(&f, &x, p, 8);
  const std::unique_ptr<ceres::CostFunction> cost8(WilcoxMeasurementFactor::Create(f));
  EXPECT_LT(blocks8.size(), blocks.size());
  EXPECT_NEAR(testing::Residuals(*cost8, blocks8)[0], 0.5, 1e-9);
  testing::ExpectJacobiansMatchNumeric(*cost8, blocks8);
}

TEST(WilcoxFactors, ArticulationOverTheBumpWithAContactPatch) {
  const Profiles p(120);
  const double x = 0.2813;  // the middle wheel (x + 0.24) sits on the bump at 0.52
  WilcoxMeasurementFactor f{WilcoxMeasurementFactor::kArticulation,
                            0.24,
                            0.024,
                            0.00004,
                            0.0217,
                            wilcox::RunCovering(x, x, 0.05, 0.01, 120),
                            wilcox::RunCovering(x + 0.24, x + 0.24, 0.05, 0.01, 120),
                            wilcox::RunCovering(x, x, 0.05, 0.01, 120),
                            wilcox::RunCovering(x + 0.24, x + 0.24, 0.05, 0.01, 120)};
  const std::vector<const double*> blocks = Blocks(&f, &x, p, 8);
  const std::unique_ptr<ceres::CostFunction> cost(WilcoxMeasurementFactor::Create(f));
  // The ramp alone gives 0.024 exactly; the averaged bump adds part of its 2 mm.
  const double r = testing::Residuals(*cost, blocks)[0] * 0.00004;
  EXPECT_LT(r, 0.0);
  EXPECT_GT(r, -0.002);
  testing::ExpectJacobiansMatchNumeric(*cost, blocks, 1e-5);
}

}  // namespace
}  // namespace slipgraph
