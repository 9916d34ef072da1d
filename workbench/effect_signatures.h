// How each catalogue effect betrays its absence: the residual series it would bend and the shape
// it would bend them into. A signature turns a model's residuals (workbench/model_residuals.h)
// into pairs (y, g) with y ~ c + theta g, theta the effect's magnitude in the catalogue's unit;
// the workbench fits theta with a HAC standard error (workbench/robust_statistics.h) on each
// pair. That is a score (Lagrange-multiplier) test of theta = 0 at the current solution, made
// robust to the colored residuals a smoother leaves.
//
// Adding an effect's test is one entry in the table of effect_signatures.cpp.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "model/model_config.h"
#include "workbench/model_residuals.h"

namespace slipgraph {

// One residual series an effect bends: y (normalized residuals) against g (the effect's
// derivative, normalized the same way), over the samples where both are finite.
struct SignatureSeries {
  std::string stream;
  std::vector<double> t, y, g;
  // Optional: the sd of a common-mode error in y (the solution's own uncertainty, normalized
  // like y), which the test treats as fully correlated across samples (a conservative bound).
  std::vector<double> y_common_sd;
  // How many alternatives the signature searched to choose this series (a change point, a patch):
  // the p-value is multiplied by it (Bonferroni). 1 for a fixed shape.
  double searched = 1.0;
  std::string where;  // the chosen alternative, for the report ("patch 18-36 m")
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
};

// Every effect with a signature, in catalogue order.
const std::vector<EffectSignature>& EffectSignatures();
const EffectSignature* FindSignature(const std::string& effect);

}  // namespace slipgraph
