// Wilcox's slippage and sinkage estimate as a factor graph (issue 8), per side: the rear wheel's
// position per cycle, the terrain y and the sinkage s as node values on a 1 cm grid along the
// path, a factor per range sample and per articulation measurement (factors/wilcox_factors.h),
// the odometry prior on each advance, and smoothness priors on y (curvature) and s (slope).
// Built cycle by cycle: each new position starts from a search over the advance on the profiles
// mapped so far (as the baseline searches its histograms; below), the newly ranged ground extends
// the terrain, and every `refine_every` cycles the whole graph is refined; a final solve at the
// end.
// (From the baseline's positions instead, the joint problem stays in the baseline's local
// minimum: odometry error unchanged; from the true positions it stays there: 0.004 %.)
#pragma once

#include "solvers/wilcox_baseline.h"

namespace slipgraph {

struct WilcoxGraphOptions {
  double node_spacing_m = 0.01;
  int nodes_per_block = 8;          // nodes per Ceres parameter block (1: a block per node)
  double margin_m = 0.05;           // how far a position may move from its initial value
  double y_curvature_sd_m = 0.003;  // second difference of y between nodes
  double s_slope_sd_m = 0.001;      // difference of s between nodes
  double s_prior_sd_m = 0.05;       // s around 0
  int max_iterations = 100;         // the final solve
  int refine_every = 1;             // cycles between intermediate solves (5 iterations each)
  int window_cycles = 10;           // the intermediate solves move only the last this many cycles
  // Both sides in one problem sharing the rear wheels' positions (a rigid rover driving straight;
  // the odometry prior on the sides' mean rim motion); each side keeps its own terrain and
  // sinkage, and the left/right check then compares the sinkage alone.
  bool shared_advance = false;
  // Marginal sd of each advance and front sinkage (ceres::Covariance, SPARSE_QR).
  bool covariance = true;
  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const;
};

// The advance prior's slip law is WilcoxOptions' prior_slip and prior_slip_per_slope; with
// learn_slip each cycle's prior takes the law as the baseline had learned it by that cycle (the
// baseline runs first in any case: it gives the rim motion and the fallback).
//
// The search for each new advance scores the factors against the profiles estimated so far, so
// each factor's variance there adds WilcoxOptions::histogram_sd_m (those profiles' own error; the
// factors in the solve keep the measurement's sd alone, the profiles being parameters there).
// While the rear wheel is on the guessed ground under the start, the search takes out the ride
// height offset that best aligns the factors, as the baseline does, and leaves out factors whose
// far wheel is on guessed ground. Measured (docs/wilcox.md): before these two, a prior slip
// other than 0 sent the start into a wrong minimum on some runs.
WilcoxResult EstimateWilcoxGraph(const DriveLog& log, const WilcoxOptions& options = {},
                                 const WilcoxGraphOptions& graph = {});

}  // namespace slipgraph
