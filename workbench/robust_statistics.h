// Statistics the workbench's tests rest on, robust to the colored residuals a smoother leaves:
// a least-squares slope with heteroskedasticity- and autocorrelation-consistent (HAC, Newey-West
// with Andrews' AR(1) plug-in bandwidth) standard error, the Ljung-Box whiteness test, and
// chi-square tail probabilities (Boost.Math).
#pragma once

#include <cstddef>
#include <vector>

namespace slipgraph {

struct SlopeFit {
  double slope = 0.0;      // theta in y = c + theta g + e
  double sd = 0.0;         // its HAC standard error
  double naive_sd = 0.0;   // the white-noise standard error, for comparison
  double common_sd = 0.0;  // the common-mode part of sd (0 without common_sd)
  double intercept = 0.0;
  double lag = 0.0;                 // the Bartlett bandwidth used (samples)
  double variance_explained = 0.0;  // 1 - var(e) / var(y)
  size_t n = 0;
  double z() const { return sd > 0.0 ? slope / sd : 0.0; }
};

// Fits y = c + theta g by least squares over the samples where both are finite; the slope's
// standard error from the Bartlett-kernel long-run variance of (g - mean g) e. Fewer than 10
// usable samples or a constant g give n and sd 0.
// common_sd (optional, same length): the sd of an error in y shared by all samples (fully
// correlated); its contribution (sum (g_i - mean g) common_sd_i)^2 / S_gg^2 is added to the
// slope's variance.
// common_next_corr (optional, same length): the correlation of that error between sample i and
// i + 1 (a Markov chain: corr(i, j) is the product between them) instead of full correlation.
SlopeFit FitSlopeHac(const std::vector<double>& y, const std::vector<double>& g,
                     const std::vector<double>& common_sd = {},
                     const std::vector<double>& common_next_corr = {});

// The Newey-West (Bartlett kernel) estimate of Var(sum h_i) for a zero-mean, autocorrelated and
// heteroskedastic series h, with Andrews' (1991) AR(1) plug-in bandwidth (returned in *lag, in
// samples, when lag is not null).
double BartlettLongRunVariance(const std::vector<double>& h, double* lag = nullptr);

// Ljung-Box Q over lags 1..max_lag of the finite samples of r (mean removed), and its upper tail
// probability under chi-square(max_lag). Fewer samples than 2 max_lag gives p = 1.
struct WhitenessTest {
  double q = 0.0;
  int lags = 0;
  double p_value = 1.0;
  double lag1_autocorrelation = 0.0;
};
WhitenessTest LjungBox(const std::vector<double>& r, int max_lag);

// P(X > x) for X ~ chi-square(dof).
double ChiSquareUpperTail(double x, double dof);
// The quantile q (0..1) of chi-square(dof).
double ChiSquareQuantile(double q, double dof);
// P(|Z| > z) for a standard normal Z.
double NormalTwoSided(double z);
// The z with P(|Z| > z) = p.
double NormalTwoSidedQuantile(double p);

}  // namespace slipgraph
