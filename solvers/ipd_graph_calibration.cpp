#include "solvers/ipd_graph_calibration.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <set>
#include <stdexcept>

#include "factors/diagonal_prior.h"
#include "factors/difference_prior.h"
#include "factors/ipd_segment_factor.h"
#include "factors/marginal_prior.h"
#include "model/option_check.h"
#include "solvers/chain_covariance.h"
#include "solvers/ipd_covariance_matching.h"
#include "solvers/ipd_noise_likelihood.h"
#include "solvers/ipd_terrain_memory.h"
#include "solvers/marginalization.h"

namespace slipgraph {

bool IpdGraphOptions::IsValid(std::string* error) const {
  return OptionCheck("IpdGraphOptions", error)
             .Positive("block_s", block_s)
             .Positive("window_block_s", window_block_s)
             .Positive("window_s", window_s)
             .AtLeast("max_iterations", max_iterations, 1)
             .Positive("walk_huber_sd", walk_huber_sd)
             .NonNegative("jump_sd", jump_sd)
             .NonNegative("q_likelihood_rounds", q_likelihood_rounds) &&
         q_likelihood.IsValid(error);
}
namespace {

using Alpha = std::array<double, ipd::kAlphaSize>;

// The walk from alpha block a to b; huber_sd > 0: Huber beyond that norm (IpdGraphOptions).
ceres::ResidualBlockId AddWalk(ceres::Problem* problem, double sd, double huber_sd, double* a,
                               double* b) {
  ceres::LossFunction* loss = huber_sd > 0.0 ? new ceres::HuberLoss(huber_sd) : nullptr;
  return problem->AddResidualBlock(DifferencePrior<ipd::kAlphaSize>::Create(Alpha{}, sd), loss, a,
                                   b);
}

ceres::Solver::Options SolverOptions(int max_iterations) {
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  o.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  o.max_num_iterations = max_iterations;
  o.logging_type = ceres::SILENT;
  return o;
}

// The block index of time t (blocks of block_s from the log's first segment).
int BlockOf(double t, double t0, double block_s) {
  return std::max(0, static_cast<int>(std::floor((t - t0) / block_s)));
}

ceres::CostFunction* SegmentFactor(const IpdSegment& seg, const Alpha& alpha,
                                   const IpdOptions& options, const Eigen::Vector3d& q) {
  const ipd::PredictionCovarianceTerms terms = ipd::PredictionCovariance(
      seg.steps, alpha.data(), options.gravity_mps2, seg.sigma_start, seg.sigma_end);
  return IpdSegmentFactor::Create(seg.steps, seg.measured, terms.Total(q), options.gravity_mps2);
}

std::array<double, ipd::kAlphaSize> PriorSd(const IpdOptions& options) {
  std::array<double, ipd::kAlphaSize> sd;
  sd.fill(options.alpha_prior_sd);
  return sd;
}

}  // namespace

IpdCalibrationResult CalibrateIpdWindow(const DriveLog& log, const IpdOptions& options,
                                        const IpdGraphOptions& graph) {
  std::string error;
  if (!options.IsValid(&error) || !graph.IsValid(&error)) throw std::invalid_argument(error);
  IpdCalibrationResult result;
  result.segments = BuildIpdSegments(log, options);
  const std::vector<IpdSegment>& segments = result.segments;
  if (segments.empty()) return result;
  const double t0 = segments.front().t_start;
  const double block_s = graph.window_block_s;
  StochasticCalibrator stochastic(options);
  ceres::Problem::Options problem_options;
  problem_options.enable_fast_removal = true;
  ceres::Problem problem(problem_options);
  std::deque<Alpha> blocks;  // alpha blocks in the window, oldest first
  int first_block = 0;       // block index of blocks.front()
  Alpha latest{};            // the newest solved alpha (predictions use it)
  Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize> latest_covariance =
      Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize>::Identity() * options.alpha_prior_sd *
      options.alpha_prior_sd;
  const Alpha zero{};
  const double walk_sd = options.alpha_walk_sd * std::sqrt(block_s);

  size_t next_segment_to_add = 0;
  size_t next_prediction = 0;
  IpdCovarianceMatching matching(options.match_covariance_segments);
  const int last_block = BlockOf(segments.back().t_end, t0, block_s);
  std::map<int, ceres::ResidualBlockId> walk_into;  // block index -> the walk from the previous
  std::set<int> jumped, recalled_into;
  int gated_in_a_row = 0, jumps = 0, recalls = 0;
  IpdTerrainMemory memory(options);
  double model_since_t = t0;  // the current model's start: the last jump or recall
  // Jumps found from the innovations (solvers/jump_detector.h, as the EKF): hypotheses only as
  // far back as the window still holds the block to free.
  JumpDetectorOptions jump_options = IpdJumpDetectorOptions(options);
  jump_options.window =
      std::max(1, std::min(jump_options.window,
                           static_cast<int>((graph.window_s - 2.0 * block_s) / options.spacing_s)));
  JumpDetector<ipd::kAlphaSize, 3> detector(jump_options);
  // Frees the walk into `block` (a jump: the terrain changed), once per block; nothing when the
  // block has no walk in the window or has jumped already.
  const auto free_walk = [&](int block, double t) {
    const int index = block - first_block;
    if (index <= 0 || index >= static_cast<int>(blocks.size()) || !walk_into.count(block) ||
        jumped.count(block)) {
      return;
    }
    memory.Misfit({Eigen::Map<const Eigen::Matrix<double, ipd::kAlphaSize, 1>>(latest.data()),
                   latest_covariance, stochastic.q()},
                  model_since_t, t);
    model_since_t = t;
    problem.RemoveResidualBlock(walk_into[block]);
    walk_into[block] =
        AddWalk(&problem, graph.jump_sd, 0.0, blocks[index - 1].data(), blocks[index].data());
    jumped.insert(block);
    ++jumps;
  };
  for (int j = 0; j <= last_block + 1; ++j) {
    const double block_end = t0 + (j + 1) * block_s;
    // Predictions of segments starting before this block's solve use the newest solved alpha.
    while (next_prediction < segments.size() && segments[next_prediction].t_start < block_end) {
      const IpdSegment& seg = segments[next_prediction++];
      result.no_slip.push_back(EvaluatePrediction(seg, zero.data(), options, stochastic.q()));
      PredictionError e = EvaluatePrediction(seg, latest.data(), options, stochastic.q());
      e.parameter_covariance = ParameterCovariance(seg, latest.data(), latest_covariance, options);
      e.predicted_covariance += e.parameter_covariance;
      matching.Apply(seg.t_end, &e);
      result.calibrated.push_back(e);
    }
    // Add alpha blocks up to j, each tied to the previous by the walk.
    while (first_block + static_cast<int>(blocks.size()) <= j) {
      blocks.push_back(blocks.empty() ? Alpha{} : blocks.back());
      double* alpha = blocks.back().data();
      problem.AddParameterBlock(alpha, ipd::kAlphaSize);
      if (blocks.size() == 1 && first_block == 0) {
        problem.AddResidualBlock(DiagonalPrior<ipd::kAlphaSize>::Create(Alpha{}, PriorSd(options)),
                                 nullptr, alpha);
      } else if (blocks.size() > 1) {
        walk_into[first_block + static_cast<int>(blocks.size()) - 1] = AddWalk(
            &problem, walk_sd, graph.walk_huber_sd, blocks[blocks.size() - 2].data(), alpha);
      }
    }
    // Segments that have ended by the block's end, on the block of their midpoint.
    bool added = false;
    while (next_segment_to_add < segments.size() &&
           segments[next_segment_to_add].t_end <= block_end) {
      const IpdSegment& seg = segments[next_segment_to_add++];
      const int b = BlockOf(0.5 * (seg.t_start + seg.t_end), t0, block_s);
      const int index = std::clamp(b - first_block, 0, static_cast<int>(blocks.size()) - 1);
      const SegmentLinearization l = LinearizeSegment(seg, latest.data(), options);
      const ipd::PredictionCovarianceTerms terms = ipd::PredictionCovariance(
          seg.steps, latest.data(), options.gravity_mps2, seg.sigma_start, seg.sigma_end);
      const Eigen::Matrix3d HPH = l.H * latest_covariance * l.H.transpose();
      // A jump frees the walk into a block (once per block): the detector's jump (into the
      // block of the first segment after it), or segments failing the gate in a row at the
      // newest alpha (into theirs).
      const Eigen::Matrix3d S = HPH + terms.Total(stochastic.q());
      const SegmentLikelihood score = Likelihood(l.residual, Eigen::LDLT<Eigen::Matrix3d>(S));
      const bool gated = score.nis > kSegmentGateChi2;
      gated_in_a_row = gated ? gated_in_a_row + 1 : 0;
      const int block = first_block + index;
      JumpDetector<ipd::kAlphaSize, 3>::Jump jump;
      if (graph.jump_sd > 0.0 && options.jump.enabled &&
          detector.Measure(0.5 * (seg.t_start + seg.t_end), l.residual, l.H, S, &jump)) {
        free_walk(BlockOf(jump.t, t0, block_s), seg.t_end);
        detector.Restart();
      } else {
        // The window's update on this segment, as the detector's filter sees it.
        detector.Updated(latest_covariance * l.H.transpose() * S.inverse(), l.H);
      }
      if (graph.jump_sd > 0.0 && options.readmit_after > 0 &&
          gated_in_a_row > options.readmit_after) {
        free_walk(block, seg.t_end);
      }
      // Back on a terrain driven before (solvers/ipd_terrain_memory.h): the newest block takes
      // the stored model as its prior instead of the walk from the block before it.
      IpdSlipModel stored;
      const int newest = first_block + static_cast<int>(blocks.size()) - 1;
      if (memory.Score(seg, score.log_likelihood, &stored) && blocks.size() > 1 &&
          walk_into.count(newest) && !recalled_into.count(newest)) {
        problem.RemoveResidualBlock(walk_into[newest]);
        walk_into.erase(newest);
        problem.AddResidualBlock(
            new MarginalPrior({ipd::kAlphaSize}, stored.alpha, stored.P.inverse(),
                              Eigen::VectorXd::Zero(ipd::kAlphaSize)),
            nullptr, blocks.back().data());
        for (int i = 0; i < ipd::kAlphaSize; ++i) latest[i] = blocks.back()[i] = stored.alpha[i];
        latest_covariance = stored.P;
        detector.Restart();
        stochastic.Recall(stored.q);
        model_since_t = seg.t_end;
        recalled_into.insert(newest);
        ++recalls;
      }
      // Q from the residual the segment leaves with the alpha known before it (as the EKF does).
      if (options.calibrate_q) stochastic.Update(l.residual, terms, HPH, options.spacing_s);
      problem.AddResidualBlock(SegmentFactor(seg, blocks[index], options, stochastic.q()), nullptr,
                               blocks[index].data());
      added = true;
    }
    if (!added) continue;
    ceres::Solver::Summary summary;
    ceres::Solve(SolverOptions(graph.max_iterations), &problem, &summary);
    if (!summary.IsSolutionUsable()) {
      result.notes.push_back("block " + std::to_string(j) + ": solve failed (" + summary.message +
                             "); alpha kept");
      continue;
    }
    latest = blocks.back();
    {
      std::vector<double*> chain;
      for (Alpha& a : blocks) chain.push_back(a.data());
      const ChainCovariance covariance = ComputeChainCovariance(&problem, chain, {});
      if (covariance.ok) latest_covariance = covariance.states.back();
    }
    result.update_t.push_back(block_end);
    result.alpha.push_back(latest);
    result.q.push_back(stochastic.q());
    // Marginalize blocks older than the window.
    while (static_cast<double>(blocks.size()) * block_s > graph.window_s && blocks.size() > 1) {
      Marginalization m = Marginalize(problem, {blocks.front().data()});
      problem.RemoveParameterBlock(blocks.front().data());
      blocks.pop_front();
      ++first_block;
      walk_into.erase(first_block);  // its walk went with the block before it
      if (m.prior && !m.kept.empty()) {
        problem.AddResidualBlock(m.prior.release(), nullptr, m.kept);
      } else if (!m.error.empty()) {
        result.notes.push_back("marginalization failed (" + m.error +
                               "): the window restarts from its prior");
        problem.AddResidualBlock(
            DiagonalPrior<ipd::kAlphaSize>::Create(blocks.front(), PriorSd(options)), nullptr,
            blocks.front().data());
      }
    }
  }
  if (jumps > 0) {
    result.notes.push_back(std::to_string(jumps) +
                           " block(s) where the slip model jumped (segments failed the gate in "
                           "a row, or the jump detector found one): the walk into them freed");
  }
  const std::string memory_note = memory.Describe(recalls);
  if (!memory_note.empty()) result.notes.push_back(memory_note);
  result.final_alpha = latest;
  std::vector<double*> chain;
  for (Alpha& a : blocks) chain.push_back(a.data());
  const ChainCovariance covariance = ComputeChainCovariance(&problem, chain, {});
  if (covariance.ok) {
    for (int i = 0; i < ipd::kAlphaSize; ++i) {
      result.final_alpha_sd[i] = std::sqrt(covariance.states.back()(i, i));
    }
  }
  result.final_q = stochastic.q();
  return result;
}

IpdCalibrationResult CalibrateIpdBatch(const DriveLog& log, const IpdOptions& options,
                                       const IpdGraphOptions& graph) {
  std::string error;
  if (!options.IsValid(&error) || !graph.IsValid(&error)) throw std::invalid_argument(error);
  // Q first, from the online EKF's stochastic calibration; then every block at once.
  const IpdCalibrationResult ekf = CalibrateIpdEkf(log, options);
  IpdCalibrationResult result;
  result.segments = ekf.segments;
  const std::vector<IpdSegment>& segments = result.segments;
  if (segments.empty()) return result;
  const double t0 = segments.front().t_start;
  const int n_blocks = BlockOf(segments.back().t_end, t0, graph.block_s) + 1;
  const auto block_of = [&](const IpdSegment& seg) {
    return std::min(n_blocks - 1, BlockOf(0.5 * (seg.t_start + seg.t_end), t0, graph.block_s));
  };
  std::vector<Alpha> blocks(n_blocks, Alpha{});
  // Q per block: the EKF's final Q everywhere to start; then, by maximum likelihood from the
  // residuals the solved alpha leaves (solvers/ipd_noise_likelihood.h), and alpha solved again
  // with the segments weighed by it.
  std::vector<Eigen::Vector3d> q(n_blocks, ekf.final_q);
  const double walk_sd = options.alpha_walk_sd * std::sqrt(graph.block_s);
  const int rounds = 1 + (graph.q_by_likelihood ? graph.q_likelihood_rounds : 0);
  for (int round = 0; round < rounds; ++round) {
    if (round > 0) {
      std::vector<NoiseLikelihoodSegment> fit_segments;
      fit_segments.reserve(segments.size());
      for (const IpdSegment& seg : segments) {
        const int b = block_of(seg);
        NoiseLikelihoodSegment f;
        f.residual = LinearizeSegment(seg, blocks[b].data(), options).residual;
        f.terms = ipd::PredictionCovariance(seg.steps, blocks[b].data(), options.gravity_mps2,
                                            seg.sigma_start, seg.sigma_end);
        f.block = b;
        fit_segments.push_back(f);
      }
      NoiseLikelihoodOptions noise = graph.q_likelihood;
      noise.block_s = graph.block_s;
      noise.segment_weight = options.spacing_s / options.segment_s;
      noise.q_prior = ekf.final_q;
      const NoiseLikelihoodResult fit = FitNoiseByLikelihood(fit_segments, n_blocks, noise, q);
      if (!fit.ok) {
        result.notes.push_back("Q by maximum likelihood failed (" + fit.message +
                               "): the EKF's final Q kept");
        break;
      }
      q = fit.q;
    }
    ceres::Problem problem;
    problem.AddResidualBlock(DiagonalPrior<ipd::kAlphaSize>::Create(Alpha{}, PriorSd(options)),
                             nullptr, blocks[0].data());
    for (int j = 1; j < n_blocks; ++j) {
      AddWalk(&problem, walk_sd, graph.walk_huber_sd, blocks[j - 1].data(), blocks[j].data());
    }
    for (const IpdSegment& seg : segments) {
      const int b = block_of(seg);
      problem.AddResidualBlock(SegmentFactor(seg, blocks[b], options, q[b]), nullptr,
                               blocks[b].data());
    }
    ceres::Solver::Summary summary;
    ceres::Solve(SolverOptions(50), &problem, &summary);
    if (!summary.IsSolutionUsable()) {
      if (round == 0) {
        result = ekf;
        result.notes.push_back("batch solve failed (" + summary.message + "): the EKF's result");
        return result;
      }
      result.notes.push_back("batch re-solve with Q by maximum likelihood failed (" +
                             summary.message + ")");
      break;
    }
  }
  // The reported covariance matched to the errors as the online forms do: where the model is
  // biased (tight turns at low speed on ipd35m) the errors outgrow eq. (15)'s variance, which
  // Q by likelihood, weighing each segment by its own variance, does not take back.
  const Alpha zero{};
  IpdCovarianceMatching matching(options.match_covariance_segments);
  for (const IpdSegment& seg : segments) {
    const int b = block_of(seg);
    result.no_slip.push_back(EvaluatePrediction(seg, zero.data(), options, q[b]));
    PredictionError e = EvaluatePrediction(seg, blocks[b].data(), options, q[b]);
    matching.Apply(seg.t_end, &e);
    result.calibrated.push_back(e);
  }
  for (int j = 0; j < n_blocks; ++j) {
    result.update_t.push_back(t0 + (j + 1) * graph.block_s);
    result.alpha.push_back(blocks[j]);
    result.q.push_back(q[j]);
  }
  result.final_alpha = blocks.back();
  result.final_q = q.back();
  result.notes.push_back(
      "batch: each segment predicted with the alpha of its own block "
      "(post-processing, not causal)");
  return result;
}

}  // namespace slipgraph
