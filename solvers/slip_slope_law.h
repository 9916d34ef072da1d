// The advance prior's slip-versus-slope law, learned as the rover drives (Wilcox Sec. 3 step 2:
// "modify the estimates of m_x and sigma_x using prior estimates to adapt and refine our Bayesian
// prior"; Sec. 5: "estimate the slip versus slope function").
//
//   slip = a + b slope
//
// fitted by recursive least squares to each cycle's slip as the terrain matching alone measured
// it: the MAP advance with the prior's own information taken out (for Gaussians, the data's
// estimate is (P_post a_map - P_prior m) / (P_post - P_prior)). Without that the prior would be
// fitted to itself. The fit starts from the user's law with an sd on each coefficient and
// forgets old cycles exponentially, back towards that start, so a change of soil is followed.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <string>

#include "model/option_check.h"

namespace slipgraph {

struct SlipSlopeLawOptions {
  double slip_sd = 0.1;            // the user's level-ground slip, sd
  double slip_per_slope_sd = 1.0;  // the user's slip per unit slope, sd
  double memory_cycles = 100.0;    // forgetting: an old cycle's weight falls by e over this many
  double slip_noise_sd = 0.03;     // the slip's own cycle-to-cycle variation, added to each look
  // A cycle whose matching carries less information than this fraction of the prior's is not a
  // measurement of the slip (smooth ground: the MAP is the prior).
  double min_data_fraction = 0.2;

  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const {
    return OptionCheck("SlipSlopeLawOptions", error)
        .Positive("slip_sd", slip_sd)
        .Positive("slip_per_slope_sd", slip_per_slope_sd)
        .Positive("memory_cycles", memory_cycles)
        .NonNegative("slip_noise_sd", slip_noise_sd)
        .Within("min_data_fraction", min_data_fraction, 0.0, 1.0);
  }
};

class SlipSlopeLaw {
 public:
  SlipSlopeLaw(double slip, double slip_per_slope, const SlipSlopeLawOptions& options = {})
      : options_(options) {
    prior_info_ = Eigen::Vector2d(1.0 / (options.slip_sd * options.slip_sd),
                                  1.0 / (options.slip_per_slope_sd * options.slip_per_slope_sd))
                      .asDiagonal();
    prior_vector_ = prior_info_ * Eigen::Vector2d(slip, slip_per_slope);
    info_ = prior_info_;
    vector_ = prior_vector_;
    coefficients_ = Eigen::Vector2d(slip, slip_per_slope);
  }

  double Slip(double slope) const { return coefficients_(0) + coefficients_(1) * slope; }
  double slip() const { return coefficients_(0); }
  double slip_per_slope() const { return coefficients_(1); }
  int cycles_used() const { return used_; }
  // The coefficients' sd from the fit's information (the law as a slowly drifting one, which the
  // forgetting models: for a law that never changes it errs on the large side, up to sqrt(2)).
  double slip_sd() const { return std::sqrt(info_.inverse()(0, 0)); }
  double slip_per_slope_sd() const { return std::sqrt(info_.inverse()(1, 1)); }

  // One cycle: the slope it drove, its rim motion, the prior's mean and sd on the advance, the
  // MAP advance and the curvature of the MAP's cost (chi-square, prior included) at it. Returns
  // false (and learns nothing) when the matching added too little to the prior.
  bool AddCycle(double slope, double rim_m, double prior_mean_m, double prior_sd_m,
                double map_advance_m, double cost_curvature_per_m2) {
    const double lambda = std::exp(-1.0 / options_.memory_cycles);
    info_ = prior_info_ + lambda * (info_ - prior_info_);
    vector_ = prior_vector_ + lambda * (vector_ - prior_vector_);
    const double p_prior = 1.0 / (prior_sd_m * prior_sd_m);
    const double p_post = 0.5 * cost_curvature_per_m2;
    const double p_data = p_post - p_prior;
    if (!(rim_m > 1e-6) || !std::isfinite(p_post) ||
        p_data < options_.min_data_fraction * p_prior) {
      Solve();
      return false;
    }
    const double advance = (p_post * map_advance_m - p_prior * prior_mean_m) / p_data;
    const double slip = 1.0 - advance / rim_m;
    const double variance =
        1.0 / (p_data * rim_m * rim_m) + options_.slip_noise_sd * options_.slip_noise_sd;
    const Eigen::Vector2d h(1.0, slope);
    info_ += h * h.transpose() / variance;
    vector_ += h * slip / variance;
    ++used_;
    Solve();
    return true;
  }

 private:
  void Solve() { coefficients_ = info_.inverse() * vector_; }

  SlipSlopeLawOptions options_;
  Eigen::Matrix2d prior_info_, info_;
  Eigen::Vector2d prior_vector_, vector_, coefficients_;
  int used_ = 0;
};

}  // namespace slipgraph
