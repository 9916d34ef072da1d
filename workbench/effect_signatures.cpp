#include "workbench/effect_signatures.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "factors/catalogue_terms.h"
#include "factors/ward_dynamics.h"
#include "factors/ward_state.h"
#include "io/measurement_stream.h"
#include "problems/ward_factor_source.h"
#include "sim/random.h"

namespace slipgraph {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The unexplained force balance against a shape h(state index) in m/s^2 per unit magnitude, over
// the states where the model says a_dist ~ 0.
SignatureSeries ForceSeriesWith(const ModelResiduals& m, const std::function<double(size_t)>& h) {
  SignatureSeries s;
  s.stream = "accelerometer";
  for (size_t k = 0; k < m.states.size(); ++k) {
    const StateContext& c = m.states[k];
    if (!std::isfinite(c.unexplained_force) || !(c.force_sd > 0.0)) {
      // A skipped state still carries the chain's correlation to the next kept one.
      if (!s.y_common_next_corr.empty()) {
        s.y_common_next_corr.back() *= c.force_state_next_correlation;
      }
      continue;
    }
    s.t.push_back(c.t);
    s.y.push_back(c.unexplained_force / c.force_sd);
    s.g.push_back(h(k) / c.force_sd);
    s.y_common_sd.push_back(c.force_state_sd / c.force_sd);
    s.y_common_next_corr.push_back(c.force_state_next_correlation);
  }
  return s;
}

// The effect's score test on the whole graph (workbench/graph_score_test.h) as a series.
std::optional<SlopeFit> FitOf(const GraphScore& g) {
  if (!g.tested) return std::nullopt;
  SlopeFit fit;
  fit.slope = g.magnitude;
  fit.sd = g.sd();
  fit.naive_sd = g.model_sd;
  fit.lag = g.lag;
  fit.n = g.states;
  return fit;
}

// The score test of the term named `effect` on the whole graph (its column in the effect block).
SignatureSeries GraphSeries(const ModelResiduals& m, const std::string& effect) {
  SignatureSeries s;
  s.stream = "graph";
  const int index = m.EffectIndex(effect);
  if (index < 0 || static_cast<size_t>(index) >= m.graph_scores.size()) return s;
  s.fit = FitOf(m.graph_scores[index]);
  s.graph_column = [index](const GraphProjector& g) { return g.EffectColumn(index); };
  return s;
}

// The GNSS velocity residuals against a shape h(state index) in m/s per unit magnitude.
SignatureSeries GnssSeries(const ModelResiduals& m, const std::function<double(size_t)>& h) {
  SignatureSeries s;
  s.stream = "gnss";
  const StreamResiduals* gnss = m.Find("gnss");
  if (gnss == nullptr) return s;
  for (size_t i = 0; i < gnss->t.size(); ++i) {
    s.t.push_back(gnss->t[i]);
    s.y.push_back(gnss->normalized[i]);
    s.g.push_back(h(gnss->state[i]) / gnss->sd[i]);
  }
  return s;
}

// Index of the state at or before t (states are in time order).
size_t StateAt(const ModelResiduals& m, double t) {
  const auto it = std::upper_bound(m.states.begin(), m.states.end(), t,
                                   [](double v, const StateContext& c) { return v < c.t; });
  return it == m.states.begin() ? 0 : static_cast<size_t>(it - m.states.begin()) - 1;
}

// Mean of f over states [begin, end), skipping non-finite values.
double MeanOver(const ModelResiduals& m, long begin, long end,
                const std::function<double(const StateContext&)>& f) {
  double sum = 0.0;
  int count = 0;
  for (long k = std::max(0L, begin); k < std::min<long>(end, m.states.size()); ++k) {
    const double v = f(m.states[k]);
    if (std::isfinite(v)) sum += v, ++count;
  }
  return count > 0 ? sum / count : kNaN;
}

// Derivative of f at state k from the means over two windows that leave out k itself (so the
// noise of sample k does not enter its own regressor): (mean[k+3, k+8] - mean[k-8, k-3]) / dt.
double DerivativeAround(const ModelResiduals& m, size_t k,
                        const std::function<double(const StateContext&)>& f) {
  const long i = static_cast<long>(k);
  if (i < 8 || i + 9 > static_cast<long>(m.states.size())) return kNaN;
  const double dt =
      0.5 * (m.states[i + 8].t + m.states[i + 3].t) - 0.5 * (m.states[i - 3].t + m.states[i - 8].t);
  return (MeanOver(m, i + 3, i + 9, f) - MeanOver(m, i - 8, i - 2, f)) / dt;
}

// The best interval [a, b) of basis cells (metres of path, seconds of log) for a force on it,
// against the same force on all cells (projected out: the interval must stand out from the
// whole), with min_cells and, for a change point, b fixed at the end. statistic: S^2 / I of the
// contrast with the factors' sd; p: the scan's own p-value from 4000 draws of the cell scores
// under the null, N(0, Gram) (a fixed seed: the same log gives the same answer; Bonferroni over
// thousands of overlapping intervals would be far too strict). share: the interval's Gram with
// the whole over the whole's, the weight of the whole in the contrast shape.
struct IntervalScan {
  double statistic = -1.0, p = 1.0, share = 0.0;
  size_t a = 0, b = 0;
};

IntervalScan ScanIntervals(const ProjectedBasis& projected, size_t min_cells, bool tails_only) {
  IntervalScan out;
  const size_t cells = static_cast<size_t>(projected.score.size());
  if (cells < min_cells + 1) return out;
  // Prefix sums of the Gram matrix: any interval's Gram with any other in O(1).
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(cells + 1, cells + 1);
  for (size_t i = 0; i < cells; ++i) {
    for (size_t j = 0; j < cells; ++j) {
      gram(i + 1, j + 1) = projected.gram(i, j) + gram(i, j + 1) + gram(i + 1, j) - gram(i, j);
    }
  }
  const double g_all = gram(cells, cells);
  if (!(g_all > 0.0)) return out;
  const auto WithAll = [&](size_t a, size_t b) { return gram(b, cells) - gram(a, cells); };
  const auto Scan = [&](const Eigen::VectorXd& prefix) {
    IntervalScan best;
    const double total = prefix[cells];
    for (size_t a = 0; a + min_cells <= cells; ++a) {
      for (size_t b = tails_only ? cells : a + min_cells; b <= cells; ++b) {
        const double g_pa = WithAll(a, b);
        const double information =
            gram(b, b) - gram(a, b) - gram(b, a) + gram(a, a) - g_pa * g_pa / g_all;
        if (!(information > 1e-12 * g_all)) continue;
        const double sab = prefix[b] - prefix[a] - g_pa / g_all * total;
        if (sab * sab / information > best.statistic) {
          best.statistic = sab * sab / information, best.a = a, best.b = b;
        }
      }
    }
    return best;
  };
  Eigen::VectorXd prefix(cells + 1);
  prefix[0] = 0.0;
  for (size_t j = 0; j < cells; ++j) prefix[j + 1] = prefix[j] + projected.score[j];
  out = Scan(prefix);
  if (out.statistic <= 0.0) return out;
  out.share = WithAll(out.a, out.b) / g_all;
  const Eigen::LLT<Eigen::MatrixXd> root(projected.gram +
                                         1e-12 * projected.gram.diagonal().maxCoeff() *
                                             Eigen::MatrixXd::Identity(cells, cells));
  std::mt19937_64 rng(20261123);
  sim::UnitNormal normal;
  const int draws = 4000;
  int exceed = 0;
  Eigen::VectorXd z(cells);
  for (int d = 0; d < draws; ++d) {
    for (size_t j = 0; j < cells; ++j) z[j] = normal(rng);
    const Eigen::VectorXd sample = root.matrixL() * z;
    for (size_t j = 0; j < cells; ++j) prefix[j + 1] = prefix[j] + sample[j];
    exceed += Scan(prefix).statistic >= out.statistic;
  }
  out.p = (exceed + 1.0) / (draws + 1.0);
  return out;
}

// An external force shape h (m/s^2 per unit magnitude, per state) as a signature series: its
// score test on the graph, and its column for the omnibus test's "after the best candidate".
void SetForceFit(const ModelResiduals& m, const std::vector<double>& h, SignatureSeries* s) {
  s->fit = FitOf(m.graph->TestForce(h));
  s->graph_column = [h](const GraphProjector& g) { return g.ForceColumn(h); };
}

// A scanned force shape h: as SetForceFit, and the scan's p-value as the effective number of
// intervals searched (a multiplier on the chosen one's own p-value).
void SetScanFit(const ModelResiduals& m, const std::vector<double>& h, const IntervalScan& scan,
                SignatureSeries* s) {
  SetForceFit(m, h, s);
  s->searched = std::max(1.0, scan.p / std::max(1e-300, NormalTwoSided(std::sqrt(scan.statistic))));
}

// "x.xx" with `digits` significant digits.
std::string Figure(double value, int digits = 2) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*g", digits, value);
  return text;
}

// Each catalogue effect's physical limits (EffectSignature::plausible), generous enough that
// every magnitude the simulator's catalogue uses passes on its drives. An external force opposing
// motion cannot push, and beyond half the robot's weight it would stop it.
void AttachPlausibleRanges(std::vector<EffectSignature>* list) {
  using Range = std::function<PlausibleRange(const DriveLog&)>;
  const auto fixed = [](double low, double high, const char* basis) -> Range {
    return [=](const DriveLog&) { return PlausibleRange{low, high, basis}; };
  };
  const double inf = std::numeric_limits<double>::infinity();
  const auto over = [inf](double limit, double extent) {
    return extent > 0.0 ? limit / extent : inf;
  };
  const std::map<std::string, Range> ranges = {
      {"quadratic_drag",
       [over](const DriveLog& log) {
         const DriveExtent e = ExtentOf(log);
         return PlausibleRange{
             0.0, over(0.5 * e.weight_n, e.speed_mps * e.speed_mps),
             "up to half the robot's weight at its top speed, " + Figure(e.speed_mps) + " m/s"};
       }},
      {"turn_slip",
       [over](const DriveLog& log) {
         const DriveExtent e = ExtentOf(log);
         return PlausibleRange{0.0, over(0.5, e.yaw_rate_radps),
                               "up to half the robot's weight at its top yaw rate, " +
                                   Figure(e.yaw_rate_radps) + " rad/s"};
       }},
      {"sinkage_resistance", fixed(0.0, 0.5, "up to half the robot's weight")},
      {"slope_slip",
       [over](const DriveLog& log) {
         const DriveExtent e = ExtentOf(log);
         const double limit = over(0.9, e.grade_rad);
         return PlausibleRange{-limit, limit,
                               "traction changed by at most 90 % on its steepest grade, " +
                                   Figure(e.grade_rad) + " rad"};
       }},
      {"wheel_radius_error", fixed(-0.15, 0.15, "a rolling radius within 15 % of the nominal")},
      {"terrain_change", fixed(-0.9, 4.0, "traction between a tenth and five times the model's")},
      {"load_transfer", fixed(0.0, 4.0, "the vehicle's geometry gives 1")},
      {"gps_velocity_averaging", fixed(0.0, 3.0, "a mean over up to three fix intervals")},
      {"imu_mounting_pitch", fixed(-kMaxImuMountingPitchRad, kMaxImuMountingPitchRad,
                                   "a mounting pitch within 0.2 rad (11 deg)")},
      {"clock_offset", fixed(-1.0, 1.0, "the streams of one robot within 1 s")},
      {"tire_traction_level",
       fixed(-0.9, 4.0, "traction between a tenth and five times the law's")},
      {"tire_slip_stiffness", fixed(-0.9, 9.0, "a slope between a tenth and ten times the law's")},
      {"rolling_resistance_level",
       fixed(-1.0, 9.0, "a rolling resistance between none and ten times the law's")},
  };
  for (EffectSignature& s : *list) {
    const auto it = ranges.find(s.effect);
    if (it != ranges.end()) s.plausible = it->second;
  }
}

std::vector<EffectSignature> MakeSignatures() {
  std::vector<EffectSignature> list;
  list.push_back(
      {"gps_velocity_averaging",
       "GNSS velocity residual against -(v(t) - v(t - T)) / 2, T the fix interval", nullptr,
       [](const ModelResiduals& m, const DriveLog&, const ModelConfig&) {
         std::vector<double> previous(m.states.size(), kNaN);
         std::vector<SignatureSeries> out;
         SignatureSeries s = GnssSeries(m, [&](size_t k) {
           const double t = m.states[k].t;
           const auto it = std::lower_bound(m.gnss_times.begin(), m.gnss_times.end(), t - 1e-6);
           if (it == m.gnss_times.begin()) return kNaN;
           const size_t j = StateAt(m, *(it - 1));
           return -0.5 * (m.states[k].x[ward::kVbx] - m.states[j].x[ward::kVbx]);
         });
         out.push_back(s);
         return out;
       },
       [](double magnitude, DriveLog* log) {
         // A mean over [t - theta T, t] is the velocity at t - theta T / 2: move the stamps.
         for (size_t i = log->gps.size(); i-- > 1;) {
           log->gps[i].t -= 0.5 * magnitude * (log->gps[i].t - log->gps[i - 1].t);
         }
       }});
  list.push_back({"wheel_radius_error",
                  "score test on the graph of its term's column (factors/catalogue_terms.h)",
                  nullptr,
                  [](const ModelResiduals& m, const DriveLog&, const ModelConfig&) {
                    return std::vector<SignatureSeries>{GraphSeries(m, "wheel_radius_error")};
                  },
                  nullptr});
  list.push_back(
      {"imu_mounting_pitch",
       "accelerometer z residual (a_z - g cos pitch cos roll) against a_x, both band-passed "
       "(0.5 s moving average less the 5 s one)",
       nullptr,
       [](const ModelResiduals& m, const DriveLog&, const ModelConfig& model) {
         SignatureSeries s;
         s.stream = "accelerometer_z";
         const double sd = model.measurement.imu_sd_accel_mps2;
         const double g0 = 9.80665;
         for (const StateContext& c : m.states) {
           if (!std::isfinite(c.accel_z) || !std::isfinite(c.accel_x)) continue;
           s.t.push_back(c.t);
           s.y.push_back((c.accel_z - g0 * std::cos(c.pitch_rad) * std::cos(c.roll_rad)) / sd);
           s.g.push_back(c.accel_x / sd);
         }
         // The z accelerometer's bias drifts (Gauss-Markov) and would correlate by chance with
         // slow patterns of a_x (hills), and a chassis's vibration (10-15 Hz on hiddenm, drawn
         // for each axis) is noise in both y and g, which biases the slope toward zero and widens
         // its sd: the test keeps what varies over seconds, where a pitched mounting still shows
         // every speed change.
         constexpr double kShortS = 0.5, kLongS = 5.0;
         s.y = BandPass(s.t, s.y, kShortS, kLongS);
         s.g = BandPass(s.t, s.g, kShortS, kLongS);
         return std::vector<SignatureSeries>{s};
       },
       [](double delta, DriveLog* log) { RotateImuAxesBack(delta, log); }});
  list.push_back({"slope_slip", "score test on the graph of its term's column (traction x |grade|)",
                  nullptr,
                  [](const ModelResiduals& m, const DriveLog&, const ModelConfig&) {
                    return std::vector<SignatureSeries>{GraphSeries(m, "slope_slip")};
                  },
                  nullptr});
  list.push_back({"turn_slip",
                  "score test on the graph of its term's column (-g |yaw rate| sgn(v))", nullptr,
                  [](const ModelResiduals& m, const DriveLog&, const ModelConfig&) {
                    return std::vector<SignatureSeries>{GraphSeries(m, "turn_slip")};
                  },
                  nullptr});
  list.push_back(
      {"sinkage_resistance",
       "score test on the graph of an external force -g sgn(v) over the best patch of path, "
       "against the same force over the whole path (scanned on a 1 m grid, patches of 3 m and "
       "more; the scan's p-value from 4000 draws of the metre scores under the null)",
       nullptr,
       [](const ModelResiduals& m, const DriveLog&, const ModelConfig&) {
         SignatureSeries s;
         s.stream = "graph";
         if (m.graph == nullptr || !m.graph->ok() || m.states.empty()) return std::vector{s};
         // Distance along the path at each state, and one basis shape per metre of it.
         const size_t n = m.states.size();
         const std::vector<double> s_path = PathDistances(m);
         const auto Resistance = [&](size_t k) {
           return -9.80665 * std::tanh(20.0 * m.states[k].x[ward::kVbx]);
         };
         const size_t metres = static_cast<size_t>(std::floor(s_path.back())) + 1;
         std::vector<std::vector<double>> basis(metres, std::vector<double>(n, 0.0));
         for (size_t k = 0; k < n; ++k) basis[static_cast<size_t>(s_path[k])][k] = Resistance(k);
         const IntervalScan found = ScanIntervals(m.graph->ProjectForces(basis), 3, false);
         if (found.statistic < 0.0) return std::vector{s};
         const size_t best_a = found.a, best_b = found.b;
         std::vector<double> h(n, 0.0);
         for (size_t k = 0; k < n; ++k) {
           const bool in = s_path[k] >= best_a && s_path[k] < best_b;
           h[k] = ((in ? 1.0 : 0.0) - found.share) * Resistance(k);
         }
         SetScanFit(m, h, found, &s);
         char where[64];
         std::snprintf(where, sizeof(where), "patch %zu-%zu m", best_a, best_b);
         s.where = where;
         // The patch's time spans (it may be driven more than once).
         for (size_t k = 0; k < n; ++k) {
           if (!(s_path[k] >= best_a && s_path[k] < best_b)) continue;
           const double t = m.states[k].t;
           const double step = k + 1 < n ? m.states[k + 1].t - t : 0.01;
           if (!s.windows.empty() && t - s.windows.back().second <= 2.0 * step) {
             s.windows.back().second = t + step;
           } else {
             s.windows.push_back({t, t + step});
           }
         }
         return std::vector{s};
       },
       nullptr});
  list.push_back({"load_transfer",
                  "graph score of its term: the driven front wheels' traction change when the "
                  "body's acceleration unloads them (m a h_cg / (2 L) per wheel, per unit scale; "
                  "castor vehicles)",
                  nullptr,
                  [](const ModelResiduals& m, const DriveLog& log, const ModelConfig&) {
                    if (log.vehicle.type != VehicleType::kDiffDriveCastor) {
                      return std::vector<SignatureSeries>{};
                    }
                    return std::vector{GraphSeries(m, "load_transfer")};
                  },
                  nullptr});
  list.push_back(
      {"terrain_change",
       "score test on the graph of a traction scale that changes at one moment (scanned on a 1 s "
       "grid, at least 5 s before the end), against the same scale over the whole log; magnitude: "
       "the relative change (a scale of 0.6 is -0.4); added as its term from the change on",
       nullptr,
       [](const ModelResiduals& m, const DriveLog& log, const ModelConfig& model) {
         SignatureSeries s;
         s.stream = "graph";
         const size_t n = m.states.size();
         if (m.graph == nullptr || !m.graph->ok() || n < 2) return std::vector{s};
         const ward::Params p = ward::MakeParams(log.vehicle, model);
         const double t0 = m.states.front().t;
         const size_t seconds = static_cast<size_t>(std::floor(m.states.back().t - t0)) + 1;
         std::vector<double> traction(n, 0.0);
         std::vector<std::vector<double>> basis(seconds, std::vector<double>(n, 0.0));
         for (size_t k = 0; k < n; ++k) {
           const StateContext& c = m.states[k];
           const ward::TireForces<double> f = ward::ComputeTireForces(
               c.x.data(), ward::Attitude<double>{c.roll_rad, c.pitch_rad}, p);
           traction[k] = (f.traction_left_n + f.traction_right_n) / p.mass_kg;
           basis[static_cast<size_t>(c.t - t0)][k] = traction[k];
         }
         const IntervalScan found = ScanIntervals(m.graph->ProjectForces(basis), 5, true);
         if (found.statistic < 0.0) return std::vector{s};
         std::vector<double> h(n, 0.0);
         for (size_t k = 0; k < n; ++k) {
           const bool after = static_cast<size_t>(m.states[k].t - t0) >= found.a;
           h[k] = ((after ? 1.0 : 0.0) - found.share) * traction[k];
         }
         SetScanFit(m, h, found, &s);
         char where[64];
         std::snprintf(where, sizeof(where), "from t = %.0f s", t0 + found.a);
         s.where = where;
         // The changed terrain: from the change to the end of the log (a model term there).
         s.windows.push_back({t0 + found.a, m.states.back().t + 1.0});
         return std::vector{s};
       },
       nullptr});
  list.push_back({"quadratic_drag", "score test on the graph of its term's column (-v |v| / m)",
                  nullptr,
                  [](const ModelResiduals& m, const DriveLog&, const ModelConfig&) {
                    return std::vector<SignatureSeries>{GraphSeries(m, "quadratic_drag")};
                  },
                  nullptr});
  list.push_back(
      {"clock_offset",
       "force balance against -d a_x / dt; attitude heading minus integrated gyro against the yaw "
       "rate, both high-passed at 5 s",
       [](const DriveLog& log) {
         // One IMU sample period: the resolution of the stamps themselves.
         return log.imu.size() > 1 ? (log.imu.back().t - log.imu.front().t) / (log.imu.size() - 1)
                                   : 0.01;
       },
       [](const ModelResiduals& m, const DriveLog& log, const ModelConfig&) {
         const auto accel = [](const StateContext& c) { return c.accel_x; };
         const SignatureSeries force =
             ForceSeriesWith(m, [&](size_t k) { return -DerivativeAround(m, k, accel); });
         // The gyro's integrated heading against the attitude stream's heading, which is
         // stamped on the log's clock: IMU stamps late by delta make the integral lag by delta,
         // psi_att - psi_gyro = const + delta yaw_rate. (The wheels are no reference here: the
         // body's yaw rate lags theirs by the tire dynamics, tens of ms.) Without an attitude
         // yaw, only the force-balance series remains.
         SignatureSeries yaw;
         yaw.stream = "attitude_yaw";
         if (log.attitude.size() > 10) {
           const HeadingSeries h = AttitudeAndGyroHeadings(m, log);
           yaw.t = h.t;
           for (size_t i = 0; i < h.t.size(); ++i) {
             yaw.y.push_back((h.attitude[i] - h.gyro[i]) / h.sd[i]);
             yaw.g.push_back(h.rate[i] / h.sd[i]);
           }
           // The difference walks (gyro noise and bias error integrate): test what varies faster
           // than 5 s, as for the z accelerometer.
           yaw.y = HighPass(yaw.t, yaw.y, 5.0);
           yaw.g = HighPass(yaw.t, yaw.g, 5.0);
         }
         return std::vector<SignatureSeries>{force, yaw};
       },
       [](double offset, DriveLog* log) { MoveImuStampsBack(offset, log); }});
  return list;
}

}  // namespace

namespace {

// A model term's test without a signature of its own: its column on the graph.
EffectSignature TermSignature(const EffectTerm& term) {
  EffectSignature s;
  s.effect = term.name;
  s.test = "graph score of its model term (" + term.unit + ")";
  const std::string name = term.name;
  s.series = [name](const ModelResiduals& m, const DriveLog&, const ModelConfig&) {
    return std::vector<SignatureSeries>{GraphSeries(m, name)};
  };
  return s;
}

}  // namespace

const EffectRegistry& EffectRegistry::Catalogue() {
  static const EffectRegistry kCatalogue = [] {
    EffectRegistry r;
    r.signatures_ = MakeSignatures();
    for (const EffectTerm& term : CatalogueTerms().all()) r.Add(term);
    AttachPlausibleRanges(&r.signatures_);
    return r;
  }();
  return kCatalogue;
}

const EffectRegistry& EffectRegistry::CatalogueWithParameters() {
  static const EffectRegistry kWithParameters = [] {
    EffectRegistry r = Catalogue();
    r.AddParameterCandidates();
    AttachPlausibleRanges(&r.signatures_);
    return r;
  }();
  return kWithParameters;
}

void EffectRegistry::Add(EffectTerm term) {
  if (!term.model_parameter && FindSignature(term.name) == nullptr) {
    signatures_.push_back(TermSignature(term));
  }
  terms_.Add(std::move(term));
}

void EffectRegistry::AddParameterCandidates() {
  for (const EffectTerm& term : terms_.all()) {
    if (term.model_parameter && FindSignature(term.name) == nullptr) {
      signatures_.push_back(TermSignature(term));
    }
  }
}

void EffectRegistry::Add(EffectSignature signature) {
  for (EffectSignature& s : signatures_) {
    if (s.effect == signature.effect) {
      s = std::move(signature);
      return;
    }
  }
  signatures_.push_back(std::move(signature));
}

const EffectSignature* EffectRegistry::FindSignature(const std::string& effect) const {
  for (const EffectSignature& s : signatures_) {
    if (s.effect == effect) return &s;
  }
  return nullptr;
}

bool EffectRegistry::CanAdd(const std::string& effect) const {
  const EffectSignature* signature = FindSignature(effect);
  return FindTerm(effect) != nullptr || (signature != nullptr && signature->correct);
}

std::string EffectRegistry::Names() const {
  std::string names;
  for (const EffectSignature& s : signatures_) names += (names.empty() ? "" : ", ") + s.effect;
  return names;
}

namespace {

double Percentile99(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const size_t i = static_cast<size_t>(0.99 * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(i), values.end());
  return values[i];
}

}  // namespace

DriveExtent ExtentOf(const DriveLog& log) {
  DriveExtent e;
  e.weight_n = log.vehicle.mass_kg * 9.80665;
  std::vector<double> speed, yaw_rate, grade;
  for (const WheelSample& w : log.wheels) {
    const SideSpeeds s = DrivenSideSpeeds(w, log.vehicle.type);
    const double v = 0.5 * log.vehicle.wheel_radius_m * (s.left_radps + s.right_radps);
    if (std::isfinite(v)) speed.push_back(std::abs(v));
  }
  for (const ImuSample& imu : log.imu) {
    if (std::isfinite(imu.gz)) yaw_rate.push_back(std::abs(imu.gz));
  }
  for (const AttitudeSample& a : log.attitude) {
    if (std::isfinite(a.pitch)) grade.push_back(std::abs(a.pitch));
  }
  e.speed_mps = Percentile99(std::move(speed));
  e.yaw_rate_radps = Percentile99(std::move(yaw_rate));
  e.grade_rad = Percentile99(std::move(grade));
  return e;
}

namespace {

// x's mean over [t_i - window_s / 2, t_i + window_s / 2] at each i (t ascending).
std::vector<double> CentredMovingAverage(const std::vector<double>& t, const std::vector<double>& x,
                                         double window_s) {
  std::vector<double> out(x.size());
  size_t begin = 0, end = 0;
  double sum = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    while (end < x.size() && t[end] <= t[i] + 0.5 * window_s) sum += x[end++];
    while (t[begin] < t[i] - 0.5 * window_s) sum -= x[begin++];
    out[i] = sum / static_cast<double>(end - begin);
  }
  return out;
}

}  // namespace

std::vector<double> HighPass(const std::vector<double>& t, const std::vector<double>& x,
                             double window_s) {
  std::vector<double> out = CentredMovingAverage(t, x, window_s);
  for (size_t i = 0; i < out.size(); ++i) out[i] = x[i] - out[i];
  return out;
}

std::vector<double> BandPass(const std::vector<double>& t, const std::vector<double>& x,
                             double short_s, double long_s) {
  std::vector<double> out = CentredMovingAverage(t, x, short_s);
  const std::vector<double> slow = CentredMovingAverage(t, x, long_s);
  for (size_t i = 0; i < out.size(); ++i) out[i] -= slow[i];
  return out;
}

HeadingSeries AttitudeAndGyroHeadings(const ModelResiduals& m, const DriveLog& log) {
  HeadingSeries h;
  double psi_gyro = 0.0, psi_att = 0.0, previous_att = kNaN;
  double previous_t = m.states.empty() ? 0.0 : m.states.front().t, previous_rate = 0.0;
  bool started = false;
  for (const StateContext& c : m.states) {
    const double rate = c.gyro_z - m.gyro_offset - c.x[ward::kGyroBias];
    if (!std::isfinite(rate)) continue;
    if (started) psi_gyro += 0.5 * (rate + previous_rate) * (c.t - previous_t);
    started = true;
    previous_t = c.t, previous_rate = rate;
    const long a = LatestAtOrBefore(log.attitude, c.t, 1e-6);
    if (a < 0 || std::abs(log.attitude[a].t - c.t) > 1e-3) continue;
    const double measured = log.attitude[a].yaw;
    if (!std::isfinite(measured)) continue;
    psi_att = std::isfinite(previous_att)
                  ? psi_att + std::remainder(measured - previous_att, 2.0 * M_PI)
                  : measured;
    previous_att = measured;
    const double sd = log.attitude[a].sd_yaw > 0.0 ? log.attitude[a].sd_yaw : 0.01;
    h.t.push_back(c.t);
    h.attitude.push_back(psi_att);
    h.gyro.push_back(psi_gyro);
    h.rate.push_back(rate);
    h.sd.push_back(sd);
  }
  return h;
}

}  // namespace slipgraph
