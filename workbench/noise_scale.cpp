#include "workbench/noise_scale.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "workbench/robust_statistics.h"

namespace slipgraph {
namespace {

// l(lambda) - l(1) of the header, over the pooled rows.
double LogLikelihoodGain(const std::vector<double>& z, const std::vector<double>& q,
                         double lambda) {
  double gain = 0.0;
  for (size_t i = 0; i < z.size(); ++i) {
    const double ratio = 1.0 + (lambda - 1.0) * q[i];
    gain -= 0.5 * (std::log(ratio) + z[i] * z[i] / ratio - z[i] * z[i]);
  }
  return gain;
}

// The maximum-likelihood lambda over [1e-3, 1e6]: a grid in log lambda, then a golden-section
// search between the best point's neighbours.
double MaximumLikelihoodScale(const std::vector<double>& z, const std::vector<double>& q) {
  const double lo = std::log(1e-3), hi = std::log(1e6);
  const int grid = 90;
  int best = 0;
  double best_gain = -1e300;
  for (int k = 0; k <= grid; ++k) {
    const double gain = LogLikelihoodGain(z, q, std::exp(lo + (hi - lo) * k / grid));
    if (gain > best_gain) best_gain = gain, best = k;
  }
  double a = lo + (hi - lo) * std::max(0, best - 1) / grid;
  double b = lo + (hi - lo) * std::min(grid, best + 1) / grid;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 60; ++it) {
    const double c = b - golden * (b - a), d = a + golden * (b - a);
    if (LogLikelihoodGain(z, q, std::exp(c)) > LogLikelihoodGain(z, q, std::exp(d))) {
      b = d;
    } else {
      a = c;
    }
  }
  return std::exp(0.5 * (a + b));
}

}  // namespace

double NoiseScaleFinding::sd_scale() const { return std::sqrt(variance_scale); }

std::string NoiseKeyOf(const std::string& measurement) {
  static const std::map<std::string, std::string> keys = {
      {"gnss", "measurement_noise.gps_sd_v"},
      {"encoder_left", "measurement_noise.wheels_sd_omega"},
      {"encoder_right", "measurement_noise.wheels_sd_omega"},
      {"gyro", "measurement_noise.imu_sd_gyro"},
      {"accelerometer", "measurement_noise.imu_sd_accel"}};
  const auto it = keys.find(measurement);
  return it == keys.end() ? std::string() : it->second;
}

std::vector<NoiseScaleFinding> TestNoiseScales(const EkfStats& stats, double alpha,
                                               double sd_tolerance, size_t min_updates) {
  struct Pool {
    NoiseScaleFinding finding;
    std::vector<std::array<double, 3>> rows;  // t, z, q
    std::vector<double> z, q;                 // in time order
  };
  std::vector<Pool> pools;
  for (const auto& [name, series] : stats.innovations) {
    const std::string key = NoiseKeyOf(name);
    if (key.empty() || series.measurement_share.size() != series.normalized.size()) continue;
    auto it = std::find_if(pools.begin(), pools.end(),
                           [&](const Pool& p) { return p.finding.key == key; });
    if (it == pools.end()) {
      pools.push_back({});
      it = pools.end() - 1;
      it->finding.key = key;
    }
    it->finding.measurements.push_back(name);
    const auto take = [&](const std::vector<double>& t, const std::vector<double>& z,
                          const std::vector<double>& q) {
      for (size_t i = 0; i < z.size() && i < q.size() && i < t.size(); ++i) {
        if (!std::isfinite(z[i]) || !(q[i] > 0.0 && q[i] <= 1.0)) continue;
        it->rows.push_back({t[i], z[i], q[i]});
      }
    };
    take(series.t, series.normalized, series.measurement_share);
    // A noise stated too small sends the innovations past the gate: left out, the test would
    // see the ones that happened to be small.
    take(series.gated_t, series.gated_normalized, series.gated_measurement_share);
  }
  // In time order, for the long-run variance (the two encoders and the gated fixes interleave).
  for (Pool& pool : pools) {
    std::stable_sort(pool.rows.begin(), pool.rows.end(),
                     [](const auto& a, const auto& b) { return a[0] < b[0]; });
    for (const auto& row : pool.rows) pool.z.push_back(row[1]), pool.q.push_back(row[2]);
  }
  std::vector<NoiseScaleFinding> out;
  for (Pool& pool : pools) {
    if (pool.z.size() < min_updates) continue;
    NoiseScaleFinding& f = pool.finding;
    const size_t n = pool.z.size();
    f.updates = n;
    // The score at the null's edge lambda_0 = tolerance^2.
    const double lambda0 = sd_tolerance * sd_tolerance;
    std::vector<double> c(n);
    double score = 0.0;
    for (size_t i = 0; i < n; ++i) {
      f.nis_mean += pool.z[i] * pool.z[i] / n;
      const double d = 1.0 + (lambda0 - 1.0) * pool.q[i];
      c[i] = 0.5 * pool.q[i] / d * (pool.z[i] * pool.z[i] / d - 1.0);
      score += c[i];
    }
    const double mean = score / n;
    for (double& ci : c) ci -= mean;
    const double variance = BartlettLongRunVariance(c);
    f.statistic = variance > 0.0 ? score * score / variance : 0.0;
    f.variance_scale = MaximumLikelihoodScale(pool.z, pool.q);
    f.p_value = score > 0.0 ? 0.5 * ChiSquareUpperTail(f.statistic, 1.0) : 1.0;
    out.push_back(f);
  }
  for (NoiseScaleFinding& f : out) {
    f.p_value = std::min(1.0, f.p_value * out.size());
    f.significant = f.p_value < alpha;
  }
  return out;
}

}  // namespace slipgraph
