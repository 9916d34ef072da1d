// "A parameter of the model is off" as a candidate (EffectRegistry::CatalogueWithParameters,
// `diagnose --parameters`): on a simulated drive whose model states a tire law twice as stiff at
// small slip as the terrain's (At and C2 doubled), the slip stiffness is ranked first and
// significant with the relative change the truth implies (-0.5); with the terrain's own law it
// is not significant; and without --parameters the candidates are the catalogue's alone.
#include <gtest/gtest.h>

#include <algorithm>

#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "workbench/diagnosis.h"

namespace slipgraph {
namespace {

DriveLog HiddenNone() {
  const sim::ScenarioRun run = sim::ExpandScenario("hidden/none", 1).at(0);
  return sim::Simulate(run.scenario, run.seed).log;
}

const CandidateScore* Find(const Diagnosis& d, const std::string& effect) {
  const auto it = std::find_if(d.candidates.begin(), d.candidates.end(),
                               [&](const CandidateScore& c) { return c.effect == effect; });
  return it == d.candidates.end() ? nullptr : &*it;
}

TEST(ParameterCandidates, OnlyWhenAsked) {
  const EffectRegistry& plain = EffectRegistry::Catalogue();
  const EffectRegistry& with = EffectRegistry::CatalogueWithParameters();
  EXPECT_EQ(plain.FindSignature("tire_slip_stiffness"), nullptr);
  ASSERT_NE(with.FindSignature("tire_slip_stiffness"), nullptr);
  EXPECT_EQ(with.signatures().size(), plain.signatures().size() + 3);
  // Both know the terms: a model may name them and --with adds them.
  EXPECT_NE(plain.FindTerm("tire_traction_level"), nullptr);
  EXPECT_TRUE(plain.CanAdd("rolling_resistance_level"));
  EXPECT_TRUE(with.FindSignature("tire_slip_stiffness")->plausible != nullptr);
}

TEST(ParameterCandidates, AStiffLawIsFoundAndTheTerrainsIsNot) {
  const DriveLog log = HiddenNone();
  DiagnosisOptions options;
  options.effects = &EffectRegistry::CatalogueWithParameters();

  ModelConfig stiff = DefaultModelConfig(log.vehicle);
  stiff.tire.At *= 2.0;
  stiff.tire.C2 *= 2.0;
  const Diagnosis off = Diagnose(log, stiff, options);
  ASSERT_FALSE(off.candidates.empty());
  const CandidateScore& top = off.candidates.front();
  EXPECT_EQ(top.effect, "tire_slip_stiffness");
  EXPECT_TRUE(top.significant);
  EXPECT_NEAR(top.magnitude, -0.5, 0.15) << top.magnitude << " +- " << top.magnitude_sd;

  const Diagnosis right = Diagnose(log, DefaultModelConfig(log.vehicle), options);
  const CandidateScore* stiffness = Find(right, "tire_slip_stiffness");
  ASSERT_NE(stiffness, nullptr);
  EXPECT_FALSE(stiffness->significant) << stiffness->magnitude;
}

}  // namespace
}  // namespace slipgraph
