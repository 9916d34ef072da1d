#include "solvers/chain_covariance.h"

#include <ceres/cost_function.h>
#include <ceres/crs_matrix.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <unordered_map>
#include <utility>

namespace slipgraph {

using Eigen::MatrixXd;

namespace {

// The block LDL' of H = [T B; B' C] with T block tridiagonal (see the header). M: the state
// size when known at compile time (7 for the Ward window: fixed-size Eigen blocks, no
// allocations per block), else Eigen::Dynamic.
template <int M>
struct ChainFactorization {
  using Block = Eigen::Matrix<double, M, M>;
  using Border = Eigen::Matrix<double, M, Eigen::Dynamic>;
  int n = 0, m = 0, g = 0;
  std::vector<Block> N, D_inv;  // N_k = T_{k+1,k} D_k^-1
  std::vector<Border> B, X;     // X = T^-1 B
  Eigen::LLT<MatrixXd> S;       // S = C - B' X
  std::string error;
};

// T^-1 rhs (one block of rows per state) by forward and back substitution through the LDL'.
template <int M, typename Rhs>
std::vector<Rhs> SolveT(const ChainFactorization<M>& f, const std::vector<Rhs>& rhs) {
  const int n = f.n;
  std::vector<Rhs> x(n);
  for (int k = 0; k < n; ++k) x[k] = k > 0 ? Rhs(rhs[k] - f.N[k - 1] * x[k - 1]) : rhs[0];
  for (int k = 0; k < n; ++k) x[k] = f.D_inv[k] * x[k];
  for (int k = n - 2; k >= 0; --k) x[k] -= f.N[k].transpose() * x[k + 1];
  return x;
}

// H = J'J in flat column-major buffers: D[k] = T_kk (upper triangle), U[k] = T_{k,k+1},
// B[k] = H_{k,globals}, C (upper triangle); filled one residual block at a time.
struct Information {
  Information(int n, int m, int g)
      : n(n),
        m(m),
        g(g),
        D(static_cast<size_t>(n) * m * m, 0.0),
        U(D.size(), 0.0),
        B(static_cast<size_t>(n) * m * g, 0.0),
        C(static_cast<size_t>(g) * g, 0.0) {}

  // Adds one residual block's Jb' Jb (hb: its upper triangle, row-major, count x count) whose
  // column a is index[a] of state block[a] (-1: of the globals, stacked). False (with error) when
  // the block links states that are not neighbours.
  bool Add(const std::vector<int>& block, const std::vector<int>& index,
           const std::vector<double>& hb) {
    const int count = static_cast<int>(block.size());
    const int mm = m * m;
    // Runs of columns of one parameter block with consecutive indices; each pair of runs adds
    // its part of hb to one destination, at origin + ia * sa + ib * sb (no branch per element).
    segments_.clear();
    for (int a = 0; a < count; ++a) {
      if (!segments_.empty()) {
        Segment& s = segments_.back();
        if (s.k == block[a] && s.index + s.length == index[a] && s.position + s.length == a) {
          ++s.length;
          continue;
        }
      }
      segments_.push_back({block[a], index[a], a, 1});
    }
    for (size_t si = 0; si < segments_.size(); ++si) {
      for (size_t ti = si; ti < segments_.size(); ++ti) {
        const Segment& s = segments_[si];
        const Segment& t = segments_[ti];
        double* origin = nullptr;
        int sa = 1, sb = 1;
        if (s.k < 0 && t.k < 0) {  // C, upper triangle
          origin = C.data();
          sa = s.index <= t.index ? 1 : g;
          sb = s.index <= t.index ? g : 1;
        } else if (s.k < 0) {  // a state's border B
          origin = B.data() + static_cast<size_t>(t.k) * m * g, sa = m, sb = 1;
        } else if (t.k < 0) {
          origin = B.data() + static_cast<size_t>(s.k) * m * g, sa = 1, sb = m;
        } else if (s.k == t.k && si == ti) {  // D, upper triangle: ia <= ib in one run
          origin = D.data() + static_cast<size_t>(s.k) * mm, sa = 1, sb = m;
        } else if (t.k == s.k + 1) {
          origin = U.data() + static_cast<size_t>(s.k) * mm, sa = 1, sb = m;
        } else if (s.k == t.k + 1) {
          origin = U.data() + static_cast<size_t>(t.k) * mm, sa = m, sb = 1;
        } else if (s.k != t.k) {
          error = "a residual block links states " + std::to_string(std::min(s.k, t.k)) + " and " +
                  std::to_string(std::max(s.k, t.k)) + ": not a chain";
          return false;
        }
        for (int i = 0; i < s.length; ++i) {
          const double* h = hb.data() + static_cast<size_t>(s.position + i) * count + t.position;
          const int ia = s.index + i;
          for (int j = si == ti ? i : 0; j < t.length; ++j) {
            const int ib = t.index + j;
            if (origin != nullptr) {
              origin[ia * sa + ib * sb] += h[j];
            } else {  // one state in two runs: D by the smaller index
              D[static_cast<size_t>(s.k) * mm + std::min(ia, ib) + m * std::max(ia, ib)] += h[j];
            }
          }
        }
      }
    }
    return true;
  }

  int n, m, g;
  std::vector<double> D, U, B, C;
  std::string error;

 private:
  struct Segment {
    int k, index, position, length;  // state (-1: the globals), first index, first column
  };
  std::vector<Segment> segments_;
};

// The upper triangle of Jb' Jb, row-major, for `rows` rows of `count` columns (row-major): a
// few rows of a few columns, where plain loops beat a general matrix product.
void AddOuterProducts(const double* jb, int rows, int count, std::vector<double>* hb) {
  hb->assign(static_cast<size_t>(count) * count, 0.0);
  for (int r = 0; r < rows; ++r) {
    const double* jr = jb + static_cast<size_t>(r) * count;
    for (int a = 0; a < count; ++a) {
      const double ja = jr[a];
      if (ja == 0.0) continue;
      double* h = hb->data() + static_cast<size_t>(a) * count;
      for (int b = a; b < count; ++b) h[b] += ja * jr[b];
    }
  }
}

// H from a Jacobian in Problem::Evaluate's layout (the states' columns, then the globals').
bool AssembleFromJacobian(const ceres::CRSMatrix& J, Information* info) {
  const int m = info->m, state_columns = info->n * m;
  std::vector<int> block, index;
  std::vector<double> hb;
  for (int row = 0; row < J.num_rows;) {
    // Rows of one residual block share their columns: take them together.
    const int begin = J.rows[row], count = J.rows[row + 1] - begin;
    int last = row + 1;
    while (last < J.num_rows && J.rows[last + 1] - J.rows[last] == count &&
           std::equal(J.cols.begin() + begin, J.cols.begin() + begin + count,
                      J.cols.begin() + J.rows[last])) {
      ++last;
    }
    AddOuterProducts(J.values.data() + begin, last - row, count, &hb);
    row = last;
    block.resize(count);
    index.resize(count);
    for (int a = 0; a < count; ++a) {
      const int c = J.cols[begin + a];
      block[a] = c >= state_columns ? -1 : c / m;
      index[a] = c >= state_columns ? c - state_columns : c % m;
    }
    if (!info->Add(block, index, hb)) return false;
  }
  return true;
}

// H, the gradient J'r (states, then globals) and the cost from each residual block's own
// evaluation (Problem::EvaluateResidualBlock, loss-corrected as Problem::Evaluate is): no program
// and no sparse Jacobian built per call. A block's parameters that are neither a state nor a
// global are held constant, as Problem::Evaluate holds the blocks it is not given.
bool AssembleFromBlocks(ceres::Problem* problem, const std::vector<double*>& states,
                        const std::vector<double*>& globals, Information* info, double* cost,
                        std::vector<double>* gradient) {
  const int m = info->m, state_columns = info->n * m;
  struct Place {
    int state, first, size;  // state -1: a global, its first index among the globals'
  };
  std::unordered_map<const double*, Place> where;
  where.reserve(states.size() + globals.size());
  for (size_t k = 0; k < states.size(); ++k) where[states[k]] = {static_cast<int>(k), 0, m};
  int offset = 0;
  for (double* p : globals) {
    const int size = problem->ParameterBlockTangentSize(p);
    where[p] = {-1, offset, size};
    offset += size;
  }
  gradient->assign(static_cast<size_t>(state_columns + info->g), 0.0);
  *cost = 0.0;
  std::vector<ceres::ResidualBlockId> ids;
  problem->GetResidualBlocks(&ids);
  std::vector<double*> blocks;
  std::vector<int> block, index, sizes;
  std::vector<double> residuals, jb, hb;
  std::vector<std::vector<double>> jacobians;
  std::vector<double*> jacobian_pointers;
  for (const ceres::ResidualBlockId id : ids) {
    problem->GetParameterBlocksForResidualBlock(id, &blocks);
    const int rows = problem->GetCostFunctionForResidualBlock(id)->num_residuals();
    jacobians.resize(blocks.size());
    jacobian_pointers.assign(blocks.size(), nullptr);
    sizes.assign(blocks.size(), 0);
    block.clear();
    index.clear();
    for (size_t i = 0; i < blocks.size(); ++i) {
      const auto it = where.find(blocks[i]);
      if (it == where.end()) continue;
      const Place& place = it->second;
      sizes[i] = place.size;
      jacobians[i].resize(static_cast<size_t>(rows) * sizes[i]);
      jacobian_pointers[i] = jacobians[i].data();
      for (int j = 0; j < sizes[i]; ++j) {
        block.push_back(place.state);
        index.push_back(place.first + j);
      }
    }
    residuals.resize(rows);
    double block_cost = 0.0;
    if (!problem->EvaluateResidualBlock(id, true, &block_cost, residuals.data(),
                                        jacobian_pointers.data())) {
      info->error = "a residual block could not be evaluated";
      return false;
    }
    *cost += block_cost;
    const int count = static_cast<int>(block.size());
    if (count == 0) continue;
    // The block's Jacobian, row-major over its free columns.
    jb.resize(static_cast<size_t>(rows) * count);
    int column = 0;
    for (size_t i = 0; i < blocks.size(); ++i) {
      if (jacobian_pointers[i] == nullptr) continue;
      for (int r = 0; r < rows; ++r) {
        std::copy_n(jacobians[i].data() + static_cast<size_t>(r) * sizes[i], sizes[i],
                    jb.data() + static_cast<size_t>(r) * count + column);
      }
      column += sizes[i];
    }
    for (int a = 0; a < count; ++a) {
      double sum = 0.0;
      for (int r = 0; r < rows; ++r) sum += jb[static_cast<size_t>(r) * count + a] * residuals[r];
      const int c = block[a] < 0 ? state_columns + index[a] : block[a] * m + index[a];
      (*gradient)[c] += sum;
    }
    AddOuterProducts(jb.data(), rows, count, &hb);
    if (!info->Add(block, index, hb)) return false;
  }
  return true;
}

// Factors an assembled H; false (with f->error) when it is not positive definite.
template <int M>
bool Factor(const Information& info, ChainFactorization<M>* f) {
  using Block = typename ChainFactorization<M>::Block;
  const int n = info.n, m = info.m, g = info.g, mm = m * m;
  f->n = n, f->m = m, f->g = g;
  const std::vector<double>&Dbuf = info.D, &Ubuf = info.U, &Bbuf = info.B, &Cbuf = info.C;
  f->B.resize(n);
  for (int k = 0; k < n; ++k) {
    f->B[k] = Eigen::Map<const MatrixXd>(Bbuf.data() + static_cast<size_t>(k) * m * g, m, g);
  }
  // Block LDL' of T: D_k <- pivots, N_k = T_{k+1,k} D_k^-1.
  f->N.resize(n);
  f->D_inv.resize(n);
  Block D, U_previous;
  for (int k = 0; k < n; ++k) {
    D = Eigen::Map<const MatrixXd>(Dbuf.data() + static_cast<size_t>(k) * mm, m, m)
            .template selfadjointView<Eigen::Upper>();
    if (k > 0) D -= f->N[k - 1] * U_previous;
    Eigen::LLT<Block> llt(D);
    if (llt.info() != Eigen::Success) {
      f->error = "the information of state " + std::to_string(k) +
                 " is not positive definite (a direction no factor constrains)";
      return false;
    }
    f->D_inv[k] = llt.solve(Block::Identity(m, m));
    U_previous = Eigen::Map<const MatrixXd>(Ubuf.data() + static_cast<size_t>(k) * mm, m, m);
    if (k + 1 < n) f->N[k] = U_previous.transpose() * f->D_inv[k];
  }
  if (g == 0) return true;
  // The border: X = T^-1 B, S = C - B' X.
  f->X = SolveT(*f, f->B);
  MatrixXd S = Eigen::Map<const MatrixXd>(Cbuf.data(), g, g).selfadjointView<Eigen::Upper>();
  for (int k = 0; k < n; ++k) S -= f->B[k].transpose() * f->X[k];
  f->S.compute(S);
  if (f->S.info() != Eigen::Success) {
    f->error = "the global parameters' information is not positive definite";
    return false;
  }
  return true;
}

// Diagonal and first sub-diagonal blocks of H^-1 from the factorization: Takahashi's recursion
// on T, corrected for the border.
// first_states >= 0: only cov(x_k) for k < first_states (the recursion still runs over all of
// them; the border's correction and `next` are skipped for the rest).
template <int M>
ChainCovariance Marginals(const ChainFactorization<M>& f, int first_states = -1) {
  using Block = typename ChainFactorization<M>::Block;
  ChainCovariance out;
  const int n = f.n;
  const bool all = first_states < 0;
  const int wanted = all ? n : std::min(n, first_states);
  out.states.assign(n, MatrixXd());
  if (all) out.next.assign(n > 0 ? n - 1 : 0, MatrixXd());
  Block state = f.D_inv[n - 1];
  if (all || n - 1 < wanted) out.states[n - 1] = state;
  for (int k = n - 2; k >= 0; --k) {
    const Block sub = -state * f.N[k];  // Sigma_{k+1,k}
    if (all) out.next[k] = sub;
    state = f.D_inv[k] - f.N[k].transpose() * sub;
    if (k < wanted) out.states[k] = state;
  }
  if (f.g > 0) {
    out.globals = f.S.solve(MatrixXd::Identity(f.g, f.g));
    for (int k = 0; k < wanted; ++k) out.states[k] += f.X[k] * out.globals * f.X[k].transpose();
    if (all) {
      for (int k = 0; k + 1 < n; ++k) {
        out.next[k] += f.X[k + 1] * out.globals * f.X[k].transpose();
      }
    }
  }
  out.ok = true;
  return out;
}

// Checks the blocks: the states' size m and the globals' tangent size g; false with *error.
bool Sizes(ceres::Problem* problem, const std::vector<double*>& states,
           const std::vector<double*>& globals, int* m, int* g, std::string* error) {
  if (states.empty()) {
    *error = "no states";
    return false;
  }
  *m = problem->ParameterBlockSize(states[0]);
  *g = 0;
  for (double* p : globals) *g += problem->ParameterBlockTangentSize(p);
  for (double* x : states) {
    if (problem->ParameterBlockSize(x) != *m) {
      *error = "the states differ in size";
      return false;
    }
  }
  return true;
}

// H, the gradient and the cost at the current values, factored; false with *error.
template <int M>
bool Linearize(ceres::Problem* problem, const std::vector<double*>& states,
               const std::vector<double*>& globals, int m, int g, double* cost,
               std::vector<double>* gradient, ChainFactorization<M>* f, std::string* error) {
  Information info(static_cast<int>(states.size()), m, g);
  if (!AssembleFromBlocks(problem, states, globals, &info, cost, gradient)) {
    *error = info.error;
    return false;
  }
  if (!Factor(info, f)) {
    *error = f->error;
    return false;
  }
  return true;
}

// H [dx; dg] = -[g_x; g_g] on a factorization: y = T^-1 (-g_x), S dg = -g_g - B' y,
// dx = y - X dg.
template <int M>
void Solve(const ChainFactorization<M>& f, const std::vector<double>& gradient,
           std::vector<Eigen::VectorXd>* dx, Eigen::VectorXd* dg) {
  using Vector = Eigen::Matrix<double, M, 1>;
  const int n = f.n, m = f.m, g = f.g;
  std::vector<Vector> minus_gx(n);
  for (int k = 0; k < n; ++k) {
    minus_gx[k] = -Eigen::Map<const Eigen::VectorXd>(gradient.data() + k * m, m);
  }
  const std::vector<Vector> y = SolveT(f, minus_gx);
  dx->assign(n, Eigen::VectorXd());
  if (g > 0) {
    Eigen::VectorXd rhs = -Eigen::Map<const Eigen::VectorXd>(gradient.data() + n * m, g);
    for (int k = 0; k < n; ++k) rhs -= f.B[k].transpose() * y[k];
    *dg = f.S.solve(rhs);
    for (int k = 0; k < n; ++k) (*dx)[k] = y[k] - f.X[k] * *dg;
  } else {
    dg->resize(0);
    for (int k = 0; k < n; ++k) (*dx)[k] = y[k];
  }
}

template <int M>
void SensitivityFrom(const ceres::CRSMatrix& J, int n, int m, int g,
                     const std::vector<Eigen::VectorXd>& shifts, ChainSensitivity* out) {
  ChainFactorization<M> f;
  Information info(n, m, g);
  if (!AssembleFromJacobian(J, &info)) {
    out->error = info.error;
    return;
  }
  if (!Factor(info, &f)) {
    out->error = f.error;
    return;
  }
  out->states.resize(shifts.size());
  out->globals.resize(shifts.size());
  std::vector<double> gradient(static_cast<size_t>(J.num_cols));
  for (size_t j = 0; j < shifts.size(); ++j) {
    // J' t over the CRS rows.
    std::fill(gradient.begin(), gradient.end(), 0.0);
    for (int row = 0; row < J.num_rows; ++row) {
      const double t = shifts[j][row];
      if (t == 0.0) continue;
      for (int e = J.rows[row]; e < J.rows[row + 1]; ++e) gradient[J.cols[e]] += J.values[e] * t;
    }
    Solve(f, gradient, &out->states[j], &out->globals[j]);
  }
  out->ok = true;
}

}  // namespace

ChainSensitivity ComputeChainSensitivity(ceres::Problem* problem,
                                         const std::vector<double*>& states,
                                         const std::vector<double*>& globals,
                                         const std::vector<Eigen::VectorXd>& residual_shifts) {
  ChainSensitivity out;
  int m = 0, g = 0;
  if (!Sizes(problem, states, globals, &m, &g, &out.error)) return out;
  // The shifts are indexed by Problem::Evaluate's rows: its Jacobian, in its order.
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = states;
  options.parameter_blocks.insert(options.parameter_blocks.end(), globals.begin(), globals.end());
  options.apply_loss_function = true;
  ceres::CRSMatrix J;
  if (!problem->Evaluate(options, nullptr, nullptr, nullptr, &J)) {
    out.error = "the Jacobian could not be evaluated";
    return out;
  }
  for (const Eigen::VectorXd& t : residual_shifts) {
    if (t.size() != J.num_rows) {
      out.error = "a residual shift has " + std::to_string(t.size()) + " rows, the problem " +
                  std::to_string(J.num_rows);
      return out;
    }
  }
  const int n = static_cast<int>(states.size());
  if (m == 7) {
    SensitivityFrom<7>(J, n, m, g, residual_shifts, &out);
  } else {
    SensitivityFrom<Eigen::Dynamic>(J, n, m, g, residual_shifts, &out);
  }
  return out;
}

namespace {

template <int M>
ChainCovariance CovarianceAt(ceres::Problem* problem, const std::vector<double*>& states,
                             const std::vector<double*>& globals, int m, int g) {
  ChainCovariance out;
  ChainFactorization<M> f;
  double cost = 0.0;
  std::vector<double> gradient;
  if (!Linearize(problem, states, globals, m, g, &cost, &gradient, &f, &out.error)) return out;
  return Marginals(f);
}

template <int M>
ChainStep StepAt(ceres::Problem* problem, const std::vector<double*>& states,
                 const std::vector<double*>& globals, int m, int g, bool with_covariance,
                 int covariance_states) {
  ChainStep out;
  ChainFactorization<M> f;
  std::vector<double> gradient;
  if (!Linearize(problem, states, globals, m, g, &out.cost, &gradient, &f, &out.error)) {
    return out;
  }
  Solve(f, gradient, &out.states, &out.globals);
  if (with_covariance) out.covariance = Marginals(f, covariance_states);
  out.ok = true;
  return out;
}

}  // namespace

bool ChainCost(const ceres::Problem& problem, double* cost) {
  std::vector<ceres::ResidualBlockId> ids;
  problem.GetResidualBlocks(&ids);
  std::vector<double> residuals;
  *cost = 0.0;
  for (const ceres::ResidualBlockId id : ids) {
    residuals.resize(problem.GetCostFunctionForResidualBlock(id)->num_residuals());
    double block_cost = 0.0;
    if (!problem.EvaluateResidualBlock(id, true, &block_cost, residuals.data(), nullptr)) {
      return false;
    }
    *cost += block_cost;
  }
  return true;
}

ChainCovariance ComputeChainCovariance(ceres::Problem* problem, const std::vector<double*>& states,
                                       const std::vector<double*>& globals) {
  int m = 0, g = 0;
  ChainCovariance out;
  if (!Sizes(problem, states, globals, &m, &g, &out.error)) return out;
  return m == 7 ? CovarianceAt<7>(problem, states, globals, m, g)
                : CovarianceAt<Eigen::Dynamic>(problem, states, globals, m, g);
}

ChainStep ComputeChainStep(ceres::Problem* problem, const std::vector<double*>& states,
                           const std::vector<double*>& globals, bool with_covariance,
                           int covariance_states) {
  int m = 0, g = 0;
  ChainStep out;
  if (!Sizes(problem, states, globals, &m, &g, &out.error)) return out;
  return m == 7 ? StepAt<7>(problem, states, globals, m, g, with_covariance, covariance_states)
                : StepAt<Eigen::Dynamic>(problem, states, globals, m, g, with_covariance,
                                         covariance_states);
}

}  // namespace slipgraph
