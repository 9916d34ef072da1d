#include "solvers/window_smoother.h"

#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "model/option_check.h"
#include "problems/owned_functions.h"
#include "solvers/chain_covariance.h"
#include "solvers/chain_solver.h"
#include "solvers/marginalization.h"
#include "solvers/smoothed_detection.h"

namespace slipgraph {

bool WindowSmootherOptions::IsValid(std::string* error) const {
  return OptionCheck("WindowSmootherOptions", error)
             .Positive("window_s", window_s)
             .AtLeast("update_every", update_every, 1)
             .AtLeast("max_iterations", max_iterations, 1)
             .AtLeast("threads", threads, 1)
             .NonNegative("step_sd_tolerance", step_sd_tolerance)
             .NonNegative("function_tolerance", function_tolerance)
             .NonNegative("stiffness_prior_sd", stiffness_prior_sd)
             .NonNegative("no_pull_back_sd_density", no_pull_back_sd_density)
             .NonNegative("reject_distance_sd", reject_distance_sd)
             .NonNegative("min_immobilized_s", min_immobilized_s) &&
         filter.IsValid(error) && problem.IsValid(error);
}
namespace {

using namespace ward;  // NOLINT: state indices
using Clock = std::chrono::steady_clock;

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

class Window {
 public:
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  ~Window() {
    OwnedFunctions functions;
    functions.TakeAll(problem_);
    functions.DeleteAll();  // the problem's blocks only point at them; it is destroyed after
  }
  Window(const WardFactorSource& source, const WindowSmootherOptions& options,
         WindowSmootherResult* result)
      : source_(source),
        options_(options),
        result_(result),
        problem_(OptionsOwningNoFunctions(true)) {
    solver_options_.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solver_options_.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
    solver_options_.max_num_iterations = options.max_iterations;
    solver_options_.num_threads = 1;
    solver_options_.logging_type = ceres::SILENT;
    solver_options_.function_tolerance = 1e-10;
    solver_options_.gradient_tolerance = 1e-10;
    solver_options_.parameter_tolerance = 1e-10;
    // Causal start: the offsets the EKF had at the first state.
    const WardEstimate& first = source.initial(0);
    offsets_ = {first.accel_offset_mps2, first.gyro_offset_radps};
    problem_.AddParameterBlock(offsets_.data(), 2);
    source_.AddOffsetPrior(offsets_, offsets_.data(), &problem_, &added_);
    if (source.options().stiffness_prior_sd > 0.0) {
      stiffness_.assign(source.stiffness_node_count(), 0.0);
      node_.assign(stiffness_.size(), Node::kAbsent);
    }
  }

  // Adds wheel sample k (the next one) as a state, initialised from the EKF, with its factors.
  void Push(size_t k) {
    const bool first = states_.empty();
    if (first) first_ = k;
    states_.emplace_back();
    std::copy(source_.initial(k).x.begin(), source_.initial(k).x.end(), states_.back().begin());
    double* x = states_.back().data();
    problem_.AddParameterBlock(x, kStateSize);
    if (first) source_.AddStatePrior(k, x, &problem_, &added_);
    double* previous = first ? nullptr : states_[states_.size() - 2].data();
    AddStiffnessNodesFor(k);
    source_.AddStep(k, previous, x,
                    {offsets_.data(), nullptr, stiffness_.empty() ? nullptr : stiffness_.data()},
                    &problem_, &added_, &counts_);
    source_.AddLateBodyVelocity(
        k, [&](size_t j) { return j >= first_ && j < k ? states_[j - first_].data() : nullptr; },
        &problem_, &added_, &counts_);
    KeepVelocityMeasurements();
    added_.clear();
  }

  // Solves and moves every state older than the window out (all of them when final).
  void Update(bool final) {
    const Clock::time_point start = Clock::now();
    const std::deque<std::array<double, kStateSize>> before = states_;
    const std::array<double, 2> offsets_before = offsets_;
    const std::vector<double> stiffness_before = stiffness_;
    // Back to the pre-solve values (same addresses: the elements are assigned in place).
    const auto restore = [&] {
      states_ = before;
      offsets_ = offsets_before;
      std::copy(stiffness_before.begin(), stiffness_before.end(), stiffness_.begin());
    };
    const double newest = NewestTime();
    size_t leaving = 0;
    while (leaving < states_.size() &&
           (final || source_.time(first_ + leaving) < newest - options_.window_s)) {
      ++leaving;
    }
    std::vector<std::array<double, kStateSize>> sd(leaving);
    bool have_sd = false, solved = false, failed = false;
    ++result_->updates;
    if (options_.solver == WindowSolver::kChainGaussNewton) {
      solved = SolveOnTheChain(leaving, &sd, &have_sd);
      if (!solved) {
        restore();
        have_sd = false;
        ++result_->chain_fallbacks;
      }
    } else if (options_.solver == WindowSolver::kChainLevenbergMarquardt) {
      std::vector<double*> states;
      for (auto& x : states_) states.push_back(x.data());
      ChainSolverOptions chain;
      chain.max_iterations = options_.max_iterations;
      chain.step_sd_tolerance = options_.step_sd_tolerance;
      chain.function_tolerance = options_.function_tolerance;
      chain.threads = options_.threads;
      ceres::Solver::Summary summary;
      solved = SolveOnChain(&problem_, states, Globals(), chain, &summary);
      if (!solved) {
        restore();
        if (result_->chain_fallbacks++ == 0) Note(summary.message + ": Ceres");
      } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
        ++result_->unconverged_updates;
      }
    }
    if (!solved) {
      ceres::Solver::Summary summary;
      ceres::Solve(solver_options_, &problem_, &summary);
      failed = !summary.IsSolutionUsable();
      if (failed) {
        restore();
        ++result_->failed_updates;
        Note("window ending at t=" + std::to_string(newest) + " s failed (" + summary.message +
             "): its leaving states are the EKF's");
      } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
        ++result_->unconverged_updates;
      }
    }
    if (!failed && options_.reject_distance_sd > 0.0 && !states_.empty()) {
      const double distance = VelocityDistanceSd();
      result_->update_distance_sd.push_back(distance);
      if (distance > options_.reject_distance_sd && !VelocityMeasurementsPreferWindow()) {
        restore();
        SetStatesToFrontEnd();
        if (result_->rejected_updates++ == 0) {
          Note("window ending at t=" + std::to_string(newest) + " s rejected (velocity " +
               std::to_string(distance) +
               " front-end sd from the front end's, no better fit to the velocity "
               "measurements): its states are the EKF's again");
        }
        failed = true;
        have_sd = false;
      }
    }
    double update_ms = MillisecondsSince(start);
    if (!have_sd) {  // the Gauss-Newton step's factorization gives them; the others do not
      have_sd = !failed && leaving > 0 && options_.covariance && Covariance(leaving, &sd);
    }

    const Clock::time_point marginalization_start = Clock::now();
    for (size_t i = 0; i < leaving; ++i) {
      const size_t k = first_;
      WardEstimate e = source_.initial(k);
      if (!failed) {
        std::copy(states_.front().begin(), states_.front().end(), e.x.begin());
        e.accel_offset_mps2 = offsets_[0];
        e.gyro_offset_radps = offsets_[1];
        if (have_sd) {
          for (int j = 0; j < kStateSize; ++j) {
            const double law = options_.law_spread_in_sd && k < result_->ekf.law_spread_sd.size()
                                   ? result_->ekf.law_spread_sd[k][j]
                                   : 0.0;
            e.sd[j] = std::sqrt(sd[i][j] * sd[i][j] + law * law);
          }
        }
      }
      result_->estimates[k] = e;
      result_->lag_s[k] = newest - source_.time(k);
      result_->from_filter[k] = failed;
      if (final) {
        states_.pop_front();
        ++first_;
        continue;
      }
      Marginalization m;
      if (!failed) {
        m = Marginalize(problem_, {states_.front().data()});
        if (!m.prior) {
          ++result_->failed_marginalizations;
          Note("marginalizing t=" + std::to_string(source_.time(k)) + " s failed (" + m.error +
               "): the window restarts from an EKF prior");
          failed = true;
        }
      }
      RemoveParameterBlock(states_.front().data());
      states_.pop_front();
      ++first_;
      if (m.prior && !m.kept.empty()) problem_.AddResidualBlock(m.prior.release(), nullptr, m.kept);
    }
    if (!final && leaving > 0) MarginalizeStiffnessNodes();
    velocity_blocks_.erase(std::remove_if(velocity_blocks_.begin(), velocity_blocks_.end(),
                                          [&](const VelocityBlock& b) { return b.k < first_; }),
                           velocity_blocks_.end());
    if (failed && !states_.empty() && leaving > 0) {
      source_.AddStatePrior(first_, states_.front().data(), &problem_, &added_);
      added_.clear();
    }
    update_ms += MillisecondsSince(marginalization_start);
    if (!final) result_->update_ms.push_back(update_ms);
  }

  const FactorCounts& counts() const { return counts_; }
  // The slip-stiffness walk's nodes (empty when the law's stiffness is taken as exact).
  const std::vector<double>& stiffness() const { return stiffness_; }

 private:
  // Removes x and the residual blocks on it, and deletes their cost and loss functions (the
  // window's, problems/owned_functions.h; the rest go at the end).
  void RemoveParameterBlock(double* x) {
    std::vector<ceres::ResidualBlockId> ids;
    problem_.GetResidualBlocksForParameterBlock(x, &ids);
    OwnedFunctions functions;
    functions.Take(problem_, ids);
    problem_.RemoveParameterBlock(x);
    functions.DeleteAll();
  }

  double NewestTime() const { return source_.time(first_ + states_.size() - 1); }

  // The blocks every state may touch: the IMU offsets, then the stiffness nodes in the problem.
  std::vector<double*> Globals() {
    std::vector<double*> globals = {offsets_.data()};
    for (size_t j = 0; j < node_.size(); ++j) {
      if (node_[j] == Node::kInProblem) globals.push_back(&stiffness_[j]);
    }
    return globals;
  }

  // The first stiffness node that state k's factors may touch: its IMU samples reach half a
  // wheel cycle either side of it (kImuReachS is generous).
  size_t FirstNodeOf(size_t k, double reach_s) const {
    size_t j = 0;
    double u = 0.0;
    source_.StiffnessNodesAt(source_.time(k) + reach_s, &j, &u);
    return j;
  }

  // Every node up to the pair state k's factors touch, each with its prior or walk step.
  void AddStiffnessNodesFor(size_t k) {
    if (stiffness_.empty()) return;
    const size_t last = std::min(stiffness_.size() - 1, FirstNodeOf(k, kImuReachS) + 1);
    for (size_t j = 0; j <= last; ++j) {
      if (node_[j] != Node::kAbsent) continue;
      source_.AddStiffnessNode(j, stiffness_.data(), &problem_, &added_);
      node_[j] = Node::kInProblem;
    }
  }

  // Nodes that no state left in the window touches go the way of the states: marginalized into
  // the prior (their information reaches the next node through the walk step).
  void MarginalizeStiffnessNodes() {
    if (stiffness_.empty() || states_.empty()) return;
    const size_t first_touched = FirstNodeOf(first_, -kImuReachS);
    for (size_t j = 0; j < first_touched; ++j) {
      if (node_[j] != Node::kInProblem) continue;
      Marginalization m = Marginalize(problem_, {&stiffness_[j]});
      if (!m.prior && !m.error.empty()) {
        ++result_->failed_marginalizations;
        Note("marginalizing the slip-stiffness node " + std::to_string(j) + " failed (" + m.error +
             "): its information is dropped");
      }
      RemoveParameterBlock(&stiffness_[j]);
      node_[j] = Node::kMarginalized;
      if (m.prior && !m.kept.empty()) problem_.AddResidualBlock(m.prior.release(), nullptr, m.kept);
    }
  }

  // Gauss-Newton on the window's chain structure (WindowSolver::kChainGaussNewton), at most
  // max_iterations steps, each from one evaluation and one block-tridiagonal factorization that
  // also gives the leaving states' sd. False (values partly moved: the caller restores them)
  // when the problem is not a chain, the information is singular or a step raises the cost.
  bool SolveOnTheChain(size_t leaving, std::vector<std::array<double, kStateSize>>* sd,
                       bool* have_sd) {
    std::vector<double*> states;
    for (auto& x : states_) states.push_back(x.data());
    const bool want_sd = options_.covariance && leaving > 0;
    const int iterations = std::max(1, options_.max_iterations);
    // This update's blocks, read from the problem once for its iterations and their costs.
    ChainLinearization linearization;
    ChainStep step;
    bool linearized = false;  // at the current values, by the previous iteration's check
    for (int iteration = 0; iteration < iterations; ++iteration) {
      std::string error;
      if ((!linearized && !linearization.Linearize(&problem_, states, Globals(), &error)) ||
          !linearization.Step(0.0, &step)) {
        if (error.empty()) error = step.error;
        if (result_->chain_fallbacks == 0) Note("chain Gauss-Newton: " + error + "; Ceres");
        return false;
      }
      if (want_sd) {  // at this step's linearization point (the last one's, after the loop)
        const ChainCovariance covariance =
            linearization.LastStepCovariance(static_cast<int>(leaving));
        for (size_t i = 0; i < leaving; ++i) {
          for (int j = 0; j < kStateSize; ++j) {
            (*sd)[i][j] = std::sqrt(std::max(0.0, covariance.states[i](j, j)));
          }
        }
        *have_sd = true;
      }
      for (size_t k = 0; k < states_.size(); ++k) {
        for (int j = 0; j < kStateSize; ++j) states_[k][j] += step.states[k][j];
      }
      offsets_[0] += step.globals[0];
      offsets_[1] += step.globals[1];
      int g = 2;
      for (size_t j = 0; j < node_.size(); ++j) {
        if (node_[j] != Node::kInProblem) continue;
        stiffness_[j] =
            std::max(source_.options().stiffness_min, stiffness_[j] + step.globals[g++]);
      }
      // The step's cost: before another step, from the linearization that step needs anyway
      // (one evaluation of the blocks instead of two); after the last, the cost alone.
      double cost = 0.0;
      if (iteration + 1 < iterations) {
        std::string ignored;
        linearized = linearization.Linearize(&problem_, states, Globals(), &ignored);
        cost = linearized ? linearization.cost() : std::nan("");
      } else if (!linearization.Cost(&cost)) {
        cost = std::nan("");
      }
      if (!std::isfinite(cost) || cost > step.cost * (1.0 + 1e-9) + 1e-12) {
        return false;  // the step made it worse: a nonlinearity Levenberg-Marquardt handles
      }
      if (step.cost - cost <= 1e-10 * step.cost) break;  // converged
    }
    return true;
  }

  // The velocity factors (GNSS, another estimator's) just added, each with its state's index.
  void KeepVelocityMeasurements() {
    std::vector<double*> blocks;
    for (const AddedFactor& f : added_) {
      if (std::strcmp(f.kind, "gnss") != 0 && std::strcmp(f.kind, "body_velocity") != 0) continue;
      problem_.GetParameterBlocksForResidualBlock(f.id, &blocks);
      for (size_t i = 0; i < states_.size(); ++i) {
        if (states_[i].data() != blocks.front()) continue;
        velocity_blocks_.push_back({f.id, first_ + i});
        break;
      }
    }
  }

  // How far the window's velocity is from the front end's: the RMS over the window's states of
  // the difference in the front end's sd.
  double VelocityDistanceSd() const {
    double sum = 0.0;
    for (size_t i = 0; i < states_.size(); ++i) {
      const WardEstimate& front = source_.initial(first_ + i);
      const double d = (states_[i][kVbx] - front.x[kVbx]) / std::max(front.sd[kVbx], 1e-9);
      sum += d * d;
    }
    return std::sqrt(sum / states_.size());
  }

  // Whether the window's velocity measurements fit its solution better than the front end's
  // estimate at the same states. False when the window holds none: nothing to say which is right.
  bool VelocityMeasurementsPreferWindow() {
    if (velocity_blocks_.empty()) return false;
    const auto cost = [&] {
      double total = 0.0;
      for (const VelocityBlock& b : velocity_blocks_) {
        double c = 0.0;
        if (!problem_.EvaluateResidualBlock(b.id, true, &c, nullptr, nullptr)) return HUGE_VAL;
        total += c;
      }
      return total;
    };
    const double window = cost();
    const std::deque<std::array<double, kStateSize>> solved = states_;
    SetStatesToFrontEnd();
    const double front_end = cost();
    states_ = solved;
    return window <= front_end;
  }

  // The window's states set to the front end's estimates (in place: same addresses).
  void SetStatesToFrontEnd() {
    for (size_t i = 0; i < states_.size(); ++i) {
      const std::array<double, kStateSize>& x = source_.initial(first_ + i).x;
      std::copy(x.begin(), x.end(), states_[i].begin());
    }
  }

  // Marginal sd of the `leaving` oldest states, from the window's information.
  bool Covariance(size_t leaving, std::vector<std::array<double, kStateSize>>* sd) {
    const Clock::time_point start = Clock::now();
    std::vector<double*> states;
    for (auto& x : states_) states.push_back(x.data());
    const ChainCovariance covariance = ComputeChainCovariance(&problem_, states, Globals());
    const bool ok = covariance.ok;
    if (ok) {
      for (size_t i = 0; i < leaving; ++i) {
        for (int j = 0; j < kStateSize; ++j) {
          (*sd)[i][j] = std::sqrt(std::max(0.0, covariance.states[i](j, j)));
        }
      }
    } else if (result_->covariance_failures++ == 0) {
      Note("covariance recovery failed in a window (" + covariance.error +
           "): the EKF's sd stands there");
    }
    result_->covariance_ms.push_back(MillisecondsSince(start));
    return ok;
  }

  void Note(const std::string& text) {
    if (result_->notes.size() < 50) result_->notes.push_back(text);
  }

  const WardFactorSource& source_;
  const WindowSmootherOptions& options_;
  WindowSmootherResult* result_;
  ceres::Problem problem_;
  ceres::Solver::Options solver_options_;
  std::deque<std::array<double, kStateSize>> states_;
  std::array<double, 2> offsets_{};
  // The slip-stiffness walk's nodes, all of them (fixed addresses), and where each one is.
  enum class Node { kAbsent, kInProblem, kMarginalized };
  static constexpr double kImuReachS = 0.5;
  std::vector<double> stiffness_;
  std::vector<Node> node_;
  size_t first_ = 0;  // log index of states_.front()
  std::vector<AddedFactor> added_;
  FactorCounts counts_;
  // The window's velocity measurements, each with the log index of its state.
  struct VelocityBlock {
    ceres::ResidualBlockId id;
    size_t k;
  };
  std::vector<VelocityBlock> velocity_blocks_;
};

}  // namespace

WindowSmootherResult SmoothWindowed(const DriveLog& log, const ModelConfig& model,
                                    const WindowSmootherOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  return SmoothWindowed(log, model, RunEkf(log, model, options.filter), options);
}

WindowSmootherResult SmoothWindowed(const DriveLog& log, const ModelConfig& model, FilterResult ekf,
                                    const WindowSmootherOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  WindowSmootherResult result;
  result.ekf = std::move(ekf);
  const size_t n = result.ekf.estimates.size();
  if (options.keep_front_end_estimates) {
    result.estimates = result.ekf.estimates;
  } else {
    result.estimates = std::move(result.ekf.estimates);
    result.ekf.estimates.clear();
  }
  result.lag_s.assign(n, 0.0);
  result.from_filter.assign(n, true);
  for (const std::string& effect : model.effects) {
    result.notes.push_back("effect '" + effect +
                           "' is named in the model but the window smoother has no effect "
                           "terms yet (the batch smoother has): ignored");
  }
  if (n < 2) {
    result.notes.push_back("fewer than two wheel samples: EKF estimates reported");
    return result;
  }
  WardProblemOptions problem_options = WithFilterSettings(options.problem, options.filter);
  if (options.law_from_front_end && result.ekf.law.size() == n) {
    problem_options.law_per_state = result.ekf.law;
    result.notes.push_back(
        "the tire law at each state is the one the front end's bank weighed there");
  }
  if (options.disturbance_from_front_end && result.ekf.disturbance_density.size() == n) {
    problem_options.disturbance_density_per_state = result.ekf.disturbance_density;
  }
  if (options.bias_from_front_end && problem_options.accel_bias.empty()) {
    problem_options.accel_bias = result.ekf.stats.wheel_bias_checks;
  }
  const bool soils = model.ListsSoils();
  problem_options.stiffness_prior_sd = soils ? options.stiffness_prior_sd : 0.0;
  problem_options.no_pull_back_sd_density = options.no_pull_back_sd_density;

  // The states' initial values. Without the front end's estimates kept, they are the result's
  // own, which the window overwrites only as a state leaves, after its last read of that state's
  // initial value.
  const WardFactorSource source(
      log, model, options.keep_front_end_estimates ? result.ekf.estimates : result.estimates,
      problem_options);
  Window window(source, options, &result);
  const size_t every = static_cast<size_t>(std::max(1, options.update_every));
  const long total = static_cast<long>((n - 1) / every + 1);
  long done = 0;
  const auto progress = [&] {
    if (options.progress) options.progress({options.progress_stage, ++done, total});
  };
  for (size_t k = 0; k < n; ++k) {
    window.Push(k);
    if ((k + 1) % every == 0 && k + 1 < n) window.Update(false), progress();
  }
  window.Update(true);
  progress();
  if (options.covariance && options.law_spread_in_sd &&
      std::any_of(result.ekf.law_spread_sd.begin(), result.ekf.law_spread_sd.end(),
                  [](const std::array<double, kStateSize>& s) { return s[kVbx] > 0.0; })) {
    result.notes.push_back(
        "the sd include the tire law's uncertainty as the front end sees it (the bank's spread "
        "of the soils' estimates, or its shift with the law's slope)");
  }
  DetectImmobilizationOnSmoothedStates(model, log.vehicle, options.min_immobilized_s,
                                       &result.estimates);
  result.counts = window.counts();
  result.stiffness = window.stiffness();
  result.notes.insert(result.notes.begin(), result.counts.Describe());
  return result;
}

WindowSmootherOptions ChunkedOptions(double chunk_min, double overlap_s, double wheel_rate_hz,
                                     const BatchSmootherOptions& batch) {
  WindowSmootherOptions options;
  options.window_s = overlap_s;
  options.update_every = std::max(1, static_cast<int>(chunk_min * 60.0 * wheel_rate_hz));
  options.max_iterations = batch.max_iterations;
  options.solver = WindowSolver::kChainLevenbergMarquardt;  // minutes from the EKF
  options.threads = batch.threads;
  options.step_sd_tolerance = batch.step_sd_tolerance;
  options.function_tolerance = batch.function_tolerance;
  options.covariance = batch.covariance;
  options.law_spread_in_sd = batch.consider_law_uncertainty;
  options.filter = batch.filter;
  options.problem = batch.problem;
  options.min_immobilized_s = batch.min_immobilized_s;
  options.progress = batch.progress;
  options.progress_stage = "chunk";
  options.keep_front_end_estimates = false;
  options.reject_distance_sd = 0.0;  // a chunk is the batch's solution, as the batch's is kept
  // The batch's own problem: its weak constraint 3 and its disturbance walk, not the window's.
  options.no_pull_back_sd_density = batch.problem.no_pull_back_sd_density;
  options.disturbance_from_front_end = false;
  options.bias_from_front_end = batch.bias_from_front_end;
  // The batch's slip stiffness, where the window estimates one (the model lists its soils).
  options.stiffness_prior_sd = batch.problem.stiffness_prior_sd;
  return options;
}

namespace {

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const size_t i = std::min(values.size() - 1, static_cast<size_t>(p * (values.size() - 1) + 0.5));
  return values[i];
}

}  // namespace

std::string DescribeWindowRun(const WindowSmootherResult& result) {
  std::ostringstream out;
  const long from_filter = std::count(result.from_filter.begin(), result.from_filter.end(), true);
  out << "window smoother: " << result.updates << " updates, " << result.failed_updates
      << " failed, " << result.rejected_updates << " rejected, " << result.unconverged_updates
      << " at the iteration bound, " << result.failed_marginalizations
      << " failed marginalizations; " << from_filter << " samples carry the EKF's estimate\n";
  if (result.chain_fallbacks > 0) {
    out << "  chain Gauss-Newton: " << result.chain_fallbacks
        << " updates solved by Ceres instead (a step raised the cost, or the window was not a "
           "chain)\n";
  }
  if (result.covariance_ms.empty()) {
    out << "  update latency (solve, covariance and marginalization): p50 "
        << Percentile(result.update_ms, 0.5) << " ms, p99 " << Percentile(result.update_ms, 0.99)
        << " ms\n";
  } else {
    out << "  update latency (solve + marginalization): p50 " << Percentile(result.update_ms, 0.5)
        << " ms, p99 " << Percentile(result.update_ms, 0.99) << " ms; covariance p50 "
        << Percentile(result.covariance_ms, 0.5) << " ms, p99 "
        << Percentile(result.covariance_ms, 0.99) << " ms\n";
  }
  if (!result.stiffness.empty()) {
    out << "  tire law's slip stiffness x (1 + theta): theta";
    for (double theta : result.stiffness) out << " " << theta;
    out << " at the walk's nodes\n";
  }
  if (!result.lag_s.empty()) {
    out << "  lag of the refined estimate: median " << Percentile(result.lag_s, 0.5) << " s\n";
  }
  for (const std::string& note : result.notes) out << "  " << note << "\n";
  for (const std::string& note : result.ekf.notes) out << "  front end: " << note << "\n";
  return out.str();
}

std::vector<ExtraColumn> OnlineColumns(const WindowSmootherResult& result) {
  std::vector<ExtraColumn> extra = {{"lag_s", result.lag_s}, {"from_filter", {}}};
  for (size_t k = 0; k < result.estimates.size(); ++k) {
    extra[1].values.push_back(result.from_filter[k] ? 1.0 : 0.0);
  }
  // A run that did not keep the front end's estimates (the chunked mode) has none to show.
  if (result.ekf.estimates.size() != result.estimates.size()) return extra;
  std::vector<ExtraColumn> ekf = {{"ekf_v_bx", {}},     {"ekf_sd_v_bx", {}},
                                  {"ekf_a_dist", {}},   {"ekf_sd_a_dist", {}},
                                  {"ekf_slip_ema", {}}, {"ekf_immobilized", {}}};
  for (const WardEstimate& e : result.ekf.estimates) {
    ekf[0].values.push_back(e.x[kVbx]);
    ekf[1].values.push_back(e.sd[kVbx]);
    ekf[2].values.push_back(e.x[kAdist]);
    ekf[3].values.push_back(e.sd[kAdist]);
    ekf[4].values.push_back(e.slip.slip_ema);
    ekf[5].values.push_back(e.slip.immobilized ? 1.0 : 0.0);
  }
  ekf.insert(ekf.end(), extra.begin(), extra.end());
  return ekf;
}

}  // namespace slipgraph
