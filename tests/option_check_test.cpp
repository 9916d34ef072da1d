// Options validated in one place: OptionCheck names the struct, field and value of the first
// failure; every options struct's defaults pass its IsValid, a bad value is named, and the entry
// points refuse invalid options before they run.
#include "model/option_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "evaluation/evaluation.h"
#include "io/log_reader.h"
#include "problems/ward_factor_source.h"
#include "solvers/batch_smoother.h"
#include "solvers/ekf_runner.h"
#include "solvers/ipd_calibration.h"
#include "solvers/ipd_graph_calibration.h"
#include "solvers/jump_detector.h"
#include "solvers/model_identification.h"
#include "solvers/multiple_model_ekf.h"
#include "solvers/trust_check.h"
#include "solvers/ward_ekf.h"
#include "solvers/wilcox_baseline.h"
#include "solvers/wilcox_graph.h"
#include "solvers/window_smoother.h"
#include "workbench/diagnosis.h"

namespace slipgraph {
namespace {

TEST(OptionCheck, NamesTheFirstFailureOnly) {
  std::string error;
  EXPECT_TRUE(
      OptionCheck("S", &error).Positive("a", 1.0).AtLeast("n", 3, 1).Within("f", 0.5, 0, 1));
  EXPECT_TRUE(error.empty());
  EXPECT_FALSE(OptionCheck("S", &error).Positive("a", 1.0).NonNegative("b", -2.0).Positive("c", 0));
  EXPECT_EQ(error, "S.b = -2: must be non-negative");
  EXPECT_FALSE(OptionCheck("S", &error).Positive("a", NAN));
  EXPECT_EQ(error, "S.a = nan: must be positive");
  EXPECT_FALSE(OptionCheck("S", &error).Within("f", 1.5, 0.0, 1.0));
  EXPECT_EQ(error, "S.f = 1.5: must lie in [0, 1]");
  EXPECT_FALSE(OptionCheck("S", &error).AtLeast("n", 0, 1));
  EXPECT_EQ(error, "S.n = 0: must be at least 1");
}

// `options` valid as it is; with `spoil` applied, invalid with an error naming `field`.
template <typename Options, typename Spoil>
void ExpectValidatedField(Options options, Spoil spoil, const std::string& field) {
  std::string error;
  EXPECT_TRUE(options.IsValid(&error)) << error;
  spoil(&options);
  EXPECT_FALSE(options.IsValid(&error)) << field;
  EXPECT_NE(error.find(field), std::string::npos) << error;
}

TEST(OptionsValidation, DefaultsPassAndABadFieldIsNamed) {
  ExpectValidatedField(
      ReadOptions{}, [](auto* o) { o->max_bad_fraction = 2.0; }, "ReadOptions.max_bad_fraction");
  ExpectValidatedField(
      EkfOptions{}, [](auto* o) { o->gps_gate_chi2 = 0.0; }, "EkfOptions.gps_gate_chi2");
  ExpectValidatedField(
      MultipleModelOptions{}, [](auto* o) { o->switch_time_s = -1.0; },
      "MultipleModelOptions.switch_time_s");
  ExpectValidatedField(
      FilterRunOptions{}, [](auto* o) { o->ekf.initial_sd[3] = 0.0; }, "EkfOptions.initial_sd");
  ExpectValidatedField(
      WardProblemOptions{}, [](auto* o) { o->stiffness_min = -1.5; },
      "WardProblemOptions.stiffness_min");
  ExpectValidatedField(
      BatchSmootherOptions{}, [](auto* o) { o->problem.decay_sd_density = 0; },
      "WardProblemOptions.decay_sd_density");
  ExpectValidatedField(
      WindowSmootherOptions{}, [](auto* o) { o->update_every = 0; },
      "WindowSmootherOptions.update_every");
  ExpectValidatedField(
      TrustOptions{}, [](auto* o) { o->wheel_scale = 0.5; }, "wheel_scale");
  ExpectValidatedField(
      IdentifyOptions{}, [](auto* o) { o->threads = 0; }, "threads");
  ExpectValidatedField(
      DiagnosisOptions{}, [](auto* o) { o->alpha = 1.0; }, "DiagnosisOptions.alpha");
  ExpectValidatedField(
      WilcoxOptions{}, [](auto* o) { o->learn.min_data_fraction = 2.0; },
      "SlipSlopeLawOptions.min_data_fraction");
  ExpectValidatedField(
      WilcoxGraphOptions{}, [](auto* o) { o->nodes_per_block = 0; },
      "WilcoxGraphOptions.nodes_per_block");
  ExpectValidatedField(
      IpdOptions{}, [](auto* o) { o->q_initial.y() = 0.0; }, "IpdOptions.q_initial");
  ExpectValidatedField(
      IpdGraphOptions{}, [](auto* o) { o->q_likelihood.max_iterations = 0; }, "max_iterations");
  ExpectValidatedField(
      JumpDetectorOptions{}, [](auto* o) { o->window = 0; }, "JumpDetectorOptions.window");
  ExpectValidatedField(
      EvaluationOptions{}, [](auto* o) { o->false_grace_after_s = -1.0; },
      "EvaluationOptions.false_grace_after_s");
}

// The entry points refuse invalid options before they read anything of the log.
TEST(OptionsValidation, EntryPointsRefuseInvalidOptions) {
  const DriveLog log;
  const ModelConfig model;
  FilterRunOptions filter;
  filter.ekf.wheels_gate_chi2 = -1.0;
  EXPECT_THROW(RunEkf(log, model, filter), std::invalid_argument);
  WindowSmootherOptions window;
  window.window_s = 0.0;
  EXPECT_THROW(SmoothWindowed(log, model, FilterResult{}, window), std::invalid_argument);
  WilcoxOptions wilcox;
  wilcox.bin_m = 0.0;
  EXPECT_THROW(EstimateWilcoxBaseline(log, wilcox), std::invalid_argument);
  IpdOptions ipd;
  ipd.segment_s = 0.0;
  EXPECT_THROW(CalibrateIpdEkf(log, ipd), std::invalid_argument);
  ReadOptions read;
  read.max_bad_fraction = -0.1;
  EXPECT_THROW(ReadDriveLog(LogFilesInMemory("memory", {}), read), std::invalid_argument);
}

}  // namespace
}  // namespace slipgraph
