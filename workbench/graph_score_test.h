// Rao's score (Lagrange-multiplier) test of each model effect's magnitude on the whole factor
// graph at a smoother's solution.
//
// The smoother absorbs a missing force into what the model lets move: the velocity shifts a few
// mm/s, the slip follows, and the force balance closes again; a test that looks at one residual
// stream (the force balance against the effect's shape) then sees almost nothing. The score test
// on the graph does not: with J the whitened Jacobian of every factor at the solution, split into
// the nuisance columns N (states, IMU offsets, the effects already in the model) and the effect's
// column t, and r the whitened residuals,
//
//   w = (I - N (N'N)^-1 N') t          the effect's direction the nuisance cannot mimic
//   S = w' r,   I = w' w               efficient score and information
//   theta = -S / I,   sd = 1 / sqrt(I)  (one Gauss-Newton step from theta = 0)
//
// S^2 / I is chi-square with 1 dof under theta = 0 when the factors' sigmas are right. They are
// not exactly (quantized encoders, a disturbance walk that is a modelling device), so the test
// also gives a robust variance: S as a sum over states of c_k = sum over state k's rows of
// w_i e_i, e = r + w theta the residuals with the one-step magnitude taken out, and Var(S) from
// the Newey-West long-run variance of c_k (Boos 1992; Wooldridge's robust LM test). The
// workbench uses the larger of the two.
#pragma once

#include <array>
#include <vector>

#include "factors/model_effects.h"
#include "problems/ward_batch_problem.h"

namespace slipgraph {

struct GraphScore {
  bool tested = false;     // false: in the model already, or the system was singular
  double magnitude = 0.0;  // one-step estimate -S / I, in the catalogue's unit
  double model_sd = 0.0;   // 1 / sqrt(I): the factors' own sigmas
  double robust_sd = 0.0;  // sqrt(Var_HAC(S)) / I
  double lag = 0.0;        // the Bartlett bandwidth of the robust variance (states)
  size_t states = 0;
  double sd() const { return robust_sd > model_sd ? robust_sd : model_sd; }
};

// `problem` holds every model effect as a parameter block (no manifold) and its parameter blocks
// are set to the solution; `in_model` lists the effects the user's model has (nuisance, not
// tested). Throws std::runtime_error when Ceres cannot evaluate the problem.
std::array<GraphScore, kModelEffectCount> GraphScoreTests(WardProblem& problem,
                                                          const std::vector<int>& in_model);

}  // namespace slipgraph
