// Bone weights by Laplace diffusion (bone_weights.h, Sujar et al. 2018, §3.3).
#include "vesalius/posing/bone_weights.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/sparse_cholesky.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <Eigen/LU>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

namespace vesalius::posing {
namespace {

using Eigen::Index;
using SpMat = Eigen::SparseMatrix<double>;

void checkInputs(const MatrixX3d& V, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex) {
  if (boneOfVertex.size() != V.rows())
    throw UsageError("bone weights: boneOfVertex has " + std::to_string(boneOfVertex.size()) + " entries for " +
                     std::to_string(V.rows()) + " vertices");
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= V.rows()))
    throw BadInput("", "bone weights: a tet refers to a vertex that does not exist");
  if (V.rows() == 0 || boneOfVertex.maxCoeff() < 0) throw BadInput("", "bone weights: no vertex is labelled as bone");
  if (boneOfVertex.minCoeff() < -1) throw BadInput("", "bone weights: a bone label is below -1");
  std::vector<char> used(std::size_t(boneOfVertex.maxCoeff() + 1), 0);
  for (Index i = 0; i < boneOfVertex.size(); ++i)
    if (boneOfVertex[i] >= 0) used[std::size_t(boneOfVertex[i])] = 1;
  for (std::size_t j = 0; j < used.size(); ++j)
    if (!used[j]) throw BadInput("", "bone weights: bone " + std::to_string(j) + " has no vertex");
}

// Free vertices that no chain of tets links to a bone vertex: K has a kernel there.
void checkEveryFreeVertexReachesABone(const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex) {
  std::vector<int> parent(std::size_t(boneOfVertex.size()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[std::size_t(v)] != v) v = parent[std::size_t(v)] = parent[std::size_t(parent[std::size_t(v)])];
    return v;
  };
  for (Index t = 0; t < T.rows(); ++t)
    for (int k = 1; k < 4; ++k) parent[std::size_t(root(T(t, k)))] = root(T(t, 0));
  std::vector<char> hasBone(parent.size(), 0);
  for (Index v = 0; v < boneOfVertex.size(); ++v)
    if (boneOfVertex[v] >= 0) hasBone[std::size_t(root(int(v)))] = 1;
  long stranded = 0;
  for (Index v = 0; v < boneOfVertex.size(); ++v) stranded += !hasBone[std::size_t(root(int(v)))];
  if (stranded > 0)
    throw BadInput("", "bone weights: " + std::to_string(stranded) +
                           " vertices are in no connected part of the tet mesh that touches a bone");
}

// Vertex adjacency through tet edges plus the diagonal, column-compressed with sorted rows, values zero.
// Built from sorted unique edges rather than 16 triplets per tet, which would take 16 times the memory.
SpMat stiffnessPattern(Index n, const MatrixX4i& T) {
  std::vector<std::uint64_t> edges(std::size_t(6 * T.rows()));
  tbb::parallel_for(Index(0), T.rows(), [&](Index t) {
    std::size_t e = std::size_t(6 * t);
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const std::uint64_t lo = std::uint64_t(std::min(T(t, a), T(t, b))), hi = std::uint64_t(std::max(T(t, a), T(t, b)));
        edges[e++] = lo << 32 | hi;
      }
  });
  tbb::parallel_sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<int> below(std::size_t(n), 0), outer(std::size_t(n + 1), 0);  // below: rows above the diagonal
  for (const std::uint64_t e : edges) {
    ++below[e & 0xffffffffu];
    ++outer[std::size_t(e >> 32) + 1];
    ++outer[std::size_t(e & 0xffffffffu) + 1];
  }
  for (Index v = 0; v < n; ++v) outer[std::size_t(v + 1)] += outer[std::size_t(v)] + 1;
  std::vector<int> inner(std::size_t(outer.back())), low(outer.begin(), outer.end() - 1), high(static_cast<std::size_t>(n));
  for (Index v = 0; v < n; ++v) {
    inner[std::size_t(outer[std::size_t(v)] + below[std::size_t(v)])] = int(v);
    high[std::size_t(v)] = outer[std::size_t(v)] + below[std::size_t(v)] + 1;
  }
  // Edges come sorted by (lower, higher) vertex, so each column's rows arrive in increasing order.
  for (const std::uint64_t e : edges) {
    const int a = int(e >> 32), b = int(e & 0xffffffffu);
    inner[std::size_t(low[std::size_t(b)]++)] = a;
    inner[std::size_t(high[std::size_t(a)]++)] = b;
  }
  std::vector<double> values(inner.size(), 0.0);
  return Eigen::Map<const SpMat>(n, n, Index(inner.size()), outer.data(), inner.data(), values.data());
}

// Clamps to [0, 1] and rescales each row to sum 1 (bone_weights.h says why it may be needed).
void clampAndNormalize(Eigen::MatrixXd& W) {
  tbb::parallel_for(Index(0), W.rows(), [&](Index i) {
    W.row(i) = W.row(i).cwiseMax(0.0).cwiseMin(1.0);
    W.row(i) /= W.row(i).sum();
  });
}

}  // namespace

SpMat stiffnessMatrix(const MatrixX3d& V, const MatrixX4i& T) {
  SpMat K = stiffnessPattern(V.rows(), T);
  for (Index t = 0; t < T.rows(); ++t) {
    Eigen::Matrix3d E;
    for (int k = 0; k < 3; ++k) E.col(k) = (V.row(T(t, k + 1)) - V.row(T(t, 0))).transpose();
    const double volume = E.determinant() / 6.0;
    if (!(volume > 0.0))
      throw BadInput("", "bone weights: tet " + std::to_string(t) + " is flat or inverted");
    Eigen::Matrix<double, 4, 3> G;  // row a: gradient of the barycentric function of corner a
    G.bottomRows<3>() = E.inverse();
    G.row(0) = -G.bottomRows<3>().colwise().sum();
    const Eigen::Matrix4d local = volume * G * G.transpose();
    for (int c = 0; c < 4; ++c) {
      const int* rows = K.innerIndexPtr() + K.outerIndexPtr()[T(t, c)];
      const int* end = K.innerIndexPtr() + K.outerIndexPtr()[T(t, c) + 1];
      for (int r = 0; r < 4; ++r)
        K.valuePtr()[std::lower_bound(rows, end, T(t, r)) - K.innerIndexPtr()] += local(r, c);
    }
  }
  return K;
}

Eigen::MatrixXd computeBoneWeights(const MatrixX3d& V, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
                                   const BoneWeightsOptions& options) {
  checkInputs(V, T, boneOfVertex);
  checkEveryFreeVertexReachesABone(T, boneOfVertex);
  const Index n = V.rows(), bones = boneOfVertex.maxCoeff() + 1;
  const SpMat K = stiffnessMatrix(V, T);
  std::vector<Index> freeIndex(std::size_t(n), -1);
  Index freeCount = 0;
  for (Index v = 0; v < n; ++v)
    if (boneOfVertex[v] < 0) freeIndex[std::size_t(v)] = freeCount++;
  // A = K_FF and B = -K_FB W_B (eq. 5), one column per bone; K is symmetric, so column v is row v.
  SpMat A(freeCount, freeCount);
  A.reserve(K.nonZeros());
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(freeCount, bones);
  for (Index v = 0; v < n; ++v) {
    const Index f = freeIndex[std::size_t(v)];
    if (f < 0) continue;
    A.startVec(f);
    for (SpMat::InnerIterator it(K, v); it; ++it) {
      const Index r = freeIndex[std::size_t(it.row())];
      if (r >= 0)
        A.insertBack(r, f) = it.value();
      else
        B(f, boneOfVertex[it.row()]) -= it.value();
    }
  }
  A.finalize();
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, bones);
  if (freeCount > 0) {
    SparseCholesky cholesky;
    cholesky.factor(A);
    const Eigen::MatrixXd X = cholesky.solve(B);
    for (Index v = 0; v < n; ++v)
      if (freeIndex[std::size_t(v)] >= 0) W.row(v) = X.row(freeIndex[std::size_t(v)]);
  }
  for (Index v = 0; v < n; ++v)
    if (boneOfVertex[v] >= 0) W(v, boneOfVertex[v]) = 1.0;
  if (options.clampAndNormalize) clampAndNormalize(W);
  return W;
}

}  // namespace vesalius::posing
