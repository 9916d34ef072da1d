// The accelerometer factor (factors/accelerometer_factor.h) with each kind of unknown: with the
// law's coefficients and the radius errors (at the model's law it is the plain factor; at another
// law the plain factor of that law; a radius error scales its side's wheel speed); with the slip
// stiffness (scaling v_rel by s is the law with At and C2 both scaled by s, a hand identity of
// eq. 8; theta interpolated between its two nodes); with effect terms (at zero magnitudes it is
// the factor without them; a force, a slip and a traction term by hand). Every
// Jacobian against numeric differentiation.
#include "factors/accelerometer_factor.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "tests/factor_check.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

AccelerometerUnknowns WithLaw() {
  AccelerometerUnknowns u;
  u.law = true;
  return u;
}

AccelerometerUnknowns Stiffness(double share_b) {
  AccelerometerUnknowns u;
  u.stiffness = true;
  u.stiffness_share = share_b;
  return u;
}

// The LAGR robot with the law the user of ward21 states (the soils' mean), at a turning state.
struct LawFixture {
  ward::Params params = testing::LagrParams();
  ward::Attitude<double> attitude{0.02, -0.05};
  std::vector<double> x = {0.7, 0.01, -0.2, 6.5, 7.1, 0.3, 0.002};
  std::vector<double> offsets = {0.05, -0.001};
  LawFixture() {
    params.tire = {0.475, 13.25, 0.068};
    params.rolling = {0.0625, 16.25, 0.02};
  }
};

double Residual(const ceres::CostFunction& cost, const std::vector<const double*>& blocks) {
  return testing::Residuals(cost, blocks).at(0);
}

// The plain factor's Jacobians, taken from f_tire's partials, against automatic differentiation
// of the balance as eq. (11) writes it, and against numeric differentiation; at rest too (v_rel
// = v_fwd = 0, the laws' Taylor branches).
struct PlainReference {
  AccelerometerReading reading;
  template <typename T>
  bool operator()(const T* x, const T* offsets, T* residual) const {
    const ward::TireForces<T> forces = ward::ComputeTireForces(x, reading.loads, reading.params);
    residual[0] = reading.Residual(forces.f_tire_mps2, x, offsets);
    return true;
  }
};

TEST(AccelerometerFactor, PlainJacobiansAsAutomaticDifferentiation) {
  LawFixture f;
  std::vector<std::vector<double>> states = {
      f.x, std::vector<double>(7, 0.0), {-0.4, -0.02, 0.6, -1.0, -2.5, -0.2, 0.001}};
  for (const std::vector<double>& x : states) {
    std::unique_ptr<ceres::CostFunction> factor(
        AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
    ceres::AutoDiffCostFunction<PlainReference, 1, ward::kStateSize, 2> reference(
        new PlainReference{AccelerometerReading(f.params, f.attitude, 0.3, 0.08)});
    const double* blocks[] = {x.data(), f.offsets.data()};
    double r = 0.0, r_ref = 0.0, j0[7], j1[2], k0[7], k1[2];
    double* jac[] = {j0, j1};
    double* ref[] = {k0, k1};
    ASSERT_TRUE(factor->Evaluate(blocks, &r, jac));
    ASSERT_TRUE(reference.Evaluate(blocks, &r_ref, ref));
    // The same arithmetic on Jets of other widths: equal to rounding.
    EXPECT_NEAR(r, r_ref, 1e-12 * (1.0 + std::abs(r_ref)));
    for (int i = 0; i < 7; ++i) EXPECT_NEAR(j0[i], k0[i], 1e-12 * (1.0 + std::abs(k0[i])));
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(j1[i], k1[i], 1e-12 * (1.0 + std::abs(k1[i])));
    double r_plain = 0.0;
    ASSERT_TRUE(factor->Evaluate(blocks, &r_plain, nullptr));
    EXPECT_NEAR(r_plain, r_ref, 1e-12 * (1.0 + std::abs(r_ref)));
    testing::ExpectJacobiansMatchNumeric(*factor, {x.data(), f.offsets.data()}, 1e-5);
  }
}

TEST(AccelerometerFactorWithLaw, IsTheAccelerometerFactorOfTheLawItIsGiven) {
  LawFixture f;
  std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, WithLaw()));
  const std::array<double, 2> no_error = {0.0, 0.0};
  std::array<double, kLawCoefficientCount> law = LawCoefficients(f.params.tire, f.params.rolling);
  std::unique_ptr<ceres::CostFunction> plain(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  EXPECT_NEAR(Residual(*factor, {f.x.data(), f.offsets.data(), law.data(), no_error.data()}),
              Residual(*plain, {f.x.data(), f.offsets.data()}), 1e-12);

  // Another law (every coefficient moved): the factor built with the model's law, given the
  // other law as its block, is the plain factor of a model with the other law.
  law = {0.6, 21.0, 0.03, 0.04, 0.05};
  ward::Params other = f.params;
  SetLawCoefficients(law, &other.tire, &other.rolling);
  std::unique_ptr<ceres::CostFunction> plain_other(
      AccelerometerFactor::Create(other, f.attitude, 0.3, 0.08));
  const double r = Residual(*factor, {f.x.data(), f.offsets.data(), law.data(), no_error.data()});
  EXPECT_NEAR(r, Residual(*plain_other, {f.x.data(), f.offsets.data()}), 1e-12);
  // Control: it is not the model's law's residual.
  EXPECT_GT(std::abs(r - Residual(*plain, {f.x.data(), f.offsets.data()})), 0.1);
}

TEST(AccelerometerFactorWithLaw, ARadiusErrorScalesItsSidesWheelSpeed) {
  LawFixture f;
  std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, WithLaw()));
  const std::array<double, kLawCoefficientCount> law =
      LawCoefficients(f.params.tire, f.params.rolling);
  const std::array<double, 2> errors = {0.03, -0.02};
  std::vector<double> scaled = f.x;
  scaled[ward::kOmegaLeft] *= 1.03;
  scaled[ward::kOmegaRight] *= 0.98;
  const std::array<double, 2> none = {0.0, 0.0};
  EXPECT_NEAR(Residual(*factor, {f.x.data(), f.offsets.data(), law.data(), errors.data()}),
              Residual(*factor, {scaled.data(), f.offsets.data(), law.data(), none.data()}), 1e-12);
}

TEST(AccelerometerFactorWithLaw, JacobiansMatchNumeric) {
  LawFixture f;
  std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, WithLaw()));
  const std::array<double, kLawCoefficientCount> law = {0.6, 21.0, 0.03, 0.04, 0.05};
  const std::array<double, 2> errors = {0.03, -0.02};
  // A driving slip (v_rel about 0.05 and 0.1 m/s, where At matters) and one near zero relative
  // velocity, where the saturation bends most.
  for (double v_rel : {0.05, 0.002}) {
    std::vector<double> x = f.x;
    x[ward::kOmegaLeft] = (x[ward::kVbx] + v_rel) / 0.25 / 1.03;
    x[ward::kOmegaRight] = (x[ward::kVbx] + 2.0 * v_rel) / 0.25 / 0.98;
    x[ward::kYawRate] = 0.0;
    testing::ExpectJacobiansMatchNumeric(*factor,
                                         {x.data(), f.offsets.data(), law.data(), errors.data()});
  }
}

struct StiffnessFixture {
  ward::Params params;
  ward::Attitude<double> attitude{0.02, -0.05};
  std::vector<double> x = {0.7, 0.01, -0.2, 6.5, 7.1, 0.3, 0.002};
  std::vector<double> offsets = {0.05, -0.001};
  StiffnessFixture() {
    params.mass_kg = 117.0;
    params.tire = {0.475, 13.25, 0.068};
  }
};

TEST(AccelerometerFactorWithStiffness, IsTheAccelerometerFactorAtTheLawsStiffness) {
  StiffnessFixture f;
  double zero_a = 0.0, zero_b = 0.0;
  const double* blocks[] = {f.x.data(), f.offsets.data(), &zero_a, &zero_b};
  std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, Stiffness(0.4)));
  std::unique_ptr<ceres::CostFunction> plain(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  double r = 0.0, r_plain = 0.0;
  ASSERT_TRUE(factor->Evaluate(blocks, &r, nullptr));
  ASSERT_TRUE(plain->Evaluate(blocks, &r_plain, nullptr));
  EXPECT_NEAR(r, r_plain, 1e-12);
}

TEST(AccelerometerFactorWithStiffness, ScalesAtAndC2AndInterpolatesItsNodes) {
  StiffnessFixture f;
  // theta = (1 - u) theta_a + u theta_b = 0.6 * -0.4 + 0.4 * 0.1 = -0.2: s = 0.8.
  double theta_a = -0.4, theta_b = 0.1;
  const double* blocks[] = {f.x.data(), f.offsets.data(), &theta_a, &theta_b};
  std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, Stiffness(0.4)));
  double r = 0.0;
  ASSERT_TRUE(factor->Evaluate(blocks, &r, nullptr));
  ward::Params scaled = f.params;
  scaled.tire.At *= 0.8;
  scaled.tire.C2 *= 0.8;
  std::unique_ptr<ceres::CostFunction> plain(
      AccelerometerFactor::Create(scaled, f.attitude, 0.3, 0.08));
  double r_plain = 0.0;
  ASSERT_TRUE(plain->Evaluate(blocks, &r_plain, nullptr));
  EXPECT_NEAR(r, r_plain, 1e-12);
  // The scale matters at this slip: the law's own stiffness gives another residual.
  std::unique_ptr<ceres::CostFunction> law(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  double r_law = 0.0;
  ASSERT_TRUE(law->Evaluate(blocks, &r_law, nullptr));
  EXPECT_GT(std::abs(r - r_law), 1e-3);
}

TEST(AccelerometerFactorWithStiffness, JacobianMatchesNumeric) {
  StiffnessFixture f;
  const std::vector<double> theta_a = {-0.3}, theta_b = {0.2};
  const std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, Stiffness(0.25)));
  testing::ExpectJacobiansMatchNumeric(
      *factor, {f.x.data(), f.offsets.data(), theta_a.data(), theta_b.data()}, 1e-6);
}

// A force shape that uses the state nonlinearly and the context; a slip and a traction shape
// that use the wheel and the state.
struct TestForce {
  template <typename T>
  T operator()(const T* x, const EffectContext& c, const ward::Params& p) const {
    using std::sin;
    return -x[ward::kVbx] * x[ward::kYawRate] * x[ward::kYawRate] / p.mass_kg +
           sin(T(c.attitude.pitch_rad)) + 0.1 * x[ward::kOmegaLeft] * c.accel_x_mps2 +
           0.2 * c.window;
  }
};

struct TestSlip {
  template <typename T>
  T operator()(const WheelTraction<T>& w, const T* x, const EffectContext&,
               const ward::Params&) const {
    return 0.5 * w.rim_speed_mps + 0.1 * x[ward::kVbx];
  }
};

struct TestTraction {
  template <typename T>
  T operator()(const WheelTraction<T>& w, const T*, const EffectContext&,
               const ward::Params&) const {
    return 3.0 * w.v_rel_mps + 0.01 * w.normal_n / 100.0;
  }
};

struct EffectFixture {
  ward::Params params = testing::LagrParams();
  ward::Attitude<double> attitude{0.02, -0.05};
  std::vector<double> x = {0.7, 0.01, -0.2, 6.5, 7.1, 0.3, 0.002};
  std::vector<double> offsets = {0.05, -0.001};
  EffectTerm force = MakeForceTerm<TestForce>("test_force", "-", 1.0, "");
  EffectTerm slip = MakeSlipTerm<TestSlip>("test_slip", "-", 1.0, "");
  EffectTerm traction = MakeTractionTerm<TestTraction>("test_traction", "-", 1.0, "");
  std::vector<double> theta = {0.4, 0.05, -0.3};
  AccelerometerUnknowns Unknowns() const {
    AccelerometerUnknowns u;
    u.effects = {&force, &slip, &traction};
    u.windows = {1.0, 0.0, 0.0};
    u.t_s = 3.0;
    return u;
  }
  double Residual(const AccelerometerUnknowns& u, const std::vector<double>& magnitudes) const {
    std::unique_ptr<ceres::CostFunction> factor(
        AccelerometerFactor::Create(params, attitude, 0.35, 0.08, u));
    return testing::Residuals(*factor, {x.data(), offsets.data(), magnitudes.data()}).at(0);
  }
};

TEST(AccelerometerFactorWithEffects, IsThePlainFactorAtZeroMagnitudes) {
  EffectFixture f;
  std::unique_ptr<ceres::CostFunction> plain(
      AccelerometerFactor::Create(f.params, f.attitude, 0.35, 0.08));
  EXPECT_NEAR(f.Residual(f.Unknowns(), {0.0, 0.0, 0.0}),
              testing::Residuals(*plain, {f.x.data(), f.offsets.data()}).at(0), 1e-12);
}

TEST(AccelerometerFactorWithEffects, AddsEachTermToThePrediction) {
  EffectFixture f;
  const double base = f.Residual(f.Unknowns(), {0.0, 0.0, 0.0});
  // The force by hand: h = -v yaw^2 / m + sin(pitch) + 0.1 w_l a_x + 0.2 (inside its window).
  const double h = -0.7 * 0.09 / f.params.mass_kg + std::sin(-0.05) + 0.1 * 6.5 * 0.35 + 0.2 * 1.0;
  EXPECT_NEAR(f.Residual(f.Unknowns(), {0.4, 0.0, 0.0}), base - 0.4 * h / 0.08, 1e-12);
  // Slip then traction by hand, both sides: the law at the shifted relative velocity, scaled by
  // 1 + theta g with g seeing the shifted wheel.
  const ward::AttitudeLoads<double> loads = ward::ComputeAttitudeLoads(f.attitude, f.params);
  const ward::TireForces<double> t = ward::ComputeTireForces(f.x.data(), loads, f.params);
  const double r = f.params.wheel_radius_m;
  const double n[2] = {loads.driven_left_n, loads.driven_right_n};
  const double v_rel[2] = {t.v_rel_left_mps, t.v_rel_right_mps};
  const double rim[2] = {f.x[ward::kOmegaLeft] * r, f.x[ward::kOmegaRight] * r};
  const double before[2] = {t.traction_left_n, t.traction_right_n};
  double added = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double shifted = v_rel[i] + 0.05 * (0.5 * rim[i] + 0.1 * f.x[ward::kVbx]);
    const double traction = TractionForceN(n[i], shifted, f.params.tire);
    added += traction * (1.0 - 0.3 * (3.0 * shifted + 0.01 * n[i] / 100.0)) - before[i];
  }
  EXPECT_NEAR(f.Residual(f.Unknowns(), {0.0, 0.05, -0.3}), base - added / f.params.mass_kg / 0.08,
              1e-12);
  EXPECT_GT(std::abs(added), 1.0);  // newtons: the check is not vacuous
}

TEST(AccelerometerFactorWithEffects, JacobiansMatchNumeric) {
  EffectFixture f;
  std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.35, 0.08, f.Unknowns()));
  testing::ExpectJacobiansMatchNumeric(*factor, {f.x.data(), f.offsets.data(), f.theta.data()},
                                       1e-6);
  ASSERT_EQ(factor->parameter_block_sizes(), (std::vector<int>{7, 2, 3}));
}

TEST(AccelerometerFactorWithEffects, MoreThanTenTermsTakeTheWideJets) {
  EffectFixture f;
  AccelerometerUnknowns u = f.Unknowns();
  std::vector<double> theta = f.theta;
  while (u.effects.size() <= static_cast<size_t>(kNarrowEffectTerms)) {
    u.effects.push_back(&f.force);
    u.windows.push_back(0.0);
    theta.push_back(0.1);
  }
  std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.35, 0.08, u));
  testing::ExpectJacobiansMatchNumeric(*factor, {f.x.data(), f.offsets.data(), theta.data()}, 1e-6);
}

TEST(AccelerometerFactor, AtMostTheJetsWidthOfEffectTerms) {
  EffectFixture f;
  AccelerometerUnknowns u;
  u.effects.assign(kMaxEffectTerms + 1, &f.force);
  EXPECT_THROW(AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, u),
               std::invalid_argument);
}

TEST(AccelerometerFactor, TheLawExcludesTheStiffnessAndTheEffects) {
  EffectFixture f;
  AccelerometerUnknowns law_and_stiffness = WithLaw();
  law_and_stiffness.stiffness = true;
  AccelerometerUnknowns law_and_effects = f.Unknowns();
  law_and_effects.law = true;
  for (const AccelerometerUnknowns& u : {law_and_stiffness, law_and_effects}) {
    EXPECT_THROW(AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, u),
                 std::invalid_argument);
  }
}

// The stiffness walk with effect terms (the workbench's null model with a varying law): the
// stiffness factor's residual with the effects' part added as the plain factor adds it, and every
// block's Jacobian (state, offsets, both nodes, the magnitudes) numerically.
TEST(AccelerometerFactorWithStiffnessAndEffects, IsTheStiffnessFactorWithTheEffectsAdded) {
  EffectFixture f;
  AccelerometerUnknowns both = f.Unknowns();
  both.stiffness = true;
  both.stiffness_share = 0.25;
  const std::vector<double> theta_a = {-0.3}, theta_b = {0.2}, zero(f.theta.size(), 0.0);
  const std::unique_ptr<ceres::CostFunction> factor(
      AccelerometerFactor::Create(f.params, f.attitude, 0.35, 0.08, both));
  ASSERT_EQ(
      factor->parameter_block_sizes(),
      (std::vector<int32_t>{ward::kStateSize, 2, 1, 1, static_cast<int32_t>(f.theta.size())}));
  const std::unique_ptr<ceres::CostFunction> stiffness(
      AccelerometerFactor::Create(f.params, f.attitude, 0.35, 0.08, Stiffness(0.25)));
  const std::vector<const double*> nodes = {f.x.data(), f.offsets.data(), theta_a.data(),
                                            theta_b.data()};
  std::vector<const double*> blocks = nodes;
  blocks.push_back(zero.data());
  EXPECT_NEAR(testing::Residuals(*factor, blocks).at(0),
              testing::Residuals(*stiffness, nodes).at(0), 1e-12);
  blocks.back() = f.theta.data();
  const double effects_part = f.Residual(f.Unknowns(), f.theta) - f.Residual(f.Unknowns(), zero);
  EXPECT_NEAR(testing::Residuals(*factor, blocks).at(0),
              testing::Residuals(*stiffness, nodes).at(0) + effects_part, 1e-12);
  testing::ExpectJacobiansMatchNumeric(*factor, blocks, 1e-6);
}

}  // namespace
}  // namespace slipgraph
