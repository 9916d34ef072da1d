#include "solvers/model_choice_variance.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace slipgraph {

double OtherModelProbability(double log_likelihood_ratio) {
  if (std::isnan(log_likelihood_ratio)) {
    throw std::invalid_argument("OtherModelProbability: the likelihood ratio is not a number");
  }
  // 1 / (1 + e^-x), written so that neither tail overflows.
  if (log_likelihood_ratio >= 0.0) return 1.0 / (1.0 + std::exp(-log_likelihood_ratio));
  const double e = std::exp(log_likelihood_ratio);
  return e / (1.0 + e);
}

void AddModelChoiceVariance(const std::vector<WardEstimate>& other, double p_other,
                            std::vector<WardEstimate>* kept) {
  if (!(p_other >= 0.0 && p_other <= 1.0)) {
    throw std::invalid_argument("AddModelChoiceVariance: p_other " + std::to_string(p_other) +
                                " is not in [0, 1]");
  }
  if (other.size() != kept->size()) {
    throw std::invalid_argument("AddModelChoiceVariance: " + std::to_string(other.size()) +
                                " states of the other model against " +
                                std::to_string(kept->size()));
  }
  for (size_t k = 0; k < other.size(); ++k) {
    WardEstimate& e = (*kept)[k];
    const WardEstimate& o = other[k];
    if (o.t != e.t) {
      throw std::invalid_argument("AddModelChoiceVariance: state " + std::to_string(k) +
                                  " of the other model is at another time");
    }
    for (size_t i = 0; i < e.sd.size(); ++i) {
      const double d = o.x[i] - e.x[i];
      e.sd[i] = std::sqrt(e.sd[i] * e.sd[i] + p_other * d * d);
    }
  }
}

}  // namespace slipgraph
