#include "solvers/chain_solver.h"

#include <ceres/manifold.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "model/option_check.h"
#include "solvers/chain_covariance.h"

namespace slipgraph {

namespace {

using Clock = std::chrono::steady_clock;

// A damping mu = 1 / radius at most this (relative to diag(H)) leaves the step Gauss-Newton's.
constexpr double kUndampedMu = 1e-6;
// An extension shorter than this many steps is not worth a cost evaluation.
constexpr double kMinExtrapolationLength = 1.5;
// The radius's bounds: Ceres' max_trust_region_radius, and below min_trust_region_radius (1e-32)
// the solve ends.
constexpr double kMaxRadius = 1e16, kMinRadius = 1e-32;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The problem's free parameters in the chain's order (states, then globals): their values, the
// bounds on them and their manifolds, and a step's application.
class Parameters {
 public:
  Parameters(const ceres::Problem& problem, const std::vector<double*>& states,
             const std::vector<double*>& globals) {
    std::vector<double*> blocks = states;
    blocks.insert(blocks.end(), globals.begin(), globals.end());
    for (double* p : blocks) {
      Block b;
      b.values = p;
      b.size = problem.ParameterBlockSize(p);
      b.tangent = problem.ParameterBlockTangentSize(p);
      b.manifold = problem.GetManifold(p);
      for (int i = 0; i < b.size; ++i) {
        const double lower = problem.GetParameterLowerBound(p, i);
        const double upper = problem.GetParameterUpperBound(p, i);
        if (lower > -std::numeric_limits<double>::max() ||
            upper < std::numeric_limits<double>::max()) {
          b.bounds.push_back({i, lower, upper});
        }
      }
      ambient_ += b.size;
      info_.push_back(std::move(b));
    }
  }

  // Every free parameter's values, block by block.
  std::vector<double> Values() const {
    std::vector<double> values;
    values.reserve(ambient_);
    for (const Block& b : info_) values.insert(values.end(), b.values, b.values + b.size);
    return values;
  }
  void SetValues(const std::vector<double>& values) const {
    size_t at = 0;
    for (const Block& b : info_) {
      std::copy_n(values.begin() + at, b.size, b.values);
      at += b.size;
    }
  }

  // x <- Project(Plus(x, d)) block by block; d (states', then globals' tangent coordinates)
  // becomes the step taken: the projection's where a bound cut it (Euclidean blocks).
  void Apply(std::vector<Eigen::VectorXd>* states, Eigen::VectorXd* globals) {
    const size_t n_states = states->size();
    int global_at = 0;
    std::vector<double> next;
    for (size_t j = 0; j < info_.size(); ++j) {
      const Block& b = info_[j];
      double* d = j < n_states ? (*states)[j].data() : globals->data() + global_at;
      if (j >= n_states) global_at += b.tangent;
      if (b.manifold != nullptr) {
        next.resize(b.size);
        b.manifold->Plus(b.values, d, next.data());
        std::copy(next.begin(), next.end(), b.values);
      } else {
        for (int i = 0; i < b.size; ++i) b.values[i] += d[i];
      }
      for (const Bound& bound : b.bounds) {
        double& x = b.values[bound.index];
        const double before = x - (b.manifold == nullptr ? d[bound.index] : 0.0);
        x = std::clamp(x, bound.lower, bound.upper);
        if (b.manifold == nullptr) d[bound.index] = x - before;
      }
    }
  }

  // The largest component of x - Project(x - g), Ceres' gradient test with bounds (Euclidean
  // blocks; a manifold block's |g|).
  double ProjectedGradientMaxNorm(const std::vector<double>& gradient) const {
    double largest = 0.0;
    size_t at = 0;
    for (const Block& b : info_) {
      for (int i = 0; i < b.tangent; ++i) {
        double component = gradient[at + i];
        if (b.manifold == nullptr) {
          for (const Bound& bound : b.bounds) {
            if (bound.index != i) continue;
            const double x = b.values[i];
            component = x - std::clamp(x - component, bound.lower, bound.upper);
          }
        }
        largest = std::max(largest, std::abs(component));
      }
      at += b.tangent;
    }
    return largest;
  }

  // held[column] = 1 for a parameter at a bound that the gradient pushes against: Levenberg-
  // Marquardt steps on the others (an active set). False when none is.
  bool Held(const std::vector<double>& gradient, std::vector<char>* held) const {
    held->assign(gradient.size(), 0);
    bool any = false;
    size_t at = 0;
    for (const Block& b : info_) {
      if (b.manifold == nullptr) {
        for (const Bound& bound : b.bounds) {
          const double x = b.values[bound.index], g = gradient[at + bound.index];
          if ((x <= bound.lower && g > 0.0) || (x >= bound.upper && g < 0.0)) {
            (*held)[at + bound.index] = 1;
            any = true;
          }
        }
      }
      at += b.tangent;
    }
    return any;
  }

  double Norm() const {
    double sum = 0.0;
    for (const Block& b : info_) {
      for (int i = 0; i < b.size; ++i) sum += b.values[i] * b.values[i];
    }
    return std::sqrt(sum);
  }

 private:
  struct Bound {
    int index;
    double lower, upper;
  };
  struct Block {
    double* values = nullptr;
    int size = 0, tangent = 0;
    const ceres::Manifold* manifold = nullptr;
    std::vector<Bound> bounds;
  };
  std::vector<Block> info_;
  size_t ambient_ = 0;
};

double StepNorm(const std::vector<Eigen::VectorXd>& states, const Eigen::VectorXd& globals) {
  double sum = globals.squaredNorm();
  for (const Eigen::VectorXd& d : states) sum += d.squaredNorm();
  return std::sqrt(sum);
}

}  // namespace

bool ChainSolverOptions::IsValid(std::string* error) const {
  return OptionCheck("ChainSolverOptions", error)
      .AtLeast("max_iterations", max_iterations, 1)
      .NonNegative("function_tolerance", function_tolerance)
      .NonNegative("gradient_tolerance", gradient_tolerance)
      .NonNegative("parameter_tolerance", parameter_tolerance)
      .NonNegative("step_sd_tolerance", step_sd_tolerance)
      .Positive("initial_trust_region_radius", initial_trust_region_radius)
      .Within("min_relative_decrease", min_relative_decrease, 0.0, 1.0)
      .AtLeast("extrapolation_rho", extrapolation_rho, 1.0)
      .AtLeast("max_extrapolation_length", max_extrapolation_length, 1.0)
      .AtLeast("threads", threads, 1);
}

bool SolveOnChain(ceres::Problem* problem, const std::vector<double*>& states,
                  const std::vector<double*>& globals, const ChainSolverOptions& options,
                  ceres::Solver::Summary* summary) {
  const Clock::time_point start = Clock::now();
  *summary = ceres::Solver::Summary();
  std::string invalid;
  if (!options.IsValid(&invalid)) throw std::invalid_argument(invalid);
  summary->minimizer_type = ceres::TRUST_REGION;
  summary->trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  summary->num_parameter_blocks = static_cast<int>(states.size() + globals.size());
  summary->num_residual_blocks = problem->NumResidualBlocks();
  summary->num_residuals = problem->NumResiduals();
  summary->num_line_search_steps = 0;
  const auto finish = [&](ceres::TerminationType type, const std::string& message) {
    const auto& its = summary->iterations;
    summary->num_successful_steps = static_cast<int>(
        std::count_if(its.begin() + std::min<size_t>(1, its.size()), its.end(),
                      [](const ceres::IterationSummary& it) { return it.step_is_successful; }));
    summary->num_unsuccessful_steps =
        static_cast<int>(std::max<size_t>(1, its.size()) - 1) - summary->num_successful_steps;
    summary->termination_type = type;
    summary->message = message;
    summary->total_time_in_seconds = SecondsSince(start);
    return type != ceres::FAILURE;
  };

  Parameters parameters(*problem, states, globals);
  ChainLinearization linearization;
  std::string error;
  if (!linearization.Linearize(problem, states, globals, &error, options.threads)) {
    return finish(ceres::FAILURE, "chain Levenberg-Marquardt: " + error);
  }
  double cost = linearization.cost();
  if (!std::isfinite(cost)) return finish(ceres::FAILURE, "the initial cost is not finite");
  summary->initial_cost = summary->final_cost = cost;
  double radius = options.initial_trust_region_radius;
  double decrease_factor = 2.0;
  Clock::time_point iteration_start = Clock::now();
  const auto record = [&](int iteration, bool success, double cost_change, double step_norm,
                          double relative_decrease) {
    ceres::IterationSummary it;
    it.iteration = iteration;
    it.step_is_successful = success;
    it.cost = cost;
    it.cost_change = cost_change;
    it.gradient_max_norm = parameters.ProjectedGradientMaxNorm(linearization.gradient());
    it.step_norm = step_norm;
    it.relative_decrease = relative_decrease;
    it.trust_region_radius = radius;
    it.iteration_time_in_seconds = SecondsSince(iteration_start);
    it.cumulative_time_in_seconds = SecondsSince(start);
    summary->iterations.push_back(it);
    iteration_start = Clock::now();
    if (options.progress) options.progress({options.progress_stage, iteration, 0, cost});
    return it.gradient_max_norm;
  };
  if (record(0, true, 0.0, 0.0, 0.0) <= options.gradient_tolerance) {
    return finish(ceres::CONVERGENCE, "gradient tolerance reached at the start");
  }

  ChainStep step;
  std::vector<char> held;
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    const bool stepped = linearization.Step(
        1.0 / radius, &step, parameters.Held(linearization.gradient(), &held) ? &held : nullptr);
    if (!stepped) {
      // Not positive definite at this damping: more damping, as after a rejected step.
      radius /= decrease_factor;
      decrease_factor *= 2.0;
      record(iteration, false, 0.0, 0.0, 0.0);
      if (radius < kMinRadius)
        return finish(ceres::FAILURE, "chain Levenberg-Marquardt: " + step.error);
      continue;
    }
    // -J'r . d = d'(H + mu D) d, the step's squared length in the solution's own sd while the
    // damping is negligible; before a bound shortens it.
    const double decrement = -linearization.Slope(step.states, step.globals);
    const std::vector<double> before = parameters.Values();
    const double x_norm = parameters.Norm();
    parameters.Apply(&step.states, &step.globals);
    const double step_norm = StepNorm(step.states, step.globals);
    const double predicted = linearization.PredictedDecrease(step.states, step.globals);
    double new_cost = 0.0;
    const bool evaluated =
        linearization.Cost(&new_cost, options.threads) && std::isfinite(new_cost);
    const double rho = evaluated && predicted > 0.0 ? (cost - new_cost) / predicted : -1.0;
    if (step_norm <= options.parameter_tolerance * (x_norm + options.parameter_tolerance)) {
      parameters.SetValues(before);
      record(iteration, false, 0.0, step_norm, rho);
      return finish(ceres::CONVERGENCE, "parameter tolerance reached");
    }
    if (rho < options.min_relative_decrease) {
      parameters.SetValues(before);
      radius /= decrease_factor;
      decrease_factor *= 2.0;
      record(iteration, false, 0.0, step_norm, rho);
      if (radius < kMinRadius) return finish(ceres::CONVERGENCE, "the trust region vanished");
      continue;
    }
    // The step kept more than the decrease the model predicted: the cost's true curvature
    // along it is smaller than J'J says (a robust loss in its linear part is one cause), and a
    // longer step along the same direction does better. The parabola through the cost at 0 and 1
    // with the slope at 0 gives its length; it is taken when it lowers the cost further.
    const double slope = linearization.Slope(step.states, step.globals);  // as taken
    double taken_length = 1.0;  // the step taken, in steps d
    if (rho > options.extrapolation_rho) {
      const double curvature = 2.0 * (new_cost - cost - slope);
      const double length =
          curvature > 0.0 ? std::min(options.max_extrapolation_length, -slope / curvature) : 0.0;
      if (length > kMinExtrapolationLength) {
        std::vector<Eigen::VectorXd> longer = step.states;
        Eigen::VectorXd longer_globals = step.globals * length;
        for (Eigen::VectorXd& d : longer) d *= length;
        const std::vector<double> unit = parameters.Values();
        parameters.SetValues(before);
        parameters.Apply(&longer, &longer_globals);
        double longer_cost = 0.0;
        if (linearization.Cost(&longer_cost, options.threads) && longer_cost < new_cost) {
          new_cost = longer_cost;
          taken_length = length;
          ++summary->num_line_search_steps;
        } else {
          parameters.SetValues(unit);
        }
      }
    }
    const double cost_change = cost - new_cost;
    // The rule needs a Gauss-Newton step (not one the damping shortened); an extended one moved
    // the solution taken_length times as far.
    const bool within_sd = options.step_sd_tolerance > 0.0 && 1.0 / radius <= kUndampedMu &&
                           taken_length * taken_length * decrement <=
                               options.step_sd_tolerance * options.step_sd_tolerance;
    radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3)));
    decrease_factor = 2.0;
    if (within_sd) {
      // Not linearized again: the next linearization is the caller's (its covariance). The
      // iteration's gradient is the one before the step.
      cost = summary->final_cost = new_cost;
      record(iteration, true, cost_change, step_norm, rho);
      std::ostringstream message;
      message << "the step is within " << options.step_sd_tolerance << " sd of the solution";
      return finish(ceres::CONVERGENCE, message.str());
    }
    const bool linearized =
        linearization.Linearize(problem, states, globals, &error, options.threads);
    if (!linearized) {
      parameters.SetValues(before);
      return finish(ceres::FAILURE, "chain Levenberg-Marquardt: " + error);
    }
    cost = linearization.cost();
    summary->final_cost = cost;
    const double gradient = record(iteration, true, cost_change, step_norm, rho);
    if (cost_change <= options.function_tolerance * (cost + cost_change)) {
      return finish(ceres::CONVERGENCE, "function tolerance reached");
    }
    if (gradient <= options.gradient_tolerance) {
      return finish(ceres::CONVERGENCE, "gradient tolerance reached");
    }
  }
  return finish(ceres::NO_CONVERGENCE, "maximum number of iterations reached");
}

}  // namespace slipgraph
