#include "solvers/wheel_clock.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "io/measurement_stream.h"
#include "model/option_check.h"

namespace slipgraph {
namespace {

// Sums for the regression of u (the sides' speed difference) on g (the gyro).
struct Sums {
  double n = 0.0, g = 0.0, u = 0.0, gg = 0.0, uu = 0.0, ug = 0.0;
  void Add(double gi, double ui) {
    n += 1.0, g += gi, u += ui, gg += gi * gi, uu += ui * ui, ug += ui * gi;
  }
  double VarG() const { return gg - g * g / n; }
  double VarU() const { return uu - u * u / n; }
  double Cov() const { return ug - u * g / n; }
  // The residual sum of squares of u on g with an intercept and a positive slope (the effective
  // track): a lag at which the two run against each other explains nothing.
  double Residual() const {
    if (n < 3.0) return 0.0;
    if (!(VarG() > 0.0) || !(Cov() > 0.0)) return VarU();
    return VarU() - Cov() * Cov() / VarG();
  }
};

// Per lag of the grid, per group (a log's part of a block): the sums, over the same samples at
// every lag.
using LagSums = std::vector<std::vector<Sums>>;

// The grid index of the least residual over the groups selected, and the lag it gives (s),
// refined by a parabola through its neighbours; *at_edge: the least is at the grid's end, a bound
// rather than a minimum.
double BestLag(const LagSums& sums, const std::vector<size_t>& groups, int half_steps,
               double step_s, bool* at_edge) {
  std::vector<double> residual(sums.size(), 0.0);
  for (size_t l = 0; l < sums.size(); ++l) {
    for (size_t k : groups) residual[l] += sums[l][k].Residual();
  }
  const size_t best =
      static_cast<size_t>(std::min_element(residual.begin(), residual.end()) - residual.begin());
  double lag_s = (static_cast<int>(best) - half_steps) * step_s;
  *at_edge = best == 0 || best + 1 == residual.size();
  if (!*at_edge) {
    const double a = residual[best - 1], b = residual[best], c = residual[best + 1];
    const double curvature = a - 2.0 * b + c;
    if (curvature > 0.0) lag_s += 0.5 * (a - c) / curvature * step_s;
  }
  return lag_s;
}

double Correlation(const LagSums& sums, size_t lag_index) {
  double cov = 0.0, var_g = 0.0, var_u = 0.0;
  for (const Sums& s : sums[lag_index]) {
    if (s.n < 3.0) continue;
    cov += s.Cov(), var_g += s.VarG(), var_u += s.VarU();
  }
  return var_g > 0.0 && var_u > 0.0 ? cov / std::sqrt(var_g * var_u) : std::nan("");
}

// The gyro's z at time t, linear between its samples at most max_gap_s apart, searching from
// index *j on (the queries come in increasing t); false where it has none.
bool GyroAt(const std::vector<ImuSample>& imu, double t, double max_gap_s, size_t* j, double* gz) {
  while (*j + 1 < imu.size() && imu[*j + 1].t <= t) ++*j;
  if (*j + 1 >= imu.size() || imu[*j].t > t) return false;
  const ImuSample& a = imu[*j];
  const ImuSample& b = imu[*j + 1];
  if (b.t - a.t > max_gap_s || !std::isfinite(a.gz) || !std::isfinite(b.gz)) return false;
  *gz = a.gz + (b.gz - a.gz) * (t - a.t) / (b.t - a.t);
  return true;
}

}  // namespace

bool WheelClockOptions::IsValid(std::string* error) const {
  return OptionCheck("WheelClockOptions", error)
      .Within("max_lag_s", max_lag_s, 0.0, 10.0)
      .Within("step_s", step_s, 1e-3 * max_lag_s, max_lag_s)
      .Positive("max_gap_s", max_gap_s)
      .AtLeast("blocks", blocks, 4)
      .NonNegative("min_turn_radps", min_turn_radps)
      .AtLeast("min_turning_samples", min_turning_samples, 1L)
      .NonNegative("min_sigmas", min_sigmas)
      .NonNegative("min_lag_s", min_lag_s);
}

WheelClockReading EstimateWheelClock(const std::vector<DriveLog>& logs,
                                     const WheelClockOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  WheelClockReading reading;
  const int half_steps = static_cast<int>(std::round(options.max_lag_s / options.step_s));
  const size_t lags = static_cast<size_t>(2 * half_steps + 1);
  const size_t blocks = static_cast<size_t>(options.blocks);

  // The samples with r (w_r - w_l) finite and the gyro at every lag (so that every lag is scored
  // on the same samples), each log's wheel stamps increasing (the rest of a log that steps back
  // is left out).
  struct Sample {
    size_t log;
    double t, u;
  };
  std::vector<Sample> candidates;
  for (size_t i = 0; i < logs.size(); ++i) {
    const DriveLog& log = logs[i];
    if (log.imu.size() < 2) continue;
    const double first = log.imu.front().t + options.max_lag_s;
    const double last = log.imu.back().t - options.max_lag_s;
    double previous_t = -std::numeric_limits<double>::infinity();
    for (const WheelSample& w : log.wheels) {
      if (!(w.t > previous_t)) break;
      previous_t = w.t;
      if (!(w.t >= first && w.t <= last)) continue;
      const SideSpeeds s = DrivenSideSpeeds(w, log.vehicle.type);
      const double u = log.vehicle.wheel_radius_m * (s.right_radps - s.left_radps);
      if (std::isfinite(u)) candidates.push_back({i, w.t, u});
    }
  }
  // g(k, l): the gyro at candidate k's stamp less lag l, through `visit(k, g)` for those it has.
  auto for_each_gyro = [&](size_t l, auto visit) {
    const double lag_s = (static_cast<int>(l) - half_steps) * options.step_s;
    size_t j = 0;
    for (size_t k = 0; k < candidates.size(); ++k) {
      if (k > 0 && candidates[k].log != candidates[k - 1].log) j = 0;
      double g;
      if (GyroAt(logs[candidates[k].log].imu, candidates[k].t - lag_s, options.max_gap_s, &j, &g)) {
        visit(k, g);
      }
    }
  };
  std::vector<int> seen(candidates.size(), 0);
  for (size_t l = 0; l < lags; ++l) for_each_gyro(l, [&](size_t k, double) { ++seen[k]; });
  std::vector<Sample> samples;
  for (size_t k = 0; k < candidates.size(); ++k) {
    if (seen[k] == static_cast<int>(lags)) samples.push_back(candidates[k]);
  }
  reading.samples = static_cast<long>(samples.size());
  if (samples.empty()) return reading;
  candidates = samples;  // for_each_gyro's from here on

  // Groups: (block, log) pairs, the blocks contiguous runs of equal sample counts, each group
  // with its own slope and intercept.
  const size_t groups = blocks * logs.size();
  auto block_of = [&](size_t k) { return k * blocks / samples.size(); };
  LagSums sums(lags, std::vector<Sums>(groups));
  std::vector<long> turning(blocks, 0);
  for (size_t l = 0; l < lags; ++l) {
    for_each_gyro(l, [&](size_t k, double g) {
      sums[l][block_of(k) * logs.size() + samples[k].log].Add(g, samples[k].u);
      if (static_cast<int>(l) == half_steps && std::abs(g) > options.min_turn_radps) {
        ++turning[block_of(k)];
      }
    });
  }

  long turning_total = 0;
  for (long n : turning) turning_total += n;
  if (turning_total < options.min_turning_samples) return reading;
  std::vector<size_t> all(groups);
  for (size_t k = 0; k < groups; ++k) all[k] = k;
  reading.lag_s = BestLag(sums, all, half_steps, options.step_s, &reading.at_grid_edge);
  const long nearest = std::clamp<long>(std::lround(reading.lag_s / options.step_s) + half_steps, 0,
                                        static_cast<long>(lags) - 1);
  reading.correlation = Correlation(sums, static_cast<size_t>(nearest));
  reading.correlation_at_zero = Correlation(sums, static_cast<size_t>(half_steps));

  // The sd: the standard error of the mean of the parts' own readings (those that turned
  // enough), the spread that correlated residuals give a lag.
  std::vector<double> block_lags;
  for (size_t b = 0; b < blocks; ++b) {
    if (turning[b] * options.blocks < options.min_turning_samples) continue;
    std::vector<size_t> mine;
    for (size_t i = 0; i < logs.size(); ++i) mine.push_back(b * logs.size() + i);
    bool edge;
    block_lags.push_back(BestLag(sums, mine, half_steps, options.step_s, &edge));
  }
  reading.blocks = static_cast<int>(block_lags.size());
  if (block_lags.size() >= 4) {
    double mean = 0.0, sq = 0.0;
    for (double x : block_lags) mean += x / block_lags.size();
    for (double x : block_lags) sq += (x - mean) * (x - mean);
    reading.sd_s = std::sqrt(sq / (block_lags.size() - 1) / block_lags.size());
    reading.taken = !reading.at_grid_edge && reading.lag_s >= options.min_sigmas * reading.sd_s &&
                    reading.lag_s >= options.min_lag_s;
  }
  return reading;
}

}  // namespace slipgraph
