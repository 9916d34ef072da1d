#include "workbench/robust_statistics.h"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>

namespace slipgraph {

SlopeFit FitSlopeHac(const std::vector<double>& y, const std::vector<double>& g,
                     const std::vector<double>& common_sd,
                     const std::vector<double>& common_next_corr) {
  SlopeFit fit;
  std::vector<double> ys, gs, cs, chain;  // chain[i]: corr(kept i, kept i + 1)
  const bool common = common_sd.size() == y.size();
  const bool markov = common && common_next_corr.size() == y.size();
  double carried = 1.0;  // correlation from the last kept sample to the current one
  for (size_t i = 0; i < y.size() && i < g.size(); ++i) {
    if (std::isfinite(y[i]) && std::isfinite(g[i])) {
      if (!ys.empty()) chain.push_back(carried);
      ys.push_back(y[i]);
      gs.push_back(g[i]);
      cs.push_back(common && std::isfinite(common_sd[i]) ? common_sd[i] : 0.0);
      carried = 1.0;
    }
    if (markov) carried *= std::isfinite(common_next_corr[i]) ? common_next_corr[i] : 1.0;
  }
  const size_t n = ys.size();
  if (n < 10) return fit;
  double my = 0.0, mg = 0.0;
  for (size_t i = 0; i < n; ++i) my += ys[i], mg += gs[i];
  my /= n, mg /= n;
  double sgg = 0.0, sgy = 0.0, syy = 0.0;
  for (size_t i = 0; i < n; ++i) {
    sgg += (gs[i] - mg) * (gs[i] - mg);
    sgy += (gs[i] - mg) * (ys[i] - my);
    syy += (ys[i] - my) * (ys[i] - my);
  }
  if (!(sgg > 1e-300)) return fit;
  fit.n = n;
  fit.slope = sgy / sgg;
  fit.intercept = my - fit.slope * mg;
  // Score contributions h_i = (g_i - mean g) e_i and their Bartlett long-run variance.
  std::vector<double> h(n);
  double see = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double e = ys[i] - fit.intercept - fit.slope * gs[i];
    see += e * e;
    h[i] = (gs[i] - mg) * e;
  }
  fit.variance_explained = syy > 0.0 ? 1.0 - see / syy : 0.0;
  fit.naive_sd = std::sqrt(see / std::max<double>(1.0, n - 2.0) / sgg);
  double lag = 0.0;
  const double lrv = BartlettLongRunVariance(h, &lag);
  fit.lag = lag;
  // Var(sum a_i e_i) with a_i = (g_i - mean g) c_i: fully correlated e, or a Markov chain
  // (r_i = a_i + rho_{i-1} r_{i-1}; the sum is sum a_i (2 r_i - a_i)).
  double shared_var = 0.0;
  if (markov) {
    double r = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double a = (gs[i] - mg) * cs[i];
      r = a + (i > 0 ? chain[i - 1] * r : 0.0);
      shared_var += a * (2.0 * r - a);
    }
    shared_var = std::max(shared_var, 0.0);
  } else {
    double shared = 0.0;
    for (size_t i = 0; i < n; ++i) shared += (gs[i] - mg) * cs[i];
    shared_var = shared * shared;
  }
  fit.common_sd = std::sqrt(shared_var) / sgg;
  fit.sd = std::sqrt(std::max(lrv, 0.0) + shared_var) / sgg;
  return fit;
}

double BartlettLongRunVariance(const std::vector<double>& h, double* lag_out) {
  const size_t n = h.size();
  // Andrews (1991) bandwidth for the Bartlett kernel from an AR(1) fit of h.
  double num = 0.0, den = 0.0;
  for (size_t i = 1; i < n; ++i) num += h[i] * h[i - 1], den += h[i - 1] * h[i - 1];
  double rho = den > 0.0 ? num / den : 0.0;
  rho = std::clamp(rho, -0.99, 0.99);
  const double alpha = 4.0 * rho * rho / std::pow((1.0 - rho) * (1.0 + rho), 2.0);
  const double lag = std::min(1.1447 * std::cbrt(alpha * n), 0.25 * n);
  if (lag_out != nullptr) *lag_out = lag;
  double lrv = 0.0;
  for (size_t i = 0; i < n; ++i) lrv += h[i] * h[i];
  const size_t max_l = static_cast<size_t>(std::floor(lag));
  for (size_t l = 1; l <= max_l; ++l) {
    double c = 0.0;
    for (size_t i = l; i < n; ++i) c += h[i] * h[i - l];
    lrv += 2.0 * (1.0 - l / (lag + 1.0)) * c;
  }
  return std::max(lrv, 0.0);
}

WhitenessTest LjungBox(const std::vector<double>& r, int max_lag) {
  WhitenessTest test;
  std::vector<double> x;
  for (double v : r) {
    if (std::isfinite(v)) x.push_back(v);
  }
  const size_t n = x.size();
  test.lags = max_lag;
  if (max_lag < 1 || n < 2 * static_cast<size_t>(max_lag)) return test;
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= n;
  double c0 = 0.0;
  for (double& v : x) v -= mean, c0 += v * v;
  if (!(c0 > 0.0)) return test;
  for (int l = 1; l <= max_lag; ++l) {
    double c = 0.0;
    for (size_t i = l; i < n; ++i) c += x[i] * x[i - l];
    const double rho = c / c0;
    if (l == 1) test.lag1_autocorrelation = rho;
    test.q += rho * rho / static_cast<double>(n - l);
  }
  test.q *= static_cast<double>(n) * (n + 2.0);
  test.p_value = ChiSquareUpperTail(test.q, max_lag);
  return test;
}

double ChiSquareUpperTail(double x, double dof) {
  if (!(x > 0.0)) return 1.0;
  if (!std::isfinite(x)) return 0.0;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), x));
}

double ChiSquareQuantile(double q, double dof) {
  return boost::math::quantile(boost::math::chi_squared(dof), q);
}

double NormalTwoSided(double z) {
  if (!std::isfinite(z)) return 0.0;
  return 2.0 * boost::math::cdf(boost::math::complement(boost::math::normal(), std::abs(z)));
}

double NormalTwoSidedQuantile(double p) {
  return boost::math::quantile(boost::math::complement(boost::math::normal(), 0.5 * p));
}

}  // namespace slipgraph
