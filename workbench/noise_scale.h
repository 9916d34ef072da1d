// Is a measurement's stated noise too small? A "parameter off" finding from the front end's
// innovations, not a force: a GNSS velocity sd stated ten times too small makes every fix pull
// the estimate and shows as a force the smoother cannot place, so the workbench names the stated
// noise first.
//
// Each measurement's innovations nu_i have variance s_i = h P h' + r_i under the model. With the
// stated noise scaled by lambda and the filter's h P h' held as it ran (a run with the noise
// scaled would move P too: this is the test's local approximation), s_i(lambda) = s_i (1 +
// (lambda - 1) q_i), q_i = r_i / s_i (the noise's share, EkfStats::InnovationSeries::
// measurement_share), and with z_i = nu_i / sqrt(s_i) the log-likelihood is
//
//   l(lambda) = -1/2 sum_i [ log(1 + (lambda - 1) q_i) + z_i^2 / (1 + (lambda - 1) q_i) ].
//
// A stated sd within a tolerance of the truth is no finding (noise sd are seldom known better than
// that, and a filter whose model is off has innovations somewhat larger than it states for every
// measurement): the null is lambda <= lambda_0 = tolerance^2. The score at lambda_0 is
// S = sum_i c_i, c_i = q_i / d_i (z_i^2 / d_i - 1) / 2, d_i = 1 + (lambda_0 - 1) q_i. The test is
// the robust score test, S^2 / Var(S) with Var(S) the Newey-West long-run variance of the
// centred c_i (the innovations of a filter whose model is off are correlated, and GNSS averaged
// over a second is too), one-sided: only a noise stated too small (S > 0) is a finding. A noise
// stated too large is not reported: a filter whose process noise is generous has small innovations
// for any measurement noise (the encoders' NIS on simulated logs is about 0.001), so the
// innovations cannot tell the two apart. The magnitude is the maximum-likelihood lambda (a search
// over log lambda). The rows of measurements that share a model key (the two encoders) are
// pooled in time order, with the one-row innovations (GNSS) the gate left out (a noise stated too
// small sends many past it).
#pragma once

#include <string>
#include <vector>

#include "solvers/ward_ekf.h"

namespace slipgraph {

struct NoiseScaleFinding {
  std::string key;                        // the model file's key that states the noise
  std::vector<std::string> measurements;  // the innovation series pooled under it
  size_t updates = 0;                     // innovations tested (the gated ones included)
  double nis_mean = 0.0;
  double variance_scale = 1.0;  // maximum-likelihood lambda
  double statistic = 0.0;       // S^2 / Var_HAC(S), chi-square with 1 dof at lambda_0
  double p_value = 1.0;         // one-sided, Bonferroni-adjusted over the keys tested
  bool significant = false;
  double sd_scale() const;  // sqrt(lambda): the ML noise sd over the stated
};

// The model file's key that states the noise of an innovation series of the Ward EKF
// ("gnss" -> "measurement_noise.gps_sd_v", which a log's own sd_v column overrides fix by fix);
// empty for a name it does not know.
std::string NoiseKeyOf(const std::string& measurement);

// One finding per key with at least `min_updates` innovations (with their noise shares), in
// the order of the keys' first measurement; significant at `alpha` against a stated sd within
// `sd_tolerance` (a factor) of the innovations'.
std::vector<NoiseScaleFinding> TestNoiseScales(const EkfStats& stats, double alpha = 0.01,
                                               double sd_tolerance = 1.5, size_t min_updates = 20);

}  // namespace slipgraph
