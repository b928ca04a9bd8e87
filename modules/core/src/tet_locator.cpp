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

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

namespace vesalius {
namespace {

constexpr int kLeafSize = 4;
// Median splits bound the depth by 31; a depth-first walk never stacks more than depth + 1 nodes.
constexpr int kStackSize = 64;
// Face k of a tet is the one opposite vertex k.
constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

template <class Node>
int buildTree(std::vector<Node>& nodes, std::vector<int>& order, int begin, int end,
              const std::vector<Eigen::AlignedBox3d>& boxes,
              const std::vector<Eigen::Vector3d>& centroids) {
  const int index = int(nodes.size());
  nodes.emplace_back();
  Eigen::AlignedBox3d box, centroidBox;
  box.setEmpty();
  centroidBox.setEmpty();
  for (int i = begin; i < end; ++i) {
    box.extend(boxes[order[i]]);
    centroidBox.extend(centroids[order[i]]);
  }
  nodes[index].box = box;
  if (end - begin <= kLeafSize) {
    nodes[index].begin = begin;
    nodes[index].end = end;
    return index;
  }
  int axis;
  centroidBox.sizes().maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](int x, int y) { return centroids[x][axis] < centroids[y][axis]; });
  const int left = buildTree(nodes, order, begin, mid, boxes, centroids);
  const int right = buildTree(nodes, order, mid, end, boxes, centroids);
  nodes[index].left = left;
  nodes[index].right = right;
  return index;
}

void checkMesh(const MatrixX3d& V, const MatrixX4i& T) {
  if (T.rows() == 0) throw BadInput("", "tet locator: the mesh has no tetrahedra");
  if (T.minCoeff() < 0 || T.maxCoeff() >= V.rows())
    throw BadInput("", "tet locator: a tet index is outside the " + std::to_string(V.rows()) +
                           " vertices");
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

}  // namespace

TetLocator::TetLocator(const MatrixX3d& V, const MatrixX4i& T) : V_(V), T_(T) {
  checkMesh(V_, T_);
  const int n = int(T_.rows());
  std::vector<Eigen::AlignedBox3d> boxes(n);
  std::vector<Eigen::Vector3d> centroids(n);
  for (int t = 0; t < n; ++t) {
    boxes[t].setEmpty();
    for (int k = 0; k < 4; ++k) boxes[t].extend(V_.row(T_(t, k)).transpose());
    centroids[t] = boxes[t].center();
  }
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  buildTree(nodes_, order_, 0, n, boxes, centroids);
}

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
  const double margin = 3.0 * std::max(tolerance, 0.0) * nodes_[0].box.diagonal().norm();
  const double margin2 = margin * margin;
  std::optional<TetLocation> best;
  double bestMin = -std::max(tolerance, 0.0);
  std::array<int, kStackSize> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.box.squaredExteriorDistance(p) > margin2) continue;
    if (node.left >= 0) {
      stack[top++] = node.right;
      stack[top++] = node.left;
      continue;
    }
    for (int i = node.begin; i < node.end; ++i) {
      const Eigen::Vector4d w = barycentric(order_[i], p);
      const double lowest = w.minCoeff<Eigen::PropagateNaN>();
      // Of several tets within tolerance (p near a shared face), keep the one p is deepest inside.
      if (lowest >= bestMin) {
        best = TetLocation{order_[i], w};
        bestMin = lowest;
        if (lowest >= 0.0) return best;
      }
    }
  }
  return best;
}

TetLocation TetLocator::locateOrNearest(const Eigen::Vector3d& p) const {
  if (auto inside = locate(p)) return *inside;
  TetLocation best;
  double bestDistance = std::numeric_limits<double>::infinity();
  std::array<std::pair<int, double>, kStackSize> stack;
  int top = 0;
  stack[top++] = {0, nodes_[0].box.squaredExteriorDistance(p)};
  while (top > 0) {
    const auto [index, boxDistance] = stack[--top];
    if (boxDistance >= bestDistance) continue;
    const Node& node = nodes_[index];
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) {
        Eigen::Vector4d w;
        const double d = closestOnTetSurface(V_, T_, order_[i], p, w);
        if (d < bestDistance) {
          bestDistance = d;
          best = {order_[i], w};
        }
      }
      continue;
    }
    std::pair<int, double> near{node.left, nodes_[node.left].box.squaredExteriorDistance(p)};
    std::pair<int, double> far{node.right, nodes_[node.right].box.squaredExteriorDistance(p)};
    if (far.second < near.second) std::swap(near, far);
    stack[top++] = far;
    stack[top++] = near;
  }
  return best;
}

std::vector<TetLocation> TetLocator::locateOrNearest(const MatrixX3d& P) const {
  std::vector<TetLocation> result(P.rows());
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, P.rows(), 256),
                    [&](const tbb::blocked_range<Eigen::Index>& range) {
                      for (Eigen::Index i = range.begin(); i != range.end(); ++i)
                        result[i] = locateOrNearest(Eigen::Vector3d(P.row(i).transpose()));
                    });
  return result;
}

}  // namespace vesalius
