// Levenberg-Marquardt on a chain (solvers/chain_covariance.h): states x_0..x_{n-1} where every
// residual block touches at most two consecutive states, plus a few global parameters any block
// may touch. Each iteration evaluates every residual block once and factors the block-tridiagonal
// information with its border in O(n); a rejected step is retried with more damping from the
// same factorization's inputs, without evaluating again. Ceres' trust-region solver on the same
// problem builds and sorts a general sparse J'J and runs CHOLMOD on it each iteration.
//
// The damping follows Ceres' Levenberg-Marquardt strategy: (H + mu diag(H)) d = -J'r with
// mu = 1 / radius, the radius grown by max(1/3, 1 - (2 rho - 1)^3) on a step that keeps a
// fraction rho of its predicted decrease, and shrunk by a factor that doubles on each rejection
// in a row. Bounds the problem sets on a parameter (Problem::SetParameterLowerBound) are kept by
// projecting each step onto them; a block's manifold, where it has one, takes the step.
#pragma once

#include <ceres/problem.h>
#include <ceres/solver.h>

#include <string>
#include <vector>

#include "evaluation/progress.h"

namespace slipgraph {

struct ChainSolverOptions {
  int max_iterations = 50;  // iterations, kept steps and rejected ones
  // Convergence, as Ceres' own tests: the cost's relative decrease of an accepted step, the
  // largest projected gradient component, the step's size relative to the parameters'.
  double function_tolerance = 1e-6;
  double gradient_tolerance = 1e-10;
  double parameter_tolerance = 1e-8;
  // Converged when a kept Gauss-Newton step's length in the solution's own sd, sqrt(d'H d), is
  // below this (0: off): the last step moved every estimate by less than this fraction of its
  // sd. Where the solve converges linearly the optimum is a few such steps further (a 0.01
  // tolerance left a Ward problem within 0.05 sd of it; tests/chain_solver_test.cpp).
  double step_sd_tolerance = 0.0;
  // The first damping is 1 / this (Ceres' initial_trust_region_radius).
  double initial_trust_region_radius = 1e4;
  // A step is kept when the cost falls by at least this fraction of the predicted decrease.
  double min_relative_decrease = 1e-3;
  // A kept step whose cost fell by more than this multiple of the predicted decrease is tried
  // once more, longer, as far as the parabola through the cost at both ends and the slope at the
  // start puts the minimum (at most max_extrapolation_length times the step).
  double extrapolation_rho = 1.2;
  double max_extrapolation_length = 16.0;
  // Told after each iteration (its number and cost), as this stage.
  ProgressCallback progress;
  std::string progress_stage = "chain solver: iteration";
  int threads = 1;  // residual blocks evaluated on this many threads

  bool IsValid(std::string* error) const;
};

// Solves the problem in place, starting from its current values. The summary is Ceres' type
// (initial and final cost, each iteration's cost and time, termination type and message), so
// that callers report either solver alike. Returns false when the problem is not a chain or its
// information cannot be factored at any damping (summary->message says why; the values are
// the last accepted iterate's): the caller solves it with Ceres instead.
bool SolveOnChain(ceres::Problem* problem, const std::vector<double*>& states,
                  const std::vector<double*>& globals, const ChainSolverOptions& options,
                  ceres::Solver::Summary* summary);

}  // namespace slipgraph
