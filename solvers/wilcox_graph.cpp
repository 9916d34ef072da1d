#include "solvers/wilcox_graph.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "factors/linear_factor.h"
#include "factors/wilcox_factors.h"

namespace slipgraph {
namespace {

// The odometry prior on an advance: (x_k - x_{k-1} - mean) / sd.
struct AdvancePrior {
  double mean, inverse_sd;
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    r[0] = (b[0] - a[0] - mean) * inverse_sd;
    return true;
  }
};

WilcoxSide SolveSide(const DriveLog& log, Side side, const WilcoxSide& baseline,
                     const WilcoxOptions& o, const WilcoxGraphOptions& g,
                     std::vector<std::string>* notes) {
  WilcoxSide out;
  out.side = baseline.side;
  const std::vector<WilcoxScan> scans = WilcoxScans(log, side);
  if (scans.size() < 2 || baseline.cycles.size() + 1 != scans.size()) return baseline;
  const double A = log.vehicle.axle_spacing_m;
  const double patch = o.contact_patch_fraction * log.vehicle.wheel_radius_m;
  const double h = g.node_spacing_m;
  // The grid covers the baseline's traverse plus the farthest ranged point and a margin.
  std::vector<double> x(scans.size(), 0.0);
  double span = 0.0;
  for (const WilcoxCycle& c : baseline.cycles) span += std::max(c.advance_m, c.rim_m);
  double far = 0.0;
  for (const WilcoxScan& z : scans) far = std::max(far, z.range.back().first);
  // Nodes in parameter blocks of B (factors/wilcox_factors.h says why), the grid padded to whole
  // blocks.
  const int B = std::max(1, g.nodes_per_block);
  const int needed = static_cast<int>(std::ceil((span + far + g.margin_m + patch) / h)) + 2;
  const int block_count = (needed + B - 1) / B;
  const int nodes = block_count * B;
  std::vector<double> y(nodes, 0.0), s(nodes, 0.0);

  ceres::Problem problem;
  for (double& v : x) problem.AddParameterBlock(&v, 1);
  for (int c = 0; c < block_count; ++c) {
    problem.AddParameterBlock(&y[c * B], B);
    problem.AddParameterBlock(&s[c * B], B);
  }
  const auto run = [&](double lo, double hi) {
    return wilcox::RunCovering(lo, hi, g.margin_m + patch, h, nodes);
  };
  const auto blocks_of = [&](const WilcoxMeasurementFactor& f, size_t k) {
    std::vector<double*> blocks = {&x[k]};
    for (int c : f.y_blocks) blocks.push_back(&y[c * B]);
    for (int c : f.s_blocks) blocks.push_back(&s[c * B]);
    return blocks;
  };
  // The factors of cycle k around position xk.
  const auto factors_of = [&](size_t k, double xk) {
    const WilcoxScan& z = scans[k];
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
  // A factor's squared residual at the current values (for the initial search).
  const auto cost_of = [&](const WilcoxMeasurementFactor& f, size_t k) {
    const std::vector<double*> blocks = blocks_of(f, k);
    std::vector<const double*> p(blocks.begin(), blocks.end());
    double r = 0.0;
    f(p.data(), &r);
    return r * r;
  };
  // Terrain ranged by cycle k beyond what is mapped: y = dz + the rear wheel's ride height.
  double mapped_to = 0.0;
  const auto extend_terrain = [&](size_t k) {
    const WilcoxScan& z = scans[k];
    const wilcox::GridRun whole{0, nodes, h};
    std::vector<const double*> yp(nodes), sp(nodes);
    for (int i = 0; i < nodes; ++i) yp[i] = &y[i], sp[i] = &s[i];
    const double ride = k == 0 ? 0.0
                               : wilcox::WheelProfileAt(whole, yp.data(), x[k], patch) -
                                     wilcox::ProfileAt(whole, sp.data(), x[k]);
    for (size_t j = 0; j + 1 < z.range.size(); ++j) {
      const double a = x[k] + z.range[j].first, b = x[k] + z.range[j + 1].first;
      for (int i = static_cast<int>(std::ceil(std::max(a, mapped_to) / h)); i * h <= b && i < nodes;
           ++i) {
        if (i * h <= mapped_to && k > 0) continue;
        const double f = (i * h - a) / (b - a);
        y[i] = ride + (1.0 - f) * z.range[j].second + f * z.range[j + 1].second;
      }
    }
    if (k == 0) {  // under the rover: a line from the rear wheel to the first ranged point
      const double first = z.range.front().first;
      for (int i = 0; i * h < first && i < nodes; ++i)
        y[i] = z.range.front().second * i * h / first;
    }
    mapped_to = std::max(mapped_to, x[k] + z.range.back().first);
  };
  ceres::Solver::Options step_options;
  step_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  step_options.max_num_iterations = 5;
  step_options.logging_type = ceres::SILENT;
  problem.SetParameterBlockConstant(&x[0]);
  // The elevation datum y_0 = 0 (sd 1 cm), and per block of nodes the smoothness priors that
  // start in it (they reach into the next block): y's second differences, s's first differences,
  // s around 0.
  {
    LinearFactor::Matrix datum = LinearFactor::Matrix::Zero(1, B);
    datum(0, 0) = 1.0 / 0.01;
    problem.AddResidualBlock(new LinearFactor({datum}, Eigen::VectorXd::Zero(1)), nullptr, &y[0]);
  }
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
    for (int j = 0; j < B; ++j) {
      if (j + 2 < width) {
        curvature(j, j) = curvature(j, j + 2) = 1.0 / g.y_curvature_sd_m;
        curvature(j, j + 1) = -2.0 / g.y_curvature_sd_m;
      }
      if (j + 1 < width) {
        slope(j, j) = -1.0 / g.s_slope_sd_m;
        slope(j, j + 1) = 1.0 / g.s_slope_sd_m;
      }
    }
    std::vector<double*> y_blocks = {&y[c * B]}, s_blocks = {&s[c * B]};
    if (!last) y_blocks.push_back(&y[(c + 1) * B]), s_blocks.push_back(&s[(c + 1) * B]);
    problem.AddResidualBlock(new LinearFactor(rows_of(curvature), Eigen::VectorXd::Zero(B)),
                             nullptr, y_blocks);
    problem.AddResidualBlock(new LinearFactor(rows_of(slope), Eigen::VectorXd::Zero(B)), nullptr,
                             s_blocks);
    problem.AddResidualBlock(
        new LinearFactor({LinearFactor::Matrix::Identity(B, B) / g.s_prior_sd_m},
                         Eigen::VectorXd::Zero(B)),
        nullptr, &s[c * B]);
  }
  // Cycle by cycle: search the advance on the profiles so far (the measurements that fall on
  // mapped ground), map the new ground, add the cycle's factors, refine.
  extend_terrain(0);
  for (const WilcoxMeasurementFactor& f : factors_of(0, 0.0)) {
    problem.AddResidualBlock(WilcoxMeasurementFactor::Create(f), nullptr, blocks_of(f, 0));
  }
  ceres::Solver::Summary step_summary;
  ceres::Solve(step_options, &problem, &step_summary);
  int held_blocks = 0;
  for (size_t k = 1; k < scans.size(); ++k) {
    const double rim = baseline.cycles[k - 1].rim_m;
    const double mean = rim * (1.0 - o.prior_slip);
    const double sd = std::max(1e-4, o.prior_fraction * std::abs(rim));
    double best_a = mean, best_cost = 1e300;
    const double step = 0.0005;
    for (double a = std::max(0.0, mean - 6.0 * sd - 0.01); a <= mean + 6.0 * sd + 0.01; a += step) {
      x[k] = x[k - 1] + a;
      double c = (a - mean) * (a - mean) / (sd * sd);
      for (const WilcoxMeasurementFactor& f : factors_of(k, x[k])) {
        if (x[k] + f.offset_m + patch > mapped_to) continue;  // unmapped ground
        c += cost_of(f, k);
      }
      if (c < best_cost) best_cost = c, best_a = a;
    }
    x[k] = x[k - 1] + best_a;
    extend_terrain(k);
    for (const WilcoxMeasurementFactor& f : factors_of(k, x[k])) {
      problem.AddResidualBlock(WilcoxMeasurementFactor::Create(f), nullptr, blocks_of(f, k));
    }
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<AdvancePrior, 1, 1, 1>(new AdvancePrior{mean, 1.0 / sd}),
        nullptr, &x[k - 1], &x[k]);
    // A sliding window: positions and nodes well behind the last `window_cycles` are held, so
    // each refinement costs the window, not the traverse (Ceres drops residuals on held blocks).
    if (k > static_cast<size_t>(g.window_cycles)) {
      const size_t old = k - g.window_cycles;
      problem.SetParameterBlockConstant(&x[old]);
      const int behind = static_cast<int>(std::floor((x[old] - g.margin_m - patch) / h));
      for (int c = held_blocks; c < std::min(behind / B, block_count); ++c) {
        problem.SetParameterBlockConstant(&y[c * B]);
        problem.SetParameterBlockConstant(&s[c * B]);
      }
      held_blocks = std::max(held_blocks, std::min(behind / B, block_count));
    }
    if (k % g.refine_every == 0) ceres::Solve(step_options, &problem, &step_summary);
  }
  // The final solve over everything.
  for (size_t k = 1; k < x.size(); ++k) problem.SetParameterBlockVariable(&x[k]);
  for (int c = 0; c < held_blocks; ++c) {
    problem.SetParameterBlockVariable(&y[c * B]);
    problem.SetParameterBlockVariable(&s[c * B]);
  }
  ceres::Solver::Options options = step_options;
  options.max_num_iterations = g.max_iterations;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) {
    notes->push_back(out.side + ": the graph solve failed (" + summary.message +
                     "); the baseline's estimates stand");
    return baseline;
  }
  for (size_t k = 1; k < scans.size(); ++k) {
    WilcoxCycle c = baseline.cycles[k - 1];
    c.advance_m = x[k] - x[k - 1];
    const double front = (x[k] + 2.0 * A) / h;
    const int i = std::clamp(static_cast<int>(front), 0, nodes - 2);
    c.sinkage_front_m = s[i] + (front - i) * (s[i + 1] - s[i]);
    out.cycles.push_back(c);
    out.total_advance_m += c.advance_m;
    out.total_rim_m += c.rim_m;
    out.mean_sinkage_m += c.sinkage_front_m / (scans.size() - 1);
  }
  return out;
}

}  // namespace

WilcoxResult EstimateWilcoxGraph(const DriveLog& log, const WilcoxOptions& options,
                                 const WilcoxGraphOptions& graph) {
  const WilcoxResult baseline = EstimateWilcoxBaseline(log, options);
  WilcoxResult result;
  result.notes = baseline.notes;
  for (size_t i = 0; i < baseline.sides.size(); ++i) {
    result.sides.push_back(SolveSide(log, i == 0 ? Side::kLeft : Side::kRight, baseline.sides[i],
                                     options, graph, &result.notes));
  }
  CheckWilcoxSides(log, options, &result);
  return result;
}

}  // namespace slipgraph
