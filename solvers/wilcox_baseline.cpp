#include "solvers/wilcox_baseline.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "io/measurement_stream.h"
#include "model/option_check.h"

namespace slipgraph {

bool WilcoxOptions::IsValid(std::string* error) const {
  return OptionCheck("WilcoxOptions", error)
             .Positive("bin_m", bin_m)
             .Positive("prior_fraction", prior_fraction)
             .Require("prior_slip", prior_slip < 1.0, prior_slip, "must be below 1")
             .Positive("range_sd_m", range_sd_m)
             .Positive("articulation_sd_m", articulation_sd_m)
             .Positive("histogram_sd_m", histogram_sd_m)
             .Within("contact_patch_fraction", contact_patch_fraction, 0.0, 1.0)
             .Positive("agree_sinkage_m", agree_sinkage_m)
             .Positive("agree_advance_fraction", agree_advance_fraction) &&
         learn.IsValid(error);
}
namespace {

// A histogram on [0, (n-1) b]: values at x = i b, linear in between, clamped at the ends.
struct Histogram {
  double bin = 0.01;
  std::vector<double> v;
  std::vector<char> known;  // y: the bin has been ranged (or split); s: unused

  bool KnownAt(double x) const {
    if (known.empty()) return true;
    const double u = x / bin;
    if (u < 0.0 || u > static_cast<double>(v.size() - 1)) return false;
    const size_t i = std::min(static_cast<size_t>(u), v.size() - 2);
    return known[i] && known[i + 1];
  }
  double At(double x) const {
    const double u = std::clamp(x / bin, 0.0, static_cast<double>(v.size() - 1));
    const size_t i = std::min(static_cast<size_t>(u), v.size() - 2);
    const double f = u - i;
    return (1.0 - f) * v[i] + f * v[i + 1];
  }
  double end() const { return (v.size() - 1) * bin; }
  // Mean over [x - L/2, x + L/2]: what a wheel with contact patch L rides on (Simpson, 5 points).
  double Average(double x, double length) const {
    if (length <= 0.0) return At(x);
    const double h = 0.25 * length;
    return (At(x - 2 * h) + 4 * At(x - h) + 2 * At(x) + 4 * At(x + h) + At(x + 2 * h)) / 12.0;
  }
  // Shift by dx (x -> x + dx) and subtract `down`; the last `dx` is filled by the caller.
  Histogram Translated(double dx, double down) const {
    Histogram out{bin, std::vector<double>(v.size()), {}};
    if (!known.empty()) out.known.assign(v.size(), 0);
    for (size_t i = 0; i < v.size(); ++i) {
      out.v[i] = At(i * bin + dx) - down;
      if (!known.empty()) out.known[i] = KnownAt(i * bin + dx) ? 1 : 0;
    }
    return out;
  }
  // Fill [from, to] by linear interpolation from the value at `from` to `value` at `to`.
  void ExtendLinear(double from, double to, double value) {
    const double start = At(from);
    for (size_t i = 0; i < v.size(); ++i) {
      const double x = i * bin;
      if (x <= from) continue;
      v[i] = x >= to ? value : start + (value - start) * (x - from) / (to - from);
      if (!known.empty()) known[i] = 1;
    }
  }
  // Move the bin nearest x halfway to `value`.
  void SplitTheDifference(double x, double value) {
    const size_t i = std::min(v.size() - 1, static_cast<size_t>(std::lround(x / bin)));
    v[i] = known.empty() || known[i] ? 0.5 * (v[i] + value) : value;
    if (!known.empty()) known[i] = 1;
  }
};

// Articulation and range samples of one side, grouped by cycle time.
}  // namespace

std::vector<WilcoxScan> WilcoxScans(const DriveLog& log, Side side) {
  std::map<double, WilcoxScan> by_time;
  for (const ArticulationSample& a : log.articulation) {
    if (a.side != side) continue;
    WilcoxScan& s = by_time[a.t];
    s.t = a.t;
    s.dz_mid = a.dz_mid;
    s.dz_front = a.dz_front;
  }
  for (const RangeSample& r : log.range) {
    if (r.side != side) continue;
    const auto it = by_time.find(r.t);
    if (it == by_time.end()) continue;  // ranging without articulation at that time
    // A point without a finite distance or elevation is no measurement.
    if (std::isfinite(r.d) && std::isfinite(r.dz)) it->second.range.emplace_back(r.d, r.dz);
  }
  std::vector<WilcoxScan> out;
  for (auto& [t, s] : by_time) {
    std::sort(s.range.begin(), s.range.end());
    if (s.range.size() >= 2 && std::isfinite(s.dz_mid) && std::isfinite(s.dz_front)) {
      out.push_back(std::move(s));
    }
  }
  return out;
}

double WilcoxRimMotion(const DriveLog& log, Side side, double t0, double t1) {
  const int first = side == Side::kLeft ? 0 : 3;
  const double r = log.vehicle.wheel_radius_m;
  double sum = 0.0;
  // Only the samples whose intervals overlap [t0, t1]: from the last one at or before t0.
  const size_t from = static_cast<size_t>(std::max(0L, LatestAtOrBefore(log.wheels, t0)));
  for (size_t k = from; k + 1 < log.wheels.size() && log.wheels[k].t < t1; ++k) {
    const double a = std::max(t0, log.wheels[k].t), b = std::min(t1, log.wheels[k + 1].t);
    if (b <= a) continue;
    double omega = 0.0;
    int n = 0;
    for (int w = first; w < first + 3; ++w) {
      const double value = log.wheels[k].omega_radps[w];
      if (std::isfinite(value)) omega += value, ++n;
    }
    if (n > 0) sum += r * omega / n * (b - a);
  }
  return sum;
}

double WilcoxScanSlope(const WilcoxScan& scan) {
  double sum = 0.0;
  int n = 0;
  for (const auto& [d, dz] : scan.range) {
    if (d > 0.0 && std::isfinite(dz)) sum += dz / d, ++n;
  }
  return n > 0 ? sum / n : 0.0;
}

double WilcoxCycleSlope(const std::vector<const WilcoxScan*>& scans) {
  double slope = 0.0;
  for (const WilcoxScan* scan : scans) slope += WilcoxScanSlope(*scan);
  return scans.empty() ? 0.0 : slope / scans.size();
}

double WilcoxPriorAdvance(double rim_m, double slip) {
  return rim_m * (1.0 - std::clamp(slip, -0.5, 0.9));
}

namespace {

WilcoxSide EstimateSide(const DriveLog& log, Side side, const WilcoxOptions& o) {
  WilcoxSide out;
  out.side = SideName(side);
  const std::vector<WilcoxScan> scans = WilcoxScans(log, side);
  if (scans.empty()) return out;
  const double A = log.vehicle.axle_spacing_m;
  const double far = scans.front().range.back().first;
  const double b = o.bin_m;
  Histogram y{b, std::vector<double>(static_cast<size_t>(std::ceil(far / b)) + 1, 0.0), {}};
  Histogram s{b, std::vector<double>(static_cast<size_t>(std::ceil(2.0 * A / b)) + 1, 0.0), {}};
  y.known.assign(y.v.size(), 0);
  // Start: negligible sinkage (the paper's known start), wheels and ranged points joined by lines.
  {
    const WilcoxScan& first = scans.front();
    std::vector<std::pair<double, double>> knots = {
        {0.0, 0.0}, {A, first.dz_mid}, {2.0 * A, first.dz_front}};
    knots.insert(knots.end(), first.range.begin(), first.range.end());
    for (size_t i = 0; i < y.v.size(); ++i) {
      const double x = i * b;
      size_t k = 0;
      while (k + 2 < knots.size() && knots[k + 1].first < x) ++k;
      const double f = std::clamp(
          (x - knots[k].first) / std::max(1e-9, knots[k + 1].first - knots[k].first), 0.0, 1.0);
      y.v[i] = (1.0 - f) * knots[k].second + f * knots[k + 1].second;
      y.known[i] = x >= first.range.front().first - 1e-9 ? 1 : 0;  // ranged, not guessed
    }
  }
  // Wheels ride on the terrain averaged over their contact patch (about a third of the radius);
  // the ranging sensor samples points.
  const double patch = o.contact_patch_fraction * log.vehicle.wheel_radius_m;
  const auto wheel_y = [&](const Histogram& h, double x) { return h.Average(x, patch); };
  // Each residual compares a new measurement with the histograms, which carry their own error
  // (past ranging noise, interpolation): it adds in quadrature to the measurement's.
  const double sd_h2 = o.histogram_sd_m * o.histogram_sd_m;
  const double sd_r2 = o.range_sd_m * o.range_sd_m + sd_h2;
  const double sd_a2 = o.articulation_sd_m * o.articulation_sd_m + sd_h2;
  SlipSlopeLaw law(o.prior_slip, o.prior_slip_per_slope, o.learn);
  double last_advance_var = 0.0;
  for (size_t c = 1; c < scans.size(); ++c) {
    const WilcoxScan& z = scans[c];
    WilcoxCycle cycle;
    cycle.t = z.t;
    cycle.rim_m = WilcoxRimMotion(log, side, scans[c - 1].t, z.t);
    cycle.slope = WilcoxCycleSlope({&scans[c - 1], &z});
    cycle.prior_slip = law.Slip(cycle.slope);
    const double mean = WilcoxPriorAdvance(cycle.rim_m, cycle.prior_slip);
    // The prior on this cycle's advance: the rim motion's share, and the last cycle's error,
    // which the histograms carry (they were moved by that estimate): the rover's place on its
    // own map is a random walk, not known afresh each cycle.
    const double sd_rim = std::max(1e-5, o.prior_fraction * std::abs(cycle.rim_m));
    const double sd_x = std::sqrt(sd_rim * sd_rim + last_advance_var);
    // The data's chi-square with the rear wheel at advance a: the ranged points except the
    // farthest, and the middle wheel, against the histograms. All of them are measured from the
    // rear wheel, so its ride height is an error they share: from the histograms where the
    // terrain under it has been ranged (good to histogram_sd_m), free where it has not (the
    // start, before the rear wheel reaches ground the sensor has seen); the shared part is
    // fitted and taken out, its fit returned in *ride. Deciding per candidate between the
    // histograms' ride height and a free one would favour the candidates that leave the rear
    // wheel on unranged ground, and a rover whose estimate stops there stays stopped. A
    // residual a candidate cannot form (ground beyond the map or not yet ranged) counts its
    // expected chi-square, 1, so that no candidate gains by seeing less.
    const auto fit = [&](double a, double* ride) {
      const bool ranged = y.KnownAt(a);
      const double map_ride = ranged ? wheel_y(y, a) - s.At(a) : 0.0;
      double chi2 = 0.0, sum_w = 0.0, sum_we = 0.0;
      int missing = 0;
      const auto add = [&](double e, double sd2) {
        chi2 += e * e / sd2, sum_w += 1.0 / sd2, sum_we += e / sd2;
      };
      for (size_t j = 0; j + 1 < z.range.size(); ++j) {
        const double x = a + z.range[j].first;
        if (x > y.end() || !y.KnownAt(x)) {
          ++missing;
          continue;
        }
        add(z.range[j].second - (y.At(x) - map_ride), sd_r2);
      }
      if (y.KnownAt(a + A)) {
        add(z.dz_mid - (wheel_y(y, a + A) - s.At(a + A) - map_ride), sd_a2);
      } else {
        ++missing;
      }
      const double ride_info = ranged ? 1.0 / sd_h2 : 0.0;
      const double info = sum_w + ride_info;
      const double shared = info > 0.0 ? sum_we / info : 0.0;  // the residuals' common part
      if (ride) *ride = map_ride - shared;
      return chi2 - sum_we * shared + missing;
    };
    const auto cost = [&](int i) {
      const double a = i * b;
      const double e_prior = a - mean;
      return fit(a, nullptr) + e_prior * e_prior / (sd_x * sd_x);
    };
    const int max_bins =
        std::max(3, static_cast<int>(std::ceil((std::abs(mean) + 5.0 * sd_x + 2.0 * b) / b)));
    int best = 0;
    double best_cost = cost(0);
    std::vector<double> costs(max_bins + 1);
    costs[0] = best_cost;
    for (int i = 1; i <= max_bins; ++i) {
      costs[i] = cost(i);
      if (costs[i] < best_cost) best_cost = costs[i], best = i;
    }
    double advance = best * b;
    if (best > 0 && best < max_bins) {  // parabolic interpolation
      const double cm = costs[best - 1], c0 = costs[best], cp = costs[best + 1];
      const double curvature = cm - 2.0 * c0 + cp;
      if (curvature > 0.0) {
        advance += 0.5 * (cm - cp) / curvature * b;
        cycle.cost_curvature = curvature / (b * b);
      }
    }
    cycle.advance_m = advance;
    // The MAP's variance from the cost's curvature (chi-square: 2 / curvature); none at the
    // search's edge, where the estimate is as uncertain as its prior. An error beyond the whole
    // rim motion is no estimate at all: the bound keeps a nearly flat cost from opening the next
    // search over metres.
    const double var_bound = std::max(sd_rim * sd_rim, cycle.rim_m * cycle.rim_m);
    last_advance_var =
        std::min(var_bound, cycle.cost_curvature > 0.0 ? 2.0 / cycle.cost_curvature : sd_x * sd_x);
    if (o.learn_slip) {
      law.AddCycle(cycle.slope, cycle.rim_m, mean, sd_x, advance, cycle.cost_curvature);
    }
    // Translate and re-reference to the new rear contact, at the ride height fitted there: the
    // shared offset is the rear wheel's, so the whole map moves with it.
    double ride = 0.0;
    fit(advance, &ride);
    Histogram y_new = y.Translated(advance, ride);
    Histogram s_new = s.Translated(advance, 0.0);
    const double d_far = z.range.back().first;
    y_new.ExtendLinear(y.end() - advance, d_far, z.range.back().second);
    for (size_t j = 0; j + 1 < z.range.size(); ++j) {
      y_new.SplitTheDifference(z.range[j].first, z.range[j].second);
    }
    // Sinkage: the front wheel rides on y - s = z(2); the middle wheel's residual is s's.
    s_new.ExtendLinear(s.end() - advance, 2.0 * A, wheel_y(y_new, 2.0 * A) - z.dz_front);
    s_new.SplitTheDifference(A, wheel_y(y_new, A) - z.dz_mid);
    y = std::move(y_new);
    s = std::move(s_new);
    cycle.sinkage_front_m = s.At(2.0 * A);
    out.total_advance_m += cycle.advance_m;
    out.total_rim_m += cycle.rim_m;
    out.cycles.push_back(cycle);
  }
  for (const WilcoxCycle& cycle : out.cycles) out.mean_sinkage_m += cycle.sinkage_front_m;
  if (!out.cycles.empty()) out.mean_sinkage_m /= out.cycles.size();
  out.law_slip = law.slip();
  out.law_slip_per_slope = law.slip_per_slope();
  out.law_cycles_used = law.cycles_used();
  if (o.learn_slip) {
    out.law_slip_sd = law.slip_sd();
    out.law_slip_per_slope_sd = law.slip_per_slope_sd();
  }
  return out;
}

}  // namespace

void CheckWilcoxSides(const DriveLog& log, const WilcoxOptions& options, WilcoxResult* out) {
  WilcoxResult& result = *out;
  if (result.sides.size() < 2 || result.sides[0].cycles.empty() || result.sides[1].cycles.empty()) {
    result.sides_agree = false;
    result.agreement = "one side has no usable cycles";
    return;
  }
  const WilcoxSide& l = result.sides[0];
  const WilcoxSide& r = result.sides[1];
  // Per-cycle front-sinkage difference at common cycle times, after the rover's own length.
  std::vector<double> gaps;
  std::map<double, double> right_sinkage;
  for (const WilcoxCycle& c : r.cycles) right_sinkage[c.t] = c.sinkage_front_m;
  double travelled = 0.0;
  for (const WilcoxCycle& c : l.cycles) {
    travelled += c.advance_m;
    const auto it = right_sinkage.find(c.t);
    if (it == right_sinkage.end() || travelled < 2.0 * log.vehicle.axle_spacing_m) continue;
    gaps.push_back(std::abs(c.sinkage_front_m - it->second));
  }
  double p95 = 0.0;
  if (!gaps.empty()) {
    std::sort(gaps.begin(), gaps.end());
    p95 = gaps[std::min(gaps.size() - 1, static_cast<size_t>(0.95 * gaps.size()))];
  }
  const double advance_gap = (l.total_advance_m - r.total_advance_m) /
                             std::max(1e-9, 0.5 * (l.total_advance_m + r.total_advance_m));
  result.sides_agree =
      p95 <= options.agree_sinkage_m && std::abs(advance_gap) <= options.agree_advance_fraction;
  std::ostringstream text;
  text << "front sinkage left vs right: 95th percentile of |difference| " << 1000.0 * p95
       << " mm (limit " << 1000.0 * options.agree_sinkage_m << "), mean left - right "
       << 1000.0 * (l.mean_sinkage_m - r.mean_sinkage_m) << " mm; total advance gap "
       << 100.0 * advance_gap << " % (limit " << 100.0 * options.agree_advance_fraction << " %): "
       << (result.sides_agree ? "the sides agree"
                              : "the sides disagree: the same-ruts, same-sinkage assumption "
                                "is probably violated");
  result.agreement = text.str();
}

WilcoxResult EstimateWilcoxBaseline(const DriveLog& log, const WilcoxOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  if (log.articulation.empty() || log.range.empty()) {
    throw std::invalid_argument(log.directory +
                                ": sinkage needs articulation.csv and range.csv (a rocker_bogie6 "
                                "log)");
  }
  if (!(log.vehicle.axle_spacing_m > 0.0)) {
    throw std::invalid_argument(log.directory + ": vehicle.yaml has no axle_spacing");
  }
  WilcoxResult result;
  for (Side side : {Side::kLeft, Side::kRight}) {
    result.sides.push_back(EstimateSide(log, side, options));
  }
  CheckWilcoxSides(log, options, &result);
  return result;
}

WilcoxScore ScoreWilcox(const DriveLog& log, const WilcoxResult& result) {
  WilcoxScore score;
  if (log.truth.size() < 2) return score;
  const auto truth_at = [&](double t) {
    const auto it = std::lower_bound(log.truth.begin(), log.truth.end(), t,
                                     [](const TruthSample& s, double v) { return s.t < v; });
    return it == log.truth.end() ? log.truth.back() : *it;
  };
  double error = 0.0, rim_error = 0.0, sq = 0.0, max_position_error = 0.0;
  int sides = 0;
  for (size_t k = 0; k < result.sides.size(); ++k) {
    const WilcoxSide& side = result.sides[k];
    if (side.cycles.empty()) continue;
    // The cycles' span: from the cycle before the first estimate to the last.
    const double t0 = side.cycles.front().t - 1.0, t1 = side.cycles.back().t;
    const double x0 = truth_at(std::max(log.truth.front().t, t0)).x;
    const double truth_advance = truth_at(t1).x - x0;
    if (truth_advance <= 0.0) continue;
    error += std::abs(side.total_advance_m - truth_advance) / truth_advance;
    rim_error += std::abs(side.total_rim_m - truth_advance) / truth_advance;
    ++sides;
    const int front = k == 0 ? 0 : 3;  // sinkage_fl, sinkage_fr
    const double start_x = log.truth.front().x;
    double travelled = 0.0, worst = 0.0;
    for (const WilcoxCycle& c : side.cycles) {
      const TruthSample truth = truth_at(c.t);
      // Along the way: errors that cancel in the total (uphill against downhill) show here.
      travelled += c.advance_m;
      worst = std::max(worst, std::abs(travelled - (truth.x - x0)));
      if (truth.x - start_x < 2.0 * log.vehicle.axle_spacing_m) continue;
      const double e = c.sinkage_front_m - truth.sinkage[front];
      if (!std::isfinite(e)) continue;
      sq += e * e;
      ++score.sinkage_samples;
    }
    max_position_error += worst;
  }
  if (sides > 0) {
    score.odometry_error_fraction = error / sides;
    score.rim_odometry_error_fraction = rim_error / sides;
    score.max_position_error_m = max_position_error / sides;
  }
  score.sinkage_rmse_m =
      score.sinkage_samples > 0 ? std::sqrt(sq / score.sinkage_samples) : std::nan("");
  return score;
}

}  // namespace slipgraph
