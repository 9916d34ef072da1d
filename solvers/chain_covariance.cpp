#include "solvers/chain_covariance.h"

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <numeric>
#include <unordered_map>
#include <utility>

#include "solvers/run_concurrently.h"

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

// Which of the globals' columns only a stretch of the chain touches. A column that the states'
// residual blocks touch only from state `first` to state `last` < n - 1 (a stiffness node of the
// tire law's walk) is "local": it can be eliminated right after state `last`, and a state's row
// of H holds only the local columns near it. The others (touched by the last state, by every
// state or by no state: the IMU offsets, the effects) are the "tail", eliminated last. With no
// local columns the border is dense and the factorization is ChainFactorization's, whose every
// state carries every column; with them it is FrontalFactorization's, whose states carry the
// tail and the local columns open around them (where those are at most half the border: the
// dense border's fixed-size blocks are cheaper for a few columns).
struct BorderShape {
  int g = 0, tail = 0, local = 0;  // columns: all, in the tail, local
  // Per caller column (the globals' stacked order): local or not, and its position: the tail's
  // slot (the tail keeps the caller's order) or the local position (ordered by last state).
  std::vector<char> is_local;
  std::vector<int> position;
  std::vector<int> tail_column, local_column;  // the caller column of each slot / position
  // Per state: the local positions its own blocks touch, [lo, hi) (lo == hi: none), and where
  // its row of the border starts in Information::B (n + 1 entries): tail + hi - lo columns.
  std::vector<int> lo, hi;
  std::vector<size_t> offset;
  // The frontal elimination's steps (FrontalFactorization): at step k the local positions
  // [start[k], end[k]) are open; those below start[k + 1] close with state k (n + 1 starts).
  std::vector<int> start, end;

  int Width(int k) const { return tail + hi[k] - lo[k]; }
  // The column of state k's border row that holds caller column c, and the reverse.
  int Slot(int k, int c) const { return is_local[c] ? tail + position[c] - lo[k] : position[c]; }
  int Column(int k, int slot) const {
    return slot < tail ? tail_column[slot] : local_column[lo[k] + slot - tail];
  }
};

// A dense border: every column in the tail, in the caller's order.
std::shared_ptr<const BorderShape> DenseBorder(int n, int m, int g) {
  auto shape = std::make_shared<BorderShape>();
  shape->g = shape->tail = g;
  shape->is_local.assign(g, 0);
  shape->position.resize(g);
  for (int c = 0; c < g; ++c) shape->position[c] = c;
  shape->tail_column = shape->position;
  shape->lo.assign(n, 0);
  shape->hi.assign(n, 0);
  shape->offset.resize(n + 1);
  for (int k = 0; k <= n; ++k) shape->offset[k] = static_cast<size_t>(k) * m * g;
  shape->start.assign(n + 1, 0);
  shape->end.assign(n, 0);
  return shape;
}

// T^-1 rhs (one block of rows per state) by forward and back substitution through the LDL',
// into *x (its blocks' storage kept where their sizes match).
template <int M, typename Rhs>
void SolveT(const ChainFactorization<M>& f, const std::vector<Rhs>& rhs, std::vector<Rhs>* x) {
  const int n = f.n;
  x->resize(n);
  std::vector<Rhs>& out = *x;
  for (int k = 0; k < n; ++k) {
    if (k > 0) {
      out[k] = rhs[k] - f.N[k - 1] * out[k - 1];
    } else {
      out[0] = rhs[0];
    }
  }
  for (int k = 0; k < n; ++k) out[k] = f.D_inv[k] * out[k];
  for (int k = n - 2; k >= 0; --k) out[k] -= f.N[k].transpose() * out[k + 1];
}

// H = J'J in flat column-major buffers: D[k] = T_kk (upper triangle), U[k] = T_{k,k+1},
// state k's row of the border from B[shape->offset[k]] (m x shape->Width(k): the tail's columns,
// then its own local ones), C (upper triangle, the caller's order); filled one residual block
// at a time.
struct Information {
  Information() { Reset(0, 0, 0, DenseBorder(0, 0, 0)); }

  // Zero, for n states of size m and g globals shaped as `border` (the buffers' memory kept
  // where it suffices).
  void Reset(int states, int size, int global_size, std::shared_ptr<const BorderShape> border) {
    n = states, m = size, g = global_size;
    shape = std::move(border);
    D.assign(static_cast<size_t>(n) * m * m, 0.0);
    U.assign(D.size(), 0.0);
    B.assign(shape->offset[n], 0.0);
    C.assign(static_cast<size_t>(g) * g, 0.0);
    error.clear();
  }
  // State k's row of the border: m x shape->Width(k).
  Eigen::Map<const MatrixXd> Border(int k) const {
    return {B.data() + shape->offset[k], m, shape->Width(k)};
  }

  struct Segment {
    int k, index, position, length;  // state (-1: the globals), first index, first column
  };
  // One caller's part of an assembly: where its globals' block C goes (threads add to their own
  // and sum them after), its scratch, its error.
  struct Part {
    double* C = nullptr;
    std::vector<Segment> segments;
    std::string error;
  };

  // Adds one residual block's Jb' Jb (hb: its upper triangle, row-major, count x count) whose
  // column a is index[a] of state block[a] (-1: of the globals, stacked), the globals' part to
  // part->C. False (with part->error) when the block links states that are not neighbours.
  // Parts that touch different states may add at once.
  bool Add(const int* block, const int* index, int count, const std::vector<double>& hb,
           Part* part) {
    const int mm = m * m;
    std::vector<Segment>& segments = part->segments;
    std::string& error = part->error;
    // Runs of columns of one parameter block with consecutive indices; each pair of runs adds
    // its part of hb to one destination, at origin + ia * sa + ib * sb (no branch per element).
    segments.clear();
    for (int a = 0; a < count; ++a) {
      if (!segments.empty()) {
        Segment& s = segments.back();
        if (s.k == block[a] && s.index + s.length == index[a] && s.position + s.length == a) {
          ++s.length;
          continue;
        }
      }
      segments.push_back({block[a], index[a], a, 1});
    }
    for (size_t si = 0; si < segments.size(); ++si) {
      for (size_t ti = si; ti < segments.size(); ++ti) {
        const Segment& s = segments[si];
        const Segment& t = segments[ti];
        double* origin = nullptr;
        int sa = 1, sb = 1;
        if ((s.k < 0) != (t.k < 0)) {  // a state's row of the border
          AddBorder(s, t, hb, count);
          continue;
        }
        if (s.k < 0) {  // C, upper triangle
          origin = part->C;
          sa = s.index <= t.index ? 1 : g;
          sb = s.index <= t.index ? g : 1;
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

  int n = 0, m = 0, g = 0;
  std::shared_ptr<const BorderShape> shape;
  std::vector<double> D, U, B, C;
  std::string error;

 private:
  // The part of hb between a run of a state's columns and a run of the globals' (in either
  // order), into the state's row of the border.
  void AddBorder(const Segment& s, const Segment& t, const std::vector<double>& hb, int count) {
    const bool global_first = s.k < 0;
    const int k = global_first ? t.k : s.k;
    double* row = B.data() + shape->offset[k];
    for (int i = 0; i < s.length; ++i) {
      const double* h = hb.data() + static_cast<size_t>(s.position + i) * count + t.position;
      for (int j = 0; j < t.length; ++j) {
        const int component = global_first ? t.index + j : s.index + i;
        const int column = global_first ? s.index + i : t.index + j;
        row[component + m * shape->Slot(k, column)] += h[j];
      }
    }
  }
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

// A residual block's cost, rho(|r|^2) / 2, with rho and its derivatives at |r|^2 in rho[3]
// (rho(s) = s without a loss).
double LossCost(const ceres::LossFunction* loss, double squared, double rho[3]) {
  rho[0] = squared, rho[1] = 1.0, rho[2] = 0.0;
  if (loss != nullptr) loss->Evaluate(squared, rho);
  return 0.5 * rho[0];
}

// Where each free parameter block sits: a state (its index) or the globals (its first column
// among theirs), and, for a block with a manifold, its Plus Jacobian at the current values.
struct Layout {
  struct Place {
    int state, first, size, ambient;  // state -1: a global, first: its first index among them
    const Eigen::MatrixXd* plus_jacobian = nullptr;  // ambient x tangent; null: no manifold
  };
  // The states are m-vectors without a manifold (Sizes checks it). places: the states in order,
  // then the globals. indexed: Find works (a hash of every block; needed only to read blocks).
  Layout(const ceres::Problem& problem, const std::vector<double*>& states,
         const std::vector<double*>& globals, int m, bool indexed) {
    places.reserve(states.size() + globals.size());
    for (size_t k = 0; k < states.size(); ++k) places.push_back({static_cast<int>(k), 0, m, m});
    int offset = 0;
    for (double* p : globals) {
      Place place{-1, offset, problem.ParameterBlockTangentSize(p), problem.ParameterBlockSize(p),
                  nullptr};
      if (const ceres::Manifold* manifold = problem.GetManifold(p)) {
        // Ceres' Jacobians are row-major.
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> j(place.ambient,
                                                                                 place.size);
        manifold->PlusJacobian(p, j.data());
        plus_jacobians.emplace_back(j);
        place.plus_jacobian = &plus_jacobians.back();
      }
      places.push_back(place);
      offset += place.size;
    }
    if (!indexed) return;
    where.reserve(places.size());
    for (size_t k = 0; k < states.size(); ++k) where[states[k]] = static_cast<int>(k);
    for (size_t j = 0; j < globals.size(); ++j) {
      where[globals[j]] = static_cast<int>(states.size() + j);
    }
  }
  // The place of a parameter block, -1 when it is neither a state nor a global (held constant).
  int Find(const double* p) const {
    const auto it = where.find(p);
    return it == where.end() ? -1 : it->second;
  }
  std::vector<Place> places;
  std::unordered_map<const double*, int> where;
  std::deque<Eigen::MatrixXd> plus_jacobians;  // stable addresses
};

// Residual blocks as their evaluation needs them, read from the problem once: each block's cost
// and loss functions, its parameter blocks and their places in a Layout of the same states and
// globals. A solve evaluates every block tens of times; going through Ceres' own blocks and a
// hash of the parameters each time costs more than some of the factors do.
struct BlockTable {
  std::vector<ceres::ResidualBlockId> ids;
  std::vector<const ceres::CostFunction*> functions;
  std::vector<const ceres::LossFunction*> losses;
  std::vector<size_t> first{0};     // block b's parameters: [first[b], first[b + 1])
  std::vector<double*> parameters;  // as the cost function takes them
  std::vector<int> places;          // Layout::places index, -1: held constant

  size_t size() const { return ids.size(); }
  void Clear() {
    ids.clear();
    functions.clear();
    losses.clear();
    first.assign(1, 0);
    parameters.clear();
    places.clear();
  }
  // Block `id`, its parameter blocks `blocks` (as the problem lists them) at `at` (Layout::Find).
  void Add(const ceres::Problem& problem, ceres::ResidualBlockId id,
           const std::vector<double*>& blocks, const std::vector<int>& at) {
    ids.push_back(id);
    functions.push_back(problem.GetCostFunctionForResidualBlock(id));
    losses.push_back(problem.GetLossFunctionForResidualBlock(id));
    parameters.insert(parameters.end(), blocks.begin(), blocks.end());
    places.insert(places.end(), at.begin(), at.end());
    first.push_back(parameters.size());
  }
  // Block b's cost, rho(|r|^2) / 2, into *cost; false when it cannot be evaluated.
  bool Cost(size_t b, std::vector<double>* residuals, double* cost) const {
    residuals->resize(functions[b]->num_residuals());
    if (!functions[b]->Evaluate(parameters.data() + first[b], residuals->data(), nullptr)) {
      return false;
    }
    double squared = 0.0;
    for (const double r : *residuals) squared += r * r;
    double rho[3];
    *cost = LossCost(losses[b], squared, rho);
    return true;
  }
};

// The frontal elimination's steps of a shape whose states' [lo, hi) are set: the local positions
// each step opens and closes (BorderShape::start, end), from the state each position closes with
// (`closes`, non-decreasing) and how far each position's couplings on the globals alone reach
// (reach[i] >= i). The front holds every column a state has touched, and a column's couplings
// enter before it closes (a column enters when the front's end passes it; columns close in
// position order). Returns the most local columns a front holds.
int OpenFronts(const std::vector<int>& closes, const std::vector<int>& reach, BorderShape* shape) {
  BorderShape& s = *shape;
  const int n = static_cast<int>(s.lo.size());
  s.start.resize(n + 1);
  for (int k = 0; k <= n; ++k) {
    s.start[k] =
        static_cast<int>(std::lower_bound(closes.begin(), closes.end(), k) - closes.begin());
  }
  s.end.resize(n);
  int end = 0, widest = 0;
  for (int k = 0; k < n; ++k) {
    end = std::max(end, s.hi[k]);
    for (int q = s.start[k]; q < s.start[k + 1]; ++q) end = std::max(end, reach[q] + 1);
    s.end[k] = end;
    widest = std::max(widest, end - s.start[k]);
  }
  return widest;
}

// The border's shape from the blocks each run takes (AssembleFromBlocks' tables): a global
// parameter block is local when the last state any block links it with is not the chain's
// last. Local blocks are ordered by that last state; the blocks on globals alone (a walk between
// nodes) set how far ahead a column's front must reach before it closes.
std::shared_ptr<const BorderShape> ShapeBorder(const std::vector<BlockTable>& tables,
                                               const Layout& layout, int n, int m, int g) {
  const int blocks = static_cast<int>(layout.places.size()) - n;  // global parameter blocks
  // Calls visit(lowest state, highest state) for each residual block that touches a global, its
  // global blocks in `touched` (highest -1: the block touches no state).
  std::vector<int> touched;
  const auto each_block = [&](const auto& visit) {
    for (const BlockTable& table : tables) {
      for (size_t b = 0; b < table.size(); ++b) {
        int lowest = n, highest = -1;
        touched.clear();
        for (size_t i = table.first[b]; i < table.first[b + 1]; ++i) {
          const int p = table.places[i];
          if (p < 0) continue;
          const int state = layout.places[p].state;
          if (state < 0) {
            touched.push_back(p - n);
          } else {
            lowest = std::min(lowest, state);
            highest = std::max(highest, state);
          }
        }
        if (!touched.empty()) visit(highest < 0 ? -1 : lowest, highest);
      }
    }
  };
  std::vector<int> first(blocks, n), last(blocks, -1);
  each_block([&](int lowest, int highest) {
    if (highest < 0) return;
    for (const int j : touched) {
      first[j] = std::min(first[j], lowest);
      last[j] = std::max(last[j], highest);
    }
  });
  std::vector<int> order;
  for (int j = 0; j < blocks; ++j) {
    if (last[j] >= 0 && last[j] < n - 1) order.push_back(j);
  }
  if (order.empty()) return DenseBorder(n, m, g);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return std::make_pair(last[a], first[a]) < std::make_pair(last[b], first[b]);
  });
  auto shape = std::make_shared<BorderShape>();
  BorderShape& s = *shape;
  s.g = g;
  s.is_local.assign(g, 0);
  s.position.assign(g, 0);
  std::vector<int> closes;  // per local position: the state it closes with
  for (const int j : order) {
    const Layout::Place& block = layout.places[n + j];
    for (int i = 0; i < block.size; ++i) {
      const int c = block.first + i;
      s.is_local[c] = 1;
      s.position[c] = static_cast<int>(s.local_column.size());
      s.local_column.push_back(c);
      closes.push_back(last[j]);
    }
  }
  s.local = static_cast<int>(s.local_column.size());
  for (int c = 0; c < g; ++c) {
    if (s.is_local[c]) continue;
    s.position[c] = static_cast<int>(s.tail_column.size());
    s.tail_column.push_back(c);
  }
  s.tail = static_cast<int>(s.tail_column.size());
  // Each state's local positions; how far each local position's couplings on the globals alone
  // reach (reach[i] >= i).
  s.lo.assign(n, s.local);
  s.hi.assign(n, 0);
  std::vector<int> reach(s.local);
  std::iota(reach.begin(), reach.end(), 0);
  each_block([&](int lowest, int highest) {
    int low = s.local, high = 0;
    for (const int j : touched) {
      const Layout::Place& block = layout.places[n + j];
      if (block.size == 0 || !s.is_local[block.first]) continue;
      low = std::min(low, s.position[block.first]);
      high = std::max(high, s.position[block.first] + block.size);
    }
    if (low >= high) return;
    if (highest >= 0) {
      for (const int k : {lowest, highest}) {
        s.lo[k] = std::min(s.lo[k], low);
        s.hi[k] = std::max(s.hi[k], high);
      }
      return;
    }
    for (const int j : touched) {
      const Layout::Place& block = layout.places[n + j];
      if (block.size == 0 || !s.is_local[block.first]) continue;
      for (int i = 0; i < block.size; ++i) {
        int& r = reach[s.position[block.first] + i];
        r = std::max(r, high - 1);
      }
    }
  });
  s.offset.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) {
    if (s.lo[k] >= s.hi[k]) s.lo[k] = s.hi[k] = 0;
    s.offset[k + 1] = s.offset[k] + static_cast<size_t>(m) * s.Width(k);
  }
  const int widest = OpenFronts(closes, reach, &s);
  // A front as wide as half the dense border costs more than the dense border's fixed-size
  // blocks (the window's two nodes at a node's change).
  if (2 * (widest + s.tail) > g) return DenseBorder(n, m, g);
  return shape;
}

// One residual block evaluated as Ceres' solver sees it, with scratch of its own so that threads
// may evaluate different blocks at once: the cost function called on the parameters' values (no
// Ceres state touched), its Jacobian taken to each manifold's tangent space, and residuals and
// Jacobian corrected for the block's loss as Ceres' Corrector does (Triggs et al., "Bundle
// Adjustment - A Modern Synthesis", 2000, sec. 4.3): with s = |r|^2 and rho', rho'' at s, the
// residuals are scaled by sqrt(rho') / (1 - alpha) and the Jacobian becomes
// sqrt(rho') (I - alpha r r' / s) J, alpha = 1 - sqrt(1 + 2 s rho'' / rho'); where rho'' <= 0
// (a loss past its bend) both are only scaled by sqrt(rho'). Checked against
// Problem::Evaluate's cost and gradient in a test.
class BlockEvaluation {
 public:
  BlockEvaluation() = default;
  // block and index point into its own buffers.
  BlockEvaluation(const BlockEvaluation&) = delete;
  BlockEvaluation& operator=(const BlockEvaluation&) = delete;
  // False when the cost function fails or returns a value that is not finite.
  bool Evaluate(const ceres::Problem& problem, ceres::ResidualBlockId id, const Layout& layout) {
    problem.GetParameterBlocksForResidualBlock(id, &blocks_);
    at_.clear();
    for (const double* p : blocks_) at_.push_back(layout.Find(p));
    single_.Clear();
    single_.Add(problem, id, blocks_, at_);
    return Evaluate(single_, 0, layout);
  }
  // Block b of a table built with a Layout of the same states and globals.
  bool Evaluate(const BlockTable& table, size_t b, const Layout& layout) {
    const ceres::CostFunction* function = table.functions[b];
    double* const* parameters = table.parameters.data() + table.first[b];
    const int* place_of = table.places.data() + table.first[b];
    rows = function->num_residuals();
    const size_t count_blocks = table.first[b + 1] - table.first[b];
    if (ambient_.size() < count_blocks) ambient_.resize(count_blocks);
    pointers_.resize(count_blocks);
    places_.resize(count_blocks);
    count = 0;
    for (size_t i = 0; i < count_blocks; ++i) {
      if (place_of[i] < 0) {  // held constant
        pointers_[i] = nullptr;
        places_[i] = nullptr;
        continue;
      }
      const Layout::Place& place = layout.places[place_of[i]];
      places_[i] = &place;
      ambient_[i].resize(static_cast<size_t>(rows) * place.ambient);
      pointers_[i] = ambient_[i].data();
      count += place.size;
    }
    // Each free column's state and index, written in place (the buffers only grow).
    if (block_.size() < static_cast<size_t>(count)) {
      block_.resize(count);
      index_.resize(count);
    }
    int column_at = 0;
    for (size_t i = 0; i < count_blocks; ++i) {
      if (places_[i] == nullptr) continue;
      for (int j = 0; j < places_[i]->size; ++j, ++column_at) {
        block_[column_at] = places_[i]->state;
        index_[column_at] = places_[i]->first + j;
      }
    }
    block = block_.data();
    index = index_.data();
    residuals.resize(rows);
    if (!function->Evaluate(parameters, residuals.data(), pointers_.data())) return false;
    jb.resize(static_cast<size_t>(rows) * count);
    int column = 0;
    for (size_t i = 0; i < count_blocks; ++i) {
      const Layout::Place* place = places_[i];
      if (place == nullptr) continue;
      for (int r = 0; r < rows; ++r) {
        const double* ambient = ambient_[i].data() + static_cast<size_t>(r) * place->ambient;
        double* out = jb.data() + static_cast<size_t>(r) * count + column;
        if (place->plus_jacobian == nullptr) {
          std::copy_n(ambient, place->size, out);
        } else {
          for (int c = 0; c < place->size; ++c) {
            double sum = 0.0;
            for (int a = 0; a < place->ambient; ++a) {
              sum += ambient[a] * (*place->plus_jacobian)(a, c);
            }
            out[c] = sum;
          }
        }
      }
      column += place->size;
    }
    double squared = 0.0;
    for (const double r : residuals) squared += r * r;
    if (!std::isfinite(squared)) return false;
    CorrectForLoss(table.losses[b], squared);
    const auto finite = [](double v) { return std::isfinite(v); };
    if (!std::isfinite(cost) || !std::all_of(jb.begin(), jb.end(), finite) ||
        !std::all_of(residuals.begin(), residuals.end(), finite)) {
      return false;
    }
    DropZeroColumns();
    return true;
  }

  int rows = 0, count = 0;  // residuals, free columns
  // Each free column's state (-1: globals) and index in it (count of each).
  const int* block = nullptr;
  const int* index = nullptr;
  std::vector<double> residuals, jb;  // loss-corrected; jb row-major, rows x count
  double cost = 0.0;

 private:
  void CorrectForLoss(const ceres::LossFunction* loss, double squared) {
    double rho[3];
    cost = LossCost(loss, squared, rho);
    if (loss == nullptr) return;
    const double sqrt_rho1 = std::sqrt(rho[1]);
    if (squared == 0.0 || rho[2] <= 0.0) {
      for (double& r : residuals) r *= sqrt_rho1;
      for (double& j : jb) j *= sqrt_rho1;
      return;
    }
    const double alpha = 1.0 - std::sqrt(1.0 + 2.0 * squared * rho[2] / rho[1]);
    const double alpha_over_s = alpha / squared;
    for (int c = 0; c < count; ++c) {
      double rj = 0.0;  // r' J, column c
      for (int r = 0; r < rows; ++r) rj += residuals[r] * jb[static_cast<size_t>(r) * count + c];
      for (int r = 0; r < rows; ++r) {
        double& j = jb[static_cast<size_t>(r) * count + c];
        j = sqrt_rho1 * (j - alpha_over_s * residuals[r] * rj);
      }
    }
    const double scale = sqrt_rho1 / (1.0 - alpha);
    for (double& r : residuals) r *= scale;
  }

  // Columns whose Jacobian is zero in every row left out (in place, the others' order kept): a
  // factor that reads a few of a state's components (an encoder, a bound) adds nothing to the
  // others' rows of H, and H's sums are the same to the last digit without those zeros.
  void DropZeroColumns() {
    int kept = 0;
    for (int c = 0; c < count; ++c) {
      bool zero = true;
      for (int r = 0; r < rows && zero; ++r) zero = jb[static_cast<size_t>(r) * count + c] == 0.0;
      if (zero) continue;
      if (kept != c) {
        for (int r = 0; r < rows; ++r) {
          jb[static_cast<size_t>(r) * count + kept] = jb[static_cast<size_t>(r) * count + c];
        }
        block_[kept] = block_[c];
        index_[kept] = index_[c];
      }
      ++kept;
    }
    if (kept == count) return;
    // Rows to the new width: row r's kept columns sit at r * count; move them to r * kept.
    for (int r = 1; r < rows; ++r) {
      std::copy_n(jb.data() + static_cast<size_t>(r) * count, kept,
                  jb.data() + static_cast<size_t>(r) * kept);
    }
    count = kept;
    jb.resize(static_cast<size_t>(rows) * count);
  }

  // Evaluate(problem, id, layout)'s: the block's parameters, their places, the table of it.
  std::vector<double*> blocks_;
  std::vector<int> at_;
  BlockTable single_;
  std::vector<std::vector<double>> ambient_;
  std::vector<int> block_, index_;
  std::vector<double*> pointers_;
  std::vector<const Layout::Place*> places_;
};

// H, the gradient J'r (states, then globals) and the cost from each residual block's own
// evaluation (BlockEvaluation): no program and no sparse Jacobian built per call. A block's
// parameters that are neither a state nor a global are held constant, as Problem::Evaluate holds
// the blocks it is not given. The states are cut into runs, each run's blocks summed on its own
// (on `threads` threads; the globals' block of H and of the gradient summed after, in the runs'
// order); the blocks that cross from one run to the next, and those on the globals alone, are
// added after them.
// `partition` (may be null): the blocks each run takes, read from the problem when it does not
// hold a table per run and one for after them; kept, it must come from a call on the same
// problem, states and globals (ChainLinearization keys it on them).
struct Partition {
  std::vector<BlockTable> tables;  // one per run of states, then the blocks after them
  std::shared_ptr<const BorderShape> shape;
  void clear() {
    tables.clear();
    shape.reset();
  }
};
// The blocks are summed in this many runs (at most), whatever the number of threads that take
// them, so that the sums, and so the solution to its last digit, do not depend on the threads.
constexpr int kAssemblyRuns = 8;
// info is reset to the states' size m and the globals' tangent size g, its border shaped by the
// blocks (ShapeBorder).
bool AssembleFromBlocks(ceres::Problem* problem, const std::vector<double*>& states,
                        const std::vector<double*>& globals, int m, int g, Information* info,
                        double* cost, std::vector<double>* gradient, int threads = 1,
                        Partition* partition = nullptr) {
  const int n = static_cast<int>(states.size()), state_columns = n * m;
  gradient->assign(static_cast<size_t>(state_columns + g), 0.0);
  // The runs of states, and the blocks each takes (the last list: after them).
  const int parts = std::max(1, std::min(kAssemblyRuns, n / 64));
  Partition own;
  Partition& partitioned = partition != nullptr ? *partition : own;
  std::vector<BlockTable>& taken = partitioned.tables;
  const bool read = taken.size() != static_cast<size_t>(parts) + 1;
  const Layout layout(*problem, states, globals, m, read);
  if (read) {
    taken.assign(parts + 1, {});
    std::vector<ceres::ResidualBlockId> ids;
    problem->GetResidualBlocks(&ids);
    std::vector<double*> blocks;
    std::vector<int> at;
    for (const ceres::ResidualBlockId id : ids) {
      problem->GetParameterBlocksForResidualBlock(id, &blocks);
      at.clear();
      for (const double* p : blocks) at.push_back(layout.Find(p));
      int part = 0;
      if (parts > 1) {
        int lowest = n, highest = -1;
        for (const int place : at) {
          if (place < 0 || layout.places[place].state < 0) continue;
          lowest = std::min(lowest, layout.places[place].state);
          highest = std::max(highest, layout.places[place].state);
        }
        part = highest < 0 ? parts : static_cast<int>(static_cast<long>(lowest) * parts / n);
        const int end = static_cast<int>(static_cast<long>(n) * (part + 1) / parts);
        if (highest >= end) part = parts;
      }
      taken[part].Add(*problem, id, blocks, at);
    }
    partitioned.shape = ShapeBorder(taken, layout, n, m, g);
  }
  info->Reset(n, m, g, partitioned.shape);
  std::vector<double> Cs(static_cast<size_t>(parts) * g * g, 0.0);
  std::vector<double> globals_gradient(static_cast<size_t>(parts) * g, 0.0);
  std::vector<double> costs(parts, 0.0);
  std::vector<std::string> errors(parts);
  const auto assemble = [&](const BlockTable& list, double* C, double* gradient_globals,
                            double* part_cost, std::string* error) {
    BlockEvaluation e;
    Information::Part part;
    part.C = C;
    std::vector<double> hb;
    for (size_t b = 0; b < list.size(); ++b) {
      if (!e.Evaluate(list, b, layout)) {
        *error = "a residual block could not be evaluated";
        return;
      }
      *part_cost += e.cost;
      if (e.count == 0) continue;
      for (int a = 0; a < e.count; ++a) {
        double sum = 0.0;
        for (int r = 0; r < e.rows; ++r) {
          sum += e.jb[static_cast<size_t>(r) * e.count + a] * e.residuals[r];
        }
        if (e.block[a] < 0) {
          gradient_globals[e.index[a]] += sum;
        } else {
          (*gradient)[static_cast<size_t>(e.block[a]) * m + e.index[a]] += sum;
        }
      }
      AddOuterProducts(e.jb.data(), e.rows, e.count, &hb);
      if (!info->Add(e.block, e.index, e.count, hb, &part)) {
        *error = part.error;
        return;
      }
    }
  };
  RunConcurrently(parts, threads, [&](size_t p) {
    assemble(taken[p], Cs.data() + p * g * g, globals_gradient.data() + p * g, &costs[p],
             &errors[p]);
  });
  std::string last_error;
  double last_cost = 0.0;
  std::vector<double> last_gradient(g, 0.0);
  assemble(taken[parts], info->C.data(), last_gradient.data(), &last_cost, &last_error);
  *cost = last_cost;
  for (int p = 0; p < parts; ++p) {
    if (!errors[p].empty()) {
      info->error = errors[p];
      return false;
    }
    *cost += costs[p];
    for (int i = 0; i < g * g; ++i) info->C[i] += Cs[static_cast<size_t>(p) * g * g + i];
    for (int i = 0; i < g; ++i)
      last_gradient[i] += globals_gradient[static_cast<size_t>(p) * g + i];
  }
  if (!last_error.empty()) {
    info->error = last_error;
    return false;
  }
  std::copy(last_gradient.begin(), last_gradient.end(), gradient->begin() + state_columns);
  return true;
}

// The Levenberg-Marquardt damping of one diagonal element: mu times the element, kept within
// Ceres' bounds for it (min_lm_diagonal, max_lm_diagonal) so a direction no residual reaches is
// damped too.
double Damping(double mu, double diagonal) { return mu * std::clamp(diagonal, 1e-6, 1e32); }

// Factors an assembled H (plus mu diag(H) when mu > 0, a Levenberg-Marquardt step); false (with
// f->error) when it is not positive definite.
template <int M>
bool Factor(const Information& info, ChainFactorization<M>* f, double mu = 0.0,
            const std::vector<char>* held = nullptr) {
  using Block = typename ChainFactorization<M>::Block;
  const int n = info.n, m = info.m, g = info.g, mm = m * m;
  f->n = n, f->m = m, f->g = g;
  const std::vector<double>&Dbuf = info.D, &Ubuf = info.U, &Cbuf = info.C;
  // A held column (held[column] != 0) is cut from H and gets a unit diagonal: its step is 0.
  const auto is_held = [&](int column) { return held != nullptr && (*held)[column] != 0; };
  f->B.resize(n);
  for (int k = 0; k < n; ++k) {
    f->B[k] = info.Border(k);  // the dense border: every column in the tail
    if (held == nullptr) continue;
    for (int i = 0; i < m; ++i) {
      if (is_held(k * m + i)) f->B[k].row(i).setZero();
    }
    for (int j = 0; j < g; ++j) {
      if (is_held(n * m + j)) f->B[k].col(j).setZero();
    }
  }
  // Block LDL' of T: D_k <- pivots, N_k = T_{k+1,k} D_k^-1.
  f->N.resize(n);
  f->D_inv.resize(n);
  Block D, U_previous;
  for (int k = 0; k < n; ++k) {
    D = Eigen::Map<const MatrixXd>(Dbuf.data() + static_cast<size_t>(k) * mm, m, m)
            .template selfadjointView<Eigen::Upper>();
    if (mu > 0.0) {
      for (int i = 0; i < m; ++i) D(i, i) += Damping(mu, D(i, i));
    }
    for (int i = 0; held != nullptr && i < m; ++i) {
      if (!is_held(k * m + i)) continue;
      D.row(i).setZero();
      D.col(i).setZero();
      D(i, i) = 1.0;
    }
    if (k > 0) D -= f->N[k - 1] * U_previous;
    Eigen::LLT<Block> llt(D);
    if (llt.info() != Eigen::Success) {
      f->error = "the information of state " + std::to_string(k) +
                 " is not positive definite (a direction no factor constrains)";
      return false;
    }
    f->D_inv[k] = llt.solve(Block::Identity(m, m));
    U_previous = Eigen::Map<const MatrixXd>(Ubuf.data() + static_cast<size_t>(k) * mm, m, m);
    for (int i = 0; held != nullptr && k + 1 < n && i < m; ++i) {
      if (is_held(k * m + i)) U_previous.row(i).setZero();
      if (is_held((k + 1) * m + i)) U_previous.col(i).setZero();
    }
    if (k + 1 < n) f->N[k] = U_previous.transpose() * f->D_inv[k];
  }
  if (g == 0) return true;
  // The border: X = T^-1 B, S = C - B' X.
  SolveT(*f, f->B, &f->X);
  MatrixXd S = Eigen::Map<const MatrixXd>(Cbuf.data(), g, g).selfadjointView<Eigen::Upper>();
  if (mu > 0.0) {
    for (int i = 0; i < g; ++i) S(i, i) += Damping(mu, S(i, i));
  }
  for (int j = 0; held != nullptr && j < g; ++j) {
    if (!is_held(n * m + j)) continue;
    S.row(j).setZero();
    S.col(j).setZero();
    S(j, j) = 1.0;
  }
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

// The chain with a local border (BorderShape) eliminated as a front moving along it: step k
// eliminates the pivot P_k = [x_k, the local columns that close with state k] against the rest
// R_k = [x_{k+1}, the local columns still open, the tail], with Phi the front's information
// (H's entries as they enter, less what earlier steps eliminated):
//
//   A_k = Phi_PP,   L_k = Phi_RP A_k^-1,   Phi_RR <- Phi_RR - L_k Phi_RP',
//
// and the tail's Schur complement S is left at the end. A front holds a state, the next, the local
// columns open around them and the tail, where the dense border's X = T^-1 B holds every column
// for every state: the states' share of memory and time does not grow with the local columns
// (C, g x g, does).
struct FrontalFactorization {
  std::shared_ptr<const BorderShape> shape;
  int n = 0, m = 0;
  std::vector<size_t> a_at, l_at;  // per step: A_k^-1 (p x p), L_k (r x p), column-major
  std::vector<double> a_inv, l;
  Eigen::LLT<MatrixXd> S;
  std::string error;

  int Pivot(int k) const { return m + shape->start[k + 1] - shape->start[k]; }
  int Rest(int k) const {
    return (k + 1 < n ? m : 0) + shape->end[k] - shape->start[k + 1] + shape->tail;
  }
  // The front of step k, [P_k, R_k], as variables: a state's component k m + i, the globals'
  // column c as n m + c (gradient()'s order).
  void Variables(int k, std::vector<int>* out) const {
    const BorderShape& s = *shape;
    out->clear();
    for (int i = 0; i < m; ++i) out->push_back(k * m + i);
    for (int q = s.start[k]; q < s.start[k + 1]; ++q) out->push_back(n * m + s.local_column[q]);
    for (int i = 0; k + 1 < n && i < m; ++i) out->push_back((k + 1) * m + i);
    for (int q = s.start[k + 1]; q < s.end[k]; ++q) out->push_back(n * m + s.local_column[q]);
    for (const int c : s.tail_column) out->push_back(n * m + c);
  }
  // Where variable v sits in step k's front; -1: not in it.
  int Position(int k, int v) const {
    const BorderShape& s = *shape;
    const int p = Pivot(k), r = Rest(k);
    if (v < n * m) {
      if (v / m == k) return v % m;
      return v / m == k + 1 ? p + v % m : -1;
    }
    const int c = v - n * m;
    if (!s.is_local[c]) return p + r - s.tail + s.position[c];
    const int q = s.position[c];
    if (q >= s.start[k] && q < s.start[k + 1]) return m + q - s.start[k];
    if (q >= s.start[k + 1] && q < s.end[k]) return p + (k + 1 < n ? m : 0) + q - s.start[k + 1];
    return -1;
  }
};

// H's entries as they enter the fronts of FactorFrontal, each once: a state's own (D_k, U_k, its
// row of the border) at its step, C's for a column when it enters (the tail at the first step, a
// local column when the front reaches it) with every column already in the front; damped on H's
// own diagonal and cut where a variable is held, as Factor does them.
class FrontEntries {
 public:
  FrontEntries(const Information& info, double mu, const std::vector<char>* held)
      : info_(info), mu_(mu), held_(held) {}

  // Adds step k's entries to its front (variables: FrontalFactorization::Variables(k)).
  void Enter(const FrontalFactorization& f, int k, const std::vector<int>& variables,
             MatrixXd* front) const {
    EnterState(f, k, front);
    EnterColumns(k, variables, front);
  }

 private:
  bool Held(int v) const { return held_ != nullptr && (*held_)[v] != 0; }
  // The entry between variables a and b at front positions i and j (and j, i).
  void Add(MatrixXd* phi, int i, int j, int a, int b, double value) const {
    if (Held(a) || Held(b)) return;
    (*phi)(i, j) += value;
    if (i != j) (*phi)(j, i) += value;
  }
  // A diagonal entry: damped, or 1 where the variable is held.
  void AddDiagonal(MatrixXd* phi, int i, int a, double value) const {
    (*phi)(i, i) += Held(a) ? 1.0 : value + (mu_ > 0.0 ? Damping(mu_, value) : 0.0);
  }
  double C(int a, int b) const {  // the caller's order, upper triangle
    return info_
        .C[static_cast<size_t>(std::min(a, b)) + static_cast<size_t>(info_.g) * std::max(a, b)];
  }

  void EnterState(const FrontalFactorization& f, int k, MatrixXd* front) const {
    const int n = info_.n, m = info_.m, mm = m * m, p = f.Pivot(k);
    const double* D = info_.D.data() + static_cast<size_t>(k) * mm;
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < j; ++i) Add(front, i, j, k * m + i, k * m + j, D[i + m * j]);
      AddDiagonal(front, j, k * m + j, D[j + m * j]);
    }
    if (k + 1 < n) {
      const double* U = info_.U.data() + static_cast<size_t>(k) * mm;
      for (int j = 0; j < m; ++j) {
        for (int i = 0; i < m; ++i) Add(front, i, p + j, k * m + i, (k + 1) * m + j, U[i + m * j]);
      }
    }
    const Eigen::Map<const MatrixXd> B = info_.Border(k);
    for (int slot = 0; slot < B.cols(); ++slot) {
      const int v = n * m + info_.shape->Column(k, slot);
      const int j = f.Position(k, v);
      for (int i = 0; i < m; ++i) Add(front, i, j, k * m + i, v, B(i, slot));
    }
  }

  void EnterColumns(int k, const std::vector<int>& variables, MatrixXd* front) const {
    const BorderShape& s = *info_.shape;
    const int nm = info_.n * info_.m, size = static_cast<int>(variables.size());
    const int entered = k == 0 ? 0 : s.end[k - 1];  // local positions from here enter now
    const auto enters = [&](int c) { return s.is_local[c] ? s.position[c] >= entered : k == 0; };
    for (int a = 0; a < size; ++a) {
      const int va = variables[a];
      if (va < nm || !enters(va - nm)) continue;
      for (int b = 0; b < size; ++b) {
        const int vb = variables[b];
        if (vb < nm || (b > a && enters(vb - nm))) continue;  // both enter: once
        if (b == a) {
          AddDiagonal(front, a, va, C(va - nm, va - nm));
        } else {
          Add(front, a, b, va, vb, C(va - nm, vb - nm));
        }
      }
    }
  }

  const Information& info_;
  double mu_;
  const std::vector<char>* held_;
};

// Factors an assembled H with a local border as FrontalFactorization (mu and held as Factor's).
bool FactorFrontal(const Information& info, FrontalFactorization* f, double mu = 0.0,
                   const std::vector<char>* held = nullptr) {
  const int n = info.n, m = info.m;
  f->shape = info.shape;
  f->n = n, f->m = m;
  f->a_at.resize(n + 1);
  f->l_at.resize(n + 1);
  f->a_at[0] = f->l_at[0] = 0;
  int widest = 0;
  for (int k = 0; k < n; ++k) {
    const int p = f->Pivot(k), r = f->Rest(k);
    f->a_at[k + 1] = f->a_at[k] + static_cast<size_t>(p) * p;
    f->l_at[k + 1] = f->l_at[k] + static_cast<size_t>(r) * p;
    widest = std::max(widest, p + r);
  }
  f->a_inv.resize(f->a_at[n]);
  f->l.resize(f->l_at[n]);
  const FrontEntries entries(info, mu, held);
  MatrixXd front(widest, widest), carried(widest, widest), identity;
  std::vector<int> variables, previous, moved;
  int carried_size = 0;
  for (int k = 0; k < n; ++k) {
    const int p = f->Pivot(k), r = f->Rest(k), size = p + r;
    f->Variables(k, &variables);
    auto phi = front.topLeftCorner(size, size);
    phi.setZero();
    // The previous step's rest, [x_k, the open columns, the tail], moved into this front.
    moved.resize(carried_size);
    for (int i = 0; i < carried_size; ++i) moved[i] = f->Position(k, previous[i]);
    for (int j = 0; j < carried_size; ++j) {
      for (int i = 0; i < carried_size; ++i) phi(moved[i], moved[j]) = carried(i, j);
    }
    entries.Enter(*f, k, variables, &front);
    // Eliminate the pivot.
    Eigen::LLT<MatrixXd> llt(phi.topLeftCorner(p, p));
    if (llt.info() != Eigen::Success) {
      f->error = "the information of state " + std::to_string(k) +
                 (p > m ? " and the border columns that close with it" : "") +
                 " is not positive definite (a direction no factor constrains)";
      return false;
    }
    Eigen::Map<MatrixXd> A_inv(f->a_inv.data() + f->a_at[k], p, p);
    if (identity.rows() != p) identity = MatrixXd::Identity(p, p);
    A_inv = llt.solve(identity);
    Eigen::Map<MatrixXd> L(f->l.data() + f->l_at[k], r, p);
    L.noalias() = phi.bottomLeftCorner(r, p) * A_inv;
    auto rest = carried.topLeftCorner(r, r);
    rest = phi.bottomRightCorner(r, r);
    rest.noalias() -= L * phi.bottomLeftCorner(r, p).transpose();
    carried_size = r;
    previous.assign(variables.begin() + p, variables.end());
  }
  const int tail = info.shape->tail;
  if (tail == 0) return true;
  f->S.compute(carried.topLeftCorner(tail, tail));
  if (f->S.info() != Eigen::Success) {
    f->error = "the global parameters' information is not positive definite";
    return false;
  }
  return true;
}

// H [dx; dg] = -gradient on a frontal factorization: forward through the steps, the tail by S,
// back through the steps.
void SolveFrontal(const FrontalFactorization& f, const std::vector<double>& gradient,
                  std::vector<Eigen::VectorXd>* dx, Eigen::VectorXd* dg) {
  const int n = f.n, m = f.m, nm = n * m;
  Eigen::VectorXd z = -Eigen::Map<const Eigen::VectorXd>(gradient.data(), gradient.size());
  std::vector<int> variables;
  Eigen::VectorXd pivot, rest;
  for (int k = 0; k < n; ++k) {
    const int p = f.Pivot(k), r = f.Rest(k);
    f.Variables(k, &variables);
    pivot.resize(p);
    for (int i = 0; i < p; ++i) pivot[i] = z[variables[i]];
    rest.noalias() = Eigen::Map<const MatrixXd>(f.l.data() + f.l_at[k], r, p) * pivot;
    for (int i = 0; i < r; ++i) z[variables[p + i]] -= rest[i];
  }
  const BorderShape& s = *f.shape;
  if (s.tail > 0) {
    Eigen::VectorXd tail(s.tail);
    for (int i = 0; i < s.tail; ++i) tail[i] = z[nm + s.tail_column[i]];
    tail = f.S.solve(tail);
    for (int i = 0; i < s.tail; ++i) z[nm + s.tail_column[i]] = tail[i];
  }
  for (int k = n - 1; k >= 0; --k) {
    const int p = f.Pivot(k), r = f.Rest(k);
    f.Variables(k, &variables);
    pivot.resize(p);
    rest.resize(r);
    for (int i = 0; i < p; ++i) pivot[i] = z[variables[i]];
    for (int i = 0; i < r; ++i) rest[i] = z[variables[p + i]];
    pivot = Eigen::Map<const MatrixXd>(f.a_inv.data() + f.a_at[k], p, p) * pivot;
    pivot.noalias() -= Eigen::Map<const MatrixXd>(f.l.data() + f.l_at[k], r, p).transpose() * rest;
    for (int i = 0; i < p; ++i) z[variables[i]] = pivot[i];
  }
  dx->resize(n);
  for (int k = 0; k < n; ++k) (*dx)[k] = z.segment(static_cast<Eigen::Index>(k) * m, m);
  *dg = z.tail(static_cast<Eigen::Index>(gradient.size()) - nm);
}

// Takahashi's recursion on the fronts, from the tail's S^-1 back to the first step: with Sigma_RR
// the covariance of step k's rest (a part of step k + 1's front),
//   Sigma_RP = -Sigma_RR L_k,   Sigma_PP = A_k^-1 - L_k' Sigma_RP.
// The globals' covariance holds the tail's, each local column's and those between columns that
// share a front; the entries between local columns that never do are not computed (NaN).
ChainCovariance MarginalsFrontal(const FrontalFactorization& f, int first_states = -1) {
  const int n = f.n, m = f.m, nm = n * m;
  const BorderShape& s = *f.shape;
  ChainCovariance out;
  const bool all = first_states < 0;
  const int wanted = all ? n : std::min(n, first_states);
  out.states.assign(n, MatrixXd());
  if (all) out.next.assign(n > 0 ? n - 1 : 0, MatrixXd());
  out.globals = MatrixXd::Constant(s.g, s.g, std::numeric_limits<double>::quiet_NaN());
  MatrixXd tail = s.tail > 0 ? f.S.solve(MatrixXd::Identity(s.tail, s.tail)) : MatrixXd();
  for (int i = 0; i < s.tail; ++i) {
    for (int j = 0; j < s.tail; ++j) out.globals(s.tail_column[i], s.tail_column[j]) = tail(i, j);
  }
  MatrixXd later = tail, front, rest_cov;  // step k + 1's front covariance
  std::vector<int> variables, at;
  for (int k = n - 1; k >= 0; --k) {
    const int p = f.Pivot(k), r = f.Rest(k);
    f.Variables(k, &variables);
    rest_cov.resize(r, r);
    if (k == n - 1) {
      rest_cov = later;
    } else {
      at.resize(r);
      for (int i = 0; i < r; ++i) at[i] = f.Position(k + 1, variables[p + i]);
      for (int j = 0; j < r; ++j) {
        for (int i = 0; i < r; ++i) rest_cov(i, j) = later(at[i], at[j]);
      }
    }
    const Eigen::Map<const MatrixXd> L(f.l.data() + f.l_at[k], r, p);
    front.resize(p + r, p + r);
    front.bottomRightCorner(r, r) = rest_cov;
    front.bottomLeftCorner(r, p).noalias() = -rest_cov * L;
    front.topLeftCorner(p, p) = Eigen::Map<const MatrixXd>(f.a_inv.data() + f.a_at[k], p, p);
    front.topLeftCorner(p, p).noalias() -= L.transpose() * front.bottomLeftCorner(r, p);
    front.topRightCorner(p, r) = front.bottomLeftCorner(r, p).transpose();
    if (k < wanted) out.states[k] = front.topLeftCorner(m, m);
    if (all && k + 1 < n) out.next[k] = front.block(p, 0, m, m);
    for (int j = 0; j < p + r; ++j) {
      if (variables[j] < nm) continue;
      for (int i = 0; i < p + r; ++i) {
        if (variables[i] >= nm) out.globals(variables[i] - nm, variables[j] - nm) = front(i, j);
      }
    }
    std::swap(later, front);
  }
  out.ok = true;
  return out;
}

// The factorization of either border: ChainFactorization's dense one, or the frontal one where
// the border has local columns.
template <int M>
struct AnyFactorization {
  ChainFactorization<M> chain;
  FrontalFactorization frontal;
  bool frontal_used = false;
  const std::string& error() const { return frontal_used ? frontal.error : chain.error; }
};

template <int M>
bool FactorAny(const Information& info, AnyFactorization<M>* f, double mu = 0.0,
               const std::vector<char>* held = nullptr) {
  f->frontal_used = info.shape->local > 0;
  return f->frontal_used ? FactorFrontal(info, &f->frontal, mu, held)
                         : Factor(info, &f->chain, mu, held);
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
    if (problem->GetManifold(x) != nullptr) {
      *error = "a state has a manifold (only the globals may)";
      return false;
    }
  }
  return true;
}

// H, the gradient and the cost at the current values, factored; false with *error.
template <int M>
bool Linearize(ceres::Problem* problem, const std::vector<double*>& states,
               const std::vector<double*>& globals, int m, int g, double* cost,
               std::vector<double>* gradient, AnyFactorization<M>* f, std::string* error,
               int threads = 1) {
  Information info;
  if (!AssembleFromBlocks(problem, states, globals, m, g, &info, cost, gradient, threads)) {
    *error = info.error;
    return false;
  }
  if (!FactorAny(info, f)) {
    *error = f->error();
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
  std::vector<Vector> minus_gx(n), y;
  for (int k = 0; k < n; ++k) {
    minus_gx[k] = -Eigen::Map<const Eigen::VectorXd>(gradient.data() + k * m, m);
  }
  SolveT(f, minus_gx, &y);
  dx->resize(n);  // a previous step's vectors are reused
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
void Solve(const AnyFactorization<M>& f, const std::vector<double>& gradient,
           std::vector<Eigen::VectorXd>* dx, Eigen::VectorXd* dg) {
  if (f.frontal_used) {
    SolveFrontal(f.frontal, gradient, dx, dg);
  } else {
    Solve(f.chain, gradient, dx, dg);
  }
}

template <int M>
ChainCovariance Marginals(const AnyFactorization<M>& f, int first_states = -1) {
  return f.frontal_used ? MarginalsFrontal(f.frontal, first_states)
                        : Marginals(f.chain, first_states);
}

template <int M>
void SensitivityAt(ceres::Problem* problem, const std::vector<double*>& states,
                   const std::vector<double*>& globals, int m, int g, const ResidualShifts& shifts,
                   int threads, ChainSensitivity* out) {
  Eigen::Index rows = 0;
  for (const ceres::ResidualBlockId id : shifts.blocks) {
    rows += problem->GetCostFunctionForResidualBlock(id)->num_residuals();
  }
  for (const Eigen::VectorXd& t : shifts.columns) {
    if (t.size() != rows) {
      out->error = "a residual shift has " + std::to_string(t.size()) + " rows, its blocks " +
                   std::to_string(rows);
      return;
    }
  }
  AnyFactorization<M> f;
  double cost = 0.0;
  std::vector<double> gradient;
  if (!Linearize(problem, states, globals, m, g, &cost, &gradient, &f, &out->error, threads)) {
    return;
  }
  // J' t, block by block over the blocks the shifts move.
  const size_t columns = shifts.columns.size();
  const int n = static_cast<int>(states.size()), state_columns = n * m;
  std::vector<std::vector<double>> jt(columns, std::vector<double>(state_columns + g, 0.0));
  const Layout layout(*problem, states, globals, m, true);
  BlockEvaluation e;
  Eigen::Index row = 0;
  for (const ceres::ResidualBlockId id : shifts.blocks) {
    if (!e.Evaluate(*problem, id, layout)) {
      out->error = "a residual block could not be evaluated";
      return;
    }
    for (size_t j = 0; j < columns; ++j) {
      const Eigen::VectorXd& t = shifts.columns[j];
      for (int a = 0; a < e.count; ++a) {
        double sum = 0.0;
        for (int r = 0; r < e.rows; ++r) {
          sum += e.jb[static_cast<size_t>(r) * e.count + a] * t[row + r];
        }
        const int column =
            e.block[a] < 0 ? state_columns + e.index[a] : e.block[a] * m + e.index[a];
        jt[j][column] += sum;
      }
    }
    row += e.rows;
  }
  out->states.resize(columns);
  out->globals.resize(columns);
  for (size_t j = 0; j < columns; ++j) Solve(f, jt[j], &out->states[j], &out->globals[j]);
  out->ok = true;
}

}  // namespace

ChainSensitivity ComputeChainSensitivity(ceres::Problem* problem,
                                         const std::vector<double*>& states,
                                         const std::vector<double*>& globals,
                                         const ResidualShifts& shifts, int threads) {
  ChainSensitivity out;
  int m = 0, g = 0;
  if (!Sizes(problem, states, globals, &m, &g, &out.error)) return out;
  if (shifts.columns.empty()) {
    out.ok = true;
    return out;
  }
  if (m == 7) {
    SensitivityAt<7>(problem, states, globals, m, g, shifts, threads, &out);
  } else {
    SensitivityAt<Eigen::Dynamic>(problem, states, globals, m, g, shifts, threads, &out);
  }
  return out;
}

namespace {

template <int M>
ChainCovariance CovarianceAt(ceres::Problem* problem, const std::vector<double*>& states,
                             const std::vector<double*>& globals, int m, int g, int threads) {
  ChainCovariance out;
  AnyFactorization<M> f;
  double cost = 0.0;
  std::vector<double> gradient;
  if (!Linearize(problem, states, globals, m, g, &cost, &gradient, &f, &out.error, threads)) {
    return out;
  }
  return Marginals(f);
}

}  // namespace

struct ChainLinearization::Impl {
  Information info;
  std::vector<double> gradient;
  double cost = 0.0;
  // Which blocks each run takes, kept while the problem's shape is the same, and the states'
  // and the globals' sizes.
  Partition partition;
  struct Shape {
    const ceres::Problem* problem = nullptr;
    std::vector<double*> states, globals;
    int residual_blocks = 0;
    bool operator==(const Shape& o) const {
      return problem == o.problem && residual_blocks == o.residual_blocks && states == o.states &&
             globals == o.globals;
    }
  };
  Shape partition_of;
  void Forget() {
    partition.clear();
    partition_of = Shape{};
  }
  int m = 0, g = 0;
  // The last step's factorization, its storage reused by the next (7: the Ward state).
  AnyFactorization<7> factorization7;
  AnyFactorization<Eigen::Dynamic> factorization;
  bool factored = false;  // the last Step succeeded
};

ChainLinearization::ChainLinearization() : impl_(std::make_unique<Impl>()) {}
ChainLinearization::~ChainLinearization() = default;
ChainLinearization::ChainLinearization(ChainLinearization&&) noexcept = default;
ChainLinearization& ChainLinearization::operator=(ChainLinearization&&) noexcept = default;

bool ChainLinearization::Linearize(ceres::Problem* problem, const std::vector<double*>& states,
                                   const std::vector<double*>& globals, std::string* error,
                                   int threads) {
  impl_->factored = false;
  Impl::Shape shape{problem, states, globals, problem->NumResidualBlocks()};
  if (!(shape == impl_->partition_of)) {
    // Every state's size is checked once per shape (a map lookup each).
    impl_->Forget();
    if (!Sizes(problem, states, globals, &impl_->m, &impl_->g, error)) return false;
    impl_->partition_of = std::move(shape);
  }
  int g = 0;
  for (double* p : globals) g += problem->ParameterBlockTangentSize(p);
  if (g != impl_->g) {
    impl_->Forget();
    *error = "the globals' tangent size changed";
    return false;
  }
  if (!AssembleFromBlocks(problem, states, globals, impl_->m, g, &impl_->info, &impl_->cost,
                          &impl_->gradient, threads, &impl_->partition)) {
    *error = impl_->info.error;
    return false;
  }
  return true;
}

double ChainLinearization::cost() const { return impl_->cost; }

int ChainLinearization::LocalBorderColumns() const {
  return impl_->partition.shape == nullptr ? 0 : impl_->partition.shape->local;
}

bool ChainLinearization::Cost(double* cost, int threads) const {
  const std::vector<BlockTable>& taken = impl_->partition.tables;
  if (taken.empty()) return false;
  std::vector<double> costs(taken.size(), 0.0);
  std::vector<char> ok(taken.size(), 1);
  RunConcurrently(taken.size(), threads, [&](size_t p) {
    std::vector<double> residuals;
    for (size_t b = 0; b < taken[p].size(); ++b) {
      double block_cost = 0.0;
      if (!taken[p].Cost(b, &residuals, &block_cost)) {
        ok[p] = 0;
        return;
      }
      costs[p] += block_cost;
    }
  });
  // In AssembleFromBlocks' order (the blocks after the runs first), so that at the point of
  // linearization this is cost() to its last digit.
  const size_t last = taken.size() - 1;
  if (!ok[last]) return false;
  *cost = costs[last];
  for (size_t p = 0; p < last; ++p) {
    if (!ok[p]) return false;
    *cost += costs[p];
  }
  return std::isfinite(*cost);
}

const std::vector<double>& ChainLinearization::gradient() const { return impl_->gradient; }

namespace {

template <int M>
bool DampedStep(const Information& info, const std::vector<double>& gradient, double mu,
                const std::vector<char>* held, AnyFactorization<M>* factorization,
                ChainStep* step) {
  AnyFactorization<M>& f = *factorization;
  if (!FactorAny(info, &f, mu, held)) {
    step->error = f.error();
    return false;
  }
  if (held == nullptr) {
    Solve(f, gradient, &step->states, &step->globals);
    return true;
  }
  std::vector<double> free_gradient = gradient;
  for (size_t i = 0; i < free_gradient.size(); ++i) {
    if ((*held)[i] != 0) free_gradient[i] = 0.0;
  }
  Solve(f, free_gradient, &step->states, &step->globals);
  return true;
}

}  // namespace

bool ChainLinearization::Step(double mu, ChainStep* step, const std::vector<char>* held) const {
  step->cost = impl_->cost;
  if (held != nullptr && held->size() != impl_->gradient.size()) {
    step->error = "the held columns are not the gradient's";
    return step->ok = false;
  }
  step->ok = impl_->info.m == 7 ? DampedStep<7>(impl_->info, impl_->gradient, mu, held,
                                                &impl_->factorization7, step)
                                : DampedStep<Eigen::Dynamic>(impl_->info, impl_->gradient, mu, held,
                                                             &impl_->factorization, step);
  impl_->factored = step->ok;
  return step->ok;
}

ChainCovariance ChainLinearization::LastStepCovariance(int states) const {
  if (!impl_->factored) {
    ChainCovariance out;
    out.error = "no step factored";
    return out;
  }
  return impl_->info.m == 7 ? Marginals(impl_->factorization7, states)
                            : Marginals(impl_->factorization, states);
}

double ChainLinearization::Slope(const std::vector<Eigen::VectorXd>& states,
                                 const Eigen::VectorXd& globals) const {
  const int n = impl_->info.n, m = impl_->info.m, g = impl_->info.g;
  using Eigen::Map;
  using Eigen::VectorXd;
  double slope = 0.0;
  for (int k = 0; k < n; ++k) {
    slope +=
        Map<const VectorXd>(impl_->gradient.data() + static_cast<size_t>(k) * m, m).dot(states[k]);
  }
  if (g > 0) {
    slope +=
        Map<const VectorXd>(impl_->gradient.data() + static_cast<size_t>(n) * m, g).dot(globals);
  }
  return slope;
}

double ChainLinearization::PredictedDecrease(const std::vector<Eigen::VectorXd>& states,
                                             const Eigen::VectorXd& globals) const {
  const Information& info = impl_->info;
  const int n = info.n, m = info.m, g = info.g, mm = m * m;
  using Eigen::Map;
  using Eigen::VectorXd;
  const double linear = Slope(states, globals);
  double quadratic = 0.0;  // d'H d
  for (int k = 0; k < n; ++k) {
    const VectorXd& d = states[k];
    const Map<const MatrixXd> D(info.D.data() + static_cast<size_t>(k) * mm, m, m);
    quadratic += d.dot(D.selfadjointView<Eigen::Upper>() * d);
    if (k + 1 < n) {
      const Map<const MatrixXd> U(info.U.data() + static_cast<size_t>(k) * mm, m, m);
      quadratic += 2.0 * d.dot(U * states[k + 1]);
    }
    const Map<const MatrixXd> B = info.Border(k);
    for (int slot = 0; slot < B.cols(); ++slot) {
      quadratic += 2.0 * d.dot(B.col(slot)) * globals[info.shape->Column(k, slot)];
    }
  }
  if (g > 0) {
    const Map<const MatrixXd> C(info.C.data(), g, g);
    quadratic += globals.dot(C.selfadjointView<Eigen::Upper>() * globals);
  }
  return -(linear + 0.5 * quadratic);
}

ChainCovariance ComputeChainCovariance(ceres::Problem* problem, const std::vector<double*>& states,
                                       const std::vector<double*>& globals, int threads) {
  int m = 0, g = 0;
  ChainCovariance out;
  if (!Sizes(problem, states, globals, &m, &g, &out.error)) return out;
  return m == 7 ? CovarianceAt<7>(problem, states, globals, m, g, threads)
                : CovarianceAt<Eigen::Dynamic>(problem, states, globals, m, g, threads);
}

}  // namespace slipgraph
