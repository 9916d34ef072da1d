#include "solvers/wilcox_graph.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/covariance.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>

#include "factors/difference_prior.h"
#include "factors/linear_factor.h"
#include "factors/wilcox_factors.h"
#include "model/option_check.h"

namespace slipgraph {

bool WilcoxGraphOptions::IsValid(std::string* error) const {
  return OptionCheck("WilcoxGraphOptions", error)
      .Positive("node_spacing_m", node_spacing_m)
      .AtLeast("nodes_per_block", nodes_per_block, 1)
      .Positive("margin_m", margin_m)
      .Positive("y_curvature_sd_m", y_curvature_sd_m)
      .Positive("s_slope_sd_m", s_slope_sd_m)
      .Positive("s_prior_sd_m", s_prior_sd_m)
      .AtLeast("max_iterations", max_iterations, 1)
      .AtLeast("refine_every", refine_every, 1)
      .AtLeast("window_cycles", window_cycles, 1);
}
namespace {

// One side's profiles on the grid: terrain y and sinkage s as blocks of B nodes, the side's scans
// and what of its terrain is mapped so far.
struct SideProfiles {
  std::vector<WilcoxScan> scans;
  std::vector<double> y, s;
  double mapped_to = 0.0;
  double ranged_from = 0.0;  // the first ground the sensor ranged: behind it the terrain is guessed
};

// Solves the sides in `sides` (one, or both sharing the rear wheels' positions: a rigid rover
// driving straight) and returns their estimates, or the baselines with a note when the solve
// fails.
std::vector<WilcoxSide> SolveSides(const DriveLog& log, const std::vector<Side>& sides,
                                   const std::vector<WilcoxSide>& baselines, const WilcoxOptions& o,
                                   const WilcoxGraphOptions& g, std::vector<std::string>* notes) {
  const size_t n_sides = sides.size();
  std::vector<SideProfiles> side(n_sides);
  for (size_t j = 0; j < n_sides; ++j) {
    side[j].scans = WilcoxScans(log, sides[j]);
    if (side[j].scans.size() < 2 || baselines[j].cycles.size() + 1 != side[j].scans.size() ||
        side[j].scans.size() != side[0].scans.size()) {
      return baselines;
    }
  }
  const size_t cycles = side[0].scans.size();
  const double A = log.vehicle.axle_spacing_m;
  const double patch = o.contact_patch_fraction * log.vehicle.wheel_radius_m;
  const double h = g.node_spacing_m;
  // The odometry per cycle: the sides' mean rim motion when they share the positions.
  std::vector<double> rim(cycles, 0.0);
  double span = 0.0;
  for (size_t k = 1; k < cycles; ++k) {
    double longest = 0.0;
    for (size_t j = 0; j < n_sides; ++j) {
      const WilcoxCycle& c = baselines[j].cycles[k - 1];
      rim[k] += c.rim_m / n_sides;
      longest = std::max({longest, c.advance_m, c.rim_m});
    }
    span += longest;
  }
  // The grid covers the traverse plus the farthest ranged point and a margin, in parameter blocks
  // of B nodes (factors/wilcox_factors.h says why), padded to whole blocks.
  double far = 0.0;
  for (const SideProfiles& p : side) {
    for (const WilcoxScan& z : p.scans) far = std::max(far, z.range.back().first);
  }
  const int B = std::max(1, g.nodes_per_block);
  const int needed = static_cast<int>(std::ceil((span + far + g.margin_m + patch) / h)) + 2;
  const int block_count = (needed + B - 1) / B;
  const int nodes = block_count * B;
  std::vector<double> x(cycles, 0.0);
  // The advance prior's slip law (the user's; WilcoxOptions::learn_slip is the baseline's) and
  // what it gave each cycle.
  const SlipSlopeLaw law(o.prior_slip, o.prior_slip_per_slope, o.learn);
  std::vector<double> slope(cycles, 0.0), prior_slip(cycles, 0.0);

  ceres::Problem problem;
  for (double& v : x) problem.AddParameterBlock(&v, 1);
  for (SideProfiles& p : side) {
    p.y.assign(nodes, 0.0);
    p.s.assign(nodes, 0.0);
    for (int c = 0; c < block_count; ++c) {
      problem.AddParameterBlock(&p.y[c * B], B);
      problem.AddParameterBlock(&p.s[c * B], B);
    }
  }
  const auto run = [&](double lo, double hi) {
    return wilcox::RunCovering(lo, hi, g.margin_m + patch, h, nodes);
  };
  const auto blocks_of = [&](const WilcoxMeasurementFactor& f, SideProfiles& p, size_t k) {
    std::vector<double*> blocks = {&x[k]};
    for (int c : f.y_blocks) blocks.push_back(&p.y[c * B]);
    for (int c : f.s_blocks) blocks.push_back(&p.s[c * B]);
    return blocks;
  };
  // The factors of one side's cycle k around position xk.
  const auto factors_of = [&](const SideProfiles& p, size_t k, double xk) {
    const WilcoxScan& z = p.scans[k];
    std::vector<WilcoxMeasurementFactor> out;
    const wilcox::GridRun near = run(xk, xk);
    for (int n : {1, 2}) {
      out.push_back({WilcoxMeasurementFactor::kArticulation, n * A, n == 1 ? z.dz_mid : z.dz_front,
                     o.articulation_sd_m, patch, near, run(xk + n * A, xk + n * A), near,
                     run(xk + n * A, xk + n * A)});
    }
    for (const auto& [d, dz] : z.range) {
      out.push_back({WilcoxMeasurementFactor::kRange, d, dz, o.range_sd_m, patch, near,
                     run(xk + d, xk + d), near, wilcox::GridRun{0, 0, h}});
    }
    for (WilcoxMeasurementFactor& f : out) {
      f.block_size = B;
      f.Prepare();
    }
    return out;
  };
  // A factor's residual at the current values (for the initial search).
  const auto residual_of = [&](const WilcoxMeasurementFactor& f, SideProfiles& p, size_t k) {
    const std::vector<double*> blocks = blocks_of(f, p, k);
    std::vector<const double*> values(blocks.begin(), blocks.end());
    double r = 0.0;
    f(values.data(), &r);
    return r;
  };
  // Terrain ranged by cycle k beyond what is mapped: y = dz + the rear wheel's ride height.
  const auto extend_terrain = [&](SideProfiles& p, size_t k) {
    const WilcoxScan& z = p.scans[k];
    const wilcox::GridRun whole{0, nodes, h};
    std::vector<const double*> yp(nodes), sp(nodes);
    for (int i = 0; i < nodes; ++i) yp[i] = &p.y[i], sp[i] = &p.s[i];
    const double ride = k == 0 ? 0.0
                               : wilcox::WheelProfileAt(whole, yp.data(), x[k], patch) -
                                     wilcox::ProfileAt(whole, sp.data(), x[k]);
    for (size_t j = 0; j + 1 < z.range.size(); ++j) {
      const double a = x[k] + z.range[j].first, b = x[k] + z.range[j + 1].first;
      for (int i = static_cast<int>(std::ceil(std::max(a, p.mapped_to) / h));
           i * h <= b && i < nodes; ++i) {
        if (i * h <= p.mapped_to && k > 0) continue;
        const double f = (i * h - a) / (b - a);
        p.y[i] = ride + (1.0 - f) * z.range[j].second + f * z.range[j + 1].second;
      }
    }
    if (k == 0) {  // under the rover: a line from the rear wheel to the first ranged point
      const double first = z.range.front().first;
      p.ranged_from = first;
      for (int i = 0; i * h < first && i < nodes; ++i) {
        p.y[i] = z.range.front().second * i * h / first;
      }
    }
    p.mapped_to = std::max(p.mapped_to, x[k] + z.range.back().first);
  };
  ceres::Solver::Options step_options;
  step_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  step_options.max_num_iterations = 5;
  step_options.logging_type = ceres::SILENT;
  problem.SetParameterBlockConstant(&x[0]);
  // Per side: the elevation datum y_0 = 0 (sd 1 cm), and per block of nodes the smoothness priors
  // that start in it (they reach into the next block): y's second differences, s's first
  // differences, s around 0.
  for (SideProfiles& p : side) {
    LinearFactor::Matrix datum = LinearFactor::Matrix::Zero(1, B);
    datum(0, 0) = 1.0 / 0.01;
    problem.AddResidualBlock(new LinearFactor({datum}, Eigen::VectorXd::Zero(1)), nullptr, &p.y[0]);
    for (int c = 0; c < block_count; ++c) {
      const bool last = c + 1 == block_count;
      const int width = last ? B : 2 * B;  // this block and the next
      const auto rows_of = [&](const LinearFactor::Matrix& dense) {
        std::vector<LinearFactor::Matrix> a = {dense.leftCols(B)};
        if (!last) a.push_back(dense.rightCols(B));
        return a;
      };
      LinearFactor::Matrix curvature = LinearFactor::Matrix::Zero(B, width);
      LinearFactor::Matrix slope = LinearFactor::Matrix::Zero(B, width);
      for (int i = 0; i < B; ++i) {
        if (i + 2 < width) {
          curvature(i, i) = curvature(i, i + 2) = 1.0 / g.y_curvature_sd_m;
          curvature(i, i + 1) = -2.0 / g.y_curvature_sd_m;
        }
        if (i + 1 < width) {
          slope(i, i) = -1.0 / g.s_slope_sd_m;
          slope(i, i + 1) = 1.0 / g.s_slope_sd_m;
        }
      }
      std::vector<double*> y_blocks = {&p.y[c * B]}, s_blocks = {&p.s[c * B]};
      if (!last) y_blocks.push_back(&p.y[(c + 1) * B]), s_blocks.push_back(&p.s[(c + 1) * B]);
      problem.AddResidualBlock(new LinearFactor(rows_of(curvature), Eigen::VectorXd::Zero(B)),
                               nullptr, y_blocks);
      problem.AddResidualBlock(new LinearFactor(rows_of(slope), Eigen::VectorXd::Zero(B)), nullptr,
                               s_blocks);
      problem.AddResidualBlock(
          new LinearFactor({LinearFactor::Matrix::Identity(B, B) / g.s_prior_sd_m},
                           Eigen::VectorXd::Zero(B)),
          nullptr, &p.s[c * B]);
    }
  }
  // Cycle by cycle: search the advance on the profiles so far (the measurements that fall on
  // mapped ground, every side), map the new ground, add the cycle's factors, refine.
  for (SideProfiles& p : side) {
    extend_terrain(p, 0);
    for (const WilcoxMeasurementFactor& f : factors_of(p, 0, 0.0)) {
      problem.AddResidualBlock(WilcoxMeasurementFactor::Create(f), nullptr, blocks_of(f, p, 0));
    }
  }
  ceres::Solver::Summary step_summary;
  ceres::Solve(step_options, &problem, &step_summary);
  int held_blocks = 0;
  for (size_t k = 1; k < cycles; ++k) {
    std::vector<const WilcoxScan*> cycle_scans;
    for (const SideProfiles& p : side) {
      cycle_scans.insert(cycle_scans.end(), {&p.scans[k - 1], &p.scans[k]});
    }
    slope[k] = WilcoxCycleSlope(cycle_scans);
    prior_slip[k] = law.Slip(slope[k]);
    if (o.learn_slip) {  // the baseline's law as it stood at this cycle (causal)
      prior_slip[k] = 0.0;
      for (const WilcoxSide& b : baselines) prior_slip[k] += b.cycles[k - 1].prior_slip / n_sides;
    }
    const double mean = WilcoxPriorAdvance(rim[k], prior_slip[k]);
    const double sd = std::max(1e-4, o.prior_fraction * std::abs(rim[k]));
    double best_a = mean, best_cost = 1e300;
    const double step = 0.0005;
    for (double a = std::max(0.0, mean - 6.0 * sd - 0.01); a <= mean + 6.0 * sd + 0.01; a += step) {
      x[k] = x[k - 1] + a;
      double c = (a - mean) * (a - mean) / (sd * sd);
      for (SideProfiles& p : side) {
        // While the rear wheel is on the guessed ground under the start, its ride height is
        // unknown: the offset that best aligns the factors is taken out (weighted mean of their
        // errors), and the factors whose far wheel is on guessed ground too are left out.
        const bool guessed = x[k] - patch < p.ranged_from;
        double sum_w = 0.0, sum_we = 0.0;
        for (const WilcoxMeasurementFactor& f : factors_of(p, k, x[k])) {
          if (x[k] + f.offset_m + patch > p.mapped_to) continue;  // unmapped ground
          if (guessed && x[k] + f.offset_m - patch < p.ranged_from) continue;
          // The profiles so far are estimates, good to about histogram_sd_m: the search's
          // residual has that error beside the measurement's.
          const double sd_f = std::sqrt(f.sd_m * f.sd_m + o.histogram_sd_m * o.histogram_sd_m);
          const double e = residual_of(f, p, k) * f.sd_m;
          c += e * e / (sd_f * sd_f);
          const double w = 1.0 / (sd_f * sd_f);
          sum_w += w;
          sum_we += w * e;
        }
        if (guessed && sum_w > 0.0) c -= sum_we * sum_we / sum_w;
      }
      if (c < best_cost) best_cost = c, best_a = a;
    }
    x[k] = x[k - 1] + best_a;
    for (SideProfiles& p : side) {
      extend_terrain(p, k);
      for (const WilcoxMeasurementFactor& f : factors_of(p, k, x[k])) {
        problem.AddResidualBlock(WilcoxMeasurementFactor::Create(f), nullptr, blocks_of(f, p, k));
      }
    }
    problem.AddResidualBlock(DifferencePrior<1>::Create({mean}, sd), nullptr, &x[k - 1], &x[k]);
    // A sliding window: positions and nodes well behind the last `window_cycles` are held, so
    // each refinement costs the window, not the traverse (Ceres drops residuals on held blocks).
    if (k > static_cast<size_t>(g.window_cycles)) {
      const size_t old = k - g.window_cycles;
      problem.SetParameterBlockConstant(&x[old]);
      const int behind = static_cast<int>(std::floor((x[old] - g.margin_m - patch) / h));
      const int hold = std::min(behind / B, block_count);
      for (int c = held_blocks; c < hold; ++c) {
        for (SideProfiles& p : side) {
          problem.SetParameterBlockConstant(&p.y[c * B]);
          problem.SetParameterBlockConstant(&p.s[c * B]);
        }
      }
      held_blocks = std::max(held_blocks, hold);
    }
    if (k % g.refine_every == 0) ceres::Solve(step_options, &problem, &step_summary);
  }
  // The final solve over everything.
  for (size_t k = 1; k < cycles; ++k) problem.SetParameterBlockVariable(&x[k]);
  for (int c = 0; c < held_blocks; ++c) {
    for (SideProfiles& p : side) {
      problem.SetParameterBlockVariable(&p.y[c * B]);
      problem.SetParameterBlockVariable(&p.s[c * B]);
    }
  }
  ceres::Solver::Options options = step_options;
  options.max_num_iterations = g.max_iterations;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) {
    for (const WilcoxSide& b : baselines) {
      notes->push_back(b.side + ": the graph solve failed (" + summary.message +
                       "); the baseline's estimates stand");
    }
    return baselines;
  }
  // The front wheel at cycle k: the s node before it and the fraction of the way to the next.
  const auto front_of = [&](size_t k) {
    const double front = (x[k] + 2.0 * A) / h;
    const int i = std::clamp(static_cast<int>(front), 0, nodes - 2);
    return std::make_pair(i, front - i);
  };
  // The parameter block (its first node) that holds node i of a profile.
  const auto block_of = [&](const std::vector<double>& profile, int i) {
    return &profile[(i / B) * B];
  };
  // Marginal uncertainty of each advance (x_k - x_{k-1}) and front sinkage (two interpolated s
  // nodes) from the covariance at the solution; skipped with a note when Ceres cannot compute it.
  std::map<std::pair<const double*, const double*>, Eigen::MatrixXd> cov;
  if (g.covariance) {
    std::vector<std::pair<const double*, const double*>> wanted;
    const auto want = [&](const double* a, const double* b) {
      if (cov.emplace(std::make_pair(a, b), Eigen::MatrixXd()).second) wanted.push_back({a, b});
    };
    for (size_t k = 1; k < cycles; ++k) {
      want(&x[k], &x[k]);
      want(&x[k - 1], &x[k - 1]);
      want(&x[k - 1], &x[k]);
      const int i = front_of(k).first;
      for (const SideProfiles& p : side) {
        want(block_of(p.s, i), block_of(p.s, i));
        want(block_of(p.s, i), block_of(p.s, i + 1));
        want(block_of(p.s, i + 1), block_of(p.s, i + 1));
      }
    }
    ceres::Covariance::Options cov_options;
    cov_options.algorithm_type = ceres::SPARSE_QR;
    ceres::Covariance covariance(cov_options);
    if (covariance.Compute(wanted, &problem)) {
      for (auto& [blocks, m] : cov) {
        const int rows = problem.ParameterBlockSize(blocks.first);
        const int cols = problem.ParameterBlockSize(blocks.second);
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block(rows, cols);
        covariance.GetCovarianceBlock(blocks.first, blocks.second, block.data());
        m = block;
      }
    } else {
      cov.clear();
      notes->push_back("the graph's covariance could not be computed: no standard deviations");
    }
  }
  // Covariance of element a of block pa with element b of block pb (either order).
  const auto cov_of = [&](const double* pa, int a, const double* pb, int b) {
    auto it = cov.find({pa, pb});
    if (it != cov.end() && it->second.size() > 0) return it->second(a, b);
    it = cov.find({pb, pa});
    if (it != cov.end() && it->second.size() > 0) return it->second(b, a);
    return std::numeric_limits<double>::quiet_NaN();
  };
  std::vector<WilcoxSide> out(n_sides);
  for (size_t j = 0; j < n_sides; ++j) {
    out[j].side = baselines[j].side;
    // The law is the baseline's (the user's as given when it does not learn).
    out[j].law_slip = baselines[j].law_slip;
    out[j].law_slip_per_slope = baselines[j].law_slip_per_slope;
    out[j].law_cycles_used = baselines[j].law_cycles_used;
    out[j].law_slip_sd = baselines[j].law_slip_sd;
    out[j].law_slip_per_slope_sd = baselines[j].law_slip_per_slope_sd;
    for (size_t k = 1; k < cycles; ++k) {
      WilcoxCycle c = baselines[j].cycles[k - 1];
      c.advance_m = x[k] - x[k - 1];
      c.slope = slope[k];
      c.prior_slip = prior_slip[k];
      const auto [i, w1] = front_of(k);
      const std::vector<double>& s = side[j].s;
      c.sinkage_front_m = s[i] + w1 * (s[i + 1] - s[i]);
      if (!cov.empty()) {
        const double var_advance = cov_of(&x[k], 0, &x[k], 0) + cov_of(&x[k - 1], 0, &x[k - 1], 0) -
                                   2.0 * cov_of(&x[k - 1], 0, &x[k], 0);
        c.advance_sd_m = std::sqrt(std::max(0.0, var_advance));
        const double w0 = 1.0 - w1;
        const double* b0 = block_of(s, i);
        const double* b1 = block_of(s, i + 1);
        const double var_sinkage = w0 * w0 * cov_of(b0, i % B, b0, i % B) +
                                   2.0 * w0 * w1 * cov_of(b0, i % B, b1, (i + 1) % B) +
                                   w1 * w1 * cov_of(b1, (i + 1) % B, b1, (i + 1) % B);
        c.sinkage_front_sd_m = std::sqrt(std::max(0.0, var_sinkage));
      }
      out[j].cycles.push_back(c);
      out[j].total_advance_m += c.advance_m;
      out[j].total_rim_m += c.rim_m;
      out[j].mean_sinkage_m += c.sinkage_front_m / (cycles - 1);
    }
  }
  return out;
}

}  // namespace

WilcoxResult EstimateWilcoxGraph(const DriveLog& log, const WilcoxOptions& options,
                                 const WilcoxGraphOptions& graph) {
  std::string error;
  if (!graph.IsValid(&error)) throw std::invalid_argument(error);
  const WilcoxResult baseline = EstimateWilcoxBaseline(log, options);
  WilcoxResult result;
  result.notes = baseline.notes;
  std::vector<Side> sides;
  for (size_t i = 0; i < baseline.sides.size(); ++i) {
    sides.push_back(i == 0 ? Side::kLeft : Side::kRight);
  }
  if (graph.shared_advance && sides.size() == 2) {
    result.sides = SolveSides(log, sides, baseline.sides, options, graph, &result.notes);
  } else {
    for (size_t i = 0; i < sides.size(); ++i) {
      result.sides.push_back(
          SolveSides(log, {sides[i]}, {baseline.sides[i]}, options, graph, &result.notes)[0]);
    }
  }
  CheckWilcoxSides(log, options, &result);
  return result;
}

}  // namespace slipgraph
