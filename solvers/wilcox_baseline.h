// Wilcox's MAP estimate of slippage and sinkage for a 6-wheel articulated rover, the paper's
// algorithm as the baseline (Sec. 3), one side at a time. Coordinates are along the path,
// relative to the rear wheel's contact point; the histograms hold the undisturbed terrain y(x)
// (out to the farthest ranged point) and the sinkage s(x) (out to the front wheel), so the
// wheels ride on y - s. Each cycle:
//
//  1. the measurements: middle and front wheel elevations relative to the rear (articulation,
//     z(1), z(2)) and the ranged elevations z(3..N) at distances d(j);
//  2. the MAP advance: over whole bins i, the weighted squared errors of the ranged points
//     (all but the farthest) and of the middle wheel against the histograms with the rear wheel
//     moved to bin i, plus the Gaussian prior on the advance (mean: the odometry's rim motion);
//     a parabola through the best bin and its neighbours refines it to a fraction of a bin;
//  3. the histograms are translated by the advance (linear interpolation) and re-referenced to
//     the new rear contact; y is extended to the farthest ranged point, s to the front wheel
//     (s = y - z(2) there);
//  4. "split the difference": the bins at the ranged points move halfway to the measurements,
//     and s at the middle wheel halfway to what z(1) implies.
//
// One addition to the paper: a wheel's elevation is predicted as the terrain averaged over its
// contact patch (a third of the radius), where the paper compares point values; the ranged
// points stay points. The left/right check compares the two sides' advances and sinkages.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "io/drive_log.h"

namespace slipgraph {

struct WilcoxOptions {
  double bin_m = 0.01;          // histogram resolution (the paper: about a contact patch)
  double prior_fraction = 0.1;  // sd of the advance prior as a fraction of the rim motion
  double prior_slip = 0.0;      // prior mean: rim motion x (1 - prior_slip) (the paper: 0)
  double range_sd_m = 0.002;    // ranging noise (the paper's Sojourner figure)
  double articulation_sd_m = 0.00004;
  // The histograms' own error (ranging noise carried over, interpolation between ranged points),
  // added in quadrature to each measurement's: without it the 0.04 mm articulation term trusts
  // a histogram that is only good to about a millimetre.
  double histogram_sd_m = 0.001;
  // Contact patch as a fraction of the wheel radius: wheels ride on the terrain averaged over
  // it (0: point contact, as the paper's histograms assume).
  double contact_patch_fraction = 1.0 / 3.0;
  // Left/right check: the sides disagree when the 95th percentile of the per-cycle difference of
  // their front sinkages exceeds agree_sinkage_m (each side's sinkage is good to about the
  // ranging noise, so the difference of two to about 2.8 mm sd), or their total advances differ
  // by more than agree_advance_fraction.
  double agree_sinkage_m = 0.007;
  double agree_advance_fraction = 0.02;
};

struct WilcoxCycle {
  double t = 0.0;
  double rim_m = 0.0;            // odometry: wheel rim motion since the previous cycle
  double advance_m = 0.0;        // the MAP estimate of the rear wheel's advance
  double sinkage_front_m = 0.0;  // estimated sinkage under the front wheel
  double cost_curvature = 0.0;   // the parabola's curvature at the minimum (1/m^2): confidence
  // Marginal standard deviations (the factor graph, from its covariance; NaN when not computed).
  double advance_sd_m = std::numeric_limits<double>::quiet_NaN();
  double sinkage_front_sd_m = std::numeric_limits<double>::quiet_NaN();
};

struct WilcoxSide {
  std::string side;  // "left", "right"
  std::vector<WilcoxCycle> cycles;
  double total_advance_m = 0.0, total_rim_m = 0.0;
  double mean_sinkage_m = 0.0;
};

struct WilcoxResult {
  std::vector<WilcoxSide> sides;
  bool sides_agree = true;
  std::string agreement;  // what was compared and found
  std::vector<std::string> notes;
};

// One side's measurements of one cycle: middle and front wheel elevations relative to the rear
// (articulation) and the ranged points (d, dz), sorted by d.
struct WilcoxScan {
  double t = 0.0;
  double dz_mid = 0.0, dz_front = 0.0;
  std::vector<std::pair<double, double>> range;
};
std::vector<WilcoxScan> WilcoxScans(const DriveLog& log, Side side);
// Rim motion of one side's wheels between t0 and t1 (odometry).
double WilcoxRimMotion(const DriveLog& log, Side side, double t0, double t1);
// The left/right check on a result's two sides (sets sides_agree and agreement).
void CheckWilcoxSides(const DriveLog& log, const WilcoxOptions& options, WilcoxResult* result);

// Throws std::invalid_argument naming the log when it lacks articulation or range data.
WilcoxResult EstimateWilcoxBaseline(const DriveLog& log, const WilcoxOptions& options = {});

// Against truth.csv (when present): the odometry error of the total advance as a fraction of the
// true advance, and the RMS error of the front-wheel sinkage (after the rover has moved its own
// length, when the histograms no longer hold the unknown start).
struct WilcoxScore {
  double odometry_error_fraction = 0.0;      // |estimated - true| / true, both sides averaged
  double rim_odometry_error_fraction = 0.0;  // the same for the plain rim motion
  double sinkage_rmse_m = 0.0;
  size_t sinkage_samples = 0;
};
WilcoxScore ScoreWilcox(const DriveLog& log, const WilcoxResult& result);

}  // namespace slipgraph
