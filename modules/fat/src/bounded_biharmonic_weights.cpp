#include "vesalius/fat/bounded_biharmonic_weights.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/sparse_cholesky.h"

#include <Eigen/SparseCore>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>
#include <string>

namespace vesalius::fat {

namespace {

using Index = Eigen::Index;
using SparseMatrix = Eigen::SparseMatrix<double>;

const int kStep[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// Domain voxels 6-connected to a handle voxel: a part of the domain without one has no weights.
std::vector<char> reachableFromHandles(const Grid<std::int32_t>& labels) {
  const GridGeometry& g = labels.geometry;
  std::vector<char> reached(labels.values.size(), 0);
  std::deque<Eigen::Vector3i> queue;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        if (labels.at(i, j, k) > 0) reached[g.linearIndex(i, j, k)] = 1, queue.emplace_back(i, j, k);
  while (!queue.empty()) {
    const Eigen::Vector3i v = queue.front();
    queue.pop_front();
    for (const auto& s : kStep) {
      const Eigen::Vector3i n = v + Eigen::Vector3i(s[0], s[1], s[2]);
      if (!g.contains(n.x(), n.y(), n.z())) continue;
      const std::int64_t l = g.linearIndex(n.x(), n.y(), n.z());
      if (reached[l] || labels.values[l] < 0) continue;
      reached[l] = 1;
      queue.push_back(n);
    }
  }
  return reached;
}

// The Neumann graph Laplacian over the rows' voxels, axis weights (s_min / s_a)².
SparseMatrix gridLaplacian(const BoundedBiharmonicWeights& b) {
  const GridGeometry& g = b.geometry;
  const double sMin = g.spacing.minCoeff();
  std::vector<Eigen::Triplet<double>> t;
  for (Index r = 0; r < Index(b.voxel.size()); ++r) {
    const std::int64_t v = b.voxel[r];
    const Eigen::Vector3i at(int(v % g.size.x()), int((v / g.size.x()) % g.size.y()), int(v / (std::int64_t(g.size.x()) * g.size.y())));
    double diagonal = 0;
    for (int a = 0; a < 6; ++a) {
      const Eigen::Vector3i n = at + Eigen::Vector3i(kStep[a][0], kStep[a][1], kStep[a][2]);
      if (!g.contains(n.x(), n.y(), n.z())) continue;
      const std::int32_t c = b.row[g.linearIndex(n.x(), n.y(), n.z())];
      if (c < 0) continue;
      const double w = std::pow(sMin / g.spacing[a / 2], 2);
      t.emplace_back(r, c, w);
      diagonal -= w;
    }
    t.emplace_back(r, r, diagonal);
  }
  SparseMatrix L(Index(b.voxel.size()), Index(b.voxel.size()));
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

// K with the rows and columns of `fixed` turned into identity rows, the pattern kept (explicit zeros), so
// the Cholesky analysis of K is reused.
SparseMatrix withIdentityRows(const SparseMatrix& K, const std::vector<char>& fixed) {
  SparseMatrix M = K;
  for (Index c = 0; c < M.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(M, c); it; ++it)
      if (fixed[it.row()] || fixed[c]) it.valueRef() = it.row() == c ? 1.0 : 0.0;
  return M;
}

double energy(const SparseMatrix& K, const Eigen::VectorXd& b, const Eigen::VectorXd& w) {
  return 0.5 * w.dot(K * w) - b.dot(w);
}

Eigen::VectorXd clamp01(const Eigen::VectorXd& w) { return w.cwiseMax(0.0).cwiseMin(1.0); }

struct HandleSolution {
  Eigen::VectorXd w;
  int iterations = 0;
  double residual = 0;
  bool projectedNewton = false;  // the active set method cycled
};

// Bertsekas' projected Newton method for min ½ wᵀKw − bᵀw on [0, 1]ⁿ from w (see the header).
HandleSolution projectedNewton(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd w,
                               const BoundedBiharmonicOptions& o, int handle) {
  const Index n = w.size();
  const Eigen::VectorXd diagonal = K.diagonal();
  SparseCholesky cholesky;
  HandleSolution s;
  for (;; ++s.iterations) {
    const Eigen::VectorXd g = K * w - b;
    s.residual = (w - clamp01(w - g)).cwiseAbs().maxCoeff();
    if (s.residual <= o.tolerance) break;
    if (s.iterations == o.maxIterations)
      throw NumericalFailure("bounded biharmonic weights: handle " + std::to_string(handle) + " did not converge in " +
                             std::to_string(o.maxIterations) + " iterations (KKT residual " +
                             std::to_string(s.residual) + ")");
    const double eps = std::min(o.bindingEpsilon, s.residual);
    std::vector<char> binding(n);
    for (Index i = 0; i < n; ++i) binding[i] = (w[i] <= eps && g[i] > 0) || (w[i] >= 1 - eps && g[i] < 0);
    cholesky.factor(withIdentityRows(K, binding));
    Eigen::VectorXd rhs = -g;
    for (Index i = 0; i < n; ++i) if (binding[i]) rhs[i] = 0;
    Eigen::VectorXd d = cholesky.solve(rhs);
    double newtonDecrease = 0;
    for (Index i = 0; i < n; ++i) {
      if (binding[i]) d[i] = -g[i] / diagonal[i];  // Bertsekas' diagonally scaled step on the bounds
      else newtonDecrease -= g[i] * d[i];
    }
    const double f0 = energy(K, b, w);
    double alpha = 1;
    for (int halving = 0;; ++halving, alpha *= 0.5) {
      if (halving == 60) throw NumericalFailure("bounded biharmonic weights: line search failed at handle " + std::to_string(handle));
      const Eigen::VectorXd next = clamp01(w + alpha * d);
      double required = alpha * newtonDecrease;
      for (Index i = 0; i < n; ++i) if (binding[i]) required += g[i] * (w[i] - next[i]);
      if (f0 - energy(K, b, next) >= o.armijo * required) {
        w = next;
        break;
      }
    }
  }
  s.w = std::move(w);
  return s;
}

// The minimiser with the voxels at a bound held there: state 0 free, 1 held at 0, 2 held at 1.
// K_FF w_F = b_F − K_FA c_A, solved in K's pattern (identity rows for the held voxels).
Eigen::VectorXd solveWithHeld(const SparseMatrix& K, const Eigen::VectorXd& b, const std::vector<signed char>& state,
                              SparseCholesky& cholesky) {
  const Index n = b.size();
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
  std::vector<char> held(n);
  for (Index i = 0; i < n; ++i) held[i] = state[i] != 0, c[i] = state[i] == 2 ? 1.0 : 0.0;
  Eigen::VectorXd rhs = b - K * c;
  for (Index i = 0; i < n; ++i) if (held[i]) rhs[i] = c[i];
  cholesky.factor(withIdentityRows(K, held));
  return cholesky.solve(rhs);
}

// Primal-dual active set (Hintermüller, Ito, Kunisch, SIAM J. Optim. 13(3), 2003): hold at a bound the
// voxels that would cross it, release those whose multiplier has the wrong sign, until the sets repeat.
// Returns false (w: the last iterate) if a set comes back (a cycle) or the iterations run out.
bool primalDualActiveSet(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd& w, HandleSolution& s,
                         const BoundedBiharmonicOptions& o) {
  const Index n = b.size();
  std::vector<signed char> state(n, 0);
  for (Index i = 0; i < n; ++i) state[i] = w[i] < 0 ? 1 : w[i] > 1 ? 2 : 0;
  std::set<std::string> seen;
  SparseCholesky cholesky;
  for (; s.iterations < o.maxActiveSetIterations; ++s.iterations) {
    w = solveWithHeld(K, b, state, cholesky);
    const Eigen::VectorXd g = K * w - b;
    std::vector<signed char> next(n);
    for (Index i = 0; i < n; ++i) {
      if (state[i] == 1) next[i] = g[i] > -o.tolerance ? 1 : 0;
      else if (state[i] == 2) next[i] = g[i] < o.tolerance ? 2 : 0;
      else next[i] = w[i] < -o.tolerance ? 1 : w[i] > 1 + o.tolerance ? 2 : 0;
    }
    if (next == state) {
      ++s.iterations;
      return true;
    }
    if (!seen.insert(std::string(state.begin(), state.end())).second) return false;
    state = std::move(next);
  }
  return false;
}

// Active set from the unconstrained weights; projected Newton from its last iterate if it cycles.
HandleSolution solveHandle(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd w,
                           const BoundedBiharmonicOptions& o, int handle) {
  HandleSolution s;
  if (primalDualActiveSet(K, b, w, s, o)) {
    s.w = clamp01(w);
    s.residual = (s.w - clamp01(s.w - (K * s.w - b))).cwiseAbs().maxCoeff();
    if (s.residual <= o.tolerance) return s;
  }
  HandleSolution fallback = projectedNewton(K, b, clamp01(w), o, handle);
  fallback.iterations += s.iterations;
  fallback.projectedNewton = true;
  return fallback;
}

void checkInput(const Grid<std::int32_t>& labels, int handleCount, const BoundedBiharmonicOptions& o) {
  if (handleCount < 1) throw UsageError("bounded biharmonic weights: no handle");
  if (!(o.tolerance > 0) || o.maxIterations < 1 || o.maxActiveSetIterations < 0 || !(o.bindingEpsilon >= 0) || !(o.armijo > 0 && o.armijo < 1))
    throw UsageError("bounded biharmonic weights: tolerance and armijo must be in (0, 1), iterations >= 1, epsilon >= 0");
  std::vector<std::int64_t> count(std::size_t(handleCount) + 1, 0);
  for (const std::int32_t l : labels.values) {
    if (l < -1 || l > handleCount) throw UsageError("bounded biharmonic weights: label " + std::to_string(l) + " is not in -1.." + std::to_string(handleCount));
    if (l > 0) ++count[l];
  }
  for (int j = 1; j <= handleCount; ++j)
    if (count[j] == 0) throw UsageError("bounded biharmonic weights: handle " + std::to_string(j - 1) + " has no voxel");
}

}  // namespace

BoundedBiharmonicWeights boundedBiharmonicWeights(const Grid<std::int32_t>& labels, int handleCount,
                                                  const BoundedBiharmonicOptions& options) {
  checkInput(labels, handleCount, options);
  BoundedBiharmonicWeights out;
  out.geometry = labels.geometry;
  const std::vector<char> reached = reachableFromHandles(labels);
  out.row.assign(labels.values.size(), -1);
  for (std::size_t v = 0; v < labels.values.size(); ++v) {
    if (labels.values[v] < 0) continue;
    if (!reached[v]) { ++out.unreachable; continue; }
    out.row[v] = std::int32_t(out.voxel.size());
    out.voxel.push_back(std::int64_t(v));
  }
  const Index N = Index(out.voxel.size());
  const SparseMatrix L = gridLaplacian(out);
  const SparseMatrix A = (L * L).pruned(0.0, 0.0);  // L is symmetric: Lᵀ L = L²

  // Free voxels and K = A_FF; the right-hand sides −A_FH w_H, one column per handle.
  std::vector<Index> freeOf(N, -1), freeRows;
  for (Index r = 0; r < N; ++r)
    if (labels.values[out.voxel[r]] == 0) freeOf[r] = Index(freeRows.size()), freeRows.push_back(r);
  const Index nF = Index(freeRows.size());
  out.freeVoxels = nF;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(nF, handleCount);
  std::vector<Eigen::Triplet<double>> kt;
  for (Index c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
      const Index fr = freeOf[it.row()];
      if (fr < 0) continue;
      if (freeOf[c] >= 0) kt.emplace_back(fr, freeOf[c], it.value());
      else B(fr, labels.values[out.voxel[c]] - 1) -= it.value();
    }
  SparseMatrix K(nF, nF);
  K.setFromTriplets(kt.begin(), kt.end());

  out.raw = Eigen::MatrixXd::Zero(N, handleCount);
  for (Index r = 0; r < N; ++r)
    if (freeOf[r] < 0) out.raw(r, labels.values[out.voxel[r]] - 1) = 1;
  out.iterations.assign(handleCount, 0);
  out.projectedNewton.assign(handleCount, 0);
  out.kktResidual.assign(handleCount, 0);
  out.atZero.assign(handleCount, 0);
  out.atOne.assign(handleCount, 0);
  if (nF > 0) {
    SparseCholesky unconstrained;
    unconstrained.factor(K);
    const Eigen::MatrixXd W0 = unconstrained.solve(B);
    tbb::parallel_for(0, handleCount, [&](int j) {
      const HandleSolution s = solveHandle(K, B.col(j), W0.col(j), options, j);
      for (Index f = 0; f < nF; ++f) out.raw(freeRows[f], j) = s.w[f];
      out.iterations[j] = s.iterations;
      out.projectedNewton[j] = s.projectedNewton;
      out.kktResidual[j] = s.residual;
      out.atZero[j] = (s.w.array() == 0.0).count();
      out.atOne[j] = (s.w.array() == 1.0).count();
    });
  }
  // Partition of unity by normalising, as the BBW paper does; a row of zeros (no handle reaches it
  // with positive weight) shares equally.
  out.W = out.raw;
  for (Index r = 0; r < N; ++r) {
    const double sum = out.raw.row(r).sum();
    out.maxSumDeviation = std::max(out.maxSumDeviation, std::abs(sum - 1));
    if (sum > 0) out.W.row(r) /= sum;
    else out.W.row(r).setConstant(1.0 / handleCount);
  }
  return out;
}

}  // namespace vesalius::fat
