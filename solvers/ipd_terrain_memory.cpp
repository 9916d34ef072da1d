#include "solvers/ipd_terrain_memory.h"

#include <Eigen/Cholesky>
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
  const Eigen::Matrix3d S = l.H * model.P * l.H.transpose() + terms.Total(model.q);
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(S);
  SegmentLikelihood out;
  out.nis = l.residual.dot(ldlt.solve(l.residual));
  out.log_likelihood = -0.5 * (out.nis + ldlt.vectorD().array().log().sum());
  return out;
}

IpdTerrainMemory::IpdTerrainMemory(const IpdOptions& ipd)
    : ipd_(ipd), options_(ipd.terrain_memory) {}

IpdSlipModel IpdTerrainMemory::Grown(const Stored& s, double t) const {
  IpdSlipModel m = s.model;
  const double elapsed = std::max(0.0, t - s.stored_t);
  m.P.diagonal().array() += ipd_.alpha_walk_sd * ipd_.alpha_walk_sd * elapsed;
  return m;
}

void IpdTerrainMemory::Misfit(const IpdSlipModel& current, double in_use_since, double t) {
  if (options_.capacity <= 0) return;
  search_until_ = t + options_.search_s;
  current_recent_.clear();
  for (Stored& s : models_) s.recent.clear();
  if (t - in_use_since >= options_.settle_s) Store(current, t);
}

void IpdTerrainMemory::Store(const IpdSlipModel& current, double t) {
  // The same terrain as a stored model: replace it (the newer one has seen more of it).
  const double same = ChiSquare99(ipd::kAlphaSize);
  for (Stored& s : models_) {
    const Eigen::Matrix<double, ipd::kAlphaSize, 1> d = current.alpha - s.model.alpha;
    const Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize> C = current.P + Grown(s, t).P;
    if (d.dot(C.ldlt().solve(d)) < same) {
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
    if (nis > ChiSquare99(3.0 * s.recent.size())) continue;
    if (ll > best_sum) best_sum = ll, best = &s;
  }
  if (best == nullptr || best_sum - current_sum < options_.log_bayes_factor) return false;
  *recalled = Grown(*best, segment.t_end);
  best->used_t = segment.t_end;
  // The recalled model is now the current one: the comparison starts afresh.
  current_recent_.clear();
  for (Stored& s : models_) s.recent.clear();
  return true;
}

}  // namespace slipgraph
