// The walkthrough's physics example (workbench/examples/extra_rolling_resistance.h: one file, a
// force shape and its term), added to a registry as a program would, checked end to end on a log
// simulated with that force (the simulator's extra_force_n, as a user would simulate a hypothesis):
// it is a candidate, ranked first and significant with its magnitude;
// `--with` fits it as a smoother term and the velocity error falls; on the log without the force
// it is not significant.
#include <gtest/gtest.h>

#include <cmath>

#include "factors/smooth_math.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "tests/estimate_check.h"
#include "workbench/diagnosis.h"
#include "workbench/effect_signatures.h"
#include "workbench/examples/extra_rolling_resistance.h"

namespace slipgraph {
namespace {

constexpr double kTrueFraction = 0.05;  // at 0.03 it ranks first with p 0.012: not significant

DriveLog HiddenNone(bool with_force) {
  sim::ScenarioRun run = sim::ExpandScenario("hidden/none", 1).at(0);
  if (with_force) {
    run.scenario.extra_force_n = [](const sim::ExtraForceInputs& in) {
      return -kTrueFraction * in.mass_kg * 9.80665 * SignedSaturation(in.v_mps, 20.0);
    };
  }
  return sim::Simulate(run.scenario, run.seed).log;
}

EffectRegistry WithTheExample() {
  EffectRegistry registry = EffectRegistry::Catalogue();
  registry.Add(ExtraRollingResistance());
  return registry;
}

TEST(ForceTermExample, AddedAsATermAndACandidate) {
  const EffectRegistry registry = WithTheExample();
  const EffectTerm* term = registry.FindTerm("extra_rolling_resistance");
  ASSERT_NE(term, nullptr);
  EXPECT_NE(registry.FindSignature("extra_rolling_resistance"), nullptr);
  EXPECT_TRUE(registry.CanAdd("extra_rolling_resistance"));
  // Only in this registry: the catalogue is unchanged.
  EXPECT_EQ(EffectRegistry::Catalogue().FindTerm("extra_rolling_resistance"), nullptr);
  EXPECT_EQ(registry.signatures().size(), EffectRegistry::Catalogue().signatures().size() + 1);
  // A force term whose shape is -g sgn~(v), the same on doubles and Jets.
  ASSERT_EQ(term->kind, EffectKind::kForce);
  const ward::Params params;
  double x[ward::kStateSize] = {0.8, 0, 0, 0, 0, 0, 0};
  const double value = (*term->force)(x, EffectContext(), params);
  EXPECT_NEAR(value, -params.gravity_mps2 * SignedSaturation(0.8, 20.0), 1e-12);
  EffectJet jets[ward::kStateSize];
  for (int i = 0; i < ward::kStateSize; ++i) jets[i] = EffectJet(x[i], i);
  EXPECT_DOUBLE_EQ((*term->force)(jets, EffectContext(), params).a, value);
}

TEST(ForceTermExample, FoundFittedAndQuietWhenAbsent) {
  const DriveLog log = HiddenNone(true);
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  const EffectRegistry registry = WithTheExample();
  DiagnosisOptions options;
  options.effects = &registry;
  const Diagnosis before = Diagnose(log, model, options);
  ASSERT_FALSE(before.candidates.empty());
  const CandidateScore& top = before.candidates.front();
  EXPECT_EQ(top.effect, "extra_rolling_resistance");
  EXPECT_TRUE(top.significant);
  EXPECT_EQ(top.added_as, "smoother term");
  EXPECT_TRUE(testing::EstimateOf(top.magnitude, top.magnitude_sd, kTrueFraction,
                                  0.3 * kTrueFraction, 0.3 * kTrueFraction));

  const ExtendedModel extended =
      AddEffects(log, model, before, {"extra_rolling_resistance"}, registry);
  const Diagnosis after = Diagnose(extended.log, extended.model, options);
  ASSERT_EQ(after.fitted_effects.size(), 1u);
  EXPECT_EQ(after.fitted_effects[0].name, "extra_rolling_resistance");
  EXPECT_TRUE(testing::EstimateOf(after.fitted_effects[0].value, after.fitted_effects[0].sd,
                                  kTrueFraction, 0.3 * kTrueFraction, 0.3 * kTrueFraction));
  ASSERT_TRUE(before.truth.available && after.truth.available);
  EXPECT_LT(after.truth.velocity_rmse, 0.7 * before.truth.velocity_rmse);
  ASSERT_FALSE(after.candidates.empty());  // "none significant" must test some
  for (const CandidateScore& c : after.candidates) {
    EXPECT_FALSE(c.significant) << c.effect << " " << c.magnitude;
  }

  const Diagnosis quiet = Diagnose(HiddenNone(false), model, options);
  ASSERT_FALSE(quiet.candidates.empty());  // "none significant" must test some
  for (const CandidateScore& c : quiet.candidates) {
    EXPECT_FALSE(c.significant) << c.effect << " " << c.magnitude;
  }
}

}  // namespace
}  // namespace slipgraph
