// Point location in a tet mesh.
//
// A bounding-volume hierarchy over the tets' boxes, split at the median centroid along the widest
// axis. locate() visits only the boxes that hold the point and tests the tets there by barycentric
// coordinates; the nearest-tet search walks the tree nearer child first and prunes by box distance,
// taking the closest point on a tet as the closest point on its four faces when the point is outside
// (Ericson, "Real-Time Collision Detection" (2005), §5.1.6).
#include "vesalius/core/tet_locator.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

namespace vesalius {
namespace {

// Face k of a tet is the one opposite vertex k.
constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

std::vector<Eigen::AlignedBox3d> tetBoxes(const MatrixX3d& V, const MatrixX4i& T) {
  if (T.rows() == 0) throw BadInput("", "tet locator: the mesh has no tetrahedra");
  return elementBoxes(V, T, "tet locator: a tet");
}

// Squared distance from p to the surface of tet t, and the weights of its closest point there.
double closestOnTetSurface(const MatrixX3d& V, const MatrixX4i& T, int t, const Eigen::Vector3d& p,
                           Eigen::Vector4d& weights) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& face : kFaces) {
    Eigen::Vector3d w;
    const Eigen::Vector3d q =
        closestPointOnTriangle(p, V.row(T(t, face[0])).transpose(), V.row(T(t, face[1])).transpose(),
                               V.row(T(t, face[2])).transpose(), w);
    const double d = (p - q).squaredNorm();
    if (d >= best) continue;
    best = d;
    weights.setZero();
    for (int k = 0; k < 3; ++k) weights[face[k]] = w[k];
  }
  return best;
}

// Spreads the low 21 bits of x three apart (bit k to bit 3k), for interleaving three coordinates.
std::uint64_t spreadBits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffff;
  x = (x | x << 16) & 0x1f0000ff0000ff;
  x = (x | x << 8) & 0x100f00f00f00f00f;
  x = (x | x << 4) & 0x10c30c30c30c30c3;
  x = (x | x << 2) & 0x1249249249249249;
  return x;
}

// Row indices of P sorted by the Morton code of each point on a 2^21 grid over `box` (points outside it
// clamped onto it, non-finite ones first); ties by index, so the order is the same on any thread count.
std::vector<Eigen::Index> mortonOrder(const MatrixX3d& P, const Eigen::AlignedBox3d& box) {
  const Eigen::Array3d scale = double((1 << 21) - 1) / box.sizes().array().max(1e-300);
  std::vector<std::pair<std::uint64_t, Eigen::Index>> keyed(std::size_t(P.rows()));
  tbb::parallel_for(Eigen::Index(0), P.rows(), [&](Eigen::Index p) {
    const Eigen::Array3d x = (P.row(p).transpose() - box.min()).array() * scale;
    std::uint64_t code = 0;
    if (x.allFinite())
      for (int a = 0; a < 3; ++a)
        code |= spreadBits(std::uint64_t(std::clamp(x[a], 0.0, double((1 << 21) - 1)))) << a;
    keyed[std::size_t(p)] = {code, p};
  });
  tbb::parallel_sort(keyed.begin(), keyed.end());
  std::vector<Eigen::Index> order(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace

TetLocator::TetLocator(const MatrixX3d& V, const MatrixX4i& T) : V_(V), T_(T), tree_(tetBoxes(V, T)) {}

Eigen::Vector4d TetLocator::barycentric(int t, const Eigen::Vector3d& p) const {
  if (t < 0 || t >= T_.rows())
    throw UsageError("tet " + std::to_string(t) + " does not exist (the mesh has " +
                     std::to_string(T_.rows()) + ")");
  const Eigen::Vector3d a = V_.row(T_(t, 0)).transpose();
  Eigen::Matrix3d edges;
  for (int k = 0; k < 3; ++k) edges.col(k) = V_.row(T_(t, k + 1)).transpose() - a;
  // A flat tet gives non-finite weights, which locate() rejects (a NaN weight makes the minimum NaN).
  const Eigen::Vector3d w = edges.inverse() * (p - a);
  return {1.0 - w.sum(), w[0], w[1], w[2]};
}

std::optional<TetLocation> TetLocator::locate(const Eigen::Vector3d& p, double tolerance) const {
  // A point whose weights are all >= -tolerance lies within 3 * tolerance * (tet diameter) of the
  // tet, so boxes grown by that much (with the whole mesh's diagonal as diameter) cannot miss it.
  const double margin = 3.0 * std::max(tolerance, 0.0) * tree_.bounds().diagonal().norm();
  std::optional<TetLocation> best;
  double bestMin = -std::max(tolerance, 0.0);
  tree_.near(p, margin * margin, [&](int t) {
    const Eigen::Vector4d w = barycentric(t, p);
    const double lowest = w.minCoeff<Eigen::PropagateNaN>();
    // Of several tets within tolerance (p near a shared face), keep the one p is deepest inside.
    if (!(lowest >= bestMin)) return false;  // also rejects NaN weights of a flat tet
    best = TetLocation{t, w, true};
    bestMin = lowest;
    return lowest >= 0.0;
  });
  return best;
}

TetLocation TetLocator::locateOrNearest(const Eigen::Vector3d& p) const {
  if (auto inside = locate(p)) return *inside;
  TetLocation best;
  double bestDistance = std::numeric_limits<double>::infinity();
  tree_.nearestFirst(p, bestDistance, [&](int t) {
    Eigen::Vector4d w;
    const double d = closestOnTetSurface(V_, T_, t, p, w);
    if (d < bestDistance) {
      bestDistance = d;
      best = {t, w, false};
    }
  });
  return best;
}

std::vector<TetLocation> TetLocator::locateOrNearest(const MatrixX3d& P) const {
  const std::vector<Eigen::Index> order = mortonOrder(P, tree_.bounds());
  std::vector<TetLocation> result(std::size_t(P.rows()));
  // Consecutive points of the order stay together in one task, to share the cache.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        result[std::size_t(order[i])] = locateOrNearest(Eigen::Vector3d(P.row(order[i]).transpose()));
                    });
  return result;
}

}  // namespace vesalius
