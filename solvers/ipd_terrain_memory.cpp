#include "solvers/ipd_terrain_memory.h"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

namespace slipgraph {
namespace {

double ChiSquare99(double dof) {
  return boost::math::quantile(boost::math::chi_squared(dof), 0.99);
}

}  // namespace

SegmentLikelihood ScoreSegment(const IpdSegment& segment, const IpdSlipModel& model,
                               const IpdOptions& options) {
  const SegmentLinearization l = LinearizeSegment(segment, model.alpha.data(), options);
  const ipd::PredictionCovarianceTerms terms =
      ipd::PredictionCovariance(segment.steps, model.alpha.data(), options.gravity_mps2,
                                segment.sigma_start, segment.sigma_end);
  return Likelihood(l.residual, Eigen::LDLT<Eigen::Matrix3d>(l.H * model.P * l.H.transpose() +
                                                             terms.Total(model.q)));
}

SegmentLikelihood Likelihood(const Eigen::Vector3d& residual,
                             const Eigen::LDLT<Eigen::Matrix3d>& S) {
  SegmentLikelihood out;
  out.nis = residual.dot(S.solve(residual));
  out.log_likelihood = -0.5 * (out.nis + S.vectorD().array().log().sum());
  return out;
}

IpdTerrainMemory::IpdTerrainMemory(const IpdOptions& ipd)
    : ipd_(ipd), options_(ipd.terrain_memory), same_terrain_(ChiSquare99(ipd::kAlphaSize)) {
  const int window = std::max(2, options_.window);
  nis_bound_.assign(window + 1, 0.0);
  for (int n = 1; n <= window; ++n) nis_bound_[n] = ChiSquare99(3.0 * n);
}

std::string IpdTerrainMemory::Describe(long recalled) const {
  if (recalled == 0 && models_.empty()) return "";
  return "terrain memory: " + std::to_string(stored_) + " slip model(s) stored, " +
         std::to_string(merged_) + " re-stored as the same terrain, " + std::to_string(recalled) +
         " recalled";
}

void IpdTerrainMemory::RestartComparison() {
  current_recent_.clear();
  for (Stored& s : models_) s.recent.clear();
}

IpdSlipModel IpdTerrainMemory::Grown(const Stored& s, double t) const {
  IpdSlipModel m = s.model;
  const double elapsed = std::max(0.0, t - s.stored_t);
  m.P.diagonal().array() += ipd_.alpha_walk_sd * ipd_.alpha_walk_sd * elapsed;
  return m;
}

void IpdTerrainMemory::Misfit(const IpdSlipModel& current, double in_use_since, double t) {
  if (options_.capacity <= 0) return;
  search_until_ = t + options_.search_s;
  RestartComparison();
  if (t - in_use_since >= options_.settle_s) Store(current, t);
}

void IpdTerrainMemory::Store(const IpdSlipModel& current, double t) {
  // The same terrain as a stored model: replace it (the newer one has seen more of it).
  for (Stored& s : models_) {
    const Eigen::Matrix<double, ipd::kAlphaSize, 1> d = current.alpha - s.model.alpha;
    const Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize> C = current.P + Grown(s, t).P;
    if (d.dot(C.ldlt().solve(d)) < same_terrain_) {
      s.model = current;
      s.stored_t = s.used_t = t;
      ++merged_;
      return;
    }
  }
  if (static_cast<int>(models_.size()) >= options_.capacity) {
    models_.erase(
        std::min_element(models_.begin(), models_.end(),
                         [](const Stored& a, const Stored& b) { return a.used_t < b.used_t; }));
  }
  models_.push_back({current, t, t, {}});
  ++stored_;
}

bool IpdTerrainMemory::Score(const IpdSegment& segment, double current_log_likelihood,
                             IpdSlipModel* recalled) {
  if (models_.empty() || segment.t_end > search_until_) return false;
  const size_t window = static_cast<size_t>(std::max(2, options_.window));
  current_recent_.push_back(current_log_likelihood);
  if (current_recent_.size() > window) current_recent_.pop_front();
  double current_sum = 0.0;
  for (double ll : current_recent_) current_sum += ll;
  Stored* best = nullptr;
  double best_sum = -1e300;
  for (Stored& s : models_) {
    s.recent.push_back(ScoreSegment(segment, Grown(s, segment.t_end), ipd_));
    if (s.recent.size() > window) s.recent.pop_front();
    if (s.recent.size() < 2) continue;
    double ll = 0.0, nis = 0.0;
    for (const SegmentLikelihood& x : s.recent) ll += x.log_likelihood, nis += x.nis;
    if (nis > nis_bound_[s.recent.size()]) continue;
    if (ll > best_sum) best_sum = ll, best = &s;
  }
  if (best == nullptr || best_sum - current_sum < options_.log_bayes_factor) return false;
  *recalled = Grown(*best, segment.t_end);
  best->used_t = segment.t_end;
  // The recalled model is now the current one: the comparison starts afresh.
  RestartComparison();
  return true;
}

}  // namespace slipgraph
