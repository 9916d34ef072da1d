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
// Additions to the paper: a wheel's elevation is predicted as the terrain averaged over its
// contact patch (a third of the radius), where the paper compares point values (the ranged
// points stay points); the rear wheel's ride height, which every measurement shares, is fitted
// within the histograms' error where they hold ranged ground under it and freely where they do
// not, by one rule for every candidate advance, and a residual a candidate cannot form counts its
// expected chi-square; the prior's sd carries the last cycle's error as well as the rim motion's.
// Without these the MAP can settle at zero advance once the rear wheel reaches ranged ground and
// stay there (docs/wilcox.md).
// The left/right check compares the two sides' advances and sinkages.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "solvers/slip_slope_law.h"

namespace slipgraph {

struct WilcoxOptions {
  double bin_m = 0.01;          // histogram resolution (the paper: about a contact patch)
  double prior_fraction = 0.1;  // sd of the advance prior as a fraction of the rim motion
  double prior_slip = 0.0;      // prior mean: rim motion x (1 - prior_slip) (the paper: 0)
  // Slip against slope (the paper's Sec. 3 step 2 and Sec. 5): the prior's slip is
  // prior_slip + prior_slip_per_slope x the slope the ranged points show (WilcoxScanSlope,
  // averaged over the cycle's two scans), clamped to [-0.5, 0.9]. Uphill slip grows, so a
  // constant prior over-estimates the advance uphill and under-estimates it downhill.
  double prior_slip_per_slope = 0.0;
  // Learn the law (prior_slip, prior_slip_per_slope) as the rover drives, from what the terrain
  // matching measures on each cycle (solvers/slip_slope_law.h): for a user who knows neither.
  bool learn_slip = false;
  SlipSlopeLawOptions learn;
  double range_sd_m = 0.002;  // ranging noise (the paper's Sojourner figure)
  double articulation_sd_m = 0.00004;
  // The histograms' own error (ranging noise carried over, interpolation between ranged points),
  // added in quadrature to each measurement's: without it the 0.04 mm articulation term trusts
  // a histogram that is only good to about a millimetre. It is also the sd of the rear wheel's
  // ride height read from them, an error every measurement of a cycle shares (docs/wilcox.md
  // says why not less).
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
  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const;
};

struct WilcoxCycle {
  double t = 0.0;
  double rim_m = 0.0;            // odometry: wheel rim motion since the previous cycle
  double advance_m = 0.0;        // the MAP estimate of the rear wheel's advance
  double sinkage_front_m = 0.0;  // estimated sinkage under the front wheel
  double cost_curvature = 0.0;   // the parabola's curvature at the minimum (1/m^2): confidence
  double slope = 0.0;            // the slope the cycle's scans show (WilcoxCycleSlope)
  double prior_slip = 0.0;       // the prior's slip for this cycle (the law at that slope)
  // Marginal standard deviations (the factor graph, from its covariance; NaN when not computed).
  double advance_sd_m = std::numeric_limits<double>::quiet_NaN();
  double sinkage_front_sd_m = std::numeric_limits<double>::quiet_NaN();
};

struct WilcoxSide {
  std::string side;  // "left", "right"
  std::vector<WilcoxCycle> cycles;
  double total_advance_m = 0.0, total_rim_m = 0.0;
  double mean_sinkage_m = 0.0;
  // The prior's slip law at the end (the user's, or what WilcoxOptions::learn_slip learned).
  double law_slip = 0.0, law_slip_per_slope = 0.0;
  double law_slip_sd = 0.0, law_slip_per_slope_sd = 0.0;  // SlipSlopeLaw's, when learned
  int law_cycles_used = 0;
};

struct WilcoxResult {
  std::vector<WilcoxSide> sides;
  bool sides_agree = true;
  std::string agreement;  // what was compared and found
  std::vector<std::string> notes;
};

// One side's measurements of one cycle: middle and front wheel elevations relative to the rear
// (articulation) and the ranged points (d, dz) whose values are finite, sorted by d.
struct WilcoxScan {
  double t = 0.0;
  double dz_mid = 0.0, dz_front = 0.0;
  std::vector<std::pair<double, double>> range;
};
std::vector<WilcoxScan> WilcoxScans(const DriveLog& log, Side side);
// The terrain's slope under and ahead of the rover from one scan, the paper's estimate
// (sum_j z(j) / d(j)) / N over the ranged points (z relative to the rear wheel, uphill positive).
double WilcoxScanSlope(const WilcoxScan& scan);
// The slope a cycle drove: the mean of WilcoxScanSlope over its scans (before and after, of
// each side).
double WilcoxCycleSlope(const std::vector<const WilcoxScan*>& scans);
// The advance prior's mean: rim motion x (1 - slip), the slip clamped to [-0.5, 0.9].
double WilcoxPriorAdvance(double rim_m, double slip);
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
  // The largest |estimated - true| distance travelled at any cycle (sides averaged): the errors
  // that cancel in the total, e.g. a hill's uphill and downhill.
  double max_position_error_m = 0.0;
  double sinkage_rmse_m = 0.0;
  size_t sinkage_samples = 0;
};
WilcoxScore ScoreWilcox(const DriveLog& log, const WilcoxResult& result);

}  // namespace slipgraph
