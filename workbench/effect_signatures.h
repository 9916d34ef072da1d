// How each catalogue effect betrays its absence: the residual series it would bend and the shape
// it would bend them into. A signature turns a model's residuals (workbench/model_residuals.h)
// into pairs (y, g) with y ~ c + theta g, theta the effect's magnitude in the catalogue's unit;
// the workbench fits theta with a HAC standard error (workbench/robust_statistics.h) on each
// pair. That is a score (Lagrange-multiplier) test of theta = 0 at the current solution, made
// robust to the colored residuals a smoother leaves. An effect in the physics is tested on the
// whole graph instead (workbench/graph_score_test.h: its term's column, or an external force
// shape through ModelResiduals::graph): its series carries the ready fit and no (y, g).
//
// The built-in signatures are the table in effect_signatures.cpp; EffectRegistry holds them with
// the catalogue's model terms (factors/catalogue_terms.h). A program adds its own effect to a
// registry it builds and hands to Diagnose: a signature (and, for a sensor effect, its
// correction), or a model term whose graph test comes with it. docs/adding-an-effect.md walks
// through both (workbench/examples/, tested by tests/effect_example_test.cpp and
// tests/force_term_example_test.cpp).
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "factors/effect_term.h"
#include "io/drive_log.h"
#include "model/model_config.h"
#include "workbench/model_residuals.h"
#include "workbench/robust_statistics.h"

namespace slipgraph {

// One residual series an effect bends: y (normalized residuals) against g (the effect's
// derivative, normalized the same way), over the samples where both are finite.
struct SignatureSeries {
  std::string stream;
  std::vector<double> t, y, g;
  // Optional: the sd of a common-mode error in y (the solution's own uncertainty, normalized
  // like y); fully correlated across samples unless y_common_next_corr says how it decays.
  std::vector<double> y_common_sd;
  // Optional: that error's correlation between entry i and i + 1 (else fully correlated).
  std::vector<double> y_common_next_corr;
  // How many alternatives the signature searched to choose this series (a change point, a patch):
  // the p-value is multiplied by it (Bonferroni). 1 for a fixed shape.
  double searched = 1.0;
  std::string where;  // the chosen alternative, for the report ("patch 18-36 m")
  // Its time spans in the log (for an effect that acts on windows: what `--with` gives the
  // model's effect_windows).
  std::vector<std::pair<double, double>> windows;
  // Set when the signature has already tested theta = 0 by other means (the score test on the
  // whole graph, workbench/graph_score_test.h): used as is; y and g are then empty.
  std::optional<SlopeFit> fit;
  // For a test on the graph: the tested term's raw column (GraphProjector::EffectColumn or
  // ForceColumn), so the diagnosis can ask what is left of a misfit once it is taken out.
  std::function<Eigen::VectorXd(const GraphProjector&)> graph_column;
};

struct PlausibleRange {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  std::string basis;  // what sets the limits ("half the robot's weight at its top speed, 1.4 m/s")
};

struct EffectSignature {
  std::string effect;  // catalogue name
  std::string test;    // one line: which residuals against which shape
  // Magnitudes at or below this are indistinguishable from the model's own approximations on the
  // log (for a clock offset: one IMU sample period); the test's null is |theta| <= negligible.
  std::function<double(const DriveLog&)> negligible;
  std::function<std::vector<SignatureSeries>(const ModelResiduals&, const DriveLog&,
                                             const ModelConfig&)>
      series;
  // For an effect that lives in a sensor rather than in the physics: undoes it in the log's
  // measurements for a given magnitude, so the unchanged smoother runs on corrected streams
  // (`diagnose --with`). Null when the effect needs a model term instead.
  std::function<void(double magnitude, DriveLog* log)> correct;
  // The magnitudes the physics allows for this vehicle on this log (its weight, how fast, how
  // sharply and how steeply it drove): a fit whose +-2 sd interval lies outside is reported as
  // implausible and not offered as the fix. Null: no limit known.
  std::function<PlausibleRange(const DriveLog& log)> plausible = nullptr;
};

// The effects a diagnosis knows: the smoother's terms (factors/effect_term.h) and every effect's
// signature. Built by the caller: Catalogue() and what a program adds to a copy of it.
class EffectRegistry {
 public:
  // The catalogue's terms and the built-in signatures, built once; and the same with the
  // model-parameter candidates.
  static const EffectRegistry& Catalogue();
  static const EffectRegistry& CatalogueWithParameters();

  // A model term: the smoother's, with the graph test of its column as its signature unless one
  // of its name is in the registry (or added later), or it is a model parameter
  // (EffectTerm::model_parameter), which is a candidate only after AddParameterCandidates(). A
  // term of the same name is replaced.
  void Add(EffectTerm term);
  // The model-parameter terms as candidates too: "a parameter of the model is off" beside the
  // missing effects.
  void AddParameterCandidates();
  // A signature: an effect without a model term (a sensor effect with its correction), or a
  // second opinion replacing the signature of the same name.
  void Add(EffectSignature signature);

  const EffectTerms& terms() const { return terms_; }
  // Every signature, in the order they were added (the catalogue's first).
  const std::vector<EffectSignature>& signatures() const { return signatures_; }
  const EffectSignature* FindSignature(const std::string& effect) const;
  // nullptr when the smoother has no term for `effect`.
  const EffectTerm* FindTerm(const std::string& effect) const { return terms_.Find(effect); }
  // Whether AddEffects can add `effect`: a smoother term or a measurement correction.
  bool CanAdd(const std::string& effect) const;
  // The names a diagnosis can test, comma-separated.
  std::string Names() const;

 private:
  EffectTerms terms_;
  std::vector<EffectSignature> signatures_;
};

// What bounds a magnitude's plausibility on a log: the robot's weight and how fast, how sharply
// and how steeply it drove (99th percentiles of the driven sides' mean rim speed, the gyro's
// |yaw rate| and the attitude's |pitch|, so that a spike does not set them).
struct DriveExtent {
  double weight_n = 0.0;
  double speed_mps = 0.0;
  double yaw_rate_radps = 0.0;
  double grade_rad = 0.0;
};
DriveExtent ExtentOf(const DriveLog& log);

// The attitude stream's unwrapped heading beside the gyro's integrated one (trapezoid over the
// states of g_z - c_gz - b_gz, starting at 0), at the states that have an attitude sample, with
// the gyro's rate there and the attitude yaw's sd (0.01 rad when the log has none). Clock-offset
// and gyro-scale tests compare the two.
struct HeadingSeries {
  std::vector<double> t, attitude, gyro, rate, sd;
};
HeadingSeries AttitudeAndGyroHeadings(const ModelResiduals& m, const DriveLog& log);

// x minus its centred moving average over window_s (t ascending): removes what drifts slower
// than the window, such as a sensor bias's walk. For signatures.
std::vector<double> HighPass(const std::vector<double>& t, const std::vector<double>& x,
                             double window_s);
// x's centred moving average over short_s less that over long_s (t ascending): keeps what varies
// over seconds, such as a speed change, and leaves out both a bias's slow walk and a chassis's
// vibration. A sinusoid passes at half its amplitude or more for periods between about 1.3
// short_s and 1.6 long_s. For signatures.
std::vector<double> BandPass(const std::vector<double>& t, const std::vector<double>& x,
                             double short_s, double long_s);

}  // namespace slipgraph
