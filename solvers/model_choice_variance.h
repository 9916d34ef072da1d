// The sd of an estimate chosen between two models that the data tell apart by little: the
// reported states are one model's solution, but the other's is possible too, with the
// probability its evidence gives it, and then the reported state is off by the difference of the
// two. Each state's variance becomes
//   sd_kept^2 + p_other (x_other - x_kept)^2,
// the between-model term of Bayesian model averaging's variance (Hoeting, Madigan, Raftery and
// Volinsky 1999, eq. 2 and 3), taken about the reported solution. The other model's own sd are
// not mixed in: a model that fixes a parameter the kept one estimates reports smaller sd, not a
// smaller error, and would narrow the kept solution's where the two agree.
// The probability is the caller's: the batch (BatchSmootherOptions::model_choice_variance) takes
// GNSS's likelihood ratio at the two fitted solutions, not the models' marginal evidence, which
// would also charge the richer model for its freedom.
#pragma once

#include <vector>

#include "io/state_estimate.h"

namespace slipgraph {

// The probability of the other model from the log-likelihood ratio log L_other - log L_kept
// (a cost difference, cost_kept - cost_other, for costs of half a chi-square) at even prior odds.
double OtherModelProbability(double log_likelihood_ratio);

// Widens every state's sd in `kept` as above. `other`: the other model's solution on the same
// samples (same size and times). Throws std::invalid_argument when the two do not match or
// p_other is outside [0, 1].
void AddModelChoiceVariance(const std::vector<WardEstimate>& other, double p_other,
                            std::vector<WardEstimate>* kept);

}  // namespace slipgraph
