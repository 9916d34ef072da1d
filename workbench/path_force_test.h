// Is there a force the model lacks, whatever its shape? The omnibus score test on the graph
// (workbench/graph_score_test.h) of an external force as a free function of the distance along
// the path: one basis shape per metre driven (1 m/s^2 there, 0 elsewhere), their scores S and
// projected Gram G, and X^2 = S' G^+ S against chi-square with rank(G) degrees of freedom.
//
// Its uses in the diagnosis: a model can pass every stream's chi-square bound (the tire law's
// stated uncertainty is wide) and still leave a structured force unexplained (a corrugated
// track); a candidate can be significant because it takes part of a force it does not explain.
// So the test is repeated with the best candidate's direction added to the nuisance: what is
// left after it must not be significant for the candidate to "explain" the misfit. And the
// stretches of path where the force stands out (windows of 5, 10 and 20 m and the whole path,
// Bonferroni over all windows) become failure segments.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "workbench/model_residuals.h"

namespace slipgraph {

struct PathForceTest {
  bool tested = false;
  double metre = 1.0;  // basis width along the path (m)
  double statistic = 0.0, dof = 0.0, p_value = 1.0;
  // With the candidate's direction projected out too (NaN when none was given).
  std::string after_effect;
  double after_statistic = std::numeric_limits<double>::quiet_NaN();
  double after_dof = 0.0;
  double after_p_value = std::numeric_limits<double>::quiet_NaN();
  struct Stretch {
    double s_start = 0.0, s_end = 0.0;                 // path distance (m)
    double t_start = 0.0, t_end = 0.0;                 // the states' times there
    double statistic = 0.0, dof = 0.0, p_value = 1.0;  // p Bonferroni-adjusted over windows
  };
  std::vector<Stretch> stretches;  // significant windows, overlapping ones merged
};

// X^2 = s' G^+ s over the eigen-directions of G above 1e-9 of its largest eigenvalue, and that
// rank.
std::pair<double, int> ChiSquareOfScores(const Eigen::VectorXd& score, const Eigen::MatrixXd& gram);

// candidate_column: the best candidate's raw column on the graph (GraphProjector::EffectColumn,
// ForceColumn), or null. window_m: the smallest windows' length for the stretches.
PathForceTest TestForceAlongPath(const ModelResiduals& m, const Eigen::VectorXd* candidate_column,
                                 const std::string& candidate, double alpha, double metre = 1.0,
                                 double window_m = 5.0);

}  // namespace slipgraph
