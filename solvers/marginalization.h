// Marginalization for sliding-window problems: the residual blocks that touch the parameter
// blocks leaving the window are linearized at the current values, stacked into a Gauss-Newton
// system over [leaving; kept], and the leaving blocks are eliminated by the Schur complement
//
//   H_prior = H_kk - H_km H_mm^+ H_mk,    b_prior = b_k - H_km H_mm^+ b_m,
//
// which becomes a MarginalPrior on the kept blocks. Information is carried, not thrown away, and
// for a linear-Gaussian problem the window's solution equals the full problem's (tested).
#pragma once

#include <ceres/problem.h>

#include <memory>
#include <string>
#include <vector>

#include "factors/marginal_prior.h"

namespace slipgraph {

struct Marginalization {
  // On `kept`, in that order. Null when it failed (error says why) or when no kept block
  // touches the leaving ones (kept empty, error empty: nothing to carry).
  std::unique_ptr<MarginalPrior> prior;
  std::vector<double*> kept;
  std::string error;  // why it failed (a residual block that could not be evaluated)
};

// Eliminates `leaving` from every residual block that touches it (found through the problem,
// which must have enable_fast_removal set). The caller removes the leaving blocks afterwards and
// adds the prior. Residuals and Jacobians are loss-corrected, as the solver sees them.
Marginalization Marginalize(const ceres::Problem& problem, const std::vector<double*>& leaving);

}  // namespace slipgraph
